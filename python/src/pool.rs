//! The `threads=` argument, and where a call runs. `threads=n` runs on a
//! pool of `n` threads kept for later calls (building a pool costs thread
//! start-ups, too much to pay per call), its workers on different CPUs
//! (`spread`); `None` on the default pool (one thread per core, or
//! `RAYON_NUM_THREADS` clamped as the CLI clamps it, as rayon's global
//! pool). A small call (`threads=1`, or an estimated [`SMALL_NS`] of work
//! or less) runs on the calling thread instead, its parallel loops inline
//! (issue 50): handing it to a pool and waiting costs a wake-up of a
//! worker and of the caller, 10–50 µs on a loaded 2-core machine, where
//! scipy's whole call on 16² takes 8–40 µs.
//!
//! **How a call runs inline.** rayon splits a parallel loop whenever its
//! pool has more than one thread, and a thread outside every pool hands
//! each split to the global pool. The calling thread is therefore made,
//! on its first small call, the only worker of a one-thread pool of its
//! own (`use_current_thread`): its loops then run where they are, as one
//! thread runs them. That is permanent for the thread (rayon keeps no way
//! back), so every call from Python that runs rayon code and is not small
//! installs it on a pool explicitly ([`parallel`], [`run_with`]), never on
//! the global pool implicitly.

use crate::error::value_error;
use pyo3::PyResult;
use rayon::{ThreadPool, ThreadPoolBuilder};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

static POOLS: OnceLock<Mutex<HashMap<usize, Arc<ThreadPool>>>> = OnceLock::new();

// The most threads a pool may have: the CLI's clamp of `RAYON_NUM_THREADS`;
// `splinelab._validate` refuses larger requests first, this is the backstop
// for direct calls.
use splinelab_reports::threads::MAX_THREADS;

/// Pools kept at once: a program that tries many sizes keeps the last few,
/// not one pool (and its threads) per size ever asked for.
const KEPT_POOLS: usize = 4;

/// Estimated work (nanoseconds on one thread) up to which a call with
/// `threads=None` runs on the calling thread. A parallel run of `t` ns on
/// two cores takes `t / 2` plus the hand-off (10–50 µs measured by
/// `python/bench/small_calls.py` on the loaded 2-core machine,
/// `threads=None` against `threads=1`), but it also costs CPU: the woken
/// workers' wake-up and spinning. At 60 µs (twice the hand-off, issue 50's
/// first choice) reproject's suite, whose calls are many and mid-sized,
/// took 4.4 % more CPU swapped than with scipy (50.08 against 47.97 s,
/// three alternated pairs), and the same with the pool at one thread; at
/// 200 µs the same (51.80 against 51.89 s, `python/bench/reproject_cpu.md`),
/// while calls of 60–200 µs of work run up to 1.8× longer in wall time than
/// on two threads (still 0.03–0.6 of scipy's time in `small_calls`). The
/// estimates are the local route's pricing constants
/// ([`splinelab::ndimage::local::C_GLOBAL`] per sample and axis of the
/// prefilter, a nanosecond per multiply-add of the evaluation).
pub const SMALL_NS: f64 = 200_000.0;

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
    let mut builder = ThreadPoolBuilder::new().num_threads(threads);
    if let Some(spread) = spread::Spread::new(threads) {
        builder = builder.start_handler(move |i| spread.apply(i));
    }
    let p = Arc::new(builder.build().map_err(value_error)?);
    if pools.len() >= KEPT_POOLS {
        pools.clear();
    }
    pools.insert(threads, p.clone());
    Ok(p)
}

/// The pool of `threads=None`: sized as rayon's global pool
/// ([`splinelab_reports::threads::count`]), its workers on different CPUs
/// as a `threads=n` pool's (`spread`: rayon's global pool, which the
/// default was before issue 50, ran a 1024² cubic `spline_filter` in the
/// time of one thread on the 2-core machine, 2.0 ms against 1.0 ms with
/// `threads=2`); `None` where no thread can be started (the call then
/// runs on the calling thread).
fn default_pool() -> Option<&'static ThreadPool> {
    static DEFAULT: OnceLock<Option<ThreadPool>> = OnceLock::new();
    DEFAULT
        .get_or_init(|| {
            let n = splinelab_reports::threads::count();
            let build = |n: usize| {
                let mut builder = ThreadPoolBuilder::new().num_threads(n);
                if let Some(spread) = spread::Spread::new(n) {
                    builder = builder.start_handler(move |i| spread.apply(i));
                }
                builder.build().ok()
            };
            build(n).or_else(|| build(1))
        })
        .as_ref()
}

/// Runs `f` on the calling thread, its parallel loops inline (module
/// documentation). A thread that already works for another pool (a call
/// from inside rayon) runs `f` as it is.
fn inline<R>(f: impl FnOnce() -> R) -> R {
    thread_local! {
        static ONE: Option<ThreadPool> =
            ThreadPoolBuilder::new().num_threads(1).use_current_thread().build().ok();
    }
    ONE.with(|_| ());
    f()
}

/// Runs `f` on the default pool: calls from Python that run rayon code
/// and are not priced (`check`, the local interpolant's set-up).
pub fn parallel<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    match default_pool() {
        Some(p) => p.install(f),
        None => inline(f),
    }
}

/// Runs `f` with `threads` rayon threads (`None`: the default pool), or on
/// the calling thread for `threads=1` and for work estimated at
/// `work_ns` ≤ [`SMALL_NS`] under `None` (module documentation).
pub fn run_with<R: Send>(
    threads: Option<usize>,
    work_ns: f64,
    f: impl FnOnce() -> R + Send,
) -> PyResult<R> {
    match threads {
        _ if runs_inline(threads, work_ns) => Ok(inline(f)),
        None => Ok(parallel(f)),
        Some(n) => Ok(pool(n)?.install(f)),
    }
}

/// [`run_with`] from Python: a small call ([`SMALL_NS`] or less, which
/// runs on the calling thread) keeps the GIL, since releasing and taking
/// it back costs a tenth of its arithmetic (issue 50); any other releases
/// it while it works, so that Python threads (dask's threaded scheduler
/// among them) run their calls at once, also with `threads=1`.
pub fn run_detached<R: Send>(
    py: pyo3::Python<'_>,
    threads: Option<usize>,
    work_ns: f64,
    f: impl FnOnce() -> R + Send,
) -> PyResult<R> {
    if work_ns <= SMALL_NS && runs_inline(threads, work_ns) {
        Ok(inline(f))
    } else {
        py.detach(|| run_with(threads, work_ns, f))
    }
}

/// Whether [`run_with`] runs on the calling thread.
fn runs_inline(threads: Option<usize>, work_ns: f64) -> bool {
    matches!(threads, Some(1)) || (threads.is_none() && work_ns <= SMALL_NS)
}

/// Workers of one pool on different CPUs. Why: a call from Python wakes
/// one worker, which wakes the next; when the cores were busy just before
/// the call (Python itself computing, e.g. scipy between two of our calls)
/// Linux places the woken worker on its waker's CPU and takes about 12 ms
/// to move it (sched_switch/sched_wakeup traces on 2 cores: both workers
/// taking turns on CPU 0 while CPU 1 idles, two threads no faster than
/// one; `python/bench/handoff.py` shows it as CPU time equal to wall time). Worker `i` of `n`
/// may run on the allowed CPUs `i, i + n, i + 2n, …` (the `i`-th of every
/// `n` in the process's affinity mask): no two workers of a pool share a
/// CPU, and each keeps as many CPUs to move between as `n` allows. Linux
/// only, and only for 2 or more workers and no more than the allowed CPUs.
mod spread {
    /// Bits of the affinity mask kept (CPUs 0 to 1023).
    const WORDS: usize = 16;

    #[derive(Clone)]
    pub(super) struct Spread {
        cpus: Vec<usize>,
        n: usize,
    }

    impl Spread {
        pub(super) fn new(n: usize) -> Option<Self> {
            let cpus = allowed()?;
            (n >= 2 && n <= cpus.len()).then_some(Spread { cpus, n })
        }

        /// Restricts the calling worker `i` to its share of the CPUs.
        pub(super) fn apply(&self, i: usize) {
            let mine: Vec<usize> = self
                .cpus
                .iter()
                .skip(i % self.n)
                .step_by(self.n)
                .copied()
                .collect();
            restrict(&mine);
        }
    }

    #[cfg(target_os = "linux")]
    fn allowed() -> Option<Vec<usize>> {
        let mut mask = [0u64; WORDS];
        // SAFETY: the kernel writes at most `size_of_val(&mask)` bytes into
        // `mask`, which is that long.
        #[allow(unsafe_code)]
        let rc = unsafe {
            libc::sched_getaffinity(0, std::mem::size_of_val(&mask), mask.as_mut_ptr().cast())
        };
        (rc == 0).then(|| {
            (0..WORDS * 64)
                .filter(|&c| mask.get(c / 64).is_some_and(|w| w >> (c % 64) & 1 == 1))
                .collect()
        })
    }

    #[cfg(target_os = "linux")]
    fn restrict(cpus: &[usize]) {
        let mut mask = [0u64; WORDS];
        // CPUs beyond the mask's 1024 are left out (a hint, not a promise).
        for &c in cpus {
            if let Some(w) = mask.get_mut(c / 64) {
                *w |= 1 << (c % 64);
            }
        }
        // SAFETY: the kernel reads `size_of_val(&mask)` bytes from `mask`;
        // a refusal leaves the thread's affinity as it was (a hint).
        #[allow(unsafe_code)]
        unsafe {
            libc::sched_setaffinity(0, std::mem::size_of_val(&mask), mask.as_ptr().cast());
        }
    }

    #[cfg(not(target_os = "linux"))]
    fn allowed() -> Option<Vec<usize>> {
        None
    }

    #[cfg(not(target_os = "linux"))]
    fn restrict(_: &[usize]) {}
}
