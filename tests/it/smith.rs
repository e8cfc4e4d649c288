//! Smith's bracketed 2L-systems (`.smith`): Table 1 of the paper exactly,
//! the 0L example, the stdlib plates, diagnostics with their spans, and
//! branches nailed to their angles.

use graftal::diagnostics::Diagnostics;
use graftal::driver::{self, RunOptions};
use graftal::front::smith;
use graftal::ir::{SymbolId, System};

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
    let table = include_str!("../corpus/smith/table1.txt");
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

/// The words of generations 0..=40 (fewer when they pass `max` symbols),
/// as Smith writes them.
fn generations(sys: &System, max: usize) -> Vec<String> {
    let mut out = Vec::new();
    for n in 0..=40 {
        let opts = RunOptions {
            steps: Some(n),
            max_symbols: max,
            ..RunOptions::default()
        };
        match driver::derive(sys, &opts) {
            Ok(w) => out.push(smith::smith_text(sys, w.symbols())),
            Err(_) => break,
        }
    }
    out
}

/// Translates a Smith text to pfg exactly and checks that the pfg file
/// derives the same words for 40 generations (or while they stay small).
fn derives_the_same_in_pfg(src: &str, max: usize) -> Result<usize, String> {
    use graftal::back::{self, Request};
    let c = driver::compile(graftal::source::SourceFile::new("s.smith", src));
    let sys = c.system.as_ref().ok_or("compiles")?;
    let req = Request {
        target: back::by_name("pfg").ok_or("pfg emitter")?,
        lossy: false,
        steps: None,
    };
    let t = driver::translate(&c, sys, &req);
    let text = t.text.ok_or_else(|| format!("{:?}", t.diagnostics))?;
    let pfg = graftal::front::pfg::read_ok(&text);
    let (a, b) = (generations(sys, max), generations(&pfg, 3 * max));
    let n = a.len().min(b.len());
    if a[..n] != b[..n] {
        return Err(format!("words differ:\n{text}"));
    }
    Ok(n)
}

#[test]
fn every_smith_stdlib_system_derives_the_same_in_pfg_for_40_generations() {
    for e in graftal::stdlib::ENTRIES
        .iter()
        .filter(|e| e.file.ends_with(".smith"))
    {
        let n = derives_the_same_in_pfg(e.text, 1_000_000).unwrap_or_else(|e| panic!("{e}"));
        // The 0L tree of Figure FREETREE quadruples each generation: its
        // words pass a million symbols after 10.
        let all = if e.name.ends_with("cartoon-tree") {
            11
        } else {
            41
        };
        assert_eq!(n, all, "{}", e.name);
    }
}

#[test]
fn random_rule_strings_derive_the_same_in_pfg() {
    use proptest::prelude::*;
    use proptest::test_runner::{Config, TestRunner};
    let mut runner = TestRunner::new(Config {
        cases: 24,
        failure_persistence: None,
        ..Config::default()
    });
    let image = (
        0u8..8,
        1usize..=3,
        proptest::option::of((0u8..4, 1usize..=2)),
    );
    let strategy = (proptest::collection::vec(image, 8), any::<bool>());
    runner
        .run(&strategy, |(images, start)| {
            let bits = |b: u8, n: usize| -> String {
                (0..n)
                    .map(|i| if b >> i & 1 == 1 { '1' } else { '0' })
                    .collect()
            };
            let rules: Vec<String> = images
                .iter()
                .map(|&(b, n, branch)| match branch {
                    Some((c, m)) => format!("{}[{}]", bits(b, n), bits(c, m)),
                    None => bits(b, n),
                })
                .collect();
            let src = format!("rules: {}\naxiom: {}\n", rules.join("."), u8::from(start));
            let n = derives_the_same_in_pfg(&src, 20_000).map_err(TestCaseError::fail)?;
            prop_assert!(n > 5, "{src}: only {n} generations compared");
            Ok(())
        })
        .unwrap();
}

/// The direction of each branch (the sum of the turns on its path from
/// the root, in units of the angle), in word order, with whether its turn
/// is one of `old`.
fn branch_directions(sys: &System, word: &[SymbolId], old: &[SymbolId]) -> Vec<(i64, bool)> {
    let (plus, minus) = (sys.symbols.get("+"), sys.symbols.get("-"));
    let mut stack = vec![0i64];
    let mut out = Vec::new();
    for (i, &s) in word.iter().enumerate() {
        let top = *stack.last().expect("root");
        if s == SymbolId::OPEN {
            stack.push(top);
            continue;
        }
        if s == SymbolId::CLOSE {
            stack.pop();
            continue;
        }
        let name = sys.symbols.name(s);
        let turn = if Some(s) == plus || name == "new+" {
            1
        } else if Some(s) == minus || name == "new-" {
            -1
        } else {
            continue;
        };
        *stack.last_mut().expect("branch") += turn;
        if word[i - 1] == SymbolId::OPEN {
            out.push((top + turn, old.contains(&s)));
        }
    }
    out
}

/// Nailed angles: every branch of generation n is drawn at the same angle
/// in generation n+1. The turns of generation n+1's new branches are
/// renamed (`new+`, `new-`) so that the old branches can be told apart.
#[test]
fn every_branch_keeps_its_angle_in_the_next_generation() {
    let entry = graftal::stdlib::get("smith/with-without").expect("entry");
    let sys = smith::read_ok(entry.text);
    let old: Vec<SymbolId> = ["+", "-"]
        .iter()
        .filter_map(|n| sys.symbols.get(n))
        .collect();
    let mut marked = sys.clone();
    let renamed: Vec<SymbolId> = old
        .iter()
        .map(|&s| {
            let name = format!("new{}", sys.symbols.name(s));
            let id = marked.intern(&name);
            let op = sys.op(s).expect("a turn");
            marked.set_interpretation(id, op);
            id
        })
        .collect();
    for p in &mut marked.productions {
        let w = &mut p.alternatives[0].successor;
        let ids: Vec<SymbolId> = w
            .symbols()
            .iter()
            .map(|s| old.iter().position(|o| o == s).map_or(*s, |k| renamed[k]))
            .collect();
        *w = ids.into();
    }
    let mut compared = 0;
    for n in 5..25 {
        let opts = |steps| RunOptions {
            steps: Some(steps),
            ..RunOptions::default()
        };
        let now = driver::derive(&sys, &opts(n)).expect("derives");
        marked.axiom = now.clone();
        let next = driver::derive(&marked, &opts(1)).expect("derives");
        let before = branch_directions(&sys, now.symbols(), &old);
        let after: Vec<(i64, bool)> = branch_directions(&marked, next.symbols(), &old)
            .into_iter()
            .filter(|b| b.1)
            .collect();
        assert_eq!(before, after, "generation {n}");
        compared += before.len();
    }
    assert!(compared > 100, "{compared}");
}

/// A disc at each branch end (each `]`) and at the end of the main axis;
/// none with `leaf: none`; a segment per 0 or 1.
#[test]
fn leaves_at_branch_ends_and_a_segment_per_symbol() {
    let draw = |src: &str| {
        let sys = smith::read_ok(src);
        let (w, g) = driver::geometry(&sys, &RunOptions::default()).expect("draws");
        (smith::smith_text(&sys, w.symbols()), g)
    };
    let (word, g) = draw("rules: 0.1[1].1.1.0.11.1.0\ngenerations: 10\n");
    assert_eq!(word, "001[11]11[10][001[1]]");
    assert_eq!(g.discs.len(), word.matches(']').count() + 1);
    assert_eq!(g.segments.len(), word.matches(['0', '1']).count());
    let (_, g) = draw("rules: 0.1[1].1.1.0.11.1.0\ngenerations: 10\nleaf: none\n");
    assert!(g.discs.is_empty());
}

/// `roll` turns each branch about its heading: the plant leaves the plane.
#[test]
fn a_roll_draws_in_3d() {
    let z_extent = |src: &str| {
        let sys = smith::read_ok(src);
        let (_, g) = driver::geometry(&sys, &RunOptions::default()).expect("draws");
        g.segments
            .iter()
            .flat_map(|s| [s.a[2], s.b[2]])
            .fold(0f64, |m, z| m.max(z.abs()))
    };
    let flat = "rules: 0.1[1].1.1.0.11.1.0\ngenerations: 20\n";
    assert!(z_extent(flat) < 1e-9);
    assert!(z_extent(&format!("{flat}roll: 90\n")) > 0.5);
}

/// `leaf: flower`: the discs in the flower colour, the stems in another.
#[test]
fn flowers_are_coloured_apart_from_the_stems() {
    let sys = smith::read_ok("rules: 0.1[1].1.1.0.11.1.0\ngenerations: 10\nleaf: flower\n");
    let (_, g) = driver::geometry(&sys, &RunOptions::default()).expect("draws");
    assert_eq!(g.discs.len(), 5);
    let stem = g.segments[0].colour;
    assert!(g.segments.iter().all(|s| s.colour == stem));
    assert!(g.discs.iter().all(|d| d.colour != stem));
}

/// Gene's sizes: a leaf disc of `leaf-size` and a flower of
/// `flower-size` (pixels), the stems `width` wide whatever the leaves.
#[test]
fn leaf_and_flower_sizes_and_the_stem_width_as_gene_sets_them() {
    let draw = |extra: &str| {
        let src = format!("rules: 0.1[1].1.1.0.11.1.0\ngenerations: 10\n{extra}");
        let sys = smith::read_ok(&src);
        let (_, g) = driver::geometry(&sys, &RunOptions::default()).expect("draws");
        let discs: Vec<f64> = g.discs.iter().map(|d| d.diameter).collect();
        let widths: Vec<f64> = g.segments.iter().map(|s| s.width).collect();
        assert_eq!(discs.len(), 5, "{extra}");
        assert!(g.discs.iter().all(|d| d.pixels));
        (discs, widths)
    };
    let all = |v: &[f64], x: f64| v.iter().all(|&y| (y - x).abs() < 1e-12);
    let (discs, widths) = draw("");
    assert!(all(&discs, 3.0) && all(&widths, 1.0));
    let (discs, widths) = draw("leaf-size: 5\nwidth: 2\n");
    assert!(all(&discs, 5.0) && all(&widths, 2.0));
    let (discs, widths) = draw("leaf: flower\n");
    assert!(all(&discs, 8.0) && all(&widths, 1.0));
    let (discs, widths) = draw("leaf: flower\nflower-size: 12\nleaf-size: 2\n");
    assert!(all(&discs, 12.0) && all(&widths, 1.0));
}

/// Gene's "finite set of angles": the j-th branch written (over the rule
/// string's images, and in the axiom) turns by the j-th angle of the list,
/// cyclically, and keeps it.
#[test]
fn an_angles_list_gives_each_branch_its_own_angle() {
    let sys = smith::read_ok(
        "rules: 0.1[1].1.1.0.1[0][1].1.0\nangles: 10, -20 30\naxiom: 1[1][1][1][1]\n",
    );
    let (_, g) = driver::geometry(&sys, &RunOptions::default()).expect("draws");
    let heading = |k: usize| {
        let s = &g.segments[k];
        (s.b[1] - s.a[1]).atan2(s.b[0] - s.a[0]).to_degrees()
    };
    let turns: Vec<f64> = (1..5).map(|k| heading(k) - heading(0)).collect();
    let magnitudes: Vec<i64> = turns.iter().map(|t| t.abs().round() as i64).collect();
    assert_eq!(magnitudes, [10, 20, 30, 10]);
    assert!(turns[0] * turns[1] < 0.0 && turns[0] * turns[2] > 0.0);
    // In the images: 001 -> 1[1] has the list's first angle, the two
    // branches of 101 -> 1[0][1] the second and third.
    let names = |triple: usize| -> Vec<&str> {
        let p = &sys.productions[triple];
        let w = p.alternatives[0].successor.symbols();
        w.iter()
            .map(|&s| sys.symbols.name(s))
            .filter(|n| n.starts_with('a'))
            .collect()
    };
    // Symbol 0's productions come first, in the order of `order`: both
    // neighbours 00, 01, 10, 11.
    assert_eq!(names(1), ["a0"]);
    assert_eq!(names(3), ["a1", "a2"]);
}
