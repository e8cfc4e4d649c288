//! `check` reports everything `derive` would: the file's own diagnostics
//! and what the derivation finds (E0301, E0302, which `check` says as the
//! warnings W0301, W0302: the file is valid), once each and in the same
//! order, in text and JSON, while staying quick on huge models.

use crate::common;
use common::{graftal, temp};

/// Writes `text` to a temporary `.l` file; its path.
fn file(name: &str, text: &str) -> String {
    let path = temp(name);
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

/// The codes of the JSON diagnostics on `stderr`, in order.
fn codes(stderr: &str) -> Vec<String> {
    stderr
        .lines()
        .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
        .filter_map(|d| d["code"].as_str().map(String::from))
        .collect()
}

/// The codes `derive` reports, as `check` says them: the derivation's
/// errors as warnings with codes of their own.
fn as_check(codes: Vec<String>) -> Vec<String> {
    (codes.into_iter())
        .map(|c| match c.as_str() {
            "E0301" => "W0301".to_string(),
            "E0302" => "W0302".to_string(),
            _ => c,
        })
        .collect()
}

/// The codes `check` and `derive` (with `derive_args`) report for `f`.
fn both(f: &str, derive_args: &[&str]) -> (Vec<String>, Vec<String>) {
    let check = graftal(&["check", f, "--format", "json"]);
    let mut argv = vec!["derive", f, "--format", "json", "-o", "-"];
    argv.extend_from_slice(derive_args);
    let derive = graftal(&argv);
    (codes(&check.stderr), codes(&derive.stderr))
}

#[test]
fn check_reports_the_codes_derive_reports() {
    // `--max-symbols` is check's own limit where derive would otherwise
    // derive for minutes before saying the same.
    let cap = graftal::driver::CHECK_MAX_SYMBOLS.to_string();
    let cases: [(&str, &str, &[&str], &[&str]); 5] = [
        // Headers out of the listing's order (W0001, one each) and one
        // given twice (W0002).
        (
            "headers.l",
            "axiom: F\nderivation length: 1\nangle factor: 4\nangle factor: 6\nF --> FF\n",
            &[],
            &["W0001", "W0001", "W0002", "W0001"],
        ),
        // A shadowed production (W0006).
        (
            "shadowed.l",
            "derivation length: 1\nangle factor: 4\naxiom: F\nF --> FF\nF --> F+F\n",
            &[],
            &["W0006"],
        ),
        // Too many symbols, counted on the shared tree at derive's limit.
        (
            "doubling.l",
            "derivation length: 40\nangle factor: 4\naxiom: F\nF --> FF\n",
            &[],
            &["E0301"],
        ),
        // Too many symbols, context-sensitive: derived, with a header
        // warning first.
        (
            "context.l",
            "axiom: ab\nderivation length: 100000000\nangle factor: 4\nb < a --> b\na --> ba\nb --> a\n",
            &["--max-symbols", &cap],
            &["W0001", "W0001", "E0301"],
        ),
        // A stochastic cycle that never ends: too much work.
        (
            "cycle.l",
            "derivation length: 1000000000000\nangle factor: 4\naxiom: a\na --> b : 1\na --> b : 1\nb --> a\n",
            &["--max-symbols", &cap],
            &["E0302"],
        ),
    ];
    for (name, text, args, expected) in cases {
        let f = file(name, text);
        let (check, derive) = both(&f, args);
        assert_eq!(derive, expected, "{name}");
        assert_eq!(check, as_check(derive), "{name}");
        assert!(
            check.iter().all(|c| !c.starts_with('E')),
            "{name}: {check:?}"
        );
    }
}

#[test]
fn check_says_where_derive_stops_as_a_warning_in_text() {
    let f = file(
        "doubling-text.l",
        "derivation length: 40\nangle factor: 4\naxiom: F\nF --> FF\n",
    );
    let o = graftal(&["check", &f]);
    // The file is valid: the limit is derive's, so check warns.
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert_eq!(
        o.stderr.matches("[W0301] Warning").count(),
        1,
        "{}",
        o.stderr
    );
    assert!(!o.stderr.contains("E0301"), "{}", o.stderr);
    assert!(
        o.stderr.contains("`graftal derive` stops here"),
        "{}",
        o.stderr
    );
    // Without the derivation check is silent about it.
    let o = graftal(&["check", &f, "--format", "json"]);
    assert!(o.stderr.contains(r#""severity":"warning""#), "{}", o.stderr);
}

#[test]
fn check_of_a_huge_model_stays_quick() {
    // Context-sensitive, so derived, not counted: check stops at its own
    // limit, where derive would go on to 200 million symbols.
    let f = file(
        "huge.l",
        "derivation length: 100000000\nangle factor: 4\naxiom: ab\nb < a --> b\na --> ba\nb --> a\n",
    );
    let t = std::time::Instant::now();
    let o = graftal(&["check", &f]);
    common::assert_within(t.elapsed(), std::time::Duration::from_secs(10), "check");
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert!(o.stderr.contains("`check` derives up to"), "{}", o.stderr);
}

#[test]
fn check_of_a_library_derives_each_entry_and_names_it() {
    // Two Fractint entries at Fractint's order 2: the second makes
    // 15,000² symbols, past derive's limit.
    let f = temp("lib.l");
    let huge = "F".repeat(15_000);
    std::fs::write(
        &f,
        format!("Quick {{\n  Angle 4\n  Axiom F\n  F=F+F\n}}\nHuge {{\n  Angle 4\n  Axiom F\n  F={huge}\n}}\n"),
    )
    .unwrap();
    let f = f.to_str().unwrap();
    let t = std::time::Instant::now();
    let o = graftal(&["check", f]);
    common::assert_within(t.elapsed(), std::time::Duration::from_secs(10), "check");
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert_eq!(o.stderr.matches("W0301").count(), 1, "{}", o.stderr);
    assert!(o.stderr.contains("entry `Huge`"), "{}", o.stderr);
    assert!(!o.stderr.contains("Quick"), "{}", o.stderr);
    // Chosen, the entry is what derive reads: the same code.
    let (check, derive) = both(&format!("{f}:Huge"), &[]);
    assert_eq!(check, as_check(derive));
    // The long line is one Fractint itself would not read (W0704).
    assert_eq!(check, ["W0704", "W0301"]);
}
