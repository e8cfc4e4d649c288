//! vlab's `ecosystem`: honda81 with the vigor made a radius. Each query is
//! a circle (a sphere in 3D) of radius p1 at the turtle; a circle another
//! at least as large touches or overlaps is answered 0 (so two equal ones
//! that touch both die), the others 1. Circles meet only within a group
//! (p2, truncated; 0 without). In the plane the program uses the turtle's
//! x and z.
//!
//! With `vigor` on, p2 is a vigor instead and all circles are one group:
//! a circle dies under a circle it touches that is more vigorous, or as
//! vigorous and larger, unless that one already died; the queries are
//! decided in the word's order, so an earlier death spares later circles.
//!
//! Only the current step's queries count. Computed in `f32`, as the
//! program does, so that ties fall alike.

use super::{point, Answer, Pass, Query};
use crate::ir::environment::Circles;
use std::collections::HashMap;

pub struct Ecosystem {
    three_d: bool,
    vigor: bool,
}

impl Ecosystem {
    pub fn new(c: &Circles) -> Ecosystem {
        Ecosystem {
            three_d: c.three_d,
            vigor: c.vigor,
        }
    }

    /// The circle of `q`, unless the program drops it: it needs three
    /// coordinates, and the radius (and the vigor, with `vigor` on).
    fn circle(&self, q: &Query) -> Option<Circle> {
        let [x, y, z] = point(q)?;
        let radius = *q.params.first()?;
        let second = q.params.get(1).copied();
        let (vigor, group) = if self.vigor {
            (second?, 0)
        } else {
            (1.0, second.map_or(0, |g| g as i64))
        };
        Some(Circle {
            at: if self.three_d { [x, y, z] } else { [x, z, 0.0] },
            radius,
            vigor,
            group,
        })
    }
}

/// A query the program keeps.
#[derive(Clone, Copy, Debug)]
struct Circle {
    at: [f32; 3],
    radius: f32,
    vigor: f32,
    group: i64,
}

impl Circle {
    /// Whether the two touch or overlap, as the program tests it in `f32`.
    fn touches(&self, o: &Circle) -> bool {
        let d = [0, 1, 2].map(|c| self.at[c] - o.at[c]);
        let reach = self.radius + o.radius;
        d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= reach * reach
    }

    /// Whether `o` kills `self` when vigor is off: as large, and touching.
    fn dominated_by(&self, o: &Circle) -> bool {
        self.group == o.group && self.radius <= o.radius && self.touches(o)
    }

    /// Whether `o` kills `self` when vigor is on (deaths aside).
    fn outgrown_by(&self, o: &Circle) -> bool {
        let stronger = self.vigor < o.vigor || (self.vigor == o.vigor && self.radius < o.radius);
        self.group == o.group && stronger && self.touches(o)
    }
}

impl Pass for Ecosystem {
    fn answer(&mut self, queries: &[Query]) -> Vec<Answer> {
        let circles: Vec<Option<Circle>> = queries.iter().map(|q| self.circle(q)).collect();
        let near = Near::new(&circles);
        let mut dead = vec![false; circles.len()];
        let mut answers = vec![Vec::new(); circles.len()];
        // In the word's order: with vigor on, who died earlier matters.
        for (i, c) in circles.iter().enumerate() {
            let Some(c) = c else { continue };
            let killer = |j: usize| {
                let Some(o) = &circles[j] else { return false };
                j != i
                    && if self.vigor {
                        !dead[j] && c.outgrown_by(o)
                    } else {
                        c.dominated_by(o)
                    }
            };
            dead[i] = near.candidates(i).any(killer);
            answers[i] = vec![Some(if dead[i] { 0.0 } else { 1.0 })];
        }
        answers
    }
}

/// The most cells one circle may cover; a larger one is held against
/// every circle instead.
const MAX_CELLS: f64 = 4096.0;

/// A hash of cells so that a circle is tested against the circles whose
/// boxes share a cell with its box, not against every circle (the
/// program tests all pairs in effect: the answers are the same).
struct Near {
    cell: f64,
    cells: HashMap<[i64; 3], Vec<usize>>,
    /// Circles too large, or too far out, for cells.
    wide: Vec<usize>,
    places: Vec<Place>,
}

/// Where a circle is kept.
#[derive(Clone, Copy)]
enum Place {
    /// It cannot touch anything: a coordinate or the radius is not a
    /// number (every comparison with it fails).
    Nowhere,
    /// In the cells from the first corner to the second, inclusive.
    Cells([i64; 3], [i64; 3]),
    Wide,
}

impl Near {
    fn new(circles: &[Option<Circle>]) -> Near {
        let cell = cell_size(circles);
        let mut near = Near {
            cell,
            cells: HashMap::new(),
            wide: Vec::new(),
            places: Vec::with_capacity(circles.len()),
        };
        for (i, c) in circles.iter().enumerate() {
            let place = c.as_ref().map_or(Place::Nowhere, |c| near.place(c));
            match place {
                Place::Nowhere => {}
                Place::Wide => near.wide.push(i),
                Place::Cells(lo, hi) => {
                    for key in keys(lo, hi) {
                        near.cells.entry(key).or_default().push(i);
                    }
                }
            }
            near.places.push(place);
        }
        near
    }

    /// The cells `c`'s box covers. The box reaches a little beyond the
    /// radius so that the `f32` test, which rounds, never finds a touch
    /// between boxes that do not meet.
    fn place(&self, c: &Circle) -> Place {
        if c.radius.is_nan() || c.at.iter().any(|v| v.is_nan()) {
            return Place::Nowhere;
        }
        // Past 1e18 the squared reach can overflow to infinity in `f32`,
        // which every distance passes.
        let r = f64::from(c.radius).abs();
        if r > 1e18 || c.at.iter().any(|v| v.is_infinite()) {
            return Place::Wide;
        }
        let reach = r * (1.0 + 1e-4) + 1e-18;
        let lo = c.at.map(|v| ((f64::from(v) - reach) / self.cell).floor());
        let hi = c.at.map(|v| ((f64::from(v) + reach) / self.cell).floor());
        let count: f64 = (0..3).map(|k| hi[k] - lo[k] + 1.0).product();
        if count.is_nan() || count > MAX_CELLS {
            return Place::Wide;
        }
        // `as` saturates, and keeps the order: boxes that meet still do.
        Place::Cells(lo.map(|v| v as i64), hi.map(|v| v as i64))
    }

    /// The circles that may touch circle `i` (some more than once).
    fn candidates(&self, i: usize) -> Box<dyn Iterator<Item = usize> + '_> {
        match self.places[i] {
            Place::Nowhere => Box::new(std::iter::empty()),
            Place::Wide => Box::new(0..self.places.len()),
            Place::Cells(lo, hi) => Box::new(
                keys(lo, hi)
                    .flat_map(|k| self.cells.get(&k).into_iter().flatten().copied())
                    .chain(self.wide.iter().copied()),
            ),
        }
    }
}

/// The cells from `lo` to `hi`, inclusive.
fn keys(lo: [i64; 3], hi: [i64; 3]) -> impl Iterator<Item = [i64; 3]> {
    (lo[0]..=hi[0]).flat_map(move |x| {
        (lo[1]..=hi[1]).flat_map(move |y| (lo[2]..=hi[2]).map(move |z| [x, y, z]))
    })
}

/// Cells as wide as the typical circle (twice the median radius), so that
/// most circles cover a few cells and most cells hold a few circles.
fn cell_size(circles: &[Option<Circle>]) -> f64 {
    let kept = || circles.iter().flatten();
    let mut sizes: Vec<f64> = (kept().map(|c| f64::from(c.radius).abs()))
        .filter(|r| *r <= 1e18)
        .collect();
    if sizes.is_empty() {
        return 1.0;
    }
    let mid = sizes.len() / 2;
    let (_, median, _) = sizes.select_nth_unstable_by(mid, f64::total_cmp);
    // Not so small that far circles' cells pass the range of `i64` (they
    // would all share the last one), nor below the boxes' padding.
    let far = (kept().flat_map(|c| c.at).map(|v| f64::from(v).abs()))
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    (2.0 * *median).max(far * 1e-15).max(2e-18)
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::enviro::query_at as q;

    fn with(mut q: Query, p2: f32) -> Query {
        q.params.push(p2);
        q
    }

    fn answers(three_d: bool, vigor: bool, queries: &[Query]) -> Vec<Answer> {
        Ecosystem::new(&Circles { three_d, vigor }).answer(queries)
    }

    fn flat(a: &[Answer]) -> Vec<f32> {
        a.iter()
            .map(|a| a.first().copied().flatten().unwrap_or(-1.0))
            .collect()
    }

    #[test]
    fn the_larger_of_two_touching_circles_survives_and_equal_ones_both_die() {
        let got = answers(
            false,
            false,
            &[
                q(1.0, [0.0; 3]),
                q(0.5, [1.5, 0.0, 0.0]),
                q(0.5, [10.0, 0.0, 0.0]),
            ],
        );
        assert_eq!(got, vec![vec![Some(1.0)], vec![Some(0.0)], vec![Some(1.0)]]);
        // Touching exactly at one point.
        let got = answers(false, false, &[q(0.5, [0.0; 3]), q(0.5, [0.0, 0.0, 1.0])]);
        assert_eq!(flat(&got), [0.0, 0.0]);
        let got = answers(false, false, &[q(0.5, [0.0; 3]), q(0.5, [0.0, 0.0, 1.001])]);
        assert_eq!(flat(&got), [1.0, 1.0]);
    }

    #[test]
    fn in_the_plane_y_does_not_count_and_in_space_it_does() {
        let pair = [q(0.5, [0.0; 3]), q(0.5, [0.0, 5.0, 0.0])];
        assert_eq!(flat(&answers(false, false, &pair)), [0.0, 0.0]);
        assert_eq!(flat(&answers(true, false, &pair)), [1.0, 1.0]);
    }

    #[test]
    fn groups_never_meet_and_incomplete_queries_get_no_answer() {
        let got = answers(
            false,
            false,
            &[
                with(q(0.5, [0.0; 3]), 1.9),
                q(1.0, [0.0; 3]),
                with(q(0.2, [0.0; 3]), 1.0),
                Query {
                    params: vec![1.0],
                    position: vec![0.0, 0.0],
                },
                Query {
                    params: vec![],
                    position: vec![0.0; 3],
                },
            ],
        );
        // Group 1.9 is group 1: the small one dies, the group-0 one lives.
        assert_eq!(flat(&got), [1.0, 1.0, 0.0, -1.0, -1.0]);
        assert_eq!(got[3], vec![]);
    }

    #[test]
    fn with_vigor_an_earlier_death_spares_later_circles() {
        // A chain: a touches b, b touches c, a and c apart; vigor a < b < c.
        let a = with(q(0.5, [0.0; 3]), 1.0);
        let b = with(q(0.5, [0.9, 0.0, 0.0]), 2.0);
        let c = with(q(0.5, [1.8, 0.0, 0.0]), 3.0);
        let got = answers(false, true, &[a.clone(), b.clone(), c.clone()]);
        assert_eq!(flat(&got), [0.0, 0.0, 1.0]);
        // c first kills b before a is decided, so a lives.
        let got = answers(false, true, &[c, b, a.clone()]);
        assert_eq!(flat(&got), [1.0, 0.0, 1.0]);
        // Equal vigor: the smaller dies; equal in both, neither does.
        let big = with(q(0.6, [0.9, 0.0, 0.0]), 1.0);
        assert_eq!(flat(&answers(false, true, &[a.clone(), big])), [0.0, 1.0]);
        let twin = with(q(0.5, [0.9, 0.0, 0.0]), 1.0);
        assert_eq!(flat(&answers(false, true, &[a, twin])), [1.0, 1.0]);
        // Vigor on needs the vigor.
        assert_eq!(answers(false, true, &[q(0.5, [0.0; 3])]), vec![vec![]]);
    }

    #[test]
    fn points_far_out_keep_cells_of_their_own() {
        // Radius 0: only coincident points touch. The cells are sized
        // against the farthest coordinate, not the radius.
        let mut queries: Vec<Query> = (0..20_000)
            .map(|k| q(0.0, [10_000.0 + 0.5 * k as f32, 0.0, 0.0]))
            .collect();
        queries.push(q(0.0, [10_000.0, 9.0, 0.0]));
        let got = flat(&answers(false, false, &queries));
        assert_eq!((got[0], got[1], got[20_000]), (0.0, 1.0, 0.0));
        assert_eq!(got.iter().filter(|&&a| a == 0.0).count(), 2);
    }

    /// The program's rule over all pairs, in the word's order.
    fn all_pairs(vigor: bool, circles: &[Option<Circle>]) -> Vec<f32> {
        let mut dead = vec![false; circles.len()];
        for (i, c) in circles.iter().enumerate() {
            let Some(c) = c else { continue };
            dead[i] = (circles.iter().enumerate()).any(|(j, o)| {
                let Some(o) = o else { return false };
                j != i
                    && if vigor {
                        !dead[j] && c.outgrown_by(o)
                    } else {
                        c.dominated_by(o)
                    }
            });
        }
        (circles.iter().zip(&dead))
            .map(|(c, &d)| match (c, d) {
                (None, _) => -1.0,
                (_, true) => 0.0,
                (_, false) => 1.0,
            })
            .collect()
    }

    /// A few hundred circles from a small linear congruential generator:
    /// the tree.l field (2 × 2, radii 0.01..0.06) with some larger ones,
    /// exact ties, groups, and odd values.
    fn field() -> Vec<Query> {
        let mut s = 12345u64;
        let mut next = move || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 40) as f32 / (1u64 << 24) as f32
        };
        let mut out: Vec<Query> = (0..400)
            .map(|k| {
                let r = if k % 37 == 0 {
                    0.5 * next()
                } else {
                    0.01 + 0.05 * next()
                };
                let at = [2.0 * next(), 2.0 * next(), 2.0 * next()];
                with(q(r, at), (k % 3) as f32 + 0.5 * next())
            })
            .collect();
        // Exact ties: equal circles touching at a point, both ways.
        out.push(with(q(0.25, [3.0, 0.0, 3.0]), 0.0));
        out.push(with(q(0.25, [3.5, 0.0, 3.0]), 0.0));
        out.push(with(q(0.25, [3.0, 7.0, 3.5]), 0.0));
        for odd in [f32::NAN, f32::INFINITY, -0.3, 0.0, 0.0, 1e30] {
            out.push(with(q(odd, [1.0, 1.0, 1.0]), 0.0));
        }
        out.push(q(0.1, [f32::NAN, 1.0, 1.0]));
        out.push(q(0.1, [f32::INFINITY, 1.0, 1.0]));
        out.push(q(0.1, [1e30, 1.0, -1e30]));
        out
    }

    #[test]
    fn the_grid_answers_as_all_pairs_do() {
        let queries = field();
        for three_d in [false, true] {
            for vigor in [false, true] {
                let eco = Ecosystem::new(&Circles { three_d, vigor });
                let circles: Vec<_> = queries.iter().map(|q| eco.circle(q)).collect();
                let want = all_pairs(vigor, &circles);
                let got = flat(&answers(three_d, vigor, &queries));
                assert_eq!(got, want, "3d {three_d}, vigor {vigor}");
                // The field is dense enough that both answers occur.
                assert!(got.contains(&0.0) && got.contains(&1.0));
            }
        }
    }
}
