//! Single-point evaluation of the N-D interpolant allocates nothing for
//! `ndim × (degree + 1) ≤ 24` in `f64` (issue 14): counted by a global
//! allocator that forwards to the system one. Its own binary, one test, so
//! no other thread allocates while counting.
#![allow(unsafe_code)] // GlobalAlloc is an unsafe trait; this one only counts.

use splinelab::ndarray::{Array1, Array2, Array3};
use splinelab::prelude::*;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static ALLOCS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every call is forwarded unchanged to `System`.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: the caller's contract is passed on.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as above.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by `f`.
fn count(f: impl FnOnce() -> f64) -> (usize, f64) {
    let before = ALLOCS.load(Ordering::Relaxed);
    let v = std::hint::black_box(f());
    (ALLOCS.load(Ordering::Relaxed) - before, v)
}

#[test]
fn single_point_evaluation_does_not_allocate() {
    let s1 = Array1::from_shape_fn(40, |i| (i as f64 * 0.37).sin());
    let s2 = Array2::from_shape_fn((12, 9), |(i, j)| (i as f64 - 0.5 * j as f64).cos());
    let s3 = Array3::from_shape_fn((6, 7, 5), |(i, j, k)| (i * j) as f64 - k as f64);
    for (mode, d) in [
        (Mode::Mirror, 3),
        (Mode::GridConstant, 7),
        (Mode::Nearest, 0),
    ] {
        let f1: Interpolant<f64> = Interpolant::new(&s1, Options::new(d, mode)).unwrap();
        let f2: Interpolant<f64> = Interpolant::new(&s2, Options::new(d.min(7), mode)).unwrap();
        let f3: Interpolant<f64> = Interpolant::new(&s3, Options::new(d.min(7), mode)).unwrap();
        let (n, v) = count(|| f1.eval(&[17.3]).unwrap());
        assert_eq!(n, 0, "1-D {mode} d={d}: {n} allocations");
        assert!(v.is_finite());
        let (n, _) = count(|| f2.eval(&[3.6, -1.2]).unwrap());
        assert_eq!(n, 0, "2-D {mode} d={d}: {n} allocations");
        let (n, _) = count(|| f3.eval(&[2.5, 6.4, 1.1]).unwrap());
        assert_eq!(n, 0, "3-D {mode} d={d}: {n} allocations");
        if d > 0 {
            let (n, _) = count(|| f2.eval_derivative(&[3.6, 4.2], &[1, 0]).unwrap());
            assert_eq!(n, 0, "2-D derivative {mode} d={d}: {n} allocations");
        }
    }
    // The counter works: a degree beyond the stack work space allocates.
    let big: Interpolant<f64> = Interpolant::new(&s3, Options::new(9, Mode::Mirror)).unwrap();
    let (n, _) = count(|| big.eval(&[2.5, 3.0, 1.0]).unwrap());
    assert!(n > 0);
}
