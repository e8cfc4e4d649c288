//! `obcheck`, the CelticKnot object's program: a turtle's step in the
//! plane, checked against fixed line obstacles. A `?E(0)` marks where a
//! step starts; the next `?E(p)` with p ≠ 0 is where it ends, and is
//! answered 1 when the step meets an obstacle, else 0 (and the step's end
//! becomes the next start). Queries are answered one by one, in the
//! word's order, and the start is kept from one step to the next.
//! Computed in `f32`, as the program does.

use super::{Answer, Pass, Query};
use crate::ir::environment::Obstacles;

/// How far from crossing two segments may be and still meet: the bound
/// on the product of the unnormalized sides (so it does not scale with
/// the segments' lengths).
const TOLERANCE: f32 = 0.1;

#[derive(Clone, Copy, Debug, PartialEq)]
struct Segment {
    a: [f32; 2],
    b: [f32; 2],
}

pub struct Obcheck {
    obstacles: Vec<Segment>,
    /// Where the next step starts (the program's global, at the origin
    /// until a `?E(0)` sets it).
    start: [f32; 2],
}

impl Obcheck {
    pub fn new(o: &Obstacles) -> Obcheck {
        let obstacles = (o.segments.iter())
            .map(|&[xa, ya, xb, yb]| Segment {
                a: [xa as f32, ya as f32],
                b: [xb as f32, yb as f32],
            })
            .collect();
        Obcheck {
            obstacles,
            start: [0.0, 0.0],
        }
    }

    fn one(&mut self, q: &Query) -> Answer {
        // Without a parameter, or a point in the plane, nothing to do.
        let (Some(&p1), [x, y, ..]) = (q.params.first(), &q.position[..]) else {
            return Vec::new();
        };
        if p1 == 0.0 {
            self.start = [*x, *y];
            return vec![None];
        }
        let step = Segment {
            a: self.start,
            b: [*x, *y],
        };
        if self.obstacles.iter().any(|o| meet(&step, o)) {
            return vec![Some(1.0)];
        }
        self.start = step.b;
        vec![Some(0.0)]
    }
}

impl Pass for Obcheck {
    fn answer(&mut self, queries: &[Query]) -> Vec<Answer> {
        queries.iter().map(|q| self.one(q)).collect()
    }
}

/// Which side of `s`'s line `p` lies on, times how far, times `s`'s
/// length: the cross product, unnormalized, as the program has it.
fn side(p: [f32; 2], s: &Segment) -> f32 {
    (p[0] - s.a[0]) * (s.b[1] - s.a[1]) - (p[1] - s.a[1]) * (s.b[0] - s.a[0])
}

/// Whether the segments cross, touch, or nearly do: the ends of each lie
/// on both sides of the other's line, or (within the tolerance) on it.
fn meet(s: &Segment, t: &Segment) -> bool {
    side(s.a, t) * side(s.b, t) <= TOLERANCE && side(t.a, s) * side(t.b, s) <= TOLERANCE
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The corpus's obstacles.dat (20-EnviroPgms-CPFG-CelticKnot): the
    /// borders y = 0 and y = 6, and four H letters, at x = 1, 7, 13, 19,
    /// each two verticals 4 apart over y 1..5 and a bar at y = 3.
    fn knot() -> Obcheck {
        let mut segments = vec![[0.0, 0.0, 24.0, 0.0], [0.0, 6.0, 24.0, 6.0]];
        for a in [1.0, 7.0, 13.0, 19.0] {
            segments.push([a, 1.0, a, 5.0]);
            segments.push([a, 3.0, a + 4.0, 3.0]);
            segments.push([a + 4.0, 1.0, a + 4.0, 5.0]);
        }
        Obcheck::new(&Obstacles { segments })
    }

    fn q(p1: f32, x: f32, y: f32) -> Query {
        Query {
            params: vec![p1],
            position: vec![x, y],
        }
    }

    #[test]
    fn a_step_across_a_bar_is_blocked_and_one_between_bars_is_free() {
        let mut o = knot();
        // Across the left vertical of the first H.
        let got = o.answer(&[q(0.0, 0.5, 2.0), q(1.0, 1.5, 2.0)]);
        assert_eq!(got, vec![vec![None], vec![Some(1.0)]]);
        // Across the crossbar of the second H.
        let got = o.answer(&[q(0.0, 8.0, 2.5), q(1.0, 8.5, 3.5)]);
        assert_eq!(got[1], vec![Some(1.0)]);
        // Between the first H and the second, and along the corridor.
        let got = o.answer(&[q(0.0, 5.5, 2.0), q(1.0, 6.5, 2.0)]);
        assert_eq!(got[1], vec![Some(0.0)]);
        let got = o.answer(&[q(0.0, 0.5, 0.5), q(1.0, 23.5, 0.5)]);
        assert_eq!(got[1], vec![Some(0.0)]);
    }

    #[test]
    fn a_step_ending_near_a_bar_meets_it_by_the_tolerance() {
        let mut o = knot();
        // Sides -2 and -0.04 of the bar x = 1: product 0.08 <= 0.1.
        let got = o.answer(&[q(0.0, 0.5, 2.0), q(1.0, 0.99, 2.0)]);
        assert_eq!(got[1], vec![Some(1.0)]);
        // Sides -2 and -0.4: product 0.8.
        let got = o.answer(&[q(0.0, 0.5, 2.0), q(1.0, 0.9, 2.0)]);
        assert_eq!(got[1], vec![Some(0.0)]);
    }

    #[test]
    fn the_start_moves_after_a_free_step_only_and_outlives_the_pass() {
        let mut o = knot();
        let got = o.answer(&[
            q(0.0, 5.5, 2.0),
            q(1.0, 6.5, 2.0), // free: the start moves to (6.5, 2)
            q(1.0, 7.5, 2.0), // across x = 7: blocked, the start stays
            q(1.0, 6.0, 2.5), // from (6.5, 2): free; from (7.5, 2) it would cross
        ]);
        assert_eq!(flat(&got), [None, Some(0.0), Some(1.0), Some(0.0)]);
        // The next pass starts at (6, 2.5): a step right crosses x = 7.
        let got = o.answer(&[q(1.0, 7.5, 2.5)]);
        assert_eq!(got, vec![vec![Some(1.0)]]);
        let got = o.answer(&[q(2.0, 5.5, 2.5)]);
        assert_eq!(got, vec![vec![Some(0.0)]], "any p1 but 0 is a step");
    }

    #[test]
    fn queries_without_a_parameter_or_a_point_change_nothing() {
        let mut o = knot();
        let got = o.answer(&[
            q(0.0, 5.5, 2.0),
            Query {
                params: vec![0.0],
                position: vec![0.5],
            },
            Query {
                params: vec![],
                position: vec![0.5, 2.0],
            },
            q(1.0, 6.5, 2.0),
            q(1.0, f32::NAN, 2.0),
        ]);
        assert_eq!(got[1..4], [vec![], vec![], vec![Some(0.0)]]);
        // Not a number meets nothing (every comparison fails) and becomes
        // the start, as in the program.
        assert_eq!(got[4], vec![Some(0.0)]);
        // Without obstacles every step is free.
        let mut empty = Obcheck::new(&Obstacles { segments: vec![] });
        assert_eq!(empty.answer(&[q(1.0, 3.0, 3.0)]), vec![vec![Some(0.0)]]);
    }

    fn flat(a: &[Answer]) -> Vec<Option<f32>> {
        a.iter().map(|a| a[0]).collect()
    }
}
