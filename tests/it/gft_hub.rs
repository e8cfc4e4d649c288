//! `.gft` is the hub of every translation (issue 19, item 3): for every
//! stdlib entry, every Fractint entry and every cpfg object of the corpus,
//! `translate X --to gft` and then `translate X.gft --to pfg|linf|stl`
//! gives what `translate X --to pfg|linf|stl` gives: the same file (its
//! comments aside: the IR keeps none, so `.gft` carries none and the banner
//! names the notation read), or a refusal with the same codes.

use graftal::back::{self, Request, Translation};
use graftal::driver::{self, Compiled};
use graftal::source::SourceFile;
use graftal::stdlib::ENTRIES;

use crate::common;
use common::{cpfg_object_dirs, fractint_corpus_entries, graftal, main_l, temp};

const TARGETS: [&str; 3] = ["pfg", "linf", "stl"];

fn translated(c: &Compiled, to: &str) -> Translation {
    let sys = c.system.as_ref().expect("compiles");
    let req = Request {
        target: back::by_name(to).expect("registered"),
        lossy: false,
        steps: None,
    };
    driver::translate(c, sys, &req)
}

/// A translation's text without its comments, or its error codes.
fn outcome(t: &Translation, to: &str) -> Result<String, Vec<&'static str>> {
    match &t.text {
        Some(text) if t.diagnostics.is_empty() => Ok(without_comments(text, to)),
        _ => {
            let mut codes: Vec<&str> = t.diagnostics.iter().map(|d| d.code.0).collect();
            codes.sort_unstable();
            codes.dedup();
            Err(codes)
        }
    }
}

/// `text` without the target's comments and the lines they leave blank.
fn without_comments(text: &str, to: &str) -> String {
    let mut kept = String::new();
    if to == "pfg" {
        let mut rest = text;
        while let Some(open) = rest.find("/*") {
            kept.push_str(&rest[..open]);
            rest = rest[open..]
                .find("*/")
                .map_or("", |close| &rest[open + close + 2..]);
        }
        kept.push_str(rest);
    } else {
        for line in text.lines() {
            let whole = line.trim_start() == "#" || line.trim_start().starts_with("# ");
            let code = match line.find(" # ") {
                _ if whole => "",
                Some(k) => &line[..k],
                None => line,
            };
            kept.push_str(code);
            kept.push('\n');
        }
    }
    let lines: Vec<&str> = kept
        .lines()
        .map(str::trim_end)
        .filter(|l| !l.trim().is_empty())
        .collect();
    lines.join("\n")
}

/// The differences between translating `c` directly and through `.gft`.
fn through_gft(what: &str, c: &Compiled, failures: &mut Vec<String>) {
    let gft = translated(c, "gft");
    let Some(text) = gft.text.filter(|_| gft.diagnostics.is_empty()) else {
        failures.push(format!("{what}: not written to .gft"));
        return;
    };
    let read = driver::compile(SourceFile::new("hub.gft", text.as_str()));
    let Some(sys) = read
        .system
        .as_ref()
        .filter(|_| !read.diagnostics.has_errors())
    else {
        failures.push(format!("{what}: its .gft is not read back"));
        return;
    };
    if let Err(e) = sys.same_as(c.system.as_ref().expect("compiles")) {
        failures.push(format!(
            "{what}: its .gft reads back as another system: {e}"
        ));
    }
    for to in TARGETS {
        let direct = outcome(&translated(c, to), to);
        let hub = outcome(&translated(&read, to), to);
        if direct != hub {
            failures.push(format!(
                "{what} --to {to}:\ndirect: {direct:?}\nthrough .gft: {hub:?}"
            ));
        }
    }
}

fn report(failures: Vec<String>, checked: usize) {
    assert!(
        failures.is_empty(),
        "{} of {checked}:\n{}",
        failures.len(),
        failures.join("\n\n")
    );
}

#[test]
fn every_stdlib_entry_translates_through_gft_as_directly() {
    let mut failures = Vec::new();
    for e in ENTRIES {
        let c = driver::compile(SourceFile::new(e.file, e.text));
        if c.system.is_some() {
            through_gft(e.name, &c, &mut failures);
        }
    }
    report(failures, ENTRIES.len());
}

#[test]
fn every_fractint_entry_translates_through_gft_as_directly() {
    let entries = fractint_corpus_entries();
    let mut failures = Vec::new();
    for (name, c) in &entries {
        through_gft(name, c, &mut failures);
    }
    report(failures, entries.len());
}

#[test]
fn every_cpfg_object_translates_through_gft_as_directly() {
    let mut failures = Vec::new();
    let mut checked = 0;
    for dir in cpfg_object_dirs() {
        let Some(l) = main_l(&dir) else { continue };
        let c = driver::compile(SourceFile::read(&l).unwrap());
        if c.system.is_some() {
            through_gft(&l.display().to_string(), &c, &mut failures);
            checked += 1;
        }
    }
    assert_eq!(checked, 94);
    report(failures, checked);
}

/// The same through the command line: `translate X --to gft -o X.gft`,
/// then `translate X.gft --to T`, for one entry of each notation.
#[test]
fn the_command_line_translates_through_gft_as_directly() {
    for (spec, to) in [
        ("std:koch-island", "linf"),
        ("std:linf/fig07-plant-3d", "pfg"),
        ("std:stl/fig04-plant", "pfg"),
        ("std:hogeweg-hesper-a", "stl"),
    ] {
        let gft = temp(&format!("hub-{}.gft", spec.replace([':', '/'], "-")));
        let path = gft.to_str().unwrap();
        let out = graftal(&["translate", spec, "--to", "gft", "-o", path]);
        assert_eq!(out.status, 0, "{spec}: {}", out.stderr);
        let direct = graftal(&["translate", spec, "--to", to]);
        let hub = graftal(&["translate", path, "--to", to]);
        assert_eq!(
            direct.status, hub.status,
            "{spec} --to {to}: {}",
            hub.stderr
        );
        assert_eq!(
            without_comments(&direct.stdout, to),
            without_comments(&hub.stdout, to),
            "{spec} --to {to}"
        );
    }
}
