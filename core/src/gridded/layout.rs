//! Where the samples of a grid lie in memory: any strides, negative ones
//! included (an axis given descending and flipped by numpy is read in
//! place, not copied).

/// Element `(i_0, …, i_{d−1}, b)` of a grid × `m` array is
/// `data[origin + Σ_a i_a·strides[a] + b·strides[d]]`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Layout {
    /// The position of element `(0, …, 0)` in the slice.
    pub origin: usize,
    /// Element strides of the `d` grid axes, then of the trailing axis.
    pub strides: Vec<isize>,
}

impl Layout {
    /// C order for `shape` (grid lengths, then `m`).
    ///
    /// ```
    /// use splinelab::gridded::layout::Layout;
    /// assert_eq!(Layout::c_order(&[4, 3, 2]).strides, vec![6, 2, 1]);
    /// ```
    pub fn c_order(shape: &[usize]) -> Self {
        let mut strides = vec![1isize; shape.len()];
        for a in (0..shape.len().saturating_sub(1)).rev() {
            strides[a] = strides[a + 1] * shape[a + 1] as isize;
        }
        Self { origin: 0, strides }
    }

    /// The layout of a view whose elements fill one block of memory in
    /// some order (`as_slice_memory_order`): the block and its layout, or
    /// `None` (a broadcast or sliced view: the caller copies it).
    ///
    /// ```
    /// use splinelab::gridded::layout::Layout;
    /// use ndarray::{Array3, Axis};
    /// let a = Array3::from_shape_fn((3, 4, 1), |(i, j, _)| (10 * i + j) as f64);
    /// let mut v = a.view().into_dyn();
    /// v.invert_axis(Axis(0)); // descending along axis 0, in place
    /// let (data, l) = Layout::of_view(&v).unwrap();
    /// assert_eq!(data[l.origin], 20.0); // element (0, 0) is a[2, 0]
    /// assert_eq!(data[(l.origin as isize + l.strides[0] + 3 * l.strides[1]) as usize], 13.0);
    /// ```
    pub fn of_view<'a, S>(view: &ndarray::ArrayViewD<'a, S>) -> Option<(&'a [S], Self)> {
        let data = view.to_slice_memory_order()?;
        let strides = view.strides().to_vec();
        let origin = view
            .shape()
            .iter()
            .zip(&strides)
            .filter(|(_, s)| **s < 0)
            .map(|(&n, s)| n.saturating_sub(1) * s.unsigned_abs())
            .sum();
        Some((data, Self { origin, strides }))
    }

    /// The position of `(i_0, …, i_{d−1}, 0)` plus `offset` (element steps).
    #[inline]
    pub(crate) fn at(&self, offset: isize) -> usize {
        (self.origin as isize + offset) as usize
    }
}
