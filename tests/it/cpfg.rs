//! The cpfg dialect of `.l`: parametric derivation checked by hand, and the
//! 95 objects of `tests/corpus/cpfg` read, derived and drawn.

use graftal::diagnostics::Diagnostic;
use graftal::driver::{self, RunOptions};
use graftal::front::Front;
use graftal::source::SourceFile;
use std::path::{Path, PathBuf};

use crate::common;
use common::{check_golden, main_l};

fn compile_text(src: &str) -> driver::Compiled {
    driver::compile(SourceFile::new("test.l", src))
}

/// Each diagnostic of compiling `src`: its code and span.
fn codes_and_spans(src: &str) -> Vec<(&'static str, Option<std::ops::Range<usize>>)> {
    compile_text(src)
        .diagnostics
        .iter()
        .map(|d| (d.code.0, d.span.clone()))
        .collect()
}

fn derive_text(src: &str, steps: u64) -> String {
    let c = compile_text(src);
    let sys = c.system.unwrap_or_else(|| panic!("{:#?}", c.diagnostics));
    let opts = RunOptions {
        steps: Some(steps),
        ..RunOptions::default()
    };
    graftal::front::cpfg::Cpfg.word_text(&sys, &driver::derive(&sys, &opts).unwrap())
}

#[test]
fn parametric_productions_compute_parameters() {
    // The manual's compound leaf with parameters (01-Introduction-06).
    let src = "Lsystem: 1\nderivation length: 2\nAxiom: A\nA --> I(1)[+A][-A]I(1)A\nI(x) --> I(2*x)\nendlsystem\n";
    assert_eq!(
        derive_text(src, 2),
        "I(2)[+I(1)[+A][-A]I(1)A][-I(1)[+A][-A]I(1)A]I(2)I(1)[+A][-A]I(1)A"
    );
}

#[test]
fn conditions_statements_and_context() {
    let src = "lsystem: 1
derivation length: 3
axiom: B(0)A(1)
B(t) < A(x) : {y = x + t;} y < 3 {z = y * 10;} --> A(y)C(z)
A(x) --> D
B(t) --> B(t+1)
endlsystem
";
    // Step 1: A(1) has left context B(0): y = 1 < 3, A(1)C(10).
    assert_eq!(derive_text(src, 1), "B(1)A(1)C(10)");
    // Step 2: y = 1 + 1 = 2 < 3.
    assert_eq!(derive_text(src, 2), "B(2)A(2)C(20)C(10)");
    // Step 3: y = 2 + 2 = 4, the condition fails: the next production.
    assert_eq!(derive_text(src, 3), "B(3)DC(20)C(10)");
}

#[test]
fn cut_decomposition_homomorphism_and_blocks() {
    let src = "lsystem: 1
derivation length: 2
Start: {n = 5;}
EndEach: {n = n + 1;}
axiom: A(0)[X%Y]Z
A(k) --> A(k+n)
decomposition
maximum depth: 3
Z --> QZ
homomorphism
A(k) --> F(k)
endlsystem
";
    // `%` cuts the rest of its branch in every step; Z decomposes three
    // times per step; n is 5 in step 1 and 6 in step 2.
    assert_eq!(derive_text(src, 1), "A(5)[X]QQQZ");
    assert_eq!(derive_text(src, 2), "A(11)[X]QQQQQQZ");
    // The homomorphism draws A(k) as F(k): one segment of length 11.
    let c = compile_text(src);
    let sys = c.system.unwrap();
    let opts = RunOptions {
        steps: Some(2),
        ..RunOptions::default()
    };
    let (w, values) = driver::derive_values(&sys, &opts, |_, _| {}).unwrap();
    let g = driver::interpret(&sys, &w, &values, &opts, false).unwrap();
    assert_eq!(g.segments.len(), 1);
    let s = &g.segments[0];
    let len = (0..3)
        .map(|k| (s.b[k] - s.a[k]).powi(2))
        .sum::<f64>()
        .sqrt();
    assert!((len - 11.0).abs() < 1e-9, "{len}");
}

/// cpfg cuts as it reads the word to rewrite: the `%` a step makes, and
/// what follows it in its branch, stay in that step's word (and are drawn,
/// `interpretation past %` being on by default) until the next step.
#[test]
fn a_cut_made_in_a_step_is_removed_by_the_next() {
    let src = "lsystem: 1\nderivation length: 2\naxiom: [XY]Z\nX --> %\nendlsystem\n";
    assert_eq!(derive_text(src, 1), "[%Y]Z");
    assert_eq!(derive_text(src, 2), "[]Z");
}

#[test]
fn equals_in_a_right_context_skips_the_rest_of_the_branch() {
    // cpfg's `=` (generate.c, RconDiff): skip to the `]` closing the
    // branch; `]` after it closes the branch; `=` binds nothing.
    let src = "Lsystem: 1\nderivation length: 1\nAxiom: F[+DX]G[Y][-DZ]H\n\
               F > [+D=] --> V\nG > [=][-D=] --> W\nendlsystem\n";
    assert_eq!(derive_text(src, 1), "V[+DX]W[Y][-DZ]H");
    let src = "Lsystem: 1\nignore: +\nderivation length: 1\nAxiom: A[+B(1)C]D(2)\n\
               A > [B(y)=]D(z) : y==1 && z==2 --> E(y,z)\nendlsystem\n";
    assert_eq!(derive_text(src, 1), "E(1,2)[+B(1)C]D(2)");
    // Anything but `]` after `=` never matches, and says so at the `=`.
    let src = "Lsystem: 1\nderivation length: 1\nAxiom: A[BC]\nA > [B=C] --> X\nendlsystem\n";
    let warned = codes_and_spans(src);
    let at = src.find("=C]").unwrap();
    assert_eq!(warned, [("W0826", Some(at..at + 1))]);
    assert_eq!(derive_text(src, 1), "A[BC]");
}

#[test]
fn consider_lets_a_right_context_read_out_of_its_branch() {
    // cpfg's `consider:` skips the unlisted brackets on the right
    // (generate.c, RconDiff): B in its branch sees the C after it.
    let with = |filter: &str| {
        format!(
            "Lsystem: 1\n{filter}\nderivation length: 1\nAxiom: A[+B][-B]C(1)\n\
             B > C(x) --> D(x)\nendlsystem\n"
        )
    };
    assert_eq!(derive_text(&with("consider: C"), 1), "A[+D(1)][-D(1)]C(1)");
    // `ignore:` leaves the brackets alone: `]` ends B's context.
    assert_eq!(derive_text(&with("ignore: +-"), 1), "A[+B][-B]C(1)");
    // Listed brackets keep their meaning under `consider:` too.
    assert_eq!(derive_text(&with("consider: C[]"), 1), "A[+B][-B]C(1)");
}

#[test]
fn an_at_command_graftal_does_not_carry_out_is_a_warning_at_its_span() {
    let src = "Lsystem: 1\nderivation length: 0\nAxiom: F@Q(1)F@D(2)@O(1)\nendlsystem\n";
    let warned = codes_and_spans(src);
    assert_eq!(
        warned,
        [
            ("W0823", at_in(src, "@Q(1)")),
            ("W0823", at_in(src, "@D(2)"))
        ]
    );
    // The rest is drawn.
    assert_eq!(derive_text(src, 0), "F@Q(1)F@D(2)@O(1)");
    // A contour with no generalized cylinder to sweep it along.
    let src = "Lsystem: 1\nderivation length: 0\nAxiom: @#(1)FF\nendlsystem\n";
    assert_eq!(codes_and_spans(src), [("W0823", at_in(src, "@#(1)"))]);
    let src = "Lsystem: 1\nderivation length: 0\nAxiom: @#(1)@GsF@Ge\nendlsystem\n";
    assert!(compile_text(src).diagnostics.is_empty());
}

fn at_in(src: &str, m: &str) -> Option<std::ops::Range<usize>> {
    src.find(m).map(|k| k..k + m.len())
}

#[test]
fn stochastic_choice_follows_the_weights_and_the_seed() {
    let src = "lsystem: 1\nseed: 1\nderivation length: 1\naxiom: AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAA\nA --> B : 1\nA --> C : 3\nendlsystem\n";
    let t = derive_text(src, 1);
    let (b, c) = (t.matches('B').count(), t.matches('C').count());
    assert_eq!(b + c, 120);
    assert!((15..=45).contains(&b), "B {b}, C {c}");
    assert_eq!(derive_text(src, 1), t, "same seed, same word");
}

#[test]
fn plus_turns_left_and_parameters_set_angles_and_lengths() {
    let src = "lsystem: 1\nderivation length: 0\naxiom: F(2)+(90)F(1)-F\nendlsystem\n";
    let c = compile_text(src);
    let sys = c.system.unwrap();
    let opts = RunOptions::default();
    let (w, values) = driver::derive_values(&sys, &opts, |_, _| {}).unwrap();
    let g = driver::interpret(&sys, &w, &values, &opts, false).unwrap();
    let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|k| (a[k] - b[k]).abs() < 1e-9);
    assert!(close(g.segments[0].b, [0.0, 2.0, 0.0]));
    // +(90) turns left: towards −x.
    assert!(
        close(g.segments[1].b, [-1.0, 2.0, 0.0]),
        "{:?}",
        g.segments[1]
    );
    // `-` without a parameter turns right by the default 45°.
    let d = 45f64.to_radians();
    assert!(close(g.segments[2].b, [-1.0 - d.cos(), 2.0 + d.sin(), 0.0]));
}

#[test]
fn errors_have_codes_and_spans_and_all_are_reported() {
    let src = "lsystem: 1\naxiom: A(1)\nA(x+1) --> B\nB --> C(foo(2))\nC -> D\nendlsystem\n";
    let c = compile_text(src);
    assert!(c.system.is_none());
    let codes: Vec<&str> = c.diagnostics.iter().map(|d| d.code.0).collect();
    assert!(codes.contains(&"E0831"), "{codes:?}");
    assert!(codes.contains(&"E0832"), "{codes:?}");
    assert!(codes.contains(&"E0005"), "{codes:?}");
    let at =
        |code: &str| -> &Diagnostic { c.diagnostics.iter().find(|d| d.code.0 == code).unwrap() };
    let span = at("E0831").span.clone().unwrap();
    assert_eq!(&src[span], "x+1");
    let span = at("E0832").span.clone().unwrap();
    assert_eq!(&src[span], "foo");
    let span = at("E0005").span.clone().unwrap();
    assert_eq!(&src[span], "->");
}

fn corpus() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus/cpfg");
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(&root)
        .unwrap_or_else(|e| panic!("{}: {e}", root.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_dir())
        .collect();
    dirs.sort();
    dirs
}

/// What happened to one object.
enum Outcome {
    Drawn { modules: usize, segments: usize },
    Refused(Vec<String>),
}

fn run_object(dir: &Path) -> Outcome {
    let Some(l) = main_l(dir) else {
        return Outcome::Refused(vec!["no .l file".into()]);
    };
    let file = SourceFile::read(&l).unwrap();
    let c = driver::compile(file);
    let errors: Vec<String> = c
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| format!("{} {}", d.code, d.message))
        .collect();
    let Some(sys) = c.system else {
        // Every refusal names its construct at a span.
        assert!(
            c.diagnostics
                .iter()
                .filter(|d| d.is_error())
                // A problem in a file beside the `.l` names that file.
                .all(|d| d.span.is_some() || d.side.is_some()),
            "{}: an error without a span: {errors:?}",
            dir.display()
        );
        return Outcome::Refused(errors);
    };
    let opts = RunOptions {
        max_symbols: 2_000_000,
        ..RunOptions::default()
    };
    let (w, values) = match driver::derive_values(&sys, &opts, |_, _| {}) {
        Ok(x) => x,
        Err(d) => return Outcome::Refused(vec![format!("{} {}", d.code, d.message)]),
    };
    let g = match driver::interpret(&sys, &w, &values, &opts, false) {
        Ok(g) => g,
        Err(d) => return Outcome::Refused(vec![format!("{} {}", d.code, d.message)]),
    };
    let _: &graftal::ir::Word = &w;
    let drawn = g.segments.len() + g.polygons.len() + g.discs.len();
    if drawn == 0 {
        // Nothing drawn is never silent: a warning points at the cause
        // (`?E` modules with no environment to answer them).
        assert!(
            c.diagnostics.iter().any(|d| d.span.is_some()),
            "{}: nothing drawn and nothing said",
            dir.display()
        );
    }
    Outcome::Drawn {
        modules: w.len(),
        segments: g.segments.len() + g.polygons.len() + g.discs.len(),
    }
}

#[test]
fn all_but_one_corpus_object_render() {
    let dirs = corpus();
    assert_eq!(dirs.len(), 95);
    let mut drawn = 0;
    let mut refused = Vec::new();
    for d in &dirs {
        match run_object(d) {
            Outcome::Drawn {
                segments: 0,
                modules,
            } => refused.push(format!(
                "{}: {modules} modules and nothing drawn",
                d.file_name().unwrap().to_string_lossy()
            )),
            Outcome::Drawn { .. } => drawn += 1,
            Outcome::Refused(why) => refused.push(format!(
                "{}: {}",
                d.file_name().unwrap().to_string_lossy(),
                why.join("; ")
            )),
        }
    }
    eprintln!("{drawn}/95 drawn; refused:\n{}", refused.join("\n"));
    // The one: an exercise left with `?` blanks. (Sierpinski, whose
    // growth only its environment program decides, grows: graftal runs
    // honda81.)
    assert_eq!(drawn, 94, "{drawn}/95 drawn:\n{}", refused.join("\n"));
}

/// Damaged cpfg files (bytes cut, doubled or replaced at random, from
/// real corpus files) never make graftal panic or hang: each is compiled,
/// and what compiles is derived a few steps and drawn.
#[test]
fn damaged_files_never_panic() {
    use proptest::prelude::*;
    use proptest::test_runner::{Config, TestRunner};
    let texts: Vec<String> = corpus()
        .iter()
        .filter_map(|d| main_l(d))
        .take(40)
        .map(|p| std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display())))
        .collect();
    let mut runner = TestRunner::new(Config {
        cases: 300,
        failure_persistence: None,
        ..Config::default()
    });
    let strategy = (
        0..texts.len(),
        proptest::collection::vec((any::<u16>(), 0u8..3, any::<u8>()), 1..6),
    );
    runner
        .run(&strategy, |(k, edits)| {
            let mut bytes = texts[k].clone().into_bytes();
            for (at, kind, b) in edits {
                if bytes.is_empty() {
                    break;
                }
                let i = at as usize % bytes.len();
                match kind {
                    0 => {
                        bytes.remove(i);
                    }
                    1 => bytes.insert(i, bytes[i]),
                    _ => {
                        let alphabet = b" ()[]{}:;,*<>-+=%?@~#!.0123456789Ax\n\t";
                        bytes[i] = alphabet[b as usize % alphabet.len()];
                    }
                }
            }
            let text = String::from_utf8_lossy(&bytes).into_owned();
            let c = compile_text(&text);
            if let Some(sys) = c.system {
                let opts = RunOptions {
                    steps: Some(sys.settings.steps.unwrap_or(0).min(4)),
                    max_symbols: 200_000,
                    ..RunOptions::default()
                };
                if let Ok((w, values)) = driver::derive_values(&sys, &opts, |_, _| {}) {
                    let _ = driver::interpret(&sys, &w, &values, &opts, false);
                }
            }
            Ok(())
        })
        .unwrap();
}

// ---------------------------------------------------------------------
// Golden derivations of corpus files, checked against an independent
// derivation written here from the manual's rules (§2–§4): modules with
// parameters, context-free productions with optional conditions, parallel
// rewriting, the first applicable production in file order.
// ---------------------------------------------------------------------

/// The corpus files pinned in tests/out/cpfg (context-free, no statement
/// blocks in the productions, object-like macros only).
const GOLDEN: [(&str, u64); 12] = [
    ("01-Introduction-01-quadratic-Koch/fractal.l", 2),
    ("01-Introduction-03-snowflake/fractal.l", 2),
    ("01-Introduction-04-compound/leaf.l", 3),
    ("01-Introduction-05-compound-homo/leaf.l", 3),
    ("01-Introduction-06-compound-param/leaf.l", 3),
    ("01-Introduction-07-fractal-ferns/leaf.l", 9),
    ("01-Introduction-12-alternating/leaf.l", 12),
    ("11-CPFG-Tropisms/lsystem.l", 3),
    ("11-CPFG-ConcavePolygons/fractal.l", 2),
    ("11-CPFG-DragonCurve/fractal.l", 4),
    ("11-CPFG-GeneralizedCylinder/fractal.l", 3),
    ("11-CPFG-Snowflake/fractal.l", 2),
];

/// A tiny expression evaluator over `+ - * / ^`, comparisons, `&& || !`,
/// parentheses, numbers and bound names.
struct Calc<'a> {
    t: Vec<char>,
    i: usize,
    vars: &'a [(String, f64)],
}

impl Calc<'_> {
    fn ws(&mut self) {
        while self.i < self.t.len() && self.t[self.i].is_whitespace() {
            self.i += 1;
        }
    }
    fn eat(&mut self, s: &str) -> bool {
        self.ws();
        let c: Vec<char> = s.chars().collect();
        if self.t[self.i..].starts_with(&c) {
            self.i += c.len();
            true
        } else {
            false
        }
    }
    fn or(&mut self) -> f64 {
        let mut v = self.and();
        while self.eat("||") {
            let w = self.and();
            v = ((v != 0.0) || (w != 0.0)) as u8 as f64;
        }
        v
    }
    fn and(&mut self) -> f64 {
        let mut v = self.cmp();
        while self.eat("&&") {
            let w = self.cmp();
            v = ((v != 0.0) && (w != 0.0)) as u8 as f64;
        }
        v
    }
    fn cmp(&mut self) -> f64 {
        let v = self.sum();
        for op in ["==", "!=", "<=", ">=", "<", ">"] {
            if self.eat(op) {
                let w = self.sum();
                let r = match op {
                    "==" => v == w,
                    "!=" => v != w,
                    "<=" => v <= w,
                    ">=" => v >= w,
                    "<" => v < w,
                    _ => v > w,
                };
                return r as u8 as f64;
            }
        }
        v
    }
    fn sum(&mut self) -> f64 {
        let mut v = self.prod();
        loop {
            if self.eat("+") {
                v += self.prod();
            } else if self.eat("-") {
                v -= self.prod();
            } else {
                return v;
            }
        }
    }
    fn prod(&mut self) -> f64 {
        let mut v = self.pow();
        loop {
            if self.eat("*") {
                v *= self.pow();
            } else if self.eat("/") {
                v /= self.pow();
            } else {
                return v;
            }
        }
    }
    fn pow(&mut self) -> f64 {
        let mut v = self.unary();
        while self.eat("^") {
            v = v.powf(self.unary());
        }
        v
    }
    fn unary(&mut self) -> f64 {
        if self.eat("-") {
            return -self.unary();
        }
        if self.eat("!") {
            return (self.unary() == 0.0) as u8 as f64;
        }
        if self.eat("(") {
            let v = self.or();
            self.eat(")");
            return v;
        }
        self.ws();
        let start = self.i;
        while self.i < self.t.len()
            && (self.t[self.i].is_alphanumeric() || "._".contains(self.t[self.i]))
        {
            self.i += 1;
        }
        let word: String = self.t[start..self.i].iter().collect();
        match word.parse::<f64>() {
            Ok(v) => v,
            Err(_) => self
                .vars
                .iter()
                .find(|(n, _)| *n == word)
                .map_or_else(|| panic!("unbound `{word}`"), |(_, v)| *v),
        }
    }
}

fn calc(expr: &str, vars: &[(String, f64)]) -> f64 {
    Calc {
        t: expr.chars().collect(),
        i: 0,
        vars,
    }
    .or()
}

/// Splits `text` into modules: (symbol, argument texts).
fn modules_of(text: &str) -> Vec<(String, Vec<String>)> {
    let c: Vec<char> = text.chars().filter(|c| !c.is_whitespace()).collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < c.len() {
        let sym = c[i].to_string();
        i += 1;
        let mut args = Vec::new();
        if i < c.len() && c[i] == '(' {
            let (mut depth, mut cur) = (0, String::new());
            i += 1;
            while i < c.len() {
                match c[i] {
                    '(' => {
                        depth += 1;
                        cur.push('(');
                    }
                    ')' if depth == 0 => break,
                    ')' => {
                        depth -= 1;
                        cur.push(')');
                    }
                    ',' if depth == 0 => args.push(std::mem::take(&mut cur)),
                    ch => cur.push(ch),
                }
                i += 1;
            }
            args.push(cur);
            i += 1;
        }
        out.push((sym, args));
    }
    out
}

/// Derives a context-free cpfg file independently of graftal's reader.
fn independent_derivation(src: &str, steps: u64) -> String {
    // Comments, then object-like macros.
    let mut text = String::new();
    let mut rest = src;
    while let Some(k) = rest.find("/*") {
        text.push_str(&rest[..k]);
        rest = rest[k..].find("*/").map_or("", |e| &rest[k + e + 2..]);
    }
    text.push_str(rest);
    let text: String = text
        .lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n");
    let mut macros: Vec<(String, String)> = Vec::new();
    let mut body = String::new();
    for line in text.lines() {
        if let Some(d) = line.trim_start().strip_prefix("#define") {
            let mut w = d.split_whitespace();
            let name = w.next().unwrap().to_string();
            macros.push((name, w.collect::<Vec<_>>().join(" ")));
        } else {
            // Tab-indented lines continue the previous one.
            if line.starts_with('\t') {
                body.push(' ');
            } else {
                body.push('\n');
            }
            body.push_str(line);
        }
    }
    let expand = |s: &str| -> String {
        let mut out = String::new();
        let mut word = String::new();
        let flush = |word: &mut String, out: &mut String| {
            match macros.iter().find(|(n, _)| n == word) {
                Some((_, v)) => out.push_str(&format!("({v})")),
                None => out.push_str(word),
            }
            word.clear();
        };
        for ch in s.chars() {
            if ch.is_alphanumeric() || ch == '_' {
                word.push(ch);
            } else {
                flush(&mut word, &mut out);
                out.push(ch);
            }
        }
        flush(&mut word, &mut out);
        out
    };
    let mut axiom = Vec::new();
    let mut prods: Vec<(String, Vec<String>, Option<String>, String)> = Vec::new();
    for line in body.lines() {
        let l = line.trim();
        let lower = l.to_ascii_lowercase();
        if lower.starts_with("homomorphism") || lower.starts_with("endlsystem") {
            break;
        }
        if let Some(a) = l
            .strip_prefix("axiom:")
            .or_else(|| l.strip_prefix("Axiom:"))
        {
            axiom = modules_of(a);
        } else if let Some((lhs, succ)) = l.split_once("-->") {
            let (pred, cond) = match lhs.split_once(':') {
                Some((p, c)) if c.trim() != "*" => (p, Some(expand(c))),
                Some((p, _)) => (p, None),
                None => (lhs, None),
            };
            let (sym, params) = modules_of(pred).remove(0);
            let succ = if succ.trim() == "*" {
                String::new()
            } else {
                expand(succ)
            };
            prods.push((sym, params, cond, succ));
        }
    }
    let num = |e: &str, vars: &[(String, f64)]| calc(&expand(e), vars);
    let mut word: Vec<(String, Vec<f64>)> = axiom
        .into_iter()
        .map(|(s, a)| (s, a.iter().map(|e| num(e, &[])).collect()))
        .collect();
    for _ in 0..steps {
        let mut next = Vec::new();
        for (sym, args) in &word {
            let applied = prods.iter().find_map(|(ps, params, cond, succ)| {
                if ps != sym || params.len() != args.len() {
                    return None;
                }
                let vars: Vec<(String, f64)> =
                    params.iter().cloned().zip(args.iter().copied()).collect();
                if let Some(c) = cond {
                    if calc(c, &vars) == 0.0 {
                        return None;
                    }
                }
                Some(
                    modules_of(succ)
                        .into_iter()
                        .map(|(s, a)| (s, a.iter().map(|e| calc(e, &vars)).collect()))
                        .collect::<Vec<_>>(),
                )
            });
            match applied {
                Some(m) => next.extend(m),
                None => next.push((sym.clone(), args.clone())),
            }
        }
        word = next;
    }
    let mut out = String::new();
    for (s, a) in word {
        out.push_str(&s);
        if !a.is_empty() {
            let a: Vec<String> = a.iter().map(|v| format!("{v}")).collect();
            out.push_str(&format!("({})", a.join(",")));
        }
    }
    out
}

/// `word` with every parameter in full (`{}`), as the independent
/// derivation prints it.
fn exact_text(sys: &graftal::ir::System, word: &graftal::ir::Word) -> String {
    let mut out = String::new();
    for (i, &id) in word.0.iter().enumerate() {
        out.push_str(sys.symbols.name(id));
        let args: Vec<String> = word.args(i).iter().map(|v| format!("{v}")).collect();
        if !args.is_empty() {
            out.push_str(&format!("({})", args.join(",")));
        }
    }
    out
}

#[test]
fn golden_derivations_of_corpus_files() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut failures = Vec::new();
    for (file, steps) in GOLDEN {
        let path = root.join("tests/corpus/cpfg").join(file);
        let src = std::fs::read_to_string(&path).unwrap();
        let c = driver::compile(SourceFile::read(&path).unwrap());
        let sys = c
            .system
            .unwrap_or_else(|| panic!("{file}: {:#?}", c.diagnostics));
        let opts = RunOptions {
            steps: Some(steps),
            ..RunOptions::default()
        };
        let word = driver::derive(&sys, &opts).unwrap();
        let ours = graftal::front::cpfg::Cpfg.word_text(&sys, &word);
        // Joined prefixed commands (`@O`) print as the characters cpfg reads.
        // The values are compared exactly; `derive` prints them rounded.
        let theirs = independent_derivation(&src, steps);
        assert_eq!(
            exact_text(&sys, &word),
            theirs,
            "{file}: graftal and the independent derivation differ"
        );
        let name = file.split('/').next().unwrap();
        let golden = root.join("tests/out/cpfg").join(format!("{name}.txt"));
        // Blessed only after the assertion above: never a golden the
        // independent derivation disagrees with.
        if let Err(e) = check_golden(&golden, &format!("{ours}\n")) {
            failures.push(e);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn check_says_the_dialect() {
    let path = common::object_file(
        "object",
        "leaf.l",
        "Lsystem: 1\nderivation length: 2\nAxiom: A\nA --> I[+A]A\nhomomorphism\nI --> F\nendlsystem\n",
    );
    let mut out = Vec::new();
    let mut err = Vec::new();
    let mut io = graftal::cli::Io {
        stdout: &mut out,
        stderr: &mut err,
        terminal: false,
        stdout_terminal: false,
    };
    let code = graftal::cli::run(["graftal", "check", path.to_str().unwrap()], &mut io);
    let out = String::from_utf8(out).unwrap();
    assert_eq!(code, 0, "{}", String::from_utf8_lossy(&err));
    assert!(
        out.contains("dialect: cpfg, 1 productions, 0 decomposition, 1 homomorphism"),
        "{out}"
    );
}

/// Side files resolve inside the object's folder: a view file naming a
/// file above it (`..`), an absolute path or a link that leaves the folder
/// gets E0815 and the file is not read; the same file inside is read.
#[test]
fn side_files_stay_inside_the_objects_folder() {
    let src =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus/cpfg/02-Mod-vis-3D-05-monopodial");
    let root = std::env::temp_dir().join(format!("graftal-cpfg-inside-{}", std::process::id()));
    let dir = root.join("object");
    std::fs::create_dir_all(&dir).unwrap();
    for f in [
        "leaf.l",
        "leaf.v",
        "leaf.a",
        "material.mat",
        "internode.func",
        "leaf-length.func",
    ] {
        std::fs::copy(src.join(f), dir.join(f)).unwrap();
    }
    std::fs::copy(src.join("leaf-length.func"), root.join("outside.func")).unwrap();
    let view = std::fs::read_to_string(src.join("leaf.v")).unwrap();
    let check = |named: &str| {
        let v = view.replace("function: leaf-length.func", &format!("function: {named}"));
        std::fs::write(dir.join("leaf.v"), v).unwrap();
        let l = dir.join("leaf.l");
        let o = common::graftal(&["check", "--format", "json", l.to_str().unwrap()]);
        (o.status, o.stdout + &o.stderr)
    };
    let (code, out) = check("leaf-length.func");
    assert_eq!(code, 0, "{out}");
    assert!(!out.contains("E0815"), "{out}");
    let absolute = root.join("outside.func");
    for named in [
        "../outside.func",
        "./../outside.func",
        absolute.to_str().unwrap(),
    ] {
        let (code, out) = check(named);
        assert_eq!(code, 1, "{named}: {out}");
        assert!(
            out.contains("E0815") && out.contains("outside the object"),
            "{named}: {out}"
        );
    }
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(&absolute, dir.join("link.func")).unwrap();
        let (code, out) = check("link.func");
        assert_eq!(code, 1, "{out}");
        assert!(out.contains("E0815"), "{out}");
    }
    let _ = std::fs::remove_dir_all(&root);
}

/// Decomposition and homomorphism recurse to their `maximum depth:` without
/// using the stack: a depth of 200 000 (the test thread has 2 MiB of stack)
/// expands in order, and a rewrite that branches keeps the order of a
/// depth-first expansion.
#[test]
fn maximum_depth_recursion_needs_no_stack() {
    let chain = "lsystem: 1\nderivation length: 1\naxiom: Z\ndecomposition\nmaximum depth: 200000\nZ --> QZ\nendlsystem\n";
    let word = derive_text(chain, 1);
    assert_eq!(word.len(), 200_001);
    assert_eq!(word.matches('Q').count(), 200_000);
    assert!(word.ends_with("QZ"));
    let tree = "lsystem: 1\nderivation length: 1\naxiom: A\ndecomposition\nmaximum depth: 3\nA --> [BA]C\nendlsystem\n";
    assert_eq!(derive_text(tree, 1), "[B[B[BA]C]C]C");
}

/// Every step costs work, however small the word: a block run in each of
/// 99 999 999 999 steps of a word that never grows ends at the work limit
/// (E0302, naming the step) instead of running for hours.
#[test]
fn steps_of_a_word_that_does_not_grow_end_at_the_work_limit() {
    let c = compile_text("Lsystem: 0\nStart: {t=0;}\nEndEach: {t=t+1;}\nAxiom: A\nendlsystem\n");
    let sys = c.system.unwrap();
    let opts = RunOptions {
        steps: Some(99_999_999_999),
        max_symbols: 1_000_000,
        ..RunOptions::default()
    };
    let err = driver::derive(&sys, &opts).unwrap_err();
    assert_eq!(err.code.0, "E0302");
    assert!(
        err.notes.iter().any(|n| n.starts_with("stopped in step ")),
        "{:?}",
        err.notes
    );
}

/// A view file of 40 000 unknown commands: every warning names its file
/// and line, the file indexed once rather than once for each (which took
/// 13 s for 60 000 lines).
#[test]
fn warnings_of_a_long_view_file_name_their_lines_quickly() {
    let dir = std::env::temp_dir().join(format!("graftal-cpfg-long-view-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("x.l"), "Lsystem: 1\nAxiom: F\nendlsystem\n").unwrap();
    std::fs::write(dir.join("x.v"), "bogus line\n".repeat(40_000)).unwrap();
    let started = std::time::Instant::now();
    let c = driver::compile(SourceFile::read(&dir.join("x.l")).unwrap());
    let elapsed = started.elapsed();
    let started = std::time::Instant::now();
    let json = graftal::diagnostics::render_json(&c.diagnostics.0, &c.file);
    let elapsed = elapsed + started.elapsed();
    let last: serde_json::Value = serde_json::from_str(json.lines().last().unwrap()).unwrap();
    assert_eq!(last["line"], 40000, "{last}");
    assert!(last["file"].as_str().unwrap().ends_with("x.v"), "{last}");
    common::assert_within(
        elapsed,
        std::time::Duration::from_secs(3),
        "reading a 40,000-line view file",
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A `surface:` line naming a `.s` file the folder does not have is a
/// warning at that line of the view file (cpfg reads a surface only when
/// its file exists); the module that would draw it draws nothing and
/// leaves the turtle where it is, and the rest draws (11-CPFG-Sedge's
/// `female.v` names `bract.s`, which the object lacks).
#[test]
fn a_missing_surface_file_warns_at_its_view_line_and_draws_nothing() {
    let l = common::object_file(
        "object",
        "plant.l",
        "Lsystem: 1\nderivation length: 0\nAxiom: F ~b(2) F\nendlsystem\n",
    );
    let dir = l.parent().unwrap();
    let view = "angle factor: 8\nsurface: b bract.s 1.5 3 3\n";
    std::fs::write(dir.join("plant.v"), view).unwrap();
    let c = driver::compile(SourceFile::read(&l).unwrap());
    let codes: Vec<&str> = c.diagnostics.iter().map(|d| d.code.0).collect();
    assert_eq!(codes, ["W0813"], "{:#?}", c.diagnostics);
    let d = c.diagnostics.iter().next().unwrap();
    let side = d.side.as_ref().expect("in the view file");
    assert!(side.name.ends_with("plant.v"), "{}", side.name);
    let span = d.span.clone().unwrap();
    assert_eq!(&side.text[span], "surface: b bract.s 1.5 3 3");
    let sys = c.system.expect("the rest is drawn");
    let (_, g) = driver::geometry(&sys, &RunOptions::default()).unwrap();
    assert_eq!(g.segments.len(), 2);
    assert!(g.polygons.is_empty(), "no surface is drawn");
    // `~b` did not move the turtle: the second segment starts where the
    // first ends.
    assert_eq!(g.segments[0].b, g.segments[1].a);
}

/// 11-CPFG-BackgroundScene's `background scene: background.dat` is drawn
/// with the plant: its materials come after the plant's, its shapes are
/// polygons fixed in the world, and a picture of the object shows them
/// (many more pixels than the plant's alone), in PNG and SVG.
#[test]
fn a_background_scene_is_drawn_with_the_model() {
    let dir =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus/cpfg/11-CPFG-BackgroundScene");
    let c = driver::compile(SourceFile::read(&dir.join("plant.l")).unwrap());
    let codes: Vec<&str> = c.diagnostics.iter().map(|d| d.code.0).collect();
    assert!(!codes.contains(&"W0807"), "{codes:?}");
    let sys = c.system.unwrap();
    let scene = &sys.look.scene;
    // A prism (6), a sphere, cylinders and a cone, polygons, a mesh, …
    assert!(scene.len() > 100, "{}", scene.len());
    let lighting = sys.look.lighting.as_ref().unwrap();
    assert!(scene.iter().all(|p| usize::from(p.index) >= 256));
    assert!(scene
        .iter()
        .all(|p| lighting.materials[usize::from(p.index)].is_some()));
    // The ground: `polygon -4 0 -4 …` in the scene's fourth material.
    assert!(scene.iter().any(|p| p.points.len() == 4
        && p.points
            .iter()
            .all(|q| q[1] == 0.0 && q[0].abs() == 4.0 && q[2].abs() == 4.0)));
    let drawn = |sys: &graftal::ir::System, format| {
        let mut req =
            graftal::driver::picture::Request::new(graftal::driver::picture::Target::Still(format));
        (req.width, req.height) = (96, 96);
        graftal::driver::picture::draw_system(sys, &req, &mut graftal::driver::picture::Quiet)
            .unwrap()
            .bytes
    };
    let inked = |png: &[u8]| {
        let pixels = common::rgba_pixels(png);
        pixels.iter().filter(|p| **p != pixels[0]).count()
    };
    let with = inked(&drawn(&sys, graftal::driver::picture::Format::Png));
    let mut bare = sys.clone();
    bare.look.scene.clear();
    let without = inked(&drawn(&bare, graftal::driver::picture::Format::Png));
    assert!(with > 4 * without.max(1), "{with} pixels against {without}");
    let svg = String::from_utf8(drawn(&sys, graftal::driver::picture::Format::Svg)).unwrap();
    let bare_svg = String::from_utf8(drawn(&bare, graftal::driver::picture::Format::Svg)).unwrap();
    assert!(svg.matches("<path").count() > bare_svg.matches("<path").count() + 100);
    // The scene's translucent materials (alpha 0.5) show what is behind.
    assert!(svg.contains(r#"fill-opacity="0.5""#));
    assert!(!bare_svg.contains("fill-opacity"));
}

/// cpfg's `;` and `,` wrap once around its 256 colours (`interpret.c`:
/// an index below the map's start gains 256, one past its end loses
/// 256) and truncate a parameter; a drawn `F` inside `{ }` draws its
/// segment as well as adding a vertex (cpfg passes every `F` to the
/// renderer), an `f` there adds the vertex only, and the turtle's place
/// at `{` is no vertex (04-Signaling-10-mycelis-realistic's heads and
/// pappus).
#[test]
fn colour_steps_wrap_and_polygon_steps_draw_their_edges() {
    let text = "Lsystem: 1\nderivation length: 0\n\
                Axiom: ;(0),F ;(255);F ;(7.9)F {.F f F} \nendlsystem\n";
    let l = common::object_file("wrap", "plant.l", text);
    std::fs::write(l.parent().unwrap().join("plant.v"), "angle factor: 4\n").unwrap();
    let c = driver::compile(SourceFile::read(&l).unwrap());
    let sys = c.system.expect("compiles");
    assert!(sys.settings.cpfg_polygons);
    let (_, g) = driver::geometry(&sys, &RunOptions::default()).unwrap();
    let indices: Vec<u16> = g.segments.iter().map(|s| s.index).collect();
    // 0 - 1 wraps to 255, 255 + 1 to 0, 7.9 is 7; in the polygon the two
    // `F` are drawn, the `f` is not.
    assert_eq!(indices, [255, 0, 7, 7, 7]);
    assert_eq!(g.polygons.len(), 1);
    assert_eq!(g.polygons[0].points.len(), 4, "{:?}", g.polygons[0].points);
}

/// cpfg's `@L("format", …)` writes the text printf makes of its format
/// and values at the turtle's place, in the turtle's colour, over the
/// picture: in the geometry, in SVG as `<text>`, in PNG as pixels of
/// that colour (05-Quantitative-info-flow-03-Borcher-Honda's counts).
#[test]
fn labels_are_written_where_the_turtle_stands() {
    let text = "Lsystem: 1\nderivation length: 1\nAxiom: A(7)\n\
                A(n) --> F(2);(3)@L(\"n=%d, %.1f\", n, n/2);(1)F\nendlsystem\n";
    let l = common::object_file("label", "plant.l", text);
    let dir = l.parent().unwrap();
    std::fs::write(dir.join("plant.v"), "initial color: 1\n").unwrap();
    let c = driver::compile(SourceFile::read(&l).unwrap());
    assert!(
        c.diagnostics.iter().all(|d| d.code.0 != "W0823"),
        "{:#?}",
        c.diagnostics
    );
    let sys = c.system.expect("compiles");
    assert!(sys.writes_labels());
    let (_, g) = driver::geometry(&sys, &RunOptions::default()).unwrap();
    assert_eq!(g.labels.len(), 1);
    assert_eq!(g.labels[0].text, "n=7, 3.5");
    assert_eq!(g.labels[0].at, g.segments[0].b, "where the first F ended");
    let colour = g.labels[0].colour;
    let svg = common::graftal(&["render", l.to_str().unwrap(), "-o", "-", "--to", "svg"]);
    assert!(svg.stdout.contains(">n=7, 3.5</text>"), "{}", svg.stdout);
    let png = common::temp("label.png");
    let out = common::graftal(&["render", l.to_str().unwrap(), "-o", png.to_str().unwrap()]);
    assert_eq!(out.status, 0, "{}", out.stderr);
    let pixels = common::rgba_pixels(&std::fs::read(&png).unwrap());
    let written = pixels
        .iter()
        .filter(|p| [p[0], p[1], p[2]] == [colour.0, colour.1, colour.2])
        .count();
    // Only the label is drawn in its colour (the F after it is colour 1).
    assert!(written > 20, "{written} pixels of the label's colour");
}
