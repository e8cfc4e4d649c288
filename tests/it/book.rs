//! Every example of Prusinkiewicz & Hanan (1989) that gives a string or a
//! count, run through the whole pipeline from the stdlib files.

use graftal::driver::{compile, derive, geometry, load, RunOptions};
use graftal::ir::System;
use graftal::source::SourceFile;
use graftal::turtle::Geometry;
use std::collections::HashSet;

fn system(name: &str) -> System {
    let c = compile(load(&format!("std:{name}")).unwrap());
    assert!(!c.diagnostics.has_errors(), "{name}: {:#?}", c.diagnostics);
    c.system.unwrap()
}

fn words(name: &str, n: u64) -> Vec<String> {
    let sys = system(name);
    (0..=n)
        .map(|k| {
            let opts = RunOptions {
                steps: Some(k),
                ..RunOptions::default()
            };
            derive(&sys, &opts).unwrap().display(&sys.symbols)
        })
        .collect()
}

fn draw(name: &str, n: u64) -> Geometry {
    let sys = system(name);
    let opts = RunOptions {
        steps: Some(n),
        ..RunOptions::default()
    };
    geometry(&sys, &opts).unwrap().1
}

#[test]
fn anabaena_catenula_sequence() {
    // §1.2: a_r, a_l b_r, b_l a_r a_r, a_l a_l b_r a_l b_r, b_l a_r b_l a_r a_r b_l a_r a_r
    // with A = a_r, a = a_l, B = b_r, b = b_l.
    assert_eq!(
        words("anabaena", 4),
        ["A", "aB", "bAA", "aaBaB", "bAbAAbAA"]
    );
}

#[test]
fn algae_and_fibonacci_sequences() {
    // §1.2, Fig. 1.3: b, a, ab, aba, abaab, abaababa, abaababaabaab.
    assert_eq!(
        words("algae", 6),
        ["b", "a", "ab", "aba", "abaab", "abaababa", "abaababaabaab"]
    );
    // §3.1: a -> b, b -> ba gives lengths 1, 1, 2, 3, 5, 8, ...
    let w = words("fibonacci", 12);
    let lengths: Vec<usize> = w.iter().map(String::len).collect();
    for k in 2..lengths.len() {
        assert_eq!(lengths[k], lengths[k - 1] + lengths[k - 2]);
    }
    assert_eq!(&w[..5], ["a", "b", "ba", "bab", "babba"]);
}

#[test]
fn raceme_sequence() {
    // §3.3.1, flower stage F_i written as the digit i.
    assert_eq!(
        words("raceme", 4),
        [
            "A",
            "I[I0]A",
            "I[I1]I[I0]A",
            "I[I2]I[I1]I[I0]A",
            "I[I3]I[I2]I[I1]I[I0]A"
        ]
    );
}

#[test]
fn hormone_diffusion_words() {
    // §3.4: b < a -> b on baaaaaaaa: the hormone propagates one cell per step.
    let w = words("hormone-diffusion", 8);
    for (k, word) in w.iter().enumerate() {
        assert_eq!(*word, format!("{}{}", "b".repeat(k + 1), "a".repeat(8 - k)));
    }
}

#[test]
fn acropetal_and_basipetal_signals() {
    // Fig. 3.12: J < I -> J; the parent branch is the left context of a child.
    assert_eq!(
        words("signal-acropetal", 3),
        [
            "J[I]I[I]I[I]I",
            "J[J]J[I]I[I]I",
            "J[J]J[J]J[I]I",
            "J[J]J[J]J[J]J"
        ]
    );
    // Fig. 3.13: I > J -> J; branches in the way are skipped, so the signal
    // runs down the main axis only.
    assert_eq!(
        words("signal-basipetal", 3),
        [
            "I[I]I[I]I[I]J",
            "I[I]I[I]J[I]J",
            "I[I]J[I]J[I]J",
            "J[I]J[I]J[I]J"
        ]
    );
}

#[test]
fn quadratic_koch_island_has_4_times_8_to_the_n_segments() {
    for n in 0..=5u32 {
        let g = draw("koch-island", n as u64);
        assert_eq!(g.segments.len(), 4 * 8usize.pow(n), "n = {n}");
        // A closed island: the last segment ends where the first began.
        let (first, last) = (g.segments[0].a, g.segments.last().unwrap().b);
        assert!((0..3).all(|k| (first[k] - last[k]).abs() < 1e-6), "n = {n}");
    }
}

/// The grid points a curve of unit segments visits, and its distinct segments.
fn path_stats(g: &Geometry) -> (usize, usize) {
    let key = |p: [f64; 3]| (p[0].round() as i64, p[1].round() as i64);
    let mut points = HashSet::new();
    let mut segs = HashSet::new();
    for s in &g.segments {
        let len = ((s.b[0] - s.a[0]).powi(2) + (s.b[1] - s.a[1]).powi(2)).sqrt();
        assert!((len - 1.0).abs() < 1e-9);
        let (a, b) = (key(s.a), key(s.b));
        points.insert(a);
        points.insert(b);
        segs.insert(if a < b { (a, b) } else { (b, a) });
    }
    (points.len(), segs.len())
}

#[test]
fn space_filling_curves_of_fig_2_7_visit_every_grid_point_once() {
    // (a) Peano, n = 3: 9^n - 1 segments through all 3^n x 3^n points.
    let g = draw("peano", 3);
    assert_eq!(g.segments.len(), 9usize.pow(3) - 1);
    assert_eq!(path_stats(&g), (9usize.pow(3), 9usize.pow(3) - 1));
    // (b) Hilbert, n = 5: 4^n - 1 segments through all 2^n x 2^n points.
    let g = draw("hilbert", 5);
    assert_eq!(g.segments.len(), 4usize.pow(5) - 1);
    assert_eq!(path_stats(&g), (4usize.pow(5), 4usize.pow(5) - 1));
    // (c) Sierpinski square curve, n = 4: X gives 4 f(n-1) + 8 segments, the
    // axiom F+XF+F+XF adds 4: 4 + 2·680.
    let g = draw("sierpinski-square", 4);
    assert_eq!(g.segments.len(), 4 + 2 * 680);
    let (points, segs) = path_stats(&g);
    assert_eq!(segs, g.segments.len(), "no segment is drawn twice");
    assert_eq!(
        points, segs,
        "a closed curve visits as many points as it has segments"
    );
    // (d) Quadratic Gosper curve, n = 2: 25^n segments through a 25 x 25 grid.
    let g = draw("gosper-quadratic", 2);
    assert_eq!(g.segments.len(), 625);
    assert_eq!(path_stats(&g), (626, 625));
}

#[test]
fn sixty_degree_curves_of_fig_2_8() {
    // (a) Sierpinski arrowhead: 3^n segments, none drawn twice.
    for n in 1..=6u32 {
        let g = draw("sierpinski-arrowhead", n as u64);
        assert_eq!(g.segments.len(), 3usize.pow(n));
    }
    // (b) Hexagonal Gosper curve: 7^n segments.
    for n in 1..=4u32 {
        let g = draw("gosper-hexagonal", n as u64);
        assert_eq!(g.segments.len(), 7usize.pow(n));
    }
}

#[test]
fn fig_3_11_data_files_as_printed() {
    let expect = [
        ("a", 30, 16),
        ("b", 30, 16),
        ("c", 26, 14),
        ("d", 24, 14),
        ("e", 30, 16),
    ];
    for (fig, steps, factor) in expect {
        let name = format!("hogeweg-hesper-{fig}");
        let c = compile(load(&format!("std:{name}")).unwrap());
        // The 1988 format exactly: no warning, no error.
        assert!(c.diagnostics.is_empty(), "{name}: {:#?}", c.diagnostics);
        let text = &c.file.text;
        assert!(text.starts_with(&format!("derivation length: {steps}\n")));
        assert!(!text.contains("/*"), "printed files have no comments");
        let sys = c.system.unwrap();
        assert_eq!(sys.settings.steps, Some(steps));
        assert!((sys.settings.delta - (360.0 / factor as f64).to_radians()).abs() < 1e-12);
        assert_eq!(sys.productions.len(), 10);
        let g = geometry(&sys, &RunOptions::default()).unwrap().1;
        assert!(g.segments.len() > 100, "{name} draws a plant");
        assert!(g.max_depth >= 1, "{name} branches");
    }
}

#[test]
fn line_endings_tabs_and_trailing_spaces_do_not_change_the_result() {
    let original = graftal::stdlib::get("hogeweg-hesper-c").unwrap().text;
    let variants = [
        original.replace('\n', "\r\n"),
        original.replace(' ', "\t"),
        original.replace('\n', "   \n"),
        original.trim_end().to_string(),
        original.replace('\n', " \t\r\n").trim_end().to_string(),
    ];
    let result = |text: &str| {
        let c = compile(SourceFile::new("v.l", text));
        assert!(!c.diagnostics.has_errors(), "{:#?}", c.diagnostics);
        let sys = c.system.unwrap();
        let (w, g) = geometry(&sys, &RunOptions::default()).unwrap();
        (w.display(&sys.symbols), g)
    };
    let (w0, g0) = result(original);
    for v in &variants {
        let (w, g) = result(v);
        assert_eq!(w, w0);
        assert_eq!(g, g0);
    }
}
