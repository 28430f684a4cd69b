//! The `threads=` argument: `None` runs on rayon's global pool (one thread
//! per core), `n` on a pool of `n` threads kept for later calls (building a
//! pool costs thread start-ups, too much to pay per call).

use crate::error::value_error;
use pyo3::PyResult;
use rayon::{ThreadPool, ThreadPoolBuilder};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

static POOLS: OnceLock<Mutex<HashMap<usize, Arc<ThreadPool>>>> = OnceLock::new();

/// The most threads a pool may have: the CLI's clamp of `RAYON_NUM_THREADS`
/// (`splinelab_reports::threads::MAX_THREADS`); `splinelab._validate`
/// refuses larger requests first, this is the backstop for direct calls.
pub const MAX_THREADS: usize = 256;

/// Pools kept at once: a program that tries many sizes keeps the last few,
/// not one pool (and its threads) per size ever asked for.
const KEPT_POOLS: usize = 4;

fn pool(threads: usize) -> PyResult<Arc<ThreadPool>> {
    if !(1..=MAX_THREADS).contains(&threads) {
        return Err(value_error(format!(
            "threads={threads} is outside 1..{MAX_THREADS} (None: one thread per core)"
        )));
    }
    let mut pools = POOLS
        .get_or_init(|| Mutex::new(HashMap::new()))
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some(p) = pools.get(&threads) {
        return Ok(p.clone());
    }
    let p = Arc::new(
        ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(value_error)?,
    );
    if pools.len() >= KEPT_POOLS {
        pools.clear();
    }
    pools.insert(threads, p.clone());
    Ok(p)
}

/// Runs `f` with `threads` rayon threads (`None`: the global pool).
pub fn run_with<R: Send>(threads: Option<usize>, f: impl FnOnce() -> R + Send) -> PyResult<R> {
    match threads {
        None => Ok(f()),
        Some(n) => Ok(pool(n)?.install(f)),
    }
}
