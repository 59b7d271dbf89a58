//! Independent work items on a few threads, the results in the items' order: problems
//! are planned independently, and their costs differ by orders of magnitude, so each
//! thread takes the next item not yet taken rather than a fixed share.

use std::sync::atomic::{AtomicUsize, Ordering};

/// `f` of every item, computed on at most `threads` threads (at least one), in the items'
/// order. A panic in `f` is resumed on the calling thread.
pub(crate) fn map_in_order<T: Sync, R: Send>(
    items: &[T],
    threads: usize,
    f: impl Fn(&T) -> R + Sync,
) -> Vec<R> {
    let threads = threads.clamp(1, items.len().max(1));
    if threads == 1 {
        return items.iter().map(f).collect();
    }
    let next = AtomicUsize::new(0);
    let mut results: Vec<(usize, R)> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(|| {
                    std::iter::from_fn(|| {
                        let i = next.fetch_add(1, Ordering::Relaxed);
                        items.get(i).map(|item| (i, f(item)))
                    })
                    .collect::<Vec<_>>()
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|w| w.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    });
    results.sort_by_key(|(i, _)| *i);
    results.into_iter().map(|(_, r)| r).collect()
}

#[cfg(test)]
mod tests {
    use super::map_in_order;

    #[test]
    fn results_keep_the_items_order_on_any_number_of_threads() {
        let items: Vec<u64> = (0..50).collect();
        // Uneven costs, so that the threads finish out of order.
        let slow_square = |&x: &u64| {
            std::thread::sleep(std::time::Duration::from_micros((50 - x) * 20));
            x * x
        };
        let expected: Vec<u64> = items.iter().map(|x| x * x).collect();
        for threads in [0, 1, 2, 3, 64] {
            assert_eq!(map_in_order(&items, threads, slow_square), expected);
        }
        assert!(map_in_order(&[] as &[u64], 4, slow_square).is_empty());
    }
}
