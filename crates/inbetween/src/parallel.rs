//! Independent work shared out among the machine's cores.

use std::sync::atomic::{AtomicUsize, Ordering};

/// Most threads that independent work (tracks) is shared out among.
pub(crate) const MAX_THREADS: usize = 8;

std::thread_local! {
    /// Set by [`serially`]: this thread's [`map`]s run on it alone.
    static SERIAL: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Runs `f` with every [`map`] it makes on the calling thread alone: for a caller that already
/// shares its own work out among the cores (a batch of files, one per thread), so that the
/// threads do not multiply. The results are the same either way.
pub fn serially<R>(f: impl FnOnce() -> R) -> R {
    let before = SERIAL.with(|s| s.replace(true));
    let r = f();
    SERIAL.with(|s| s.set(before));
    r
}

/// `f` of every item, in the items' order: the items are taken in order as threads come free
/// (one per core, at most `MAX_THREADS`, never more than the items), so the result is the
/// same whatever the number of threads. One core, or one item, runs on the calling thread.
pub fn map<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    if SERIAL.with(std::cell::Cell::get) {
        return items.iter().map(f).collect();
    }
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(MAX_THREADS)
        .min(items.len());
    if threads <= 1 {
        return items.iter().map(f).collect();
    }
    let next = AtomicUsize::new(0);
    let mut done: Vec<(usize, R)> = std::thread::scope(|s| {
        let workers: Vec<_> = (0..threads)
            .map(|_| {
                s.spawn(|| {
                    let mut own = Vec::new();
                    // Each index is claimed by exactly one thread.
                    loop {
                        let i = next.fetch_add(1, Ordering::Relaxed);
                        let Some(item) = items.get(i) else {
                            break;
                        };
                        own.push((i, f(item)));
                    }
                    own
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|w| w.join().unwrap_or_else(|p| std::panic::resume_unwind(p)))
            .collect()
    });
    done.sort_unstable_by_key(|(i, _)| *i);
    done.into_iter().map(|(_, r)| r).collect()
}

#[cfg(test)]
mod tests {
    #[test]
    fn results_come_in_the_items_order() {
        let items: Vec<usize> = (0..10_000).collect();
        let got = super::map(&items, |&i| {
            // Uneven work, so that threads finish out of order.
            (0..i % 97).fold(i, |a, b| a.wrapping_mul(31).wrapping_add(b)) ^ i
        });
        let want: Vec<usize> = items
            .iter()
            .map(|&i| (0..i % 97).fold(i, |a, b| a.wrapping_mul(31).wrapping_add(b)) ^ i)
            .collect();
        assert_eq!(got, want);
        assert!(super::map(&[] as &[usize], |&i| i).is_empty());
    }
}
