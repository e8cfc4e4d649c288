//! `graftal fmt` (issue 19 item 5): the canonical layout is the one the
//! `.gft` emitter writes, formatting is idempotent, comments are kept in
//! place, `--check` says which files would change, and a file with errors
//! is left as it is.

use graftal::back::{self, Request};
use graftal::diagnostics::Diagnostics;
use graftal::driver;
use graftal::format::{format, Outcome};
use graftal::source::SourceFile;
use graftal::stdlib::ENTRIES;
use std::path::Path;

use crate::common;
use common::{check_golden, graftal, temp};

/// `graftal fmt` of `text`: the formatted text, or why there is none.
fn fmt(text: &str) -> Result<String, String> {
    match format(SourceFile::new("t.gft", text)).outcome {
        Outcome::Formatted(t) => Ok(t),
        Outcome::HasErrors => Err("has errors".into()),
        Outcome::NotSame(why) => Err(why),
    }
}

/// What `translate --to gft` makes of a stdlib entry, and whether the
/// reader reads it back as the same system today.
fn translated(text: &str, file: &str) -> (String, bool) {
    let c = driver::compile(SourceFile::new(file, text));
    let sys = c.system.as_ref().expect("every stdlib entry compiles");
    let req = Request {
        target: back::by_name("gft").expect("gft is registered"),
        lossy: false,
        steps: None,
    };
    let gft = driver::translate(&c, sys, &req)
        .text
        .expect("gft never refuses");
    let mut diags = Diagnostics::default();
    let again = graftal::front::gft::read(&gft, &mut diags);
    let read = !diags.has_errors() && again.system.same_as(sys).is_ok();
    (gft, read)
}

/// Every `.gft` of a stdlib entry that the reader reads back as the same
/// system is already in the canonical layout: fmt leaves it as it is.
#[test]
fn the_emitters_layout_is_canonical_for_every_stdlib_entry() {
    let mut formatted = 0;
    for e in ENTRIES {
        let (gft, read) = translated(e.text, e.file);
        if read {
            assert_eq!(fmt(&gft).as_ref(), Ok(&gft), "{}", e.name);
            formatted += 1;
        } else {
            // Refused or formatted, never a panic.
            let _ = fmt(&gft);
        }
    }
    eprintln!("fmt: {formatted} of {} stdlib entries", ENTRIES.len());
    assert!(formatted * 2 > ENTRIES.len(), "{formatted}");
}

/// Formatting twice changes nothing, also for files out of layout.
#[test]
fn fmt_is_idempotent() {
    let mut formatted = 0;
    for e in ENTRIES {
        let (gft, _) = translated(e.text, e.file);
        // Out of layout: blank lines, extra spaces, a comment per line.
        let messy: String = gft
            .lines()
            .map(|l| format!("\n  {}   /* {} */\n", l.replace(" -> ", "->"), e.name))
            .collect();
        if let Ok(once) = fmt(&messy) {
            assert_eq!(fmt(&once).as_ref(), Ok(&once), "{}", e.name);
            assert_eq!(once.matches("/*").count(), gft.lines().count());
            formatted += 1;
        }
    }
    eprintln!("fmt twice: {formatted} of {} stdlib entries", ENTRIES.len());
    assert!(formatted * 2 > ENTRIES.len(), "{formatted}");
}

#[test]
fn comments_are_kept_in_place() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fmt");
    let src = std::fs::read_to_string(dir.join("commented.gft")).unwrap();
    let out = fmt(&src).unwrap();
    for c in src.match_indices("/*").map(|(at, _)| &src[at..]) {
        let c = &c[..c.find("*/").unwrap() + 2];
        assert!(out.contains(c), "`{c}` lost:\n{out}");
    }
    assert_eq!(fmt(&out), Ok(out.clone()));
    check_golden(&dir.join("commented.formatted.gft"), &out).unwrap();
}

#[test]
fn check_says_which_file_would_change() {
    let messy = temp("messy.gft");
    std::fs::write(&messy, "axiom   F\nF->FF /* doubles */\n").unwrap();
    let path = messy.to_str().unwrap();
    let o = graftal(&["fmt", "--check", path]);
    assert_eq!(o.status, 1, "{}", o.stderr);
    assert!(o.stdout.contains(path), "{}", o.stdout);
    assert_eq!(
        std::fs::read_to_string(&messy).unwrap(),
        "axiom   F\nF->FF /* doubles */\n",
        "--check writes nothing"
    );
    let o = graftal(&["fmt", path]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let tidy = std::fs::read_to_string(&messy).unwrap();
    assert!(tidy.contains("axiom F\nF -> FF /* doubles */\n"), "{tidy}");
    let o = graftal(&["fmt", "--check", path]);
    assert_eq!((o.status, o.stdout.as_str()), (0, ""));
}

#[test]
fn a_file_with_errors_is_not_formatted() {
    let bad = temp("bad.gft");
    let text = "stepz   3\naxiom F\n";
    std::fs::write(&bad, text).unwrap();
    for args in [vec!["fmt"], vec!["fmt", "--check"]] {
        let mut args = args;
        args.push(bad.to_str().unwrap());
        let o = graftal(&args);
        assert_eq!(o.status, 1);
        assert!(o.stderr.contains("E0900"), "{}", o.stderr);
        assert_eq!(std::fs::read_to_string(&bad).unwrap(), text);
    }
    assert_eq!(graftal(&["fmt", "/no/such/file.gft"]).status, 2);
}

#[test]
fn a_dash_reads_standard_input_and_writes_standard_output() {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_graftal"))
        .args(["fmt", "-"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(b"/* hi */\naxiom   F\n")
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("/* hi */\n"), "{text}");
    assert!(text.contains("\naxiom F\n"), "{text}");
}

/// pfg's arrow and parameters never closed were read as something else
/// (`F- -> …`, `X -> Y`), and `fmt` wrote that meaning down: both are
/// errors now, and `fmt` leaves such files as they are; a production for
/// `-`, written with a space, is still one.
#[test]
fn fmt_never_rewrites_pfgs_arrow_or_an_unclosed_module() {
    for (text, code) in [
        ("axiom F\nF --> F[+F]F[-F]F\n", "E0908"),
        ("axiom X\nX -> Y(\n", "E0909"),
    ] {
        assert_eq!(fmt(text), Err("has errors".to_string()), "{text}");
        let file = temp("bad.gft");
        std::fs::write(&file, text).unwrap();
        let o = graftal(&["fmt", file.to_str().unwrap()]);
        assert_eq!(o.status, 1, "{text}");
        assert!(o.stderr.contains(code), "{}", o.stderr);
        assert_eq!(std::fs::read_to_string(&file).unwrap(), text);
    }
    let dash = fmt("axiom F-\n- -> F\n").unwrap();
    assert!(dash.contains("- -> F"), "{dash}");
}
