//! The LinF standard library (`stdlib/linf/`, `std:linf/NAME`): every
//! example of Pereira, Rolla, Rezende & Carceroni (2003) compiles cleanly and
//! draws, and each file has the property the paper describes, measured on its
//! geometry.

use graftal::driver::{compile, derive, geometry, load, RunOptions};
use graftal::ir::{Angle, SymbolId, System, TurtleOp, Word};
use graftal::turtle::{Geometry, Vec3};
use std::f64::consts::PI;

/// Every LinF entry, by figure.
const ENTRIES: [&str; 11] = [
    "fig01-koch-curve",
    "fig03-koch-snowflake",
    "fig04-sierpinski-carpet",
    "fig05-peano-curve",
    "fig06-plant",
    "fig07-plant-3d",
    "fig08-tree-3d",
    "fig09-stochastic-plant",
    "fig10-brownian-motion",
    "fig11-feathers",
    "fig12-trees",
];

/// The entries drawn in 3D.
const THREE_D: [&str; 3] = ["fig07-plant-3d", "fig08-tree-3d", "fig09-stochastic-plant"];

fn system(name: &str) -> System {
    let c = compile(load(&format!("std:linf/{name}")).unwrap());
    assert!(
        c.diagnostics.is_empty(),
        "{name}: {}",
        c.diagnostics.render(&c.file, false)
    );
    c.system.unwrap()
}

fn opts(steps: Option<u64>, seed: u64) -> RunOptions {
    RunOptions {
        steps,
        seed,
        ..RunOptions::default()
    }
}

fn draw(sys: &System, steps: Option<u64>, seed: u64) -> (Word, Geometry) {
    geometry(sys, &opts(steps, seed)).unwrap()
}

fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: Vec3) -> f64 {
    dot(a, a).sqrt()
}

fn unit(a: Vec3) -> Vec3 {
    let n = norm(a);
    [a[0] / n, a[1] / n, a[2] / n]
}

/// The angle between two directions, in radians.
fn angle(a: Vec3, b: Vec3) -> f64 {
    dot(unit(a), unit(b)).clamp(-1.0, 1.0).acos()
}

/// `x` wrapped into (-pi, pi].
fn wrap(x: f64) -> f64 {
    let y = x.rem_euclid(2.0 * PI);
    if y > PI {
        y - 2.0 * PI
    } else {
        y
    }
}

/// The bracket depth at which each drawn segment is drawn, in drawing order
/// (the order of `Geometry::segments`).
fn segment_depths(sys: &System, word: &Word) -> Vec<usize> {
    let mut depth = 0usize;
    let mut out = Vec::new();
    for &s in word.symbols() {
        match sys.op(s) {
            Some(TurtleOp::Push) => depth += 1,
            Some(TurtleOp::Pop) => depth -= 1,
            Some(TurtleOp::Forward { draw: true }) => out.push(depth),
            _ => {}
        }
    }
    out
}

/// The number of branches `[` opened at depth 0.
fn top_level_branches(word: &Word) -> usize {
    let mut depth = 0usize;
    let mut n = 0;
    for &s in word.symbols() {
        if s == SymbolId::OPEN {
            if depth == 0 {
                n += 1;
            }
            depth += 1;
        } else if s == SymbolId::CLOSE {
            depth -= 1;
        }
    }
    n
}

/// Direction of every segment at `depth`, and of those at depth 0.
fn directions_at(sys: &System, word: &Word, g: &Geometry, depth: usize) -> Vec<Vec3> {
    let depths = segment_depths(sys, word);
    assert_eq!(depths.len(), g.segments.len());
    g.segments
        .iter()
        .zip(&depths)
        .filter(|(_, &d)| d == depth)
        .map(|(s, _)| unit(sub(s.b, s.a)))
        .collect()
}

#[test]
fn every_entry_compiles_cleanly_derives_and_draws() {
    let listed: Vec<&str> = graftal::stdlib::names()
        .filter_map(|n| n.strip_prefix("linf/"))
        .collect();
    assert_eq!(listed, ENTRIES);
    for name in ENTRIES {
        let sys = system(name);
        let steps = sys.settings.steps;
        assert!(steps.is_some_and(|n| n > 0), "{name}: no `#: steps`");
        let (word, g) = draw(&sys, None, 0);
        assert!(!g.segments.is_empty(), "{name}: nothing drawn");
        assert!(word.len() < 1_000_000, "{name}: {} symbols", word.len());
        // The 3D figures say how to look at them; the 2D ones are seen from
        // the front.
        assert_eq!(
            sys.settings.view.is_some(),
            THREE_D.contains(&name),
            "{name}: {:?}",
            sys.settings.view
        );
    }
}

#[test]
fn every_3d_figure_is_3d() {
    for name in THREE_D {
        let sys = system(name);
        for seed in 0..3 {
            let (_, g) = draw(&sys, None, seed);
            let b = g.bbox().unwrap();
            assert!(b[5] - b[2] > 0.1, "{name} seed {seed}: z extent {:?}", b);
        }
    }
}

#[test]
fn fig10_is_the_printed_listing() {
    let text = graftal::stdlib::get("linf/fig10-brownian-motion")
        .unwrap()
        .text;
    let lines: Vec<String> = text
        .lines()
        .map(|l| l.split('#').next().unwrap())
        .map(|l| l.split_whitespace().collect::<Vec<_>>().join(" "))
        .filter(|l| !l.is_empty())
        .collect();
    assert_eq!(
        lines,
        [
            "lines f",
            "angles (0, [0 2*pi])",
            "axiom f",
            "rules f = f+f"
        ]
    );
    // The default rotation draws its curvature from [0, 2 pi]; each step
    // doubles the walk, whose moves all have length 1.
    let sys = system("fig10-brownian-motion");
    assert_eq!(sys.rotations.len(), 1);
    assert_eq!(sys.rotations[0].torsion, Angle::Radians(0.0));
    assert_eq!(
        sys.rotations[0].curvature,
        Angle::Uniform {
            lo: 0.0,
            hi: 2.0 * PI
        }
    );
    for n in 0..=8u64 {
        let (_, g) = draw(&sys, Some(n), 0);
        assert_eq!(g.segments.len(), 1 << n);
        assert!(g
            .segments
            .iter()
            .all(|s| (norm(sub(s.b, s.a)) - 1.0).abs() < 1e-9));
    }
    // Different seeds, different walks.
    let a = draw(&sys, None, 0).1;
    let b = draw(&sys, None, 1).1;
    assert_ne!(a.segments.last().unwrap().b, b.segments.last().unwrap().b);
}

#[test]
fn koch_snowflake_counts_and_is_closed() {
    let sys = system("fig03-koch-snowflake");
    for n in 0..=5u64 {
        let (_, g) = draw(&sys, Some(n), 0);
        assert_eq!(g.segments.len(), 3 * 4usize.pow(n as u32), "n = {n}");
        let first = g.segments[0].a;
        let last = g.segments.last().unwrap().b;
        for k in 0..3 {
            assert!(
                (first[k] - last[k]).abs() < 1e-9,
                "n = {n}: {first:?} {last:?}"
            );
        }
        // Consecutive segments join: one closed outline.
        for w in g.segments.windows(2) {
            assert!(norm(sub(w[0].b, w[1].a)) < 1e-9);
        }
    }
}

#[test]
fn fig01_is_the_koch_curve_at_60_degrees() {
    let sys = system("fig01-koch-curve");
    assert_eq!(sys.settings.steps, Some(3));
    for n in 1..=3u64 {
        let (_, g) = draw(&sys, Some(n), 0);
        assert_eq!(g.segments.len(), 4usize.pow(n as u32));
        // Every turn is a multiple of 60 degrees.
        for w in g.segments.windows(2) {
            let t = angle(sub(w[0].b, w[0].a), sub(w[1].b, w[1].a));
            let k = (t / (PI / 3.0)).round();
            assert!((t - k * PI / 3.0).abs() < 1e-9, "{t}");
        }
        // The curve runs from the origin to (0, 3^n).
        let end = g.segments.last().unwrap().b;
        assert!(norm(sub(end, [0.0, 3f64.powi(n as i32), 0.0])) < 1e-9);
    }
}

#[test]
fn peano_curve_counts() {
    let sys = system("fig05-peano-curve");
    for n in 0..=4u64 {
        let (_, g) = draw(&sys, Some(n), 0);
        assert_eq!(g.segments.len(), 9usize.pow(n as u32), "n = {n}");
        // A single path, from the origin to (0, 3^n).
        for w in g.segments.windows(2) {
            assert!(norm(sub(w[0].b, w[1].a)) < 1e-9);
        }
        let end = g.segments.last().unwrap().b;
        assert!(norm(sub(end, [0.0, 3f64.powi(n as i32), 0.0])) < 1e-9);
    }
}

#[test]
fn sierpinski_carpet_holes() {
    let sys = system("fig04-sierpinski-carpet");
    for n in 0..=4u32 {
        let (_, g) = draw(&sys, Some(n as u64), 0);
        // The outline (4 sides of 3^n) and, for each step k, 8^(k-1) holes
        // of side 3^(n-k).
        let expected = 4 * 3usize.pow(n)
            + (1..=n)
                .map(|k| 8usize.pow(k - 1) * 4 * 3usize.pow(n - k))
                .sum::<usize>();
        assert_eq!(g.segments.len(), expected, "n = {n}");
        let b = g.bbox().unwrap();
        let side = 3f64.powi(n as i32);
        assert!((b[3] - b[0] - side).abs() < 1e-9 && (b[4] - b[1] - side).abs() < 1e-9);
    }
    // The middle ninth is a hole: no segment crosses its inside.
    let (_, g) = draw(&sys, Some(3), 0);
    let inside = |p: Vec3| {
        p[0] > 9.0 + 1e-9 && p[0] < 18.0 - 1e-9 && p[1] > 9.0 + 1e-9 && p[1] < 18.0 - 1e-9
    };
    for s in &g.segments {
        let mid = [(s.a[0] + s.b[0]) / 2.0, (s.a[1] + s.b[1]) / 2.0, 0.0];
        assert!(!inside(mid), "{s:?}");
    }
}

#[test]
fn fig06_segments_shrink_with_branch_depth() {
    let sys = system("fig06-plant");
    let (word, g) = draw(&sys, None, 0);
    let depths = segment_depths(&sys, &word);
    let max = *depths.iter().max().unwrap();
    assert!(max >= 4, "max depth {max}");
    let mut means = Vec::new();
    for d in 0..=max {
        let lengths: Vec<f64> = g
            .segments
            .iter()
            .zip(&depths)
            .filter(|(_, &k)| k == d)
            .map(|(s, _)| norm(sub(s.b, s.a)))
            .collect();
        means.push(lengths.iter().sum::<f64>() / lengths.len() as f64);
    }
    for d in 0..max {
        assert!(means[d + 1] < means[d], "mean lengths by depth: {means:?}");
    }
    // A segment's length is the product of the reductors on its way from
    // the base: the first segment of a depth-d branch at its base is .55^d.
    let shortest = g
        .segments
        .iter()
        .map(|s| norm(sub(s.b, s.a)))
        .fold(f64::INFINITY, f64::min);
    let factors: [f64; 3] = [0.55, 0.9, 0.85];
    // shortest = .55^a * .9^b * .85^c for some small a, b, c.
    let found = (0..=6).any(|a| {
        (0..=6).any(|b| {
            (0..=6).any(|c| {
                let p = factors[0].powi(a) * factors[1].powi(b) * factors[2].powi(c);
                (p - shortest).abs() < 1e-12
            })
        })
    });
    assert!(found, "shortest segment {shortest}");
}

#[test]
fn fig07_six_secondary_stems_pi_over_3_apart() {
    let sys = system("fig07-plant-3d");
    let (word, g) = draw(&sys, Some(1), 0);
    assert_eq!(top_level_branches(&word), 6);
    let axis = directions_at(&sys, &word, &g, 0);
    assert!(!axis.is_empty());
    let a = axis[0];
    // The main axis is straight.
    for d in &axis {
        assert!(angle(*d, a) < 1e-9);
    }
    let stems = directions_at(&sys, &word, &g, 1);
    assert_eq!(stems.len(), 6);
    // Azimuth of each secondary stem about the main axis, from the first.
    let proj = |d: Vec3| {
        let k = dot(d, a);
        [d[0] - k * a[0], d[1] - k * a[1], d[2] - k * a[2]]
    };
    let p0 = proj(stems[0]);
    let azimuths: Vec<f64> = stems
        .iter()
        .map(|&d| {
            let p = proj(d);
            assert!(norm(p) > 0.1, "a stem along the axis");
            dot(cross(p0, p), a).atan2(dot(p0, p))
        })
        .collect();
    // Consecutive stems (and the last and the first) are pi/3 apart, all
    // turning the same way: six directions making a full turn.
    let steps: Vec<f64> = (0..6)
        .map(|i| wrap(azimuths[(i + 1) % 6] - azimuths[i]))
        .collect();
    for s in &steps {
        assert!((s.abs() - PI / 3.0).abs() < 1e-9, "{steps:?}");
        assert!(s * steps[0] > 0.0, "{steps:?}");
    }
    // Each stem leaves the axis at the same angle.
    for d in &stems {
        assert!((angle(*d, a) - angle(stems[0], a)).abs() < 1e-9);
    }
}

#[test]
fn fig08_ten_main_branches_at_120_and_135_degrees() {
    let sys = system("fig08-tree-3d");
    let (word, g) = draw(&sys, Some(1), 0);
    assert_eq!(top_level_branches(&word), 10);
    let trunk = directions_at(&sys, &word, &g, 0);
    assert!(!trunk.is_empty());
    for d in &trunk {
        assert!(angle(*d, trunk[0]) < 1e-9, "the trunk is straight");
    }
    let branches = directions_at(&sys, &word, &g, 1);
    assert_eq!(branches.len(), 10);
    let angles: Vec<f64> = branches.iter().map(|&d| angle(d, trunk[0])).collect();
    let at = |deg: f64| {
        angles
            .iter()
            .filter(|&&a| (a - deg.to_radians()).abs() < 1e-9)
            .count()
    };
    assert_eq!((at(120.0), at(135.0)), (6, 4), "{angles:?}");
    // Ten distinct directions.
    for i in 0..10 {
        for j in 0..i {
            assert!(angle(branches[i], branches[j]) > 0.1);
        }
    }
    // At the next step every branch is a smaller tree of the same pattern.
    let (word2, g2) = draw(&sys, Some(2), 0);
    assert_eq!(top_level_branches(&word2), 10);
    let twigs = directions_at(&sys, &word2, &g2, 2);
    assert_eq!(twigs.len(), 100);
}

#[test]
fn fig09_guarded_expansion_varies_the_plants() {
    let sys = system("fig09-stochastic-plant");
    let word = |steps: Option<u64>, seed: u64| derive(&sys, &opts(steps, seed)).unwrap();
    // Same seed, same plant; another seed, another plant.
    assert_eq!(word(None, 0), word(None, 0));
    let plants: Vec<Word> = (0..4).map(|s| word(None, s)).collect();
    for i in 0..plants.len() {
        for j in 0..i {
            assert_ne!(plants[i], plants[j], "seeds {i} and {j}");
        }
    }
    // The rule i = [.5?j] is the only one that makes guarded symbols, one
    // per rewriting of `i`.
    let i = sys.symbols.get("i").unwrap();
    let guarded: Vec<SymbolId> = sys
        .symbols
        .iter()
        .filter(|(_, info)| info.guard.is_some())
        .map(|(id, _)| id)
        .collect();
    assert_eq!(guarded.len(), 1);
    let g = guarded[0];
    let guard = sys.symbols.info(g).guard.unwrap();
    assert_eq!(guard.probability, 0.5);
    assert_eq!(sys.symbols.name(guard.base), "j");
    for p in &sys.productions {
        let made = p.alternatives[0]
            .successor
            .0
            .iter()
            .filter(|&&s| s == g)
            .count();
        assert_eq!(made, usize::from(p.predecessor == [i]));
    }
    // So between step s and s+1, the guarded symbols left unexpanded are
    // those of step s+1 that no `i` of step s made.
    let steps = sys.settings.steps.unwrap();
    let count = |w: &Word, s: SymbolId| w.symbols().iter().filter(|&&x| x == s).count();
    for seed in 0..4 {
        let mut kept_total = 0;
        let mut expanded_total = 0;
        for s in 2..steps {
            let (now, next) = (word(Some(s), seed), word(Some(s + 1), seed));
            let kept = count(&next, g) - count(&now, i);
            let expanded = count(&now, g) - kept;
            kept_total += kept;
            expanded_total += expanded;
        }
        assert!(kept_total > 0 && expanded_total > 0, "seed {seed}");
        // Over the run, about half of the chances to expand are taken.
        let ratio = expanded_total as f64 / (kept_total + expanded_total) as f64;
        assert!((0.3..0.7).contains(&ratio), "seed {seed}: {ratio}");
    }
}

#[test]
fn fig11_feather_has_barbs_on_both_sides_that_vary() {
    let sys = system("fig11-feathers");
    // An interval angle models the barbs' imperfections, a guard their size.
    assert!(sys
        .rotations
        .iter()
        .any(|r| matches!(r.curvature, Angle::Uniform { .. })));
    assert!(sys.symbols.iter().any(|(_, info)| info.guard.is_some()));
    let (_, a) = draw(&sys, None, 0);
    let (_, b) = draw(&sys, None, 1);
    // The rachis runs up the y axis; barbs on both sides of it.
    let left = a.segments.iter().filter(|s| s.b[0] < -1e-6).count();
    let right = a.segments.iter().filter(|s| s.b[0] > 1e-6).count();
    assert!(left > 100 && right > 100, "{left} {right}");
    // Two realizations differ.
    assert_ne!(a.segments.len(), b.segments.len());
}

#[test]
fn fig12_two_realizations_differ() {
    let sys = system("fig12-trees");
    let (wa, a) = draw(&sys, None, 0);
    let (wb, b) = draw(&sys, None, 1);
    assert_ne!(wa, wb);
    assert_ne!(a.bbox(), b.bbox());
    // Both are trees: branching, and growing upward from the origin.
    for g in [&a, &b] {
        assert!(g.max_depth >= 5);
        let bb = g.bbox().unwrap();
        assert!(bb[1].abs() < 1e-9 && bb[4] > 3.0, "{bb:?}");
    }
}
