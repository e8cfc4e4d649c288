//! The Fractint front end: the corpus (every entry of the six library
//! files checks, derives and renders), golden derived words checked against
//! an independent derivation, geometry of known pictures, entry choice on
//! the command line, translation.
//!
//! Golden words live in tests/out/fractint/; regenerate on purpose with
//! `GRAFTAL_BLESS=1 cargo test --test it fractint::`. A golden is only written
//! when the front end agrees with the independent rewriter below, so a bug
//! in the front end cannot be blessed.

use graftal::driver::{self, compile, compile_entry, Compiled, RunOptions};
use graftal::source::SourceFile;
use graftal::turtle::{self, Segment};
use std::path::{Path, PathBuf};

use crate::common;
use common::{check_golden, graftal, temp};

fn corpus(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/corpus/fractint")
        .join(file)
}

const FILES: [(&str, usize); 6] = [
    ("fractint.l", 69),
    ("penrose.l", 13),
    ("tiling.l", 8),
    ("history/fractint.l.v15.0", 51),
    ("history/fractint.l.v16.0", 65),
    ("history/fractint.l.v19.0", 65),
];

fn load(file: &str) -> SourceFile {
    let path = corpus(file);
    SourceFile::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn entry(file: &str, name: &str) -> Compiled {
    let c = compile_entry(load(file), Some(name));
    assert!(c.system.is_some(), "{file}:{name}: {:#?}", c.diagnostics);
    c
}

fn run(n: u64) -> RunOptions {
    RunOptions {
        steps: Some(n),
        ..RunOptions::default()
    }
}

#[test]
fn every_corpus_entry_checks_derives_and_renders() {
    let mut total = 0;
    for (file, count) in FILES {
        let c = compile(load(file));
        assert_eq!(c.front.name(), "fractint", "{file}");
        let lib = c.library.as_ref().expect("a library");
        assert_eq!(lib.entries.len(), count, "{file}");
        assert!(c.needs_entry());
        assert!(!c.diagnostics.has_errors(), "{file}: {:#?}", c.diagnostics);
        for e in &lib.entries {
            let one = entry(file, &e.name);
            let sys = one.system.as_ref().unwrap();
            // Fractint's default order, then one more step.
            for steps in [None, Some(3)] {
                let opts = RunOptions {
                    steps,
                    ..RunOptions::default()
                };
                let (word, g) = driver::geometry(sys, &opts)
                    .unwrap_or_else(|d| panic!("{file}:{}: {d:?}", e.name));
                assert!(!g.is_empty(), "{file}:{} draws nothing", e.name);
                let bytes = driver::render_bytes(
                    sys,
                    &g,
                    driver::Format::Svg,
                    graftal::render::RenderOptions {
                        width: 64,
                        height: 64,
                        ..Default::default()
                    },
                )
                .unwrap();
                assert!(bytes.len() > 100, "{file}:{}", e.name);
                assert!(!word.is_empty());
            }
            total += 1;
        }
    }
    assert_eq!(total, 271);
}

#[test]
fn only_the_old_reserved_rule_warns_in_the_corpus() {
    for (file, _) in FILES {
        let c = compile(load(file));
        let codes: Vec<&str> = c.diagnostics.iter().map(|d| d.code.0).collect();
        let expected: &[&str] = if file.ends_with("v15.0") || file.ends_with("v16.0") {
            &["W0701"]
        } else {
            &[]
        };
        assert_eq!(codes, expected, "{file}");
    }
}

// ---------------------------------------------------------------------
// An independent derivation, from the help text: rules `x=string` for one
// character (several concatenate), a command with a number is one unit,
// rewriting in parallel. Deliberately naive: string processing over the
// raw entry text.

fn raw_entry(text: &str, name: &str) -> Vec<String> {
    let mut lines = Vec::new();
    let mut inside = false;
    for line in text.lines() {
        let line = line.split(';').next().unwrap().to_ascii_lowercase();
        if !inside {
            if let Some((head, rest)) = line.split_once('{') {
                if head.trim() == name.to_ascii_lowercase() {
                    inside = true;
                    lines.push(rest.to_string());
                }
            }
        } else if line.trim_start().starts_with('}') {
            break;
        } else {
            lines.push(line);
        }
    }
    assert!(inside, "no entry {name}");
    lines
}

/// Units of a string: `\30`, `@iq2`, `c12`, `<1` whole; other characters
/// one by one.
fn units(s: &str) -> Vec<String> {
    let b: Vec<char> = s.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let mut j = i + 1;
        if "/\\@c<>".contains(b[i]) {
            let mut prefixes = 0;
            while j < b.len() && prefixes < 2 && (b[j] == 'q' || b[j] == 'i') {
                j += 1;
                prefixes += 1;
            }
            while j < b.len() && (b[j].is_ascii_digit() || b[j] == '.') {
                j += 1;
            }
        }
        out.push(b[i..j].iter().collect());
        i = j;
    }
    out
}

fn naive_derive(text: &str, name: &str, steps: usize) -> String {
    let mut axiom = String::new();
    let mut rules: Vec<(char, String)> = Vec::new();
    for line in raw_entry(text, name) {
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        let (word, rest) = match line.find([' ', '\t', '=']) {
            Some(k) => (&line[..k], &line[k + 1..]),
            None => (line, ""),
        };
        let body = rest.split_whitespace().next().unwrap_or("");
        match word {
            "axiom" => axiom = body.to_string(),
            "angle" => {}
            w => {
                let head = w.chars().next().unwrap();
                match rules.iter_mut().find(|r| r.0 == head) {
                    Some(r) => r.1.push_str(body),
                    None => rules.push((head, body.to_string())),
                }
            }
        }
    }
    let mut word = units(&axiom);
    for _ in 0..steps {
        let mut next = Vec::new();
        for u in word {
            let head = u.chars().next().unwrap();
            // A rule for a character rewrites the units it starts.
            match rules.iter().find(|r| r.0 == head) {
                Some(r) => next.extend(units(&r.1)),
                None => next.push(u),
            }
        }
        word = next;
    }
    word.concat()
}

/// (file, entry, steps): several rules for one character (Snowflake2,
/// SnowflakeColor, penrose), `F=` deletion (Dragon, SnowflakeColor,
/// penrose), `!` and `@iq` (Snowflake2), `\ /` and `D` (DoubleCesaro),
/// colours (SnowflakeColor, ColorTriangGasket, Lars1Color, tiling), the
/// Fractint 16 `<=` rule, and the plain symbols `(4)` of Leaf1.
const GOLDEN: [(&str, &str, usize); 14] = [
    ("fractint.l", "Koch1", 3),
    ("fractint.l", "Dragon", 5),
    ("fractint.l", "Snowflake2", 2),
    ("fractint.l", "SnowflakeColor", 2),
    ("fractint.l", "DoubleCesaro", 3),
    ("fractint.l", "Leaf1", 6),
    ("fractint.l", "ColorTriangGasket", 3),
    ("fractint.l", "Lars1Color", 3),
    ("penrose.l", "Penrose1", 3),
    ("penrose.l", "PentaColor", 2),
    ("tiling.l", "SpiralTile", 3),
    ("tiling.l", "VoderbergTile", 3),
    ("history/fractint.l.v15.0", "SnowflakeColor", 2),
    ("history/fractint.l.v16.0", "QuadKoch", 2),
];

#[test]
fn golden_words_agree_with_an_independent_derivation() {
    let out_dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/out/fractint");
    let mut failures = Vec::new();
    for (file, name, steps) in GOLDEN {
        let c = entry(file, name);
        let sys = c.system.as_ref().unwrap();
        let word = driver::derive(sys, &run(steps as u64)).unwrap();
        let text = c.word_text(sys, &word);
        let naive = naive_derive(&c.file.text, name, steps);
        assert_eq!(text, naive, "{file}:{name} after {steps} steps");
        assert!(text.len() > 20, "{file}:{name}: too short to mean much");
        let stem = format!("{}-{name}.txt", file.replace("history/", ""));
        let path = out_dir.join(stem);
        let golden = format!("{file}:{name} -n {steps}\n{text}\n");
        // Reached (and so blessed) only when the word agrees with the
        // independent rewriter: the assertion above comes first.
        if let Err(e) = check_golden(&path, &golden) {
            failures.push(e);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_naive_rewriter_itself_knows_the_help_examples() {
    // The help text's Dragon: F deleted, x and y rewritten.
    let dragon = "Dragon {\n Angle 8\n Axiom FX\n F=\n y=+FX--FY+\n x=-FX++FY-\n}\n";
    assert_eq!(naive_derive(dragon, "Dragon", 1), "-fx++fy-");
    assert_eq!(
        units("f\\30@iq2c12<1x"),
        ["f", "\\30", "@iq2", "c12", "<1", "x"]
    );
}

// ---------------------------------------------------------------------
// Geometry: segment endpoints of known pictures. graftal's turtle starts
// heading up (+y); Fractint's `+` turns counter-clockwise.

fn segments(src: &str, steps: u64) -> Vec<Segment> {
    let c = compile(SourceFile::new("t.l", src));
    let sys = c.system.unwrap_or_else(|| panic!("{:#?}", c.diagnostics));
    let word = driver::derive(&sys, &run(steps)).unwrap();
    turtle::Run::word(&sys, &word, 0).geometry().segments
}

fn ends(s: &[Segment]) -> Vec<(f64, f64)> {
    let r = |v: f64| (v * 1e6).round() / 1e6 + 0.0;
    s.iter().map(|s| (r(s.b[0]), r(s.b[1]))).collect()
}

#[test]
fn koch_curve_from_its_segments() {
    // Angle 6: 60° turns. One step of F=F+F--F+F from F.
    let s = segments("K {\n Angle 6\n Axiom F\n F=F+F--F+F\n}\n", 1);
    let h = 3f64.sqrt() / 2.0;
    let r = |v: f64| (v * 1e6).round() / 1e6 + 0.0;
    // Up, then 60° to the left (counter-clockwise), back right, up.
    assert_eq!(ends(&s), [(0.0, 1.0), (r(-h), 1.5), (0.0, 2.0), (0.0, 3.0)]);
}

#[test]
fn dragon_curve_visits_the_expected_corners() {
    // Angle 4 dragon (Fractint's DragonCurve style): X=X+YF+, Y=-FX-Y.
    let s = segments("D {\n Angle 4\n Axiom FX\n X=X+YF+\n Y=-FX-Y\n}\n", 2);
    // FX -> F X+YF+ -> F X+YF+ + -FX-YF +
    // Moves: up; then + (left): F...; the first four endpoints:
    assert_eq!(s.len(), 4);
    assert_eq!(
        ends(&s),
        [(0.0, 1.0), (-1.0, 1.0), (-1.0, 0.0), (-2.0, 0.0)]
    );
}

#[test]
fn odd_angle_bar_is_the_largest_turn_short_of_half() {
    // Angle 5: `|` turns by 2 increments = 144°, clockwise (Fractint adds
    // maxangle/2 to the heading index, the direction of `-`).
    let s = segments("B {\n Angle 5\n Axiom F|F\n}\n", 0);
    let a = 144f64.to_radians();
    let r = |v: f64| (v * 1e6).round() / 1e6 + 0.0;
    assert_eq!(ends(&s), [(0.0, 1.0), (r(a.sin()), r(1.0 + a.cos()))]);
    // `|` is the same after `!`: only + - \ / swap.
    let t = segments("B {\n Angle 5\n Axiom F!|F\n}\n", 0);
    assert_eq!(ends(&s), ends(&t));
    // Even angles turn around exactly.
    let u = segments("B {\n Angle 6\n Axiom F|F\n}\n", 0);
    assert_eq!(ends(&u), [(0.0, 1.0), (0.0, 0.0)]);
}

#[test]
fn bang_reverses_plus_minus_and_the_real_turns() {
    let plain = segments("A {\n Angle 4\n Axiom F+F\\90D\n}\n", 0);
    let swapped = segments("A {\n Angle 4\n Axiom !F-F/90D\n}\n", 0);
    assert_eq!(ends(&plain), ends(&swapped));
    // F up, + to the left, then the real heading turned left from up.
    assert_eq!(ends(&plain), [(0.0, 1.0), (-1.0, 1.0), (-2.0, 1.0)]);
}

#[test]
fn the_two_headings_are_separate_registers() {
    // + turns only F's heading; \ only D's. @ scales both.
    let s = segments("R {\n Angle 4\n Axiom +F\\30D@2FD\n}\n", 0);
    let r = |v: f64| (v * 1e6).round() / 1e6 + 0.0;
    let (sn, cs) = 30f64.to_radians().sin_cos();
    // F: left along −x. D: 30° counter-clockwise from up.
    let d1 = (r(-1.0 - sn), r(cs));
    let f2 = (r(-1.0 - sn - 2.0), r(cs));
    let d2 = (r(-1.0 - 3.0 * sn - 2.0), r(3.0 * cs));
    assert_eq!(ends(&s), [(-1.0, 0.0), d1, f2, d2]);
}

#[test]
fn double_cesaro_is_drawn_by_the_real_heading() {
    // DoubleCesaro uses only D and \ /: its order 0 is a square.
    let c = entry("fractint.l", "DoubleCesaro");
    let sys = c.system.as_ref().unwrap();
    let w = driver::derive(sys, &run(0)).unwrap();
    let s = turtle::Run::word(sys, &w, 0).geometry().segments;
    assert_eq!(ends(&s), [(0.0, 1.0), (-1.0, 1.0), (-1.0, 0.0), (0.0, 0.0)]);
}

#[test]
fn colours_follow_fractints_rules() {
    let c = compile(SourceFile::new(
        "c.l",
        "C {\n Angle 4\n Axiom FC1F>1F>1F<255FC300FC0F<256F\n}\n",
    ));
    let mut sys = c.system.unwrap();
    // The default colour 15 is drawn black on graftal's white.
    let g = turtle::Run::word(&sys, &sys.axiom, 0).geometry();
    assert_eq!(g.segments[0].colour, graftal::ir::Rgb(0, 0, 0));
    assert_eq!(
        graftal::front::fractint::palette()[0],
        graftal::ir::Rgb(255, 255, 255)
    );
    // With a palette of distinct colours the indices show: >1 from 1
    // lands on 0 and goes to the last colour; <n wraps modulo 256; Cn too;
    // <256 from 0 lands on 0 and goes to 1.
    sys.colours = (0..=255u8).map(|i| graftal::ir::Rgb(i, 0, 0)).collect();
    let g = turtle::Run::word(&sys, &sys.axiom, 0).geometry();
    let idx: Vec<u8> = g.segments.iter().map(|s| s.colour.0).collect();
    assert_eq!(idx, [15, 1, 255, 254, 253, 44, 0, 1]);
}

// ---------------------------------------------------------------------
// The command line.

#[test]
fn entries_are_chosen_by_name_without_regard_to_case() {
    let f = corpus("fractint.l");
    let f = f.to_str().unwrap();
    let a = graftal(&["derive", &format!("{f}:dragon"), "-n", "2"]);
    assert_eq!(a.status, 0, "{}", a.stderr);
    assert_eq!(a.stdout, "--fx++fy-+++fx--fy+-\n");
    let b = graftal(&["derive", f, "--entry", "DRAGON", "-n", "2"]);
    assert_eq!(b.stdout, a.stdout);
    // Fractint's default order is 2.
    let c = graftal(&["derive", f, "--entry", "Dragon"]);
    assert_eq!(c.stdout, a.stdout);
    // No entry chosen: an error listing the names, for every command.
    for cmd in [
        vec!["derive", f],
        vec!["stats", f],
        vec!["translate", f, "--to", "pfg"],
    ] {
        let o = graftal(&cmd);
        assert_eq!(o.status, 1, "{cmd:?}");
        assert!(o.stderr.contains("E0707"), "{}", o.stderr);
        assert!(o.stderr.contains("Koch1, Koch2"), "{}", o.stderr);
        assert!(o.stdout.is_empty());
    }
    let out = temp("no-entry.png");
    let o = graftal(&["render", f, "-o", out.to_str().unwrap()]);
    assert_eq!(o.status, 1);
    assert!(!out.exists());
    // A wrong name: did you mean.
    let o = graftal(&["derive", &format!("{f}:Dragn")]);
    assert_eq!(o.status, 1);
    assert!(o.stderr.contains("E0706"), "{}", o.stderr);
    assert!(o.stderr.contains("did you mean `Dragon`?"), "{}", o.stderr);
}

#[test]
fn check_lists_entries_with_lines_and_the_dialect() {
    let f = corpus("penrose.l");
    let o = graftal(&["check", f.to_str().unwrap()]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let lines: Vec<&str> = o.stdout.lines().collect();
    assert!(
        lines[0].contains("dialect: Fractint, 13 entries"),
        "{}",
        lines[0]
    );
    assert_eq!(lines.len(), 14);
    assert!(
        lines[1].contains("Penrose1") && lines[1].contains("line 15"),
        "{}",
        lines[1]
    );
    assert!(lines[2].contains("Losanges") && lines[2].contains("line 27"));
    assert!(
        lines.iter().skip(1).all(|l| l.ends_with("ok")),
        "{}",
        o.stdout
    );
    // One broken entry does not stop the others.
    let text = std::fs::read_to_string(corpus("fractint.l"))
        .unwrap()
        .replacen("Axiom FX", "Axoim FX", 1);
    let p = temp("broken.l");
    std::fs::write(&p, text).unwrap();
    let o = graftal(&["check", p.to_str().unwrap()]);
    assert_eq!(o.status, 1);
    assert!(o.stderr.contains("E0704") && o.stderr.contains("did you mean `Axiom`?"));
    let bad: Vec<&str> = o.stdout.lines().filter(|l| !l.ends_with("ok")).collect();
    assert_eq!(bad.len(), 2, "{}", o.stdout);
    assert!(
        bad[1].contains("Dragon") && bad[1].contains("2 errors"),
        "{}",
        o.stdout
    );
    let ok = graftal(&["derive", &format!("{}:Koch1", p.display()), "-n", "1"]);
    assert_eq!(ok.status, 0, "{}", ok.stderr);
    assert_eq!(ok.stdout, "f+f--f+f--f+f--f+f--f+f--f+f\n");
}

#[test]
fn translate_a_simple_entry_to_pfg_exactly() {
    let f = corpus("fractint.l");
    let o = graftal(&[
        "translate",
        &format!("{}:Koch1", f.display()),
        "--to",
        "pfg",
    ]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert!(o.stderr.is_empty(), "{}", o.stderr);
    assert!(
        o.stdout.contains("Translated by graftal from Fractint"),
        "{}",
        o.stdout
    );
    // The pfg reads back and draws the same picture.
    let back = compile(SourceFile::new("k.l", o.stdout.clone()));
    assert_eq!(back.front.name(), "pfg");
    let pfg = back.system.expect("the translation compiles");
    let c = entry("fractint.l", "Koch1");
    let sys = c.system.as_ref().unwrap();
    let (_, g1) = driver::geometry(sys, &run(2)).unwrap();
    let (_, g2) = driver::geometry(&pfg, &run(2)).unwrap();
    assert_eq!(g1.segments.len(), g2.segments.len());
    let b1 = g1.bbox().unwrap();
    let b2 = g2.bbox().unwrap();
    for k in 0..6 {
        assert!((b1[k] - b2[k]).abs() < 1e-9, "{b1:?} {b2:?}");
    }
}

#[test]
fn translating_fractint_only_commands_is_an_error_or_lossy() {
    let f = corpus("fractint.l");
    let spec = format!("{}:Lars1Color", f.display());
    let o = graftal(&["translate", &spec, "--to", "pfg"]);
    assert_eq!(o.status, 1);
    assert!(o.stderr.contains("colour command"), "{}", o.stderr);
    let o = graftal(&["translate", &spec, "--to", "pfg", "--lossy"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert!(o.stderr.contains("Warning"), "{}", o.stderr);
    // DoubleCesaro uses only the real heading: exact in LinF.
    let o = graftal(&[
        "translate",
        &format!("{}:DoubleCesaro", f.display()),
        "--to",
        "linf",
    ]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    // Mixing both headings cannot be exact.
    let p = temp("mixed.l");
    std::fs::write(&p, "M {\n Angle 4\n Axiom F\\30D\n}\n").unwrap();
    let o = graftal(&["translate", p.to_str().unwrap(), "--to", "pfg"]);
    assert_eq!(o.status, 1);
    assert!(o.stderr.contains("second heading"), "{}", o.stderr);
}

/// A library of one entry is drawn without choosing, and `check` does not
/// ask to choose one.
#[test]
fn a_library_of_one_entry_is_not_asked_to_choose() {
    let path = temp("one.l");
    std::fs::write(&path, "Only {\n  Angle 4\n  Axiom F\n  F=F+F\n}\n").unwrap();
    let path = path.to_str().unwrap();
    let o = graftal(&["check", path]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert!(o.stdout.contains("1 entry"), "{}", o.stdout);
    assert!(!o.stdout.contains("choose one"), "{}", o.stdout);
    let o = graftal(&["derive", path, "-n", "1", "-o", "-"]);
    assert_eq!((o.status, o.stdout.trim()), (0, "f+f"), "{}", o.stderr);
}

/// The entries E0707 lists are whole names, the first ones, then how many
/// more: long names are not cut from the middle of the list.
#[test]
fn the_entries_to_choose_from_are_listed_whole() {
    let path = temp("long.l");
    let text: String = (0..30)
        .map(|i| format!("SomeRatherLongEntryName{i} {{\n Angle 4\n Axiom F\n F=F+F\n}}\n"))
        .collect();
    std::fs::write(&path, text).unwrap();
    let o = graftal(&["render", path.to_str().unwrap(), "--to", "svg", "-o", "-"]);
    assert!(o.stderr.contains("E0707"), "{}", o.stderr);
    let note = (o.stderr.lines())
        .find(|l| l.contains("note: entries:"))
        .unwrap_or_else(|| panic!("{}", o.stderr));
    let listed = note.split("entries: ").nth(1).unwrap();
    let (names, more) = listed.split_once(", … and ").expect("how many more");
    let names: Vec<&str> = names.split(", ").collect();
    for (k, name) in names.iter().enumerate() {
        assert_eq!(*name, format!("SomeRatherLongEntryName{k}"), "{note}");
    }
    assert_eq!(more, format!("{} more", 30 - names.len()));
}
