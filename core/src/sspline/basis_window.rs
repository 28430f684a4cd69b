//! The values of a centred basis's translates at one point.

/// The non-zero values of the translates of a centred basis at one point:
/// `values[l] = β(x − (first + l))`.
#[derive(Debug, Clone, PartialEq)]
pub struct BasisWindow<T> {
    /// Index `i` of the first translate `β(x − i)` in the window.
    pub first: i64,
    /// The basis values, one per translate.
    pub values: Vec<T>,
}
