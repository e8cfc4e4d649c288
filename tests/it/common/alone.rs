//! Tests that must not run beside others, and the gate of the slow suites.
//!
//! All integration tests share one binary and `cargo test` runs them on
//! parallel threads. A test that measures the peak heap counts every
//! thread's allocations (the counting allocator is the binary's), so it
//! runs again in a child process of this binary where it is the only test
//! ([`alone`]). A test that bounds wall-clock time, or keeps every core
//! busy (the fuzzer), holds [`timed`], so that no two such tests run at once.

use std::process::Command;
use std::sync::{Mutex, MutexGuard};
use std::time::Duration;

/// Names the test a child process was started to run alone.
const ALONE: &str = "GRAFTAL_TEST_ALONE";

/// Makes the calling test the only test of its process:
/// `let Some(_alone) = alone() else { return };`.
///
/// In the process `cargo test` started, runs this binary again with only
/// the calling test (named by its thread, as the test harness names it),
/// on one thread (holding [`timed`] meanwhile); fails with the child's
/// output unless it ran that one test and passed, and returns `None`: the
/// test is done. In the child, starts counting allocations
/// (`alloc::CountingWhenStarted`) and returns a guard: the test goes on.
pub fn alone() -> Option<MutexGuard<'static, ()>> {
    static ONE: Mutex<()> = Mutex::new(());
    let thread = std::thread::current();
    let name = thread
        .name()
        .expect("a test runs on a thread named after it");
    if std::env::var(ALONE).as_deref() == Ok(name) {
        crate::alloc::start_counting();
        return Some(ONE.lock().unwrap_or_else(|e| e.into_inner()));
    }
    let _timed = timed();
    let exe = std::env::current_exe().expect("this test binary");
    let out = Command::new(exe)
        .args([name, "--exact", "--test-threads=1", "--nocapture"])
        .env(ALONE, name)
        .output()
        .expect("this test binary runs again");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success() && stdout.contains("test result: ok. 1 passed"),
        "{name}, run alone, failed ({}):\n{stdout}\n{stderr}",
        out.status
    );
    eprint!("{stderr}");
    None
}

/// Held by each test that bounds wall-clock time or loads every core:
/// such tests run one at a time, beside ordinary tests only. (Held also
/// after another test failed while holding it.)
pub fn timed() -> MutexGuard<'static, ()> {
    static TIMED: Mutex<()> = Mutex::new(());
    TIMED.lock().unwrap_or_else(|e| e.into_inner())
}

/// The variable that makes `cargo test` run the slow suites.
const SLOW: &str = "GRAFTAL_SLOW";

/// Whether the slow suites run (`GRAFTAL_SLOW=1`). When they do not, says
/// on stderr that `what` was skipped and how to run it; a slow test starts
/// with `if !slow("what it checks") { return; }`.
pub fn slow(what: &str) -> bool {
    let on = std::env::var(SLOW).as_deref() == Ok("1");
    if !on {
        eprintln!("skipped (slow): {what}; {SLOW}=1 runs it");
    }
    on
}

/// A slow test that bounds wall-clock time or loads every core: [`slow`],
/// then holding [`timed`];
/// `let Some(_timed) = slow_timed("what it checks") else { return };`.
pub fn slow_timed(what: &str) -> Option<MutexGuard<'static, ()>> {
    slow(what).then(timed)
}

/// Asserts that `took` is under `bound` when the slow suites run: a
/// wall-clock bound belongs to them, since a loaded machine (or tests
/// beside it) can break it. Without `GRAFTAL_SLOW=1` says it was skipped.
#[track_caller]
pub fn assert_within(took: Duration, bound: Duration, what: &str) {
    if slow(&format!("the {bound:?} bound of {what}")) {
        assert!(took < bound, "{what}: {took:?}, over {bound:?}");
    }
}
