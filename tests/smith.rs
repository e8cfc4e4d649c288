//! Smith's bracketed 2L-systems (`.smith`): Table 1 of the paper exactly,
//! the 0L example, the stdlib plates, diagnostics with their spans, and
//! branches nailed to their angles.

use graftal::diagnostics::Diagnostics;
use graftal::driver::{self, RunOptions};
use graftal::front::smith;
use graftal::ir::System;

fn words(sys: &System, n: u64) -> String {
    let opts = RunOptions {
        steps: Some(n),
        ..RunOptions::default()
    };
    let word = driver::derive(sys, &opts).expect("derives");
    smith::smith_text(sys, word.symbols())
}

/// Table 1, copied from the paper into tests/corpus/smith/table1.txt.
#[test]
fn table_1_every_generation_as_printed() {
    let table = include_str!("corpus/smith/table1.txt");
    let sys = smith::read_ok("rules: 0.1[1].1.1.0.11.1.0\naxiom: 1\n");
    let rows: Vec<(u64, &str)> = table
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| {
            let (n, w) = l.split_once(' ').expect("n word");
            (n.parse().expect("n"), w)
        })
        .collect();
    assert_eq!(rows.len(), 11);
    for (n, printed) in rows {
        assert_eq!(words(&sys, n), printed, "generation {n}");
    }
}

#[test]
fn the_first_0l_example_and_its_three_generations() {
    let entry = graftal::stdlib::get("smith/cartoon-tree").expect("entry");
    let sys = smith::read_ok(entry.text);
    assert_eq!(words(&sys, 0), "0");
    assert_eq!(words(&sys, 1), "1[0]1[0]0");
    assert_eq!(words(&sys, 2), "11[1[0]1[0]0]11[1[0]1[0]0]1[0]1[0]0");
}

/// The paper's example of neighbours: in `0[1]` the 0 has two invisible
/// 1's, the 1 has the 0 on its left and an invisible 1 on its right.
#[test]
fn invisible_ones_and_neighbours_across_brackets() {
    // Each image names its triple: 0 -> `[lsr]` written in bits as 0 plus
    // a branch of the triple's bits, 1 likewise.
    let images: Vec<String> = (0..8)
        .map(|t| format!("{}[{t:03b}]", (t >> 1) & 1))
        .collect();
    let sys = smith::read_ok(&format!("rules: {}\naxiom: 0[1]\n", images.join(".")));
    assert_eq!(words(&sys, 1), "0[101][1[011]]");
    // Left and right neighbours skip branches.
    let sys = smith::read_ok(&format!("rules: {}\naxiom: 0[1]0[0]1\n", images.join(".")));
    assert_eq!(words(&sys, 1), "0[100][1[011]]0[001][0[001]]1[011]");
    // A branch's first symbol sees the symbol left of its `[`, earlier
    // sibling branches skipped.
    let sys = smith::read_ok(&format!("rules: {}\naxiom: 0[0][1]\n", images.join(".")));
    assert_eq!(words(&sys, 1), "0[101][0[001]][1[011]]");
}

#[test]
fn every_smith_stdlib_entry_reads_cleanly_with_its_plate() {
    let entries: Vec<_> = graftal::stdlib::ENTRIES
        .iter()
        .filter(|e| e.file.ends_with(".smith"))
        .collect();
    assert!(entries.len() >= 6);
    for e in entries {
        let sys = smith::read_ok(e.text);
        assert!(sys.settings.steps.is_some(), "{}: generation count", e.name);
        let fig = e.figure();
        assert!(
            ["Plate ", "Table ", "Figure "]
                .iter()
                .any(|k| fig.starts_with(k)),
            "{}: {fig}",
            e.name
        );
    }
}

fn diagnostics(src: &str) -> Vec<(&'static str, std::ops::Range<usize>, Option<String>)> {
    let mut d = Diagnostics::default();
    smith::read(src, &mut d);
    d.iter()
        .map(|d| (d.code.0, d.span.clone().unwrap_or(0..0), d.help.clone()))
        .collect()
}

#[test]
fn mistakes_get_their_code_span_and_help() {
    let d = diagnostics("rules: 0.1[1].1.1.0.11.1\n");
    assert_eq!((d[0].0, d[0].1.clone()), ("E0970", 7..24));
    let d = diagnostics("rules: 0.1[1.1.1.0.11.1.0\n");
    assert_eq!((d[0].0, d[0].1.clone()), ("E0971", 10..11));
    let d = diagnostics("rules: 0.1]1.1.1.0.11.1.0\n");
    assert_eq!((d[0].0, d[0].1.clone()), ("E0971", 10..11));
    let d = diagnostics("rules: 0.1[Fx].1.1.0.11.1.0\n");
    assert_eq!((d.len(), d[0].0, d[0].1.clone()), (1, "E0972", 11..13));
    let d = diagnostics("rules: 0.1[1].1.1.0.11.1.0\naxiom: 12\n");
    assert_eq!((d[0].0, d[0].1.clone()), ("E0973", 35..36));
    let d = diagnostics("rules: 0.1[1].1.1.0.11.1.0\naxiom: 1]\n");
    assert_eq!((d[0].0, d[0].1.clone()), ("E0973", 35..36));
    let d = diagnostics("rules: 0..1.1.0.11.1.0\n");
    assert_eq!((d[0].0, d[0].1.clone()), ("E0974", 9..9));
    let d = diagnostics("rules: 0.1[1].1.1.0.11.1.0\nangel: 30\n");
    assert_eq!((d[0].0, d[0].1.clone()), ("W0970", 27..32));
    assert_eq!(d[0].2.as_deref(), Some("did you mean `angle`?"));
}
