//! Parallel sweeps give bitwise-identical results whatever the thread count.

use rayon::ThreadPoolBuilder;
use splinelab_verify::conditioning::run_conditioning;

fn with_threads<R: Send>(n: usize, f: impl FnOnce() -> R + Send) -> R {
    ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .unwrap()
        .install(f)
}

#[test]
fn conditioning_sweep_is_identical_on_1_and_3_threads() {
    let degrees: Vec<usize> = (1..=12).collect();
    let one = with_threads(1, || run_conditioning(&degrees).unwrap());
    let three = with_threads(3, || run_conditioning(&degrees).unwrap());
    // Compare the serialised form: f64 fields bit for bit, MPFR as strings.
    assert_eq!(
        serde_json::to_string(&one).unwrap(),
        serde_json::to_string(&three).unwrap()
    );
    let bits = |rows: &[splinelab_verify::conditioning::CondRow]| {
        rows.iter()
            .map(|r| (r.cond2_f64.to_bits(), r.cond_inf_f64.to_bits()))
            .collect::<Vec<_>>()
    };
    assert_eq!(bits(&one), bits(&three));
}
