//! The rayon thread pool, sized safely.
//!
//! rayon reads `RAYON_NUM_THREADS` itself and panics when it cannot spawn
//! that many threads (`RAYON_NUM_THREADS=100000`). The pool is therefore
//! built here, once, with the variable clamped to [`MAX_THREADS`]; should
//! even that fail, with one thread.

/// Most worker threads: more than any machine this runs on usefully has.
pub const MAX_THREADS: usize = 256;

/// The pool's size: `RAYON_NUM_THREADS` clamped to [`MAX_THREADS`] (unset,
/// 0 or unparsable: rayon's default, one thread per core).
pub fn count() -> usize {
    let requested = std::env::var("RAYON_NUM_THREADS")
        .ok()
        .and_then(|v| v.trim().parse::<usize>().ok())
        .unwrap_or(0);
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    if requested == 0 {
        cores
    } else {
        requested.min(MAX_THREADS)
    }
}

/// Builds the global pool of [`count`] threads.
pub fn configure() {
    let n = count();
    let build = |n: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
    };
    if build(n).is_err() {
        let _ = build(1);
    }
}
