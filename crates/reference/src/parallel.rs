//! The project's one thread pool: [`parallel_map`] maps a fallible function over a slice on
//! scoped threads (std only), keeping the order. Used by the boundary-element tables
//! ([`crate::fit`]) and by the CLI's figures; the work items are long (whole solver runs), so
//! a shared counter hands them out one at a time.

use std::sync::atomic::{AtomicUsize, Ordering};

/// Maps `f` over `items` on up to `threads` scoped threads (at least 1, at most one per item)
/// and returns the results in the order of `items`, or the error of the first item (in that
/// order) that failed. Items are handed out in order, so put the longest first for load
/// balance. A panic in `f` propagates to the caller when the threads are joined.
pub fn parallel_map<T: Sync, R: Send, E: Send>(
    items: &[T],
    threads: usize,
    f: impl Fn(&T) -> Result<R, E> + Sync,
) -> Result<Vec<R>, E> {
    let threads = threads.clamp(1, items.len().max(1));
    let next = AtomicUsize::new(0);
    let mut done: Vec<(usize, Result<R, E>)> = std::thread::scope(|sc| {
        let workers: Vec<_> = (0..threads)
            .map(|_| {
                sc.spawn(|| {
                    let mut mine = Vec::new();
                    loop {
                        let i = next.fetch_add(1, Ordering::Relaxed);
                        let Some(item) = items.get(i) else { break };
                        mine.push((i, f(item)));
                    }
                    mine
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|w| match w.join() {
                Ok(v) => v,
                Err(panic) => std::panic::resume_unwind(panic),
            })
            .collect()
    });
    // Every index was handed out exactly once: sorting restores the order of `items`.
    done.sort_by_key(|(i, _)| *i);
    done.into_iter().map(|(_, r)| r).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_order_and_reports_the_first_error() {
        let items: Vec<u64> = (0..100).collect();
        for threads in [0, 1, 3, 200] {
            let out: Result<Vec<u64>, String> = parallel_map(&items, threads, |&x| Ok(x * x));
            assert_eq!(
                out.unwrap(),
                items.iter().map(|x| x * x).collect::<Vec<_>>()
            );
            let err = parallel_map(
                &items,
                threads,
                |&x| {
                    if x % 30 == 29 { Err(x) } else { Ok(x) }
                },
            );
            assert_eq!(err, Err(29));
        }
        let empty: Result<Vec<u8>, ()> = parallel_map(&[] as &[u8], 4, |&x| Ok(x));
        assert_eq!(empty, Ok(vec![]));
    }
}
