//! A pool of work buffers shared by the tasks of one pass (the prefilter
//! of an array, the blocks of one long line).

use std::sync::Mutex;

/// Work buffers shared by the tasks of one pass, each task taking one
/// and putting it back: a fresh multi-megabyte `Vec` per task is a fresh
/// mapping whose pages the kernel zeroes (perf: `clear_page` was 38% of
/// spline_filter 4096² on one thread).
pub(crate) struct Stash<B>(Mutex<Vec<B>>);

impl<B> Default for Stash<B> {
    fn default() -> Self {
        Stash(Mutex::new(Vec::new()))
    }
}

impl<B: Default> Stash<B> {
    /// `f` on a buffer (new, or left by an earlier task).
    pub(crate) fn with<R>(&self, f: impl FnOnce(&mut B) -> R) -> R {
        let lock = || self.0.lock().unwrap_or_else(|p| p.into_inner());
        let mut buf = lock().pop().unwrap_or_default();
        let r = f(&mut buf);
        lock().push(buf);
        r
    }
}
