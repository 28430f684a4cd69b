//! Throwaway probe (not committed): N-D quintic/quartic prefilter of scipy's
//! fixtures x2, x3 against 256-bit MPFR, for the N-D path and line by line.
use ndarray::{ArrayD, Axis};
use splinelab::prelude::*;
use splinelab::scalar::Mp;
use std::path::PathBuf;

fn fx(name: &str) -> ArrayD<f64> {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("fixtures/scipy").join(format!("{name}.npy"));
    ndarray_npy::read_npy(p).unwrap()
}

fn ulps(got: impl Iterator<Item = f64>, want: &[f64]) -> f64 {
    let m = want.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let unit = m * f64::EPSILON;
    got.zip(want).fold(0.0, |a, (g, w)| a.max((g - w).abs() / unit))
}

#[test]
fn probe() {
    type W = Mp<256>;
    let mut worst = [0.0f64; 3];
    for mode in Mode::ALL {
        if mode == Mode::Reflect { continue; }
        for d in 2..=5u32 {
            for k in [2, 3] {
                let x = fx(&format!("x{k}"));
                let fam = SplineFamily::Order(d + 1);
                let f = LineFilter::<f64>::new(&fam, mode, 0.7, Route::Exact).unwrap();
                let mut nd = x.clone();
                spline_filter(&mut nd, &f).unwrap();
                let mut lbl = x.clone();
                let wide = LineFilter::<W>::new(&fam, mode, 0.7, Route::Exact).unwrap();
                let mut want = x.mapv(|v| W::from_f64_exact(v));
                for axis in 0..x.ndim() {
                    for mut lane in lbl.lanes_mut(Axis(axis)) {
                        let mut line = lane.to_vec();
                        f.apply(&mut line, &mut Vec::new());
                        lane.iter_mut().zip(line).for_each(|(a, b)| *a = b);
                    }
                    for mut lane in want.lanes_mut(Axis(axis)) {
                        let mut line = lane.to_vec();
                        wide.apply(&mut line, &mut Vec::new());
                        lane.iter_mut().zip(line).for_each(|(a, b)| *a = b);
                    }
                }
                let want: Vec<f64> = want.iter().map(|v| v.to_f64()).collect();
                let sc = fx(&format!("f{k}_{mode}_{d}"));
                let e = [ulps(nd.iter().copied(), &want), ulps(lbl.iter().copied(), &want), ulps(sc.iter().copied(), &want)];
                let vs = ulps(nd.iter().copied(), sc.as_slice().unwrap());
                let vl = ulps(lbl.iter().copied(), sc.as_slice().unwrap());
                println!("{mode:?} d{d} x{k}: err nd {:.2} lbl {:.2} scipy {:.2} | vs scipy nd {vs:.2} lbl {vl:.2}", e[0], e[1], e[2]);
                for i in 0..3 { worst[i] = worst[i].max(e[i]); }
            }
        }
    }
    println!("worst err vs MPFR: nd {:.2} line-by-line {:.2} scipy {:.2}", worst[0], worst[1], worst[2]);
}
