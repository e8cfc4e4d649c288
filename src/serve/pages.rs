//! One derivation per page at a time: each page (a browser tab, named by
//! the id it makes when it loads) numbers its requests; a request waits
//! while an earlier one of its page works, and is answered "superseded"
//! without any work when a newer one came meanwhile. Each page keeps the
//! model it last compiled, so that the frames of its growth are drawn
//! without reading the text again.

use crate::driver::Compiled;
use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};

/// The most pages remembered; the one idle longest is forgotten first.
const MAX_PAGES: usize = 64;

/// The pages that sent requests.
#[derive(Default)]
pub struct Pages {
    pages: Mutex<HashMap<String, Arc<Page>>>,
    /// Counts requests, to find the page idle longest.
    clock: AtomicU64,
}

/// A page: the newest request number it sent, and its work, one at a time.
#[derive(Default)]
pub struct Page {
    newest: AtomicU64,
    last_used: AtomicU64,
    work: Mutex<Kept>,
}

/// What a page keeps between requests: the text it last compiled, with
/// its notation, and the result.
#[derive(Default)]
pub struct Kept {
    pub compiled: Option<(String, &'static str, Arc<Compiled>)>,
}

/// A request's turn at its page's work, or why it has none.
pub enum Turn<'p> {
    Go(MutexGuard<'p, Kept>),
    Superseded,
}

impl Pages {
    /// The page named `id`, made when new.
    pub fn page(&self, id: &str) -> Arc<Page> {
        let now = self.clock.fetch_add(1, Ordering::Relaxed);
        let mut pages = self.pages.lock().unwrap_or_else(|e| e.into_inner());
        if !pages.contains_key(id) && pages.len() >= MAX_PAGES {
            let idle = (pages.iter())
                .min_by_key(|(_, p)| p.last_used.load(Ordering::Relaxed))
                .map(|(k, _)| k.clone());
            if let Some(k) = idle {
                pages.remove(&k);
            }
        }
        let page = pages.entry(id.to_string()).or_default().clone();
        page.last_used.store(now, Ordering::Relaxed);
        page
    }
}

impl Page {
    /// Waits for the page's earlier work to end; request `seq` then works
    /// unless a newer request of the page arrived meanwhile.
    pub fn turn(&self, seq: u64) -> Turn<'_> {
        self.newest.fetch_max(seq, Ordering::SeqCst);
        let kept = self.work.lock().unwrap_or_else(|e| e.into_inner());
        if seq < self.newest.load(Ordering::SeqCst) {
            return Turn::Superseded;
        }
        Turn::Go(kept)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_older_request_waiting_behind_a_newer_one_is_superseded() {
        let pages = Pages::default();
        let page = pages.page("a");
        let first = page.turn(1);
        assert!(matches!(first, Turn::Go(_)));
        // While request 1 works, 2 and 3 arrive; 3 is the newest.
        page.newest.fetch_max(3, Ordering::SeqCst);
        drop(first);
        assert!(matches!(page.turn(2), Turn::Superseded));
        assert!(matches!(page.turn(3), Turn::Go(_)));
        // Another page is not held up.
        assert!(matches!(pages.page("b").turn(1), Turn::Go(_)));
    }

    #[test]
    fn pages_are_forgotten_past_the_limit() {
        let pages = Pages::default();
        for i in 0..MAX_PAGES + 10 {
            pages.page(&i.to_string());
        }
        assert_eq!(pages.pages.lock().unwrap().len(), MAX_PAGES);
        // The newest are kept.
        assert!(pages.pages.lock().unwrap().contains_key("73"));
    }
}
