//! The `.gft` standard library (`stdlib/gft/`) and the README's model side
//! by side in four notations.
//!
//! Every `std:gft/…` entry draws a picture of more than trivial geometry;
//! the book's two systems draw what their pfg entries draw; each model that
//! combines older notations shows the combination in its word and its
//! picture, and no emitter of an older notation writes it exactly. The four
//! files of the README's Koch island (`examples/koch-island.{l,linf,stl,gft}`)
//! draw the same segments, and the README shows each file as it is.

use graftal::back::{self, Request};
use graftal::driver::{self, Compiled, RunOptions};
use graftal::ir::System;
use graftal::stdlib::ENTRIES;
use graftal::turtle::{Geometry, Segment};

fn compiled(spec: &str) -> Compiled {
    let c = driver::compile(driver::load(spec).unwrap_or_else(|e| panic!("{spec}: {e:?}")));
    assert!(!c.diagnostics.has_errors(), "{spec}: {:?}", c.diagnostics);
    c
}

fn system(c: &Compiled) -> &System {
    c.system.as_ref().expect("compiles")
}

fn options(steps: Option<u64>, seed: u64) -> RunOptions {
    RunOptions {
        steps,
        seed,
        ..RunOptions::default()
    }
}

/// The word (as the file writes it) and the picture at `steps` and `seed`.
fn run(c: &Compiled, steps: Option<u64>, seed: u64) -> (String, Geometry) {
    let sys = system(c);
    let (word, g) = driver::geometry(sys, &options(steps, seed)).expect("evaluates");
    (c.word_text(sys, &word), g)
}

/// The picture of the word derived with `seed`, drawn with `draw_seed`
/// (random angles are drawn when the word is interpreted).
fn drawn_with(c: &Compiled, seed: u64, draw_seed: u64) -> Geometry {
    let sys = system(c);
    let (word, values) = driver::derive_values(sys, &options(None, seed), |_, _| {}).unwrap();
    driver::interpret(sys, &word, &values, &options(None, draw_seed), false).unwrap()
}

fn gft_entries() -> impl Iterator<Item = &'static graftal::stdlib::Entry> {
    ENTRIES.iter().filter(|e| e.name.starts_with("gft/"))
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() <= tol)
}

/// The same segments in the same order, each endpoint within 1e-9 of the
/// picture's size; `mirror` negates x in `b` first.
fn same_segments(a: &[Segment], b: &[Segment], mirror: bool) -> Result<(), String> {
    if a.len() != b.len() {
        return Err(format!("{} segments against {}", a.len(), b.len()));
    }
    let size = a
        .iter()
        .flat_map(|s| [s.a, s.b])
        .flat_map(|p| p.into_iter())
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(1.0);
    let flip = |p: [f64; 3]| if mirror { [-p[0], p[1], p[2]] } else { p };
    for (k, (s, t)) in a.iter().zip(b).enumerate() {
        if !close(s.a, flip(t.a), 1e-9 * size) || !close(s.b, flip(t.b), 1e-9 * size) {
            return Err(format!("segment {k}: {s:?} against {t:?}"));
        }
    }
    Ok(())
}

#[test]
fn every_gft_entry_draws_more_than_trivial_geometry() {
    let names: Vec<&str> = gft_entries().map(|e| e.name).collect();
    assert_eq!(names.len(), 6, "{names:?}");
    for e in gft_entries() {
        assert!(e.file.ends_with(".gft"), "{}", e.file);
        let c = compiled(&format!("std:{}", e.name));
        let (_, g) = run(&c, None, 0);
        assert!(g.segments.len() >= 100, "{}: {}", e.name, g.segments.len());
        let b = g.bbox().expect("something drawn");
        let wide = (0..3).filter(|&i| b[i + 3] - b[i] > 1.0).count();
        assert!(wide >= 2, "{}: {b:?}", e.name);
        assert!(!e.figure().is_empty(), "{} has a figure", e.name);
        if !["gft/koch-island", "gft/hogeweg-hesper-a"].contains(&e.name) {
            assert!(e.figure().starts_with("new: "), "{}", e.name);
        }
    }
}

#[test]
fn the_koch_island_is_five_lines_and_the_books_island_mirrored() {
    let e = ENTRIES
        .iter()
        .find(|e| e.name == "gft/koch-island")
        .unwrap();
    assert!(e.text.lines().count() <= 5, "{}", e.text);
    let (_, gft) = run(&compiled("std:gft/koch-island"), None, 0);
    let (_, pfg) = run(&compiled("std:koch-island"), None, 0);
    assert_eq!(gft.segments.len(), 4 * 8usize.pow(3));
    // ABOP's `-` turns left where the book's pfg `+` turns right.
    same_segments(&gft.segments, &pfg.segments, true).unwrap();
}

#[test]
fn fig_3_11a_in_gft_derives_what_pfg_derives() {
    let gft = compiled("std:gft/hogeweg-hesper-a");
    let pfg = compiled("std:hogeweg-hesper-a");
    let (wg, gg) = run(&gft, None, 0);
    let (wp, gp) = run(&pfg, None, 0);
    assert_eq!(wg, wp);
    same_segments(&gg.segments, &gp.segments, false).unwrap();
}

/// The word with every branch `[…]` removed: the main axis.
fn main_axis(word: &str) -> String {
    let mut depth = 0usize;
    let mut out = String::new();
    for c in word.chars() {
        match c {
            '[' => depth += 1,
            ']' => depth = depth.saturating_sub(1),
            _ if depth == 0 => out.push(c),
            _ => {}
        }
    }
    out
}

#[test]
fn the_signal_flowers_the_main_apex_at_step_9_and_angles_are_random() {
    let c = compiled("std:gft/signal-plant-3d");
    let apex = |n: u64| main_axis(&run(&c, Some(n), 0).0);
    for n in 0..9 {
        assert!(!apex(n).ends_with('K'), "step {n}: {}", apex(n));
    }
    assert!(apex(8).ends_with('A') || apex(8).ends_with('B'));
    assert!(apex(9).ends_with("p!K"), "{}", apex(9));
    // Once flowered, the main axis no longer grows.
    assert_eq!(apex(9).matches('J').count(), apex(12).matches('J').count());
    // Context makes the signal: without it, no internode is reached.
    let (word, g) = run(&c, None, 0);
    assert!(
        word.contains("rJ") && word.contains("gI"),
        "reached and not yet"
    );
    let colours: std::collections::HashSet<u16> = g.segments.iter().map(|s| s.index).collect();
    assert_eq!(colours.len(), 2, "reached and unreached internodes");
    assert!(!g.discs.is_empty(), "flowers");
    // The word does not depend on the seed; the Frenet intervals do.
    assert_eq!(run(&c, None, 1).0, word);
    let other = drawn_with(&c, 0, 1);
    assert_eq!(other.segments.len(), g.segments.len());
    assert!(same_segments(&g.segments, &other.segments, false).is_err());
    assert!(
        g.bbox().is_some_and(|b| b[5] - b[2] > 1.0),
        "3D: {:?}",
        g.bbox()
    );
}

#[test]
fn the_stochastic_tree_chooses_by_seed_scales_by_parameter_and_turns_at_random() {
    let c = compiled("std:gft/stochastic-tree");
    let words: std::collections::HashSet<String> = (0..4).map(|s| run(&c, None, s).0).collect();
    assert!(words.len() > 1, "the weighted alternatives choose by seed");
    let g = drawn_with(&c, 0, 0);
    let length = |s: &Segment| {
        (0..3)
            .map(|i| (s.b[i] - s.a[i]).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    let mut lengths: Vec<f64> = g.segments.iter().map(length).collect();
    lengths.sort_by(f64::total_cmp);
    lengths.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    assert!(
        lengths.len() >= 8,
        "parameters set the lengths: {lengths:?}"
    );
    assert!((lengths.last().unwrap() - 1.0).abs() < 1e-9);
    let widths: std::collections::HashSet<u64> =
        g.segments.iter().map(|s| s.width.to_bits()).collect();
    assert!(widths.len() >= 5, "parameters set the widths");
    assert!(!g.discs.is_empty(), "leaves");
    let redrawn = drawn_with(&c, 0, 1);
    assert!(same_segments(&g.segments, &redrawn.segments, false).is_err());
}

#[test]
fn the_two_heading_curve_colours_each_segment_and_turns_its_real_heading() {
    let c = compiled("std:gft/two-heading-curve");
    let (_, g) = run(&c, None, 0);
    let colours: std::collections::HashSet<u16> = g.segments.iter().map(|s| s.index).collect();
    assert!(colours.len() >= 4, "{colours:?}");
    let changes = g
        .segments
        .windows(2)
        .filter(|w| w[0].colour != w[1].colour)
        .count();
    assert!(changes * 5 > g.segments.len(), "{changes} colour changes");
    // Directions in degrees: the dragon's on the square grid, the rungs'
    // on the real heading's 15-degree steps.
    let direction = |s: &Segment| {
        let d = (s.b[1] - s.a[1]).atan2(s.b[0] - s.a[0]).to_degrees();
        (d.rem_euclid(360.0) * 1e6).round() / 1e6
    };
    let off_grid: std::collections::HashSet<u64> = g
        .segments
        .iter()
        .map(direction)
        .filter(|d| (d / 90.0 - (d / 90.0).round()).abs() > 1e-6)
        .map(|d| d.to_bits())
        .collect();
    assert!(
        off_grid.len() >= 12,
        "{} directions off the grid",
        off_grid.len()
    );
    let other = run(&c, None, 1).1;
    assert_ne!(
        g.segments.iter().map(|s| s.colour).collect::<Vec<_>>(),
        other.segments.iter().map(|s| s.colour).collect::<Vec<_>>()
    );
}

#[test]
fn no_older_notation_writes_the_combined_models() {
    for name in ["signal-plant-3d", "stochastic-tree", "two-heading-curve"] {
        let c = compiled(&format!("std:gft/{name}"));
        for to in ["pfg", "linf", "stl"] {
            let t = driver::translate(
                &c,
                system(&c),
                &Request {
                    target: back::by_name(to).unwrap(),
                    lossy: false,
                    steps: None,
                },
            );
            assert!(!t.is_exact(), "{name} written exactly in {to}");
        }
    }
}

const EXAMPLES: [&str; 4] = [
    "koch-island.l",
    "koch-island.linf",
    "koch-island.stl",
    "koch-island.gft",
];

#[test]
fn the_readme_koch_island_draws_the_same_in_four_notations() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/");
    let pictures: Vec<Geometry> = EXAMPLES
        .iter()
        .map(|f| run(&compiled(&format!("{dir}{f}")), None, 0).1)
        .collect();
    assert_eq!(pictures[0].segments.len(), 2048);
    for (f, g) in EXAMPLES.iter().zip(&pictures).skip(1) {
        same_segments(&pictures[0].segments, &g.segments, false)
            .unwrap_or_else(|e| panic!("{f}: {e}"));
    }
}

/// A file without its leading comment (`/* … */`, or `# ` lines: LinF's
/// `#:` lines are settings and stay).
fn body(text: &str) -> &str {
    if text.starts_with("/*") {
        return text.split_once("*/\n").map_or(text, |(_, rest)| rest);
    }
    let mut rest = text;
    while rest.starts_with("# ") || rest.starts_with("#\n") {
        rest = rest.split_once('\n').map_or("", |(_, r)| r);
    }
    rest
}

#[test]
fn the_readme_shows_each_koch_island_file_as_it_is() {
    let readme = include_str!("../../README.md");
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/");
    for f in EXAMPLES {
        let text = std::fs::read_to_string(format!("{dir}{f}")).unwrap();
        let shown = body(&text);
        assert!(shown.lines().count() >= 3, "{f}: {shown}");
        assert!(readme.contains(shown), "README shows examples/{f} as it is");
        assert!(
            readme.contains(&format!("examples/{f}")),
            "README names {f}"
        );
    }
}

/// `F-F-F-F`, `F -> F-F+F+FF-F-F+F` is ABOP's Fig. 1.6 (Prusinkiewicz &
/// Hanan 1989, Fig. 2.2); ABOP's Fig. 1.7b is the quadratic snowflake.
#[test]
fn the_koch_island_is_labelled_with_its_figure() {
    for file in [
        "README.md",
        "docs/gft.md",
        "stdlib/gft/INDEX.md",
        "stdlib/gft/koch-island.gft",
        "tests/corpus/gft/koch-island.gft",
    ] {
        let path = format!("{}/{file}", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(path).unwrap();
        let labels: Vec<&str> = (text.lines())
            .filter(|l| l.to_lowercase().contains("koch island") && l.contains("Fig."))
            .collect();
        assert!(!labels.is_empty(), "{file}");
        for line in labels {
            let abop_ok = !line.contains("ABOP") || line.contains("ABOP Fig. 1.6");
            assert!(abop_ok && !line.contains("1.7b"), "{file}: {line}");
        }
    }
}

/// Two trees competing for light: with the environment answering, shaded
/// apices stop (each with a leaf), most where the crowns meet, so the
/// trees draw far fewer segments than the same file without its
/// `environment` line, where every apex forks as a full symmetric tree.
#[test]
fn light_competition_thins_the_crowns_where_they_meet() {
    let c = compiled("std:gft/light-competition");
    let lit = c.system.clone().expect("it compiles");
    assert!(
        lit.environment.is_some(),
        "the file's environment line is read"
    );
    let mut dark = lit.clone();
    dark.environment = None;
    let opts = RunOptions::default();
    let (_, with) = driver::geometry(&lit, &opts).unwrap();
    let (_, without) = driver::geometry(&dark, &opts).unwrap();
    // Without answers: two trees forking 9 times, each a trunk and
    // 2 + 4 + … + 2^9 internodes.
    assert_eq!(without.segments.len(), 2 * (1 + 1022));
    assert!(
        without.discs.is_empty(),
        "no apex stops without the environment"
    );
    assert!(
        with.segments.len() * 2 < without.segments.len(),
        "{} segments with the light against {}",
        with.segments.len(),
        without.segments.len()
    );
    assert!(!with.discs.is_empty(), "shaded apices bear leaves");
    // The crowns meet in the middle (x = 0): leaves there, and the two
    // trees mirror each other, as their light does.
    let near_middle = with
        .discs
        .iter()
        .filter(|d| d.centre[0].abs() < 3.0)
        .count();
    assert!(near_middle > 0, "leaves where the crowns meet");
    let left = with.segments.iter().filter(|s| s.a[0] < 0.0).count();
    let right = with.segments.len() - left;
    assert!(
        left.abs_diff(right) * 10 <= with.segments.len(),
        "{left} against {right}"
    );
}
