//! The samples at a product of per-axis index sets, read from a
//! [`SampleSource`] a box at a time: each axis' sorted indices split into
//! contiguous runs, one [`SampleSource::read_box`] per combination of runs
//! (a window that a periodic mode folds across the end reads two runs on
//! that axis, not the whole axis between them).

use crate::ndimage::NdimageError;
use crate::ndimage::samples::SampleSource;
use crate::scalar::Real;

/// The runs `(position, first index, length)` of sorted, distinct indices.
fn runs(indices: &[usize]) -> Vec<(usize, usize, usize)> {
    let mut out: Vec<(usize, usize, usize)> = Vec::new();
    for (p, &i) in indices.iter().enumerate() {
        match out.last_mut() {
            Some((_, first, len)) if *first + *len == i => *len += 1,
            _ => out.push((p, i, 1)),
        }
    }
    out
}

/// C-order strides of `shape`.
pub(crate) fn strides(shape: &[usize]) -> Vec<usize> {
    let mut s = vec![1; shape.len()];
    for a in (0..shape.len().saturating_sub(1)).rev() {
        s[a] = s[a + 1] * shape[a + 1];
    }
    s
}

/// Calls `f(flat index, multi-index)` for every element of `shape` in C order.
pub(crate) fn for_each_index(shape: &[usize], mut f: impl FnMut(usize, &[usize])) {
    let total: usize = shape.iter().product();
    let mut idx = vec![0usize; shape.len()];
    for flat in 0..total {
        f(flat, &idx);
        for a in (0..shape.len()).rev() {
            idx[a] += 1;
            if idx[a] < shape[a] {
                break;
            }
            idx[a] = 0;
        }
    }
}

/// The boxes `(lo, hi)` [`gather`] reads for `lists`: one per combination
/// of the axes' contiguous runs.
pub(crate) fn run_boxes(lists: &[Vec<usize>]) -> Vec<(Vec<usize>, Vec<usize>)> {
    let axis_runs: Vec<Vec<(usize, usize, usize)>> = lists.iter().map(|l| runs(l)).collect();
    let counts: Vec<usize> = axis_runs.iter().map(Vec::len).collect();
    let mut out = Vec::new();
    for_each_index(&counts, |_, pick| {
        let (lo, hi) = pick
            .iter()
            .enumerate()
            .map(|(a, &r)| (axis_runs[a][r].1, axis_runs[a][r].1 + axis_runs[a][r].2))
            .unzip();
        out.push((lo, hi));
    });
    out
}

/// The samples `source[lists[0][i_0], lists[1][i_1], …]` in C order over
/// the lists (each sorted and distinct, inside the source), into `out`
/// (resized to the product of the lists' lengths). Reads only those
/// samples' runs.
pub(crate) fn gather<T, S>(
    source: &S,
    lists: &[Vec<usize>],
    out: &mut Vec<T>,
) -> Result<(), NdimageError>
where
    T: Real,
    S: SampleSource<T> + ?Sized,
{
    let shape: Vec<usize> = lists.iter().map(Vec::len).collect();
    let total: usize = shape.iter().product();
    out.clear();
    out.resize(total, T::zero());
    if total == 0 {
        return Ok(());
    }
    let axis_runs: Vec<Vec<(usize, usize, usize)>> = lists.iter().map(|l| runs(l)).collect();
    if axis_runs.iter().all(|r| r.len() == 1) {
        // One box: read straight into `out`.
        let lo: Vec<usize> = axis_runs.iter().map(|r| r[0].1).collect();
        let hi: Vec<usize> = axis_runs.iter().map(|r| r[0].1 + r[0].2).collect();
        return source.read_box(&lo, &hi, out);
    }
    let dst_strides = strides(&shape);
    let counts: Vec<usize> = axis_runs.iter().map(Vec::len).collect();
    let mut block = Vec::new();
    let mut result = Ok(());
    for_each_index(&counts, |_, pick| {
        if result.is_err() {
            return;
        }
        let chosen: Vec<&(usize, usize, usize)> = pick
            .iter()
            .enumerate()
            .map(|(a, &r)| &axis_runs[a][r])
            .collect();
        let lo: Vec<usize> = chosen.iter().map(|r| r.1).collect();
        let hi: Vec<usize> = chosen.iter().map(|r| r.1 + r.2).collect();
        let box_shape: Vec<usize> = chosen.iter().map(|r| r.2).collect();
        block.clear();
        block.resize(box_shape.iter().product(), T::zero());
        if let Err(e) = source.read_box(&lo, &hi, &mut block) {
            result = Err(e);
            return;
        }
        for_each_index(&box_shape, |k, idx| {
            let at: usize = idx
                .iter()
                .enumerate()
                .map(|(a, &i)| (chosen[a].0 + i) * dst_strides[a])
                .sum();
            out[at] = block[k].clone();
        });
    });
    result
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::Array2;

    #[test]
    fn gathers_the_product_of_index_sets_by_runs() {
        let a = Array2::from_shape_fn((6, 7), |(i, j)| (10 * i + j) as f64);
        let lists = vec![vec![0, 1, 5], vec![2, 6]];
        let mut out = Vec::new();
        gather(&a, &lists, &mut out).unwrap();
        assert_eq!(out, [2.0, 6.0, 12.0, 16.0, 52.0, 56.0]);
        assert_eq!(runs(&[0, 1, 5]), [(0, 0, 2), (2, 5, 1)]);
    }
}
