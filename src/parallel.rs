//! Threads: how many graftal's work uses (`--threads`, `GRAFTAL_THREADS`,
//! every core by default) and the one way independent pieces of work are
//! shared among them, so that what comes out never depends on how many
//! there are.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;

/// The threads to use: `asked`, or every core for 0.
pub fn threads(asked: usize) -> usize {
    if asked > 0 {
        asked
    } else {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    }
}

/// `work(0)`, …, `work(n - 1)` on up to `threads` threads (0: every core),
/// the results in index order. Each thread takes the next index not yet
/// taken, so uneven pieces still keep every thread busy; `done(finished)`
/// is called on the calling thread as each piece finishes (for a progress
/// bar), with the count finished so far.
pub fn map_in_order<T: Send>(
    n: usize,
    threads: usize,
    work: impl Fn(usize) -> T + Sync,
    mut done: impl FnMut(usize),
) -> Vec<T> {
    let threads = self::threads(threads).min(n);
    if threads <= 1 {
        return (0..n)
            .map(|i| {
                let t = work(i);
                done(i + 1);
                t
            })
            .collect();
    }
    let next = AtomicUsize::new(0);
    let mut slots: Vec<Option<T>> = (0..n).map(|_| None).collect();
    std::thread::scope(|scope| {
        let (send, receive) = mpsc::channel();
        for _ in 0..threads {
            let send = send.clone();
            let (next, work) = (&next, &work);
            scope.spawn(move || loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= n || send.send((i, work(i))).is_err() {
                    break;
                }
            });
        }
        drop(send);
        for (finished, (i, t)) in receive.into_iter().enumerate() {
            slots[i] = Some(t);
            done(finished + 1);
        }
    });
    slots
        .into_iter()
        .map(|t| t.expect("every index is worked"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn results_come_in_index_order_whatever_the_threads() {
        let one = map_in_order(100, 1, |i| i * i, |_| {});
        for threads in [2, 3, 7, 200] {
            let mut finished = Vec::new();
            let many = map_in_order(
                100,
                threads,
                |i| {
                    // Uneven pieces, so that they finish out of order.
                    std::thread::sleep(std::time::Duration::from_micros((100 - i as u64) * 20));
                    i * i
                },
                |k| finished.push(k),
            );
            assert_eq!(many, one, "{threads} threads");
            assert_eq!(finished, (1..=100).collect::<Vec<_>>());
        }
        assert!(map_in_order(0, 4, |i| i, |_| {}).is_empty());
    }

    #[test]
    fn zero_threads_is_every_core() {
        assert!(threads(0) >= 1);
        assert_eq!(threads(3), 3);
    }
}
