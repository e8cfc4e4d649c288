//! Smith (SIGGRAPH '84): the string examples of Figures KOCH and
//! SIERPINSKI (`std:smith/koch-star`, `std:smith/arrowhead`), and the growth
//! condition of item 4: the branches common to generations n and n+1 are
//! drawn at the same positions.

use graftal::driver::{self, RunOptions};
use graftal::front::smith;
use graftal::ir::{ContextFilter, SymbolId, System, Word};
use graftal::turtle::Segment;

fn std_system(name: &str) -> System {
    let file = driver::load(&format!("std:{name}")).expect("stdlib entry");
    driver::compile(file).system.expect("compiles")
}

fn opts(n: u64) -> RunOptions {
    RunOptions {
        steps: Some(n),
        ..RunOptions::default()
    }
}

fn word(sys: &System, n: u64) -> String {
    let w = driver::derive(sys, &opts(n)).expect("derives");
    w.display(&sys.symbols).to_string()
}

fn segments(sys: &System, n: u64) -> Vec<Segment> {
    driver::geometry(sys, &opts(n)).expect("draws").1.segments
}

/// A point rounded to 1e-6, so that equal points compare equal.
fn key(p: [f64; 3]) -> [i64; 3] {
    p.map(|x| (x * 1e6).round() as i64)
}

/// The distinct endpoints of `segs`.
fn vertices(segs: &[Segment]) -> Vec<[f64; 3]> {
    let mut out: Vec<[f64; 3]> = Vec::new();
    for p in segs.iter().flat_map(|s| [s.a, s.b]) {
        if !out.iter().any(|q| key(*q) == key(p)) {
            out.push(p);
        }
    }
    out
}

/// Figure KOCH on an equilateral triangle: generation 1 is the Star of
/// David, 12 segments whose 12 corners are 6 outer points on a circle, 60
/// degrees apart, and 6 inner points on a circle sqrt(3) times smaller.
#[test]
fn koch_on_a_triangle_is_a_star_of_david_at_the_first_generation() {
    let sys = std_system("smith/koch-star");
    assert_eq!(word(&sys, 0), "F++F++F");
    assert_eq!(word(&sys, 1), "F-F++F-F++F-F++F-F++F-F++F-F");
    assert_eq!(segments(&sys, 0).len(), 3);
    let segs = segments(&sys, 1);
    assert_eq!(segs.len(), 12);
    let v = vertices(&segs);
    assert_eq!(v.len(), 12);
    let centre = v
        .iter()
        .fold([0.0; 3], |c, p| [0, 1, 2].map(|i| c[i] + p[i] / 12.0));
    let polar = |p: &[f64; 3]| {
        let (x, y) = (p[0] - centre[0], p[1] - centre[1]);
        ((x * x + y * y).sqrt(), y.atan2(x).to_degrees())
    };
    let mut radii: Vec<f64> = v.iter().map(|p| polar(p).0).collect();
    radii.sort_by(f64::total_cmp);
    let (inner, outer) = (radii[0], radii[11]);
    assert!(radii[..6].iter().all(|r| (r - inner).abs() < 1e-9));
    assert!(radii[6..].iter().all(|r| (r - outer).abs() < 1e-9));
    assert!((outer / inner - 3f64.sqrt()).abs() < 1e-9);
    let mut points: Vec<f64> = v
        .iter()
        .filter(|p| (polar(p).0 - outer).abs() < 1e-9)
        .map(|p| polar(p).1)
        .collect();
    points.sort_by(f64::total_cmp);
    for pair in points.windows(2) {
        assert!((pair[1] - pair[0] - 60.0).abs() < 1e-6, "{points:?}");
    }
    // The segments are equal (the turtle's step: the picture is scaled
    // to fit, so a third of the triangle's side as Smith draws it).
    let len = |s: &Segment| {
        (0..3)
            .map(|i| (s.b[i] - s.a[i]).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    assert!(segs.iter().all(|s| (len(s) - len(&segs[0])).abs() < 1e-9));
}

/// Figure SIERPINSKI: two symbols whose spikes turn to opposite sides, so
/// that the sides swap from one generation to the next; the curve of
/// generation n is 3^n segments that never overlap (one symbol turning
/// always to the same side retraces its own segments), all within the
/// arrowhead's triangle.
#[test]
fn sierpinski_arrowhead_swaps_sides_and_never_overlaps() {
    let sys = std_system("smith/arrowhead");
    assert_eq!(word(&sys, 0), "L");
    assert_eq!(word(&sys, 1), "R+L+R");
    assert_eq!(word(&sys, 2), "L-R-L+R+L+R+L-R-L");
    for n in 1..=6u32 {
        let segs = segments(&sys, u64::from(n));
        assert_eq!(segs.len(), 3usize.pow(n));
        assert_eq!(vertices(&segs).len(), 3usize.pow(n) + 1, "generation {n}");
        // The triangle: start, end, and the apex on the turning side.
        let (a, b) = (segs[0].a, segs[segs.len() - 1].b);
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        assert!(((dx * dx + dy * dy).sqrt() - 2f64.powi(n as i32)).abs() < 1e-6);
        let side = |p: [f64; 3], q: [f64; 3], r: [f64; 3]| {
            (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
        };
        let sign = vertices(&segs)
            .iter()
            .map(|&p| side(a, b, p))
            .find(|s| s.abs() > 1e-6)
            .expect("not a line")
            .signum();
        let apex = [
            (a[0] + b[0]) / 2.0 - sign * dy * 3f64.sqrt() / 2.0,
            (a[1] + b[1]) / 2.0 + sign * dx * 3f64.sqrt() / 2.0,
            0.0,
        ];
        for p in vertices(&segs) {
            for (p0, p1) in [(a, b), (b, apex), (apex, a)] {
                assert!(sign * side(p0, p1, p) >= -1e-6, "generation {n}: {p:?}");
            }
        }
    }
}

/// One derivation step of `sys` from `from`, each image preceded by the
/// marker `|` (skipped by the contexts, drawing nothing): where each
/// symbol's image starts.
fn step_marked(sys: &System, from: &Word) -> (System, Word) {
    let mut marked = sys.clone();
    let bar = marked.intern("|");
    if let ContextFilter::Ignore(ids) = &mut marked.context {
        ids.push(bar);
    }
    for p in &mut marked.productions {
        let w = &mut p.alternatives[0].successor;
        let ids: Vec<SymbolId> = std::iter::once(bar)
            .chain(w.symbols().iter().copied())
            .collect();
        *w = ids.into();
    }
    marked.axiom = from.clone();
    let next = driver::derive(&marked, &opts(1)).expect("derives");
    (marked, next)
}

/// For each 0 or 1 of a generation (in word order): the index, among the
/// next generation's segments, of the first segment of its image on the
/// image's own axis, and how many segments that axis has.
fn images(marked: &System, next: &Word) -> Vec<(usize, usize)> {
    let bar = marked.symbols.get("|").expect("marker");
    let bits: Vec<SymbolId> = ["0", "1"]
        .iter()
        .filter_map(|n| marked.symbols.get(n))
        .collect();
    let mut out: Vec<(usize, usize)> = Vec::new();
    let (mut segment, mut depth) = (0, 0usize);
    for &s in next.symbols() {
        if s == bar {
            out.push((usize::MAX, 0));
            depth = 0;
        } else if s == SymbolId::OPEN {
            depth += 1;
        } else if s == SymbolId::CLOSE {
            depth = depth.saturating_sub(1);
        } else if bits.contains(&s) {
            if let Some(last) = out.last_mut().filter(|_| depth == 0) {
                last.0 = last.0.min(segment);
                last.1 += 1;
            }
            segment += 1;
        }
    }
    out
}

/// Item 4: every segment of generation n whose path from the root has not
/// grown (each symbol before it on the path was replaced by one segment and
/// perhaps new branches) is drawn at the very same endpoints in generation
/// n+1 (as the first segment of its image): the branches are nailed, and
/// nothing but growth below a branch moves it.
#[test]
fn branches_common_to_generations_n_and_n_plus_1_are_drawn_at_the_same_positions() {
    let sys = smith::read_ok(
        graftal::stdlib::get("smith/with-without")
            .expect("entry")
            .text,
    );
    let bits: Vec<SymbolId> = ["0", "1"]
        .iter()
        .filter_map(|n| sys.symbols.get(n))
        .collect();
    let mut compared = 0;
    for n in 5..30 {
        let now = driver::derive(&sys, &opts(n)).expect("derives");
        let before = driver::geometry(&sys, &opts(n)).expect("draws").1.segments;
        let (marked, next) = step_marked(&sys, &now);
        let after = graftal::turtle::Run::word(&marked, &next, 0)
            .geometry()
            .segments;
        let map = images(&marked, &next);
        assert_eq!(map.len(), before.len(), "one image per segment");
        // Whether the path to here has grown, per open branch.
        let mut grown = vec![false];
        let mut bit = 0;
        for &s in now.symbols() {
            if s == SymbolId::OPEN {
                grown.push(*grown.last().expect("root"));
            } else if s == SymbolId::CLOSE {
                grown.pop();
            } else if bits.contains(&s) {
                let (first, len) = map[bit];
                let top = grown.last_mut().expect("path");
                if !*top {
                    let (old, new) = (&before[bit], &after[first]);
                    assert_eq!((key(old.a), key(old.b)), (key(new.a), key(new.b)), "n={n}");
                    compared += 1;
                }
                *top |= len != 1;
                bit += 1;
            }
        }
    }
    assert!(compared > 500, "{compared}");
}
