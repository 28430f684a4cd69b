//! Time and peak anonymous memory of one call: the process's `RssAnon`
//! (Linux `/proc/self/status`) sampled every millisecond by a thread while
//! the call runs, minus its value before. Anonymous memory is what a call
//! allocates; the pages of a memory-mapped file it reads are file-backed
//! and not counted (the page cache holds them, shared and reclaimable).
//! Elsewhere than Linux the bytes are 0.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Instant;

/// The process's anonymous resident bytes now (0 where unknown).
pub fn rss_anon() -> usize {
    let Ok(status) = std::fs::read_to_string("/proc/self/status") else {
        return 0;
    };
    status
        .lines()
        .find_map(|l| l.strip_prefix("RssAnon:"))
        .and_then(|v| v.split_whitespace().next()?.parse::<usize>().ok())
        .map_or(0, |kb| kb * 1024)
}

/// `(f(), seconds, peak anonymous bytes above the start)`.
pub fn measure<R>(f: impl FnOnce() -> R) -> (R, f64, usize) {
    let base = rss_anon();
    let peak = AtomicUsize::new(base);
    let done = AtomicBool::new(false);
    std::thread::scope(|s| {
        s.spawn(|| {
            while !done.load(Ordering::Relaxed) {
                peak.fetch_max(rss_anon(), Ordering::Relaxed);
                std::thread::sleep(std::time::Duration::from_millis(1));
            }
        });
        let start = Instant::now();
        let out = f();
        let secs = start.elapsed().as_secs_f64();
        done.store(true, Ordering::Relaxed);
        peak.fetch_max(rss_anon(), Ordering::Relaxed);
        (out, secs, peak.load(Ordering::Relaxed).saturating_sub(base))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_allocation_of_64_mib_is_seen() {
        let (v, _, bytes) = measure(|| {
            let v = vec![1u8; 64 << 20];
            std::thread::sleep(std::time::Duration::from_millis(20));
            v
        });
        assert_eq!(v.len(), 64 << 20);
        if cfg!(target_os = "linux") {
            assert!(((60 << 20)..(80 << 20)).contains(&bytes), "{bytes}");
        }
    }
}
