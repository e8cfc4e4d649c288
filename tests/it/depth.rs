//! One depth limit everywhere: nesting that code follows by recursion
//! (parsers, lowering, the walks over expression trees, emitters) goes at
//! most `ir::MAX_NESTING` deep in every notation, and deeper input is one
//! E0013 at the first place past the limit, not a stack overflow. Nesting
//! that is walked with an explicit stack (branches `[ ]` in a word) is not
//! limited.
//!
//! Every test here runs on a test thread (2 MiB of stack, in the test
//! profile's build), so the inputs at the limit also show that the limit
//! fits such a stack. The deep inputs are generated, as the fuzzer made
//! them: 2,000, 5,000 and 100,000 levels.

use crate::common;

use common::{graftal, temp, Out};
use graftal::diagnostics::codes;
use graftal::driver::{compile, Compiled};
use graftal::ir::{Span, MAX_NESTING};
use graftal::source::SourceFile;
use std::time::{Duration, Instant};

const M: usize = MAX_NESTING;

/// How long a deep or huge input may take to be refused: a linear pass
/// takes a fraction of this in a debug build; a hang or a quadratic walk
/// over 100 000 rules takes minutes. Generous because the tests of this
/// file run side by side on a shared 2-core machine.
const QUICK: Duration = Duration::from_secs(3);

fn read(name: &str, text: &str) -> Compiled {
    compile(SourceFile::new(name, text))
}

/// The spans of the E0013 diagnostics.
fn too_deep(c: &Compiled) -> Vec<Span> {
    c.diagnostics
        .iter()
        .filter(|d| d.code == codes::NESTED_TOO_DEEPLY)
        .map(|d| d.span.clone().unwrap_or(0..0))
        .collect()
}

/// Compiles cleanly: a system and no error.
fn clean(c: &Compiled) -> bool {
    c.system.is_some() && !c.diagnostics.has_errors()
}

/// The codes of all diagnostics.
fn codes_of(c: &Compiled) -> Vec<&'static str> {
    c.diagnostics.iter().map(|d| d.code.0).collect()
}

/// Exactly one E0013, at the `len` bytes from `at`; nothing else is an
/// error.
fn one_at(c: &Compiled, at: usize, len: usize) {
    assert_eq!(
        too_deep(c),
        vec![Span::from(at..at + len)],
        "{:?}",
        codes_of(c)
    );
    let others = c
        .diagnostics
        .iter()
        .filter(|d| d.code != codes::NESTED_TOO_DEEPLY && d.is_error())
        .count();
    assert_eq!(others, 0, "{:?}", codes_of(c));
}

/// Where the `n`th (from 1) occurrence of `pat` starts in `text`.
fn nth(text: &str, pat: &str, n: usize) -> usize {
    text.match_indices(pat).nth(n - 1).expect("occurs").0
}

/// `graftal ARGS… FILE` in-process (on the stack the binary has), with `text` as a
/// file named `name`, and how long it took.
fn run(name: &str, text: &str, args: &[&str]) -> (Out, Duration) {
    let path = temp(name);
    std::fs::write(&path, text).unwrap();
    let path = path.to_str().unwrap().to_string();
    let mut argv: Vec<&str> = args.to_vec();
    argv.push(&path);
    let start = Instant::now();
    let out = graftal(&argv);
    (out, start.elapsed())
}

/// A deep input ends with exit 1, within a second, with one E0013 (as JSON
/// diagnostics, to count them).
fn refused_quickly(name: &str, text: &str, command: &str) {
    let (out, took) = run(name, text, &[command, "--format", "json"]);
    assert_eq!(
        out.status,
        1,
        "{name}: {}",
        &out.stderr[..out.stderr.len().min(500)]
    );
    common::assert_within(took, QUICK, name);
    let e0013 = out.stderr.matches("\"code\":\"E0013\"").count();
    assert_eq!(
        e0013,
        1,
        "{name}: {}",
        &out.stderr[..out.stderr.len().min(500)]
    );
}

fn parens(n: usize, inner: &str) -> String {
    format!("{}{inner}{}", "(".repeat(n), ")".repeat(n))
}

// --- cpfg -----------------------------------------------------------------

fn cpfg(axiom: &str) -> String {
    format!("Lsystem: 1\nderivation length: 1\nAxiom: {axiom}\nF(x) --> F(x+1)\nendlsystem\n")
}

#[test]
fn cpfg_parentheses_at_the_limit_read_and_one_more_is_one_error_at_it() {
    // `F(` is the first level.
    let at = cpfg(&format!("F{}", parens(M, "1")));
    assert!(
        clean(&read("at.l", &at)),
        "{:?}",
        codes_of(&read("at.l", &at))
    );
    let past = cpfg(&format!("F{}", parens(M + 1, "1")));
    one_at(&read("past.l", &past), nth(&past, "(", M + 1), 1);
    // Brackets (subscripts) and braces (blocks) are levels alike.
    let subscripts = format!(
        "Lsystem: 1\ndefine: {{ array a[2]; }}\nAxiom: F({}0{})\nendlsystem\n",
        "a[".repeat(M),
        "]".repeat(M)
    );
    let c = read("sub.l", &subscripts);
    one_at(&c, nth(&subscripts, "[", M + 1), 1);
    let block = |n: usize| {
        let nested = format!("{}x = 1;{}", "if (1) {".repeat(n - 1), "}".repeat(n - 1));
        format!("Lsystem: 1\nStart: {{{nested}}}\nAxiom: F(1)\nendlsystem\n")
    };
    // `Start: {` is the first level, each `if (1) {` one more; the
    // condition's `(` is one more again while it is read.
    assert!(clean(&read("block.l", &block(M))));
    let deep = block(M + 1);
    one_at(&read("block.l", &deep), nth(&deep, "(", M), 1);
}

#[test]
fn cpfg_operations_nest_to_the_same_limit() {
    // A sum of 256 terms is 256 deep; the 257th term goes past, and the
    // operator that adds it is where.
    let sum = |n: usize| cpfg(&format!("F({})", vec!["1"; n].join("+")));
    assert!(clean(&read("sum.l", &sum(M))));
    let past = sum(M + 1);
    one_at(&read("sum.l", &past), nth(&past, "+", M), 1);
    let signs = |n: usize| cpfg(&format!("F({}1)", "-".repeat(n)));
    assert!(clean(&read("neg.l", &signs(M - 1))));
    let past = signs(M);
    one_at(&read("neg.l", &past), nth(&past, "-", 1), 1);
    // `?:` nests the parser: the 257th level is the 256th `?` inside `F(`.
    let chain = |n: usize| cpfg(&format!("F({}1{})", "1?".repeat(n), ":1".repeat(n)));
    assert!(clean(&read("tern.l", &chain(M - 1))));
    let past = chain(M + 10);
    one_at(&read("tern.l", &past), nth(&past, "?", M), 1);
}

#[test]
fn cpfg_the_rest_of_the_file_still_reads() {
    // The item past the limit is read without what lies past it: the
    // axiom is still there, and the next production gets its own error.
    let text = format!(
        "Lsystem: 1\nderivation length: 2\nAxiom: F({})\nF(x) --> F(sine(x))\nendlsystem\n",
        parens(M + 500, "1")
    );
    let c = read("rest.l", &text);
    assert_eq!(too_deep(&c).len(), 1);
    assert_eq!(codes_of(&c), ["E0013", "E0832"]);
}

#[test]
fn cpfg_preprocessor_nests_to_the_same_limit() {
    // Macro calls in arguments expand by recursion.
    let calls = |n: usize| {
        format!(
            "#define f(x) x\nLsystem: 1\nAxiom: F({}1{})\nendlsystem\n",
            "f(".repeat(n),
            ")".repeat(n)
        )
    };
    assert!(clean(&read("mac.l", &calls(M))));
    // The 257th call (after the `f(` of the definition) is where.
    let past = calls(M + 1);
    one_at(&read("mac.l", &past), nth(&past, "f(", M + 2), 1);
    let c = read("mac.l", &calls(5000));
    assert_eq!(too_deep(&c).len(), 1, "{:?}", codes_of(&c));
    // Each level holds the arguments inside it: the nesting is counted
    // before that work, which would take gigabytes here.
    refused_quickly("mac.l", &calls(100_000), "check");
    // `#if` conditions are evaluated by recursion.
    let cond = |inner: &str| format!("#if {inner}\n#endif\nLsystem: 1\nAxiom: F(1)\nendlsystem\n");
    assert!(clean(&read("if.l", &cond(&parens(M, "1")))));
    let past = cond(&parens(M + 1, "1"));
    one_at(&read("if.l", &past), nth(&past, "(", M + 1), 1);
    let past = cond(&format!("{}1", "-".repeat(M + 1)));
    one_at(&read("if.l", &past), nth(&past, "-", M + 1), 1);
}

#[test]
fn cpfg_deep_inputs_end_with_exit_1_within_a_second() {
    for n in [2000, 100_000] {
        refused_quickly("p.l", &cpfg(&format!("F{}", parens(n, "1"))), "check");
        refused_quickly("u.l", &cpfg(&format!("A{}", "(".repeat(n))), "derive");
        let sum = cpfg(&format!("F({})", vec!["1"; n].join("+")));
        refused_quickly("s.l", &sum, "check");
    }
}

// --- LinF -----------------------------------------------------------------

fn linf_angle(value: &str) -> String {
    format!("lines f\nangles w = (0, {value})\naxiom f+wf\n")
}

#[test]
fn linf_angles_nest_to_the_limit_and_one_more_is_one_error_at_it() {
    // The rotation's own `(` is the first level.
    assert!(clean(&read("a.linf", &linf_angle(&parens(M - 1, "pi")))));
    let past = linf_angle(&parens(M, "pi"));
    one_at(&read("a.linf", &past), nth(&past, "(", M + 1), 1);
    let sum = |n: usize| linf_angle(&vec!["1"; n].join("+"));
    assert!(clean(&read("s.linf", &sum(M))));
    let past = sum(M + 1);
    one_at(&read("s.linf", &past), nth(&past, "+", M), 1);
    // Colours too.
    let colour = |n: usize| format!("lines f\naxiom f\ncolors (0, {}, 0)\n", parens(n, "1"));
    assert!(clean(&read("c.linf", &colour(M - 1))));
    let past = colour(M);
    one_at(&read("c.linf", &past), nth(&past, "(", M + 1), 1);
}

#[test]
fn linf_the_rest_of_the_file_still_reads() {
    // The deep rotation keeps its name (no error where it is used), and
    // an unknown name elsewhere is reported as usual.
    let text = format!(
        "lines f\nangles w = (0, {})\n  t = (0, pi)\naxiom f+wf-tg\n",
        parens(5000, "1")
    );
    let c = read("rest.linf", &text);
    assert_eq!(too_deep(&c).len(), 1, "{:?}", codes_of(&c));
    assert_eq!(codes_of(&c), ["E0013", "E0402"]);
}

#[test]
fn linf_deep_inputs_end_with_exit_1_within_a_second() {
    for n in [5000, 100_000] {
        refused_quickly("a.linf", &linf_angle(&parens(n, "1")), "check");
        // Brackets in a rotation are an error of their own; the recovery
        // that skips them recursed into them.
        let brackets = linf_angle(&"[".repeat(n));
        let (out, took) = run("b.linf", &brackets, &["check"]);
        assert_eq!(out.status, 1);
        common::assert_within(took, QUICK, "refusing a deep input");
        refused_quickly("s.linf", &linf_angle(&vec!["1"; n].join("+")), "derive");
    }
}

// --- STL ------------------------------------------------------------------

fn stl(rules: &str, seed: &str) -> String {
    format!("ANGLE 30\nB = 1 (0)\nL = 10 (0)\n{rules}SEED\n{seed}\nENDSEED\n")
}

#[test]
fn stl_brackets_and_braces_nest_to_the_limit() {
    let branch = |n: usize| stl(&format!("R1 = {}F{}\n", "[".repeat(n), "]".repeat(n)), "R1");
    assert!(clean(&read("b.stl", &branch(M))));
    let past = branch(M + 1);
    one_at(&read("b.stl", &past), nth(&past, "[", M + 1), 1);
    let terms = |n: usize| {
        stl(
            "R1 = F[+F]\n",
            &format!("{}{}", "R1{".repeat(n), "}".repeat(n)),
        )
    };
    assert!(clean(&read("t.stl", &terms(M))));
    let past = terms(M + 1);
    one_at(&read("t.stl", &past), nth(&past, "{", M + 1), 1);
}

/// Rules `Q0 = Q1F`, `Q1 = Q2F`, … `Q(n-1) = F`: each uses the next.
fn rule_chain(n: usize) -> String {
    let mut rules = String::new();
    for i in 0..n - 1 {
        rules.push_str(&format!("Q{i} = [Q{}]F\n", i + 1));
    }
    rules.push_str(&format!("Q{} = F\n", n - 1));
    stl(&rules, "Q0")
}

#[test]
fn stl_rules_used_through_rules_nest_to_the_limit() {
    // Each rule's body is a bracket around the next rule: two levels
    // each, and the last rule `F` is the 256th.
    let at = rule_chain(M / 2 + 1);
    let c = read("chain.stl", &at);
    assert!(clean(&c), "{:?}", codes_of(&c));
    let past = rule_chain(M / 2 + 2);
    let last = format!("Q{} = [", M / 2);
    one_at(
        &read("chain.stl", &past),
        nth(&past, &last, 1) + last.len() - 1,
        1,
    );
    let (out, took) = run("chain.stl", &rule_chain(100_000), &["check"]);
    assert_eq!(out.status, 1);
    common::assert_within(took, QUICK, "refusing a deep input");
}

#[test]
fn stl_deep_inputs_end_with_exit_1_within_a_second() {
    for n in [1000, 100_000] {
        let rule = stl(&format!("R1 = {}F{}\n", "[".repeat(n), "]".repeat(n)), "R1");
        refused_quickly("r.stl", &rule, "check");
        let seed = stl("R1 = F[+F]\n", &"R1{".repeat(n));
        refused_quickly("s.stl", &seed, "derive");
    }
}

#[test]
fn stl_growth_stops_at_the_limit() {
    // A count of 100,000 levels in an outline with room for all of them
    // grew a chain 100,000 terms deep; it stops at the limit.
    let text = "ANGLE 10\nB = 1 (0)\nL = 1 (0)\nR1 = [I 100000 [F]]\nSEED\nR1\nENDSEED\n\
                LAYOUT\n(clGreen) Rectangle (-5000, 0), 10000, 100000\nENDLAYOUT\n";
    let c = read("grow.stl", text);
    assert!(clean(&c), "{:?}", codes_of(&c));
    let (out, took) = run("grow.stl", text, &["stats"]);
    assert_eq!(out.status, 0, "{}", out.stderr);
    common::assert_within(took, QUICK, "refusing a deep input");
    // Written out, the rule is 100,000 brackets deep: more than STL reads.
    let (out, _) = run("grow.stl", text, &["translate", "--to", "stl"]);
    assert_eq!(out.status, 1);
    assert!(out.stderr.contains("E0013"), "{}", out.stderr);
}

// --- pfg and Fractint: branches are not limited -----------------------------

#[test]
fn pfg_branches_100000_deep_are_read_derived_and_translated() {
    let n = 100_000;
    let text = format!(
        "axiom: {}F{}\nF --> {}F{}\n",
        "[".repeat(n),
        "]".repeat(n),
        "[".repeat(n),
        "]".repeat(n)
    );
    let c = read("deep.l", &text);
    assert!(clean(&c), "{:?}", codes_of(&c));
    for args in [
        &["derive", "-n", "1"][..],
        &["translate", "--to", "pfg", "-n", "1"],
        &["translate", "--to", "linf", "-n", "1"],
        &["stats", "-n", "1"],
    ] {
        let (out, _) = run("deep.l", &text, args);
        assert_eq!(out.status, 0, "{args:?}: {}", out.stderr);
    }
    // The derived word holds the branches nested 200,000 deep.
    let (out, _) = run("deep.l", &text, &["derive", "-n", "1"]);
    assert_eq!(out.stdout.trim().len(), 4 * n + 1);
    // STL reads at most the limit: translating there says so.
    let (out, _) = run("deep.l", &text, &["translate", "--to", "stl", "-n", "1"]);
    assert_eq!(out.status, 1);
    assert!(out.stderr.contains("E0013"), "{}", out.stderr);
}

#[test]
fn linf_and_cpfg_branches_100000_deep_are_read_and_derived() {
    let n = 100_000;
    let branch = format!("{}f{}", "[".repeat(n), "]".repeat(n));
    let linf = format!("lines f\naxiom f\nrules f = {branch}\n");
    let cpfg = format!(
        "Lsystem: 1\nderivation length: 1\nAxiom: F\nF --> {}\nendlsystem\n",
        branch.replace('f', "F")
    );
    for (name, text) in [("deep.linf", linf), ("deep.l", cpfg)] {
        let c = read(name, &text);
        assert!(clean(&c), "{name}: {:?}", codes_of(&c));
        let (out, _) = run(name, &text, &["derive", "-n", "1"]);
        assert_eq!(out.status, 0, "{name}: {}", out.stderr);
        assert_eq!(out.stdout.trim().len(), 2 * n + 1, "{name}");
    }
}

#[test]
fn fractint_branches_100000_deep_are_read_and_derived() {
    let n = 100_000;
    let text = format!(
        "Deep {{\n  Angle 4\n  Axiom F\n  F={}F{}\n}}\n",
        "[".repeat(n),
        "]".repeat(n)
    );
    let c = read("deep.l", &text);
    assert!(
        c.system.is_some() && !c.diagnostics.has_errors(),
        "{:?}",
        codes_of(&c)
    );
    assert!(too_deep(&c).is_empty());
    let (out, _) = run("deep.l", &text, &["derive", "-n", "1"]);
    assert_eq!(out.status, 0, "{}", out.stderr);
    assert_eq!(out.stdout.trim().len(), 2 * n + 1);
}

// --- translating to STL: the steps are written into rules -------------------

#[test]
fn stl_translation_of_f_to_f_at_100000_steps_is_one_counted_rule() {
    let (out, took) = run(
        "f.l",
        "axiom: F\nF --> F\n",
        &["translate", "--to", "stl", "-n", "100000"],
    );
    assert_eq!(out.status, 0, "{}", out.stderr);
    common::assert_within(took, QUICK, "refusing a deep input");
    assert!(
        out.stdout.contains("Plant = [I 100000 F]"),
        "{}",
        out.stdout
    );
    // It reads back, to the one stem F derives to.
    let (back, _) = run("f.stl", &out.stdout, &["derive"]);
    assert_eq!((back.status, back.stdout.trim()), (0, "F"));
    // The file's own derivation length, however large, is the same.
    let huge = "derivation length: 99999999999\naxiom: F\nF --> F\n";
    let (out, _) = run("h.l", huge, &["translate", "--to", "stl"]);
    assert_eq!(out.status, 0, "{}", out.stderr);
    assert!(out.stdout.contains("[I 99999999999 F]"), "{}", out.stdout);
    // A word that doubles each step is too large at once.
    for n in ["1000", "100000"] {
        let (out, took) = run(
            "f.linf",
            "lines f\naxiom f\nrules f = ff\n",
            &["translate", "--to", "stl", "-n", n],
        );
        assert_eq!(out.status, 1);
        common::assert_within(took, QUICK, "refusing a deep input");
        assert!(out.stderr.contains("E0613"), "{}", out.stderr);
    }
}

/// The stems and branches of a word: its `F`s and brackets.
fn stems(word: &str) -> String {
    word.chars()
        .filter(|c| matches!(c, 'F' | '[' | ']'))
        .collect()
}

#[test]
fn stl_translation_derives_what_the_source_derives() {
    let plant = "angle factor: 8\naxiom: X\nX --> F[+X][-X]FX\nF --> FF\n";
    for n in ["1", "3", "5"] {
        let (source, _) = run("plant.l", plant, &["derive", "-n", n]);
        let (out, _) = run("plant.l", plant, &["translate", "--to", "stl", "-n", n]);
        assert_eq!(out.status, 0, "{}", out.stderr);
        let (back, _) = run("plant.stl", &out.stdout, &["derive"]);
        assert_eq!(back.status, 0, "{}", back.stderr);
        assert_eq!(stems(&back.stdout), stems(&source.stdout), "n = {n}");
    }
}

#[test]
fn stl_translation_without_a_count_nests_a_rule_per_step_to_the_limit() {
    // A, B alternate: each step is a rule holding the step before.
    let cycle = "axiom: A\nA --> B\nB --> FA\n";
    let steps = M.to_string();
    let (out, _) = run("cyc.l", cycle, &["translate", "--to", "stl", "-n", &steps]);
    assert_eq!(out.status, 0, "{}", out.stderr);
    let (back, _) = run("cyc.stl", &out.stdout, &["derive"]);
    assert_eq!(back.stdout.trim(), "F".repeat(M / 2));
    for n in [M + 1, 100_000] {
        let (out, took) = run(
            "cyc.l",
            cycle,
            &["translate", "--to", "stl", "-n", &n.to_string()],
        );
        assert_eq!(out.status, 1);
        common::assert_within(took, QUICK, "refusing a deep input");
        assert_eq!(out.stderr.matches("E0013").count(), 1, "{}", out.stderr);
    }
}
