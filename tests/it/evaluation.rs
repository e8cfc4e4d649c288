//! Evaluation chooses its method from the system's properties, never from
//! the notation the system was read in, and `stats --format json` names it.

use graftal::driver::picture::{self, DrawError, Format, Quiet, Request, Target};
use graftal::driver::{self, compile, RunOptions};
use graftal::eval::{plan, Method};
use graftal::ir::{Alternative, Production, System, Word};
use graftal::source::SourceFile;

use crate::common;
use common::graftal;

fn read(name: &str, text: &str) -> System {
    let c = compile(SourceFile::new(name, text));
    c.system
        .unwrap_or_else(|| panic!("{name}: {:#?}", c.diagnostics))
}

fn std_system(name: &str) -> System {
    let c = compile(driver::load(&format!("std:{name}")).unwrap());
    c.system.unwrap_or_else(|| panic!("std:{name}"))
}

/// The quadratic Koch curve in pfg, LinF and Fractint: one method for all
/// three, and the same word; with a context added in pfg and in cpfg, the
/// method follows the context, not the notation.
#[test]
fn the_same_system_in_three_notations_is_derived_the_same_way() {
    let sources = [
        ("koch.l", "axiom: F\nF --> F+F-F-F+F\n"),
        (
            "koch.linf",
            "lines F\nangles (0, pi/2)\naxiom F\nrules\n  F = F+F-F-F+F\n",
        ),
        ("koch.l", "Koch {\n  Angle 4\n  Axiom F\n  F=F+F-F-F+F\n}\n"),
    ];
    let mut words = Vec::new();
    for (name, text) in sources {
        let sys = read(name, text);
        assert_eq!(plan(&sys, 3), Method::SharedTree, "{name}");
        let opts = RunOptions {
            steps: Some(2),
            ..RunOptions::default()
        };
        let w = driver::derive(&sys, &opts).unwrap();
        words.push(w.display(&sys.symbols).to_uppercase());
    }
    assert!(words.windows(2).all(|w| w[0] == w[1]), "{words:?}");
    // F+F-F-F+F with each F rewritten again: 5 × 9 + 4 symbols.
    assert_eq!(words[0].len(), 49);
}

#[test]
fn each_method_is_chosen_by_what_the_system_uses() {
    // Context-free, deterministic: the shared tree; past the tree's depth,
    // the table (it has no contexts).
    let koch = std_system("koch-island");
    assert_eq!(plan(&koch, 4), Method::SharedTree);
    assert_eq!(plan(&koch, 10_000), Method::Table);
    // One-symbol contexts: the table.
    assert_eq!(plan(&std_system("hogeweg-hesper-a"), 30), Method::Table);
    // Stochastic alternatives are chosen in the table too.
    assert_eq!(plan(&std_system("stochastic-bush"), 3), Method::Table);
    // Longer contexts or predecessors, guards: the general matcher.
    let two = read("two.l", "axiom: ABA\nAB < A --> B\n");
    assert_eq!(plan(&two, 2), Method::General);
    let pair = read("pair.l", "axiom: ABA\nAB --> BA\n");
    assert_eq!(plan(&pair, 2), Method::General);
    let guarded = read("g.linf", "lines f\naxiom f\nrules\n  f = f[0.5?f]\n");
    assert_eq!(plan(&guarded, 3), Method::General);
    // Parameters: module rewriting.
    let cpfg = read(
        "p.l",
        "lsystem: 1\naxiom: A(1)\nA(x) --> F(x) A(x+1)\nendlsystem\n",
    );
    assert_eq!(plan(&cpfg, 3), Method::Modules);
}

#[test]
fn changing_a_property_of_a_system_changes_its_method() {
    let mut sys = std_system("koch-island");
    assert_eq!(plan(&sys, 3), Method::SharedTree);
    // A one-symbol left context on the first production.
    let mut with_context = sys.clone();
    let f = with_context.symbols.get("F").unwrap();
    with_context.productions[0].left = vec![f];
    assert_eq!(plan(&with_context, 3), Method::Table);
    // A second alternative makes it stochastic: no longer one tree.
    let mut stochastic = sys.clone();
    let again = stochastic.productions[0].alternatives[0].clone();
    stochastic.productions[0].alternatives.push(again);
    assert_eq!(plan(&stochastic, 3), Method::Table);
    // A two-symbol context: the general matcher.
    let mut longer = with_context.clone();
    longer.productions[0].left = vec![f, f];
    assert_eq!(plan(&longer, 3), Method::General);
    // A ring makes its ends neighbours: only module rewriting has rings.
    sys.ring = true;
    assert_eq!(plan(&sys, 3), Method::Modules);
    // A production with a condition.
    let mut conditional = std_system("koch-island");
    let mut p: Production = conditional.productions[0].clone();
    p.condition = Some(graftal::ir::program::Expr::Num(1.0));
    p.alternatives = vec![Alternative::new(1.0, Word::from(vec![f, f]))];
    conditional.productions[0] = p;
    assert_eq!(plan(&conditional, 3), Method::Modules);
}

#[test]
fn stats_in_json_name_the_derivation_method() {
    let two = common::temp("two.l");
    std::fs::write(&two, "axiom: ABA\nAB < A --> B\n").unwrap();
    for (file, method) in [
        (two.to_str().unwrap(), "general"),
        ("std:koch-island", "shared tree"),
        ("std:hogeweg-hesper-a", "table"),
        (
            concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/tests/corpus/cpfg/01-Introduction-06-compound-param/leaf.l"
            ),
            "modules",
        ),
        ("std:stochastic-bush", "table"),
    ] {
        let out = graftal(&["stats", file, "--format", "json", "-n", "3"]);
        assert_eq!(out.status, 0, "{}", out.stderr);
        let v: serde_json::Value = serde_json::from_str(&out.stdout).unwrap();
        assert_eq!(v["derivation"], method, "{file}: {}", out.stdout);
    }
}

/// A derivation that must pass `--max-symbols` whatever its random choices
/// is refused before its first step, and one whose growth its contexts
/// decide is refused in the step that passes the limit: no step beyond.
#[test]
fn a_refused_derivation_stops_before_the_work_that_would_pass_the_limit() {
    let opts = RunOptions {
        steps: Some(60),
        max_symbols: 100_000,
        ..RunOptions::default()
    };
    let bush = std_system("stochastic-bush");
    let mut steps_done = 0;
    let err = driver::derive_with_progress(&bush, &opts, |_, _| steps_done += 1).unwrap_err();
    assert_eq!(err.code.0, "E0301");
    assert_eq!(steps_done, 0, "refused only after deriving");
    assert!(err
        .notes
        .iter()
        .any(|n| n.contains("known before deriving")));

    let hh = std_system("hogeweg-hesper-a");
    let mut lengths = Vec::new();
    let err = driver::derive_with_progress(&hh, &opts, |_, len| lengths.push(len)).unwrap_err();
    assert_eq!(err.code.0, "E0301");
    assert!(lengths.iter().all(|&l| l <= 100_000), "{lengths:?}");
    let last = *lengths.last().unwrap();
    assert!(
        last * 2 > 100_000,
        "refused at {last} symbols, far below the limit"
    );
}

/// A context-free picture refused for its moves names how many there are,
/// not the limit: a colour change keeps it off the shared subtrees, which
/// have no such limit.
#[test]
fn a_refused_context_free_picture_names_its_true_number_of_moves() {
    let sys = read("big.l", "axiom: F'F\nF --> FF\n");
    let draw = |n| {
        let req = Request {
            run: RunOptions {
                steps: Some(n),
                ..RunOptions::default()
            },
            width: 64,
            height: 64,
            ..Request::new(Target::Still(Format::Png))
        };
        picture::draw_system(&sys, &req, &mut Quiet)
    };
    let message = |n| match draw(n) {
        Err(DrawError::Stopped(d)) if d.code.0 == "E0303" => (d.message, d.notes),
        other => panic!("n={n}: {:?}", other.map(|p| p.method)),
    };
    // 2 · 2^26 moves; the limit is 30 million.
    let (m, notes) = message(26);
    assert!(m.contains("moves the turtle 134217728 times"), "{m}");
    assert!(
        notes.iter().any(|n| n.contains("step 24 of 26")),
        "{notes:?}"
    );
    // 2^601, past u128: its first digits and power of ten.
    let (m, _) = message(600);
    assert!(m.contains("moves the turtle about 8.2e180 times"), "{m}");
}

/// Drawing's limit is checked before deriving too: when even the fewest
/// moves any random choices make pass `max_moves`, `render` is refused up
/// front; when they may not, the check leaves it to the derivation.
#[test]
fn a_picture_with_too_many_moves_whatever_the_choices_is_refused_before_deriving() {
    let bush = std_system("stochastic-bush");
    let opts = |n| RunOptions {
        steps: Some(n),
        max_moves: 100_000,
        ..RunOptions::default()
    };
    let draw = |n| {
        let req = Request {
            run: opts(n),
            width: 64,
            height: 64,
            ..Request::new(Target::Still(Format::Png))
        };
        picture::draw_system(&bush, &req, &mut Quiet)
    };
    let up_front = |d: &graftal::diagnostics::Diagnostic| {
        d.notes.iter().any(|n| n.contains("known before deriving"))
    };
    // Every alternative of F has at least three Fs: at least 3^11 moves.
    let Err(DrawError::Stopped(err)) = draw(11) else {
        panic!("drawn at 11 steps")
    };
    assert_eq!(err.code.0, "E0303");
    assert!(err.message.contains("at least 177147"), "{}", err.message);
    assert!(up_front(&err), "{err:?}");
    // At 10 steps the check leaves it to the derivation, which may pass.
    match draw(10) {
        Ok(_) => {}
        Err(DrawError::Stopped(d)) => assert!(!up_front(&d), "{d:?}"),
        Err(e) => panic!("{e}"),
    }
}
