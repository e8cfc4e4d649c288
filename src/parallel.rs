//! Threads: how many graftal's work uses (`--threads`, `GRAFTAL_THREADS`,
//! every core by default) and the one way independent pieces of work are
//! shared among them, so that what comes out never depends on how many
//! there are.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{mpsc, Arc, Condvar, Mutex};

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

/// `work` on each of `items`, the first on the calling thread and each
/// other on a thread of its own; the results in order. For a few items of
/// about equal work (one a thread), where [`map_in_order`]'s sharing out
/// would cost more than it evens.
pub fn on_own_threads<I, R>(items: I, work: impl Fn(I::Item) -> R + Sync) -> Vec<R>
where
    I: Iterator,
    I::Item: Send,
    R: Send,
{
    std::thread::scope(|scope| {
        let mut items = items;
        let first = items.next();
        let others: Vec<_> = items
            .map(|item| {
                let work = &work;
                scope.spawn(move || work(item))
            })
            .collect();
        let first = first.map(&work);
        let others = others
            .into_iter()
            .map(|h| h.join().expect("a thread panicked"));
        first.into_iter().chain(others).collect()
    })
}

/// Items `0..n`, each made once by `make`, fed to every one of `eaters` in
/// item order: eater `k` eats on a thread of its own (the first on the
/// calling thread), and a thread whose next item is not made yet makes the
/// next item nobody has taken. So making and eating overlap, with no
/// thread waiting for a round of others. At most `ahead` items are made
/// past the slowest eater's (those are all that is held at once). After
/// the first eater eats an item, `eaten(i, item)` is called on the calling
/// thread (for a progress bar).
pub fn feed_in_order<T: Send + Sync, E: Send>(
    n: usize,
    ahead: usize,
    eaters: &mut [E],
    make: impl Fn(usize) -> T + Sync,
    eat: impl Fn(&mut E, &T) + Sync,
    mut eaten: impl FnMut(usize, &T),
) {
    let feed = Feed {
        items: (0..n).map(|_| Mutex::new(None)).collect(),
        left: (0..n).map(|_| AtomicUsize::new(eaters.len())).collect(),
        next: AtomicUsize::new(0),
        eaten: (0..eaters.len()).map(|_| AtomicUsize::new(0)).collect(),
        ahead: ahead.max(1),
        changed: (Mutex::new(0), Condvar::new()),
        panicked: AtomicBool::new(false),
    };
    let run = |k: usize, eater: &mut E, eaten: &mut dyn FnMut(usize, &T)| {
        feed.run(k, |item| eat(eater, item), &make, eaten)
    };
    std::thread::scope(|scope| {
        let mut eaters = eaters.iter_mut().enumerate();
        let first = eaters.next();
        for (k, eater) in eaters {
            let run = &run;
            scope.spawn(move || run(k, eater, &mut |_, _| {}));
        }
        if let Some((k, eater)) = first {
            run(k, eater, &mut eaten);
        }
    });
}

/// What the threads of [`feed_in_order`] share.
struct Feed<T> {
    /// Each item, from when it is made until every eater has eaten it.
    items: Vec<Mutex<Option<Arc<T>>>>,
    /// Per item, the eaters yet to eat it.
    left: Vec<AtomicUsize>,
    /// The next item nobody has taken to make.
    next: AtomicUsize,
    /// Per eater, the items it has eaten.
    eaten: Vec<AtomicUsize>,
    ahead: usize,
    /// A count of the items made and eaten, and its signal, so that a
    /// waiting thread wakes when either may let it go on.
    changed: (Mutex<u64>, Condvar),
    /// A thread panicked: the others stop waiting for what it would have
    /// done, and panic too.
    panicked: AtomicBool,
}

/// Tells the other threads of a [`Feed`] when this one panics.
struct Alarm<'f, T>(&'f Feed<T>);

impl<T> Drop for Alarm<'_, T> {
    fn drop(&mut self) {
        if std::thread::panicking() {
            self.0.panicked.store(true, Ordering::Release);
            self.0.signal();
        }
    }
}

impl<T> Feed<T> {
    /// Eater `k`'s thread: each item in order, eaten when it is made, and
    /// items made while it waits for its next one.
    fn run(
        &self,
        k: usize,
        mut eat: impl FnMut(&T),
        make: &impl Fn(usize) -> T,
        eaten: &mut dyn FnMut(usize, &T),
    ) {
        let _alarm = Alarm(self);
        let n = self.items.len();
        for i in 0..n {
            loop {
                assert!(
                    !self.panicked.load(Ordering::Acquire),
                    "another thread of the feed panicked"
                );
                let seen = *self.changed.0.lock().unwrap_or_else(|e| e.into_inner());
                let item = self.items[i]
                    .lock()
                    .unwrap_or_else(|e| e.into_inner())
                    .clone();
                if let Some(item) = item {
                    eat(&item);
                    eaten(i, &item);
                    if self.left[i].fetch_sub(1, Ordering::AcqRel) == 1 {
                        self.items[i]
                            .lock()
                            .unwrap_or_else(|e| e.into_inner())
                            .take();
                    }
                    self.eaten[k].store(i + 1, Ordering::Release);
                    self.signal();
                    break;
                }
                if !self.make_next(make) {
                    self.wait(seen);
                }
            }
        }
    }

    /// Makes the next item nobody has taken, unless it would be more than
    /// `ahead` past the slowest eater; whether it made one.
    fn make_next(&self, make: &impl Fn(usize) -> T) -> bool {
        let slowest = self.eaten.iter().map(|e| e.load(Ordering::Acquire)).min();
        let limit = slowest.unwrap_or(0).saturating_add(self.ahead);
        let i = self.next.load(Ordering::Acquire);
        if i >= self.items.len().min(limit) {
            return false;
        }
        if self
            .next
            .compare_exchange(i, i + 1, Ordering::AcqRel, Ordering::Acquire)
            .is_err()
        {
            return true;
        }
        let item = Arc::new(make(i));
        *self.items[i].lock().unwrap_or_else(|e| e.into_inner()) = Some(item);
        self.signal();
        true
    }

    fn signal(&self) {
        *self.changed.0.lock().unwrap_or_else(|e| e.into_inner()) += 1;
        self.changed.1.notify_all();
    }

    /// Waits until the count of changes is past `seen`.
    fn wait(&self, seen: u64) {
        let mut count = self.changed.0.lock().unwrap_or_else(|e| e.into_inner());
        while *count == seen {
            count = self
                .changed
                .1
                .wait(count)
                .unwrap_or_else(|e| e.into_inner());
        }
    }
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

    #[test]
    fn every_eater_eats_every_item_once_in_order() {
        for (eaters, ahead) in [(1, 1), (2, 1), (2, 4), (3, 2), (7, 14)] {
            let made: Vec<AtomicUsize> = (0..60).map(|_| AtomicUsize::new(0)).collect();
            let mut plates: Vec<(usize, Vec<usize>)> =
                (0..eaters).map(|k| (k, Vec::new())).collect();
            let mut told = Vec::new();
            feed_in_order(
                60,
                ahead,
                &mut plates,
                |i| {
                    made[i].fetch_add(1, Ordering::Relaxed);
                    // Uneven items, so that they are made out of order.
                    std::thread::sleep(std::time::Duration::from_micros((i as u64 * 37) % 200));
                    i * 3
                },
                |(k, plate), &item| {
                    // Uneven eaters, so that some run ahead.
                    std::thread::sleep(std::time::Duration::from_micros(*k as u64 * 30));
                    plate.push(item);
                },
                |i, &item| told.push((i, item)),
            );
            let want: Vec<usize> = (0..60).map(|i| i * 3).collect();
            for (k, plate) in &plates {
                assert_eq!(plate, &want, "eater {k} of {eaters}");
            }
            assert!(made.iter().all(|m| m.load(Ordering::Relaxed) == 1));
            assert_eq!(
                told,
                want.iter()
                    .enumerate()
                    .map(|(i, &x)| (i, x))
                    .collect::<Vec<_>>()
            );
        }
    }

    #[test]
    fn a_panic_in_one_thread_ends_the_feed_not_hangs_it() {
        let mut plates = vec![0usize; 3];
        let fed = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            feed_in_order(
                50,
                2,
                &mut plates,
                |i| {
                    assert!(i != 20, "item 20 cannot be made");
                    i
                },
                |plate, &i| *plate += i,
                |_, _| {},
            )
        }));
        assert!(fed.is_err());
    }
}
