//! Rendered diagnostics, snapshot-tested as plain text (colour off) and as
//! JSON: tests/diagnostics/NAME.l -> NAME.txt and NAME.json, compared byte
//! for byte (and tests/diagnostics/stl-*.stl likewise). Regenerate on purpose with `GRAFTAL_BLESS=1 cargo test`.

use graftal::diagnostics::{codes, render_json};
use graftal::driver::compile;
use graftal::source::SourceFile;
use std::path::{Path, PathBuf};

use crate::common;
use common::check_golden;

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/diagnostics")
}

fn inputs() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.extension()
                .is_some_and(|e| e == "l" || e == "linf" || e == "stl" || e == "gft")
        })
        .collect();
    v.sort();
    v
}

fn check_snapshot(path: &Path, actual: &str, failures: &mut Vec<String>) {
    if let Err(e) = check_golden(path, actual) {
        failures.push(e);
    }
}

#[test]
fn diagnostics_match_their_snapshots() {
    let mut failures = Vec::new();
    let files = inputs();
    assert!(files.len() >= 19);
    for path in files {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let text = std::fs::read_to_string(&path).unwrap();
        let c = compile(SourceFile::new(name.clone(), text));
        assert!(!c.diagnostics.is_empty(), "{name} should have diagnostics");
        let human = c.diagnostics.render(&c.file, false);
        assert!(!human.contains('\u{1b}'), "no colour codes off a terminal");
        check_snapshot(&path.with_extension("txt"), &human, &mut failures);
        let json = render_json(&c.diagnostics.0, &c.file);
        check_snapshot(&path.with_extension("json"), &json, &mut failures);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

fn codes_of(name: &str) -> Vec<&'static str> {
    let path = dir().join(name);
    let c = compile(SourceFile::new(
        name,
        std::fs::read_to_string(path).unwrap(),
    ));
    c.diagnostics.iter().map(|d| d.code.0).collect()
}

#[test]
fn each_problem_has_its_code() {
    let cases = [
        ("unknown-header.l", codes::UNKNOWN_HEADER),
        ("header-order.l", codes::HEADER_ORDER),
        ("missing-arrow.l", codes::MISSING_ARROW),
        ("malformed-arrow.l", codes::MALFORMED_ARROW),
        ("context-misuse.l", codes::MISPLACED_CONTEXT),
        ("bracket-in-predecessor.l", codes::BRACKET_IN_PREDECESSOR),
        ("unbalanced-successor.l", codes::UNBALANCED_SUCCESSOR),
        ("unbalanced-axiom.l", codes::UNBALANCED_AXIOM),
        ("angle-factor-fraction.l", codes::BAD_ANGLE_FACTOR),
        ("angle-factor-zero.l", codes::BAD_ANGLE_FACTOR),
        ("negative-steps.l", codes::NEGATIVE_STEPS),
        ("missing-axiom.l", codes::MISSING_AXIOM),
        ("bad-probability.l", codes::BAD_PROBABILITY),
        ("missing-weight.l", codes::MISSING_WEIGHT),
        ("unexpected-eof.l", codes::UNEXPECTED_EOF),
        ("unterminated-comment.l", codes::UNTERMINATED_COMMENT),
        ("shadowed.l", codes::SHADOWED_PRODUCTION),
        ("invalid-character.l", codes::INVALID_CHARACTER),
        ("star-prefix-and-ignored-bracket.l", codes::TEXT_AFTER_STAR),
        ("star-prefix-and-ignored-bracket.l", codes::BRACKET_IGNORED),
    ];
    for (file, code) in cases {
        assert!(
            codes_of(file).contains(&code.0),
            "{file}: {:?}",
            codes_of(file)
        );
    }
}

#[test]
fn all_errors_of_a_file_in_one_run() {
    // Seven broken lines, seven errors, and the good last line still lowers.
    let codes = codes_of("many-errors.l");
    for c in [
        "E0101", "E0004", "E0005", "E0006", "E0202", "E0103", "E0003",
    ] {
        assert!(codes.contains(&c), "{c} missing from {codes:?}");
    }
}

#[test]
fn spans_point_at_the_exact_characters() {
    let c = compile(SourceFile::new(
        "x.l",
        "axiom: F\nF --> F[+F]F : 0\n".to_string(),
    ));
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.code == codes::BAD_PROBABILITY)
        .unwrap();
    assert_eq!(&c.file.text[d.span.clone().unwrap()], "0");
    assert_eq!(c.file.line_col(d.span.clone().unwrap().start), (2, 16));
    let c = compile(SourceFile::new(
        "y.l",
        "derivaton length: 3\naxiom: F\n".to_string(),
    ));
    let d = &c.diagnostics.0[0];
    assert_eq!(&c.file.text[d.span.clone().unwrap()], "derivaton length");
    assert_eq!(d.help.as_deref(), Some("did you mean `derivation length`?"));
}

#[test]
fn json_objects_carry_the_contract_fields() {
    let c = compile(SourceFile::new("j.l", "axiom: F\nF -> G\n".to_string()));
    let out = render_json(&c.diagnostics.0, &c.file);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), c.diagnostics.len());
    let v: serde_json::Value = serde_json::from_str(lines[0]).unwrap();
    for key in [
        "code", "severity", "message", "file", "line", "column", "start", "end", "labels", "notes",
        "help",
    ] {
        assert!(v.get(key).is_some(), "{key} missing: {v}");
    }
    assert_eq!(v["code"], "E0005");
    assert_eq!(v["line"], 2);
    assert_eq!(v["column"], 3);
    assert_eq!(v["start"], 11);
    assert_eq!(v["end"], 13);
    assert_eq!(v["severity"], "error");
}

#[test]
fn many_diagnostics_are_fast_and_capped() {
    // 50,000 identical productions: one shadowing warning each, found and
    // rendered in linear time; people see the first MAX_SHOWN.
    let text = format!("axiom: F\n{}", "A < B > C --> D\n".repeat(50_001));
    let t = std::time::Instant::now();
    let c = compile(SourceFile::new("many.l", text));
    assert_eq!(c.diagnostics.len(), 50_000);
    let human = c.diagnostics.render(&c.file, false);
    common::assert_within(
        t.elapsed(),
        std::time::Duration::from_secs(5),
        "50,000 diagnostics",
    );
    assert_eq!(
        human.matches("[W0006]").count(),
        graftal::diagnostics::MAX_SHOWN
    );
    assert!(human.ends_with("`--format json` lists them all\n"));
}

#[test]
fn a_string_starting_with_star_is_empty_as_in_the_listing() {
    let path = dir().join("star-prefix-and-ignored-bracket.l");
    let c = compile(SourceFile::new(
        "s.l",
        std::fs::read_to_string(path).unwrap(),
    ));
    let sys = c.system.expect("warnings only");
    // `*A < B` has an empty left context, so B -> C; `A --> *B` erases A.
    let w = graftal::driver::derive(
        &sys,
        &graftal::driver::RunOptions {
            steps: Some(1),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(w.display(&sys.symbols), "C");
}

#[test]
fn each_linf_problem_has_its_code_and_all_errors_come_in_one_run() {
    let has = |file: &str, expected: &[codes::Code]| {
        let got = codes_of(file);
        for c in expected {
            assert!(got.contains(&c.0), "{file}: no {c} in {got:?}");
        }
    };
    has(
        "linf-undeclared.linf",
        &[codes::LINF_UNDECLARED, codes::LINF_UNKNOWN_ANGLE],
    );
    has(
        "linf-signs.linf",
        &[
            codes::LINF_UNKNOWN_ANGLE,
            codes::LINF_NO_DEFAULT_ROTATION,
            codes::LINF_BARE_ANGLE,
        ],
    );
    has(
        "linf-numbers.linf",
        &[
            codes::LINF_MISSING_NUMBER,
            codes::LINF_PROBABILITY,
            codes::LINF_STRAY_NUMBER,
            codes::LINF_GUARD_TARGET,
        ],
    );
    has(
        "linf-rotations.linf",
        &[
            codes::LINF_NOT_A_PAIR,
            codes::LINF_BAD_EXPRESSION,
            codes::LINF_EMPTY_INTERVAL,
            codes::SYNTAX,
        ],
    );
    has(
        "linf-colours.linf",
        &[
            codes::LINF_COLOUR_ARITY,
            codes::LINF_COLOUR_RANGE,
            codes::LINF_COLOUR_LABEL,
        ],
    );
    has(
        "linf-blocks.linf",
        &[
            codes::LINF_OUTSIDE_BLOCK,
            codes::LINF_DUPLICATE_BLOCK,
            codes::LINF_RULE_IN_AXIOM,
            codes::LINF_RESERVED_RULE,
        ],
    );
    has(
        "linf-brackets.linf",
        &[codes::LINF_UNBALANCED, codes::LINF_COLOUR_BALANCE],
    );
    // One run reports every error of the file, each once, and no cascade:
    // the failed interval `w` stays declared, so `-w` is not reported.
    let many = codes_of("linf-many-errors.linf");
    assert_eq!(
        many,
        [
            codes::LINF_EMPTY_INTERVAL.0,
            codes::LINF_UNKNOWN_ANGLE.0,
            codes::SYNTAX.0,
            codes::SYNTAX.0,
            codes::LINF_UNDECLARED.0,
            codes::LINF_PROBABILITY.0,
            codes::LINF_RESERVED_RULE.0,
            codes::LINF_COLOUR_RANGE.0,
        ]
    );
}

/// Object productions, sub-L-systems, missing curves and the translation
/// of a parametric cpfg L-system are different problems, each with its code
/// and its `graftal explain` text.
#[test]
fn cpfg_refusals_have_codes_of_their_own() {
    let src = "lsystem: 1\nderivation length: 2\naxiom: A(1)\n\
               A(x) --> ?(3, 2) B(curveX(1, x))\nB(x) -o> A(x)\nendlsystem\n";
    let c = compile(SourceFile::new("refusals.l", src));
    let found: Vec<&str> = c.diagnostics.iter().map(|d| d.code.0).collect();
    let expected = [
        codes::CPFG_SUB_LSYSTEM,
        codes::CPFG_NO_CURVE,
        codes::CPFG_UNSUPPORTED,
    ];
    for code in expected {
        assert!(found.contains(&code.0), "{code} not in {found:?}");
    }
    let mut all: Vec<&str> = expected.iter().map(|c| c.0).collect();
    all.push(codes::TR_PARAMETRIC.0);
    all.sort_unstable();
    all.dedup();
    assert_eq!(all.len(), 4);
    for code in all {
        let info = codes::lookup(code).unwrap();
        assert!(info.explanation.len() > 100, "{code}");
    }
}

/// Each `.gft` code has a snapshot of its own (tests/diagnostics/gft-CODE-*.gft,
/// the code being the only one the file raises) and its `graftal explain` text;
/// so have the codes of `graph` blocks (E092x) and of the graph checks
/// every front end reading a graph reports (E10xx, W10xx).
#[test]
fn each_gft_code_has_its_snapshot_and_explanation() {
    let gft_codes = [
        "E0900", "E0901", "E0902", "E0903", "E0904", "E0905", "E0906", "E0907", "W0900", "W0901",
        "W0902", "W0903", "W0904", "E0920", "E0921", "E0922", "E0923", "E0924", "E0925", "E0926",
        "E1001", "E1002", "W1003", "W1004",
    ];
    for code in gft_codes {
        let prefix = format!("gft-{}-", code.to_ascii_lowercase());
        let file = inputs()
            .into_iter()
            .find(|p| {
                p.file_name()
                    .unwrap()
                    .to_string_lossy()
                    .starts_with(&prefix)
            })
            .unwrap_or_else(|| panic!("no snapshot for {code}"));
        let name = file.file_name().unwrap().to_string_lossy().to_string();
        assert_eq!(codes_of(&name), [code], "{name}");
        let out = common::graftal(&["explain", code]);
        assert_eq!(out.status, 0, "{code}");
        let info = codes::lookup(code).unwrap();
        assert!(
            out.stdout.contains(info.explanation),
            "{code}: {}",
            out.stdout
        );
    }
}

/// The cpfg mistakes cpfg itself passes in silence each get their own
/// diagnostic, at the place written, with the help a new user needs: `//`
/// between rolls, a misspelt item keyword, a parameter count no production
/// takes, `$` for the roll to horizontal, the file functions; and a
/// did-you-mean never names a name that is itself undefined.
#[test]
fn cpfg_mistakes_made_in_silence_are_each_said() {
    let name = "cpfg-mistakes.l";
    let text = std::fs::read_to_string(dir().join(name)).unwrap();
    let c = compile(SourceFile::new(name, text.clone()));
    let at = |code: &str, nth: usize| {
        let d = (c.diagnostics.iter().filter(|d| d.code.0 == code))
            .nth(nth)
            .unwrap_or_else(|| panic!("no {code} #{nth}: {:?}", c.diagnostics));
        (text[d.span.clone().unwrap()].to_string(), d.clone())
    };
    let (slashes, d) = at("W0812", 0);
    assert_eq!(slashes, "///");
    assert_eq!(d.fix.unwrap().replacement, "/ / /");
    let (key, d) = at("E0101", 0);
    assert_eq!(key, "derivaton length");
    assert_eq!(d.fix.unwrap().replacement, "derivation length");
    assert_eq!(at("W0827", 0).0, "A(1,2)");
    let (dollar, d) = at("W0825", 0);
    assert_eq!(
        (dollar.as_str(), d.fix.unwrap().replacement.as_str()),
        ("$", "@v")
    );
    let io: Vec<String> = (0..3).map(|k| at("W0822", k).0).collect();
    assert_eq!(io, ["fopen", "fscanf", "fprintf"]);
    let (second, d) = at("W0820", 2);
    assert_eq!(second, "lennn");
    assert_eq!(d.help, None, "`lenn` is undefined itself: no did-you-mean");
    assert!(
        !c.diagnostics.iter().any(|d| d.code.0 == "E0003"),
        "{:?}",
        c.diagnostics
    );
}
