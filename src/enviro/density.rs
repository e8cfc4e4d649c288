//! vlab's `honda81`: collision by vigor, after Honda's 1981 model of
//! branching. Each query is a point with a vigor (its first parameter) and
//! a group (its second, truncated; 0 without). A query is answered 0 when
//! another query of its group, at least as vigorous, lies within the
//! radius (so two of equal vigor block each other), else 1. Only the
//! queries of the current step count: nothing is kept between steps.
//! Computed in `f32`, as the program does, so that ties fall alike.

use super::{point, Answer, Pass, Query};
use crate::ir::environment::Density;
use std::collections::HashMap;

pub struct Honda81 {
    radius2: f32,
    three_d: bool,
}

impl Honda81 {
    pub fn new(d: &Density) -> Honda81 {
        let r = d.radius as f32;
        Honda81 {
            radius2: r * r,
            three_d: d.three_d,
        }
    }
}

/// A query the program keeps: where, how vigorous, which group.
struct Tip {
    at: [f32; 3],
    vigor: f32,
    group: i64,
}

impl Pass for Honda81 {
    fn answer(&mut self, queries: &[Query]) -> Vec<Answer> {
        // A query without a point in space or a vigor is not answered.
        let tips: Vec<Option<Tip>> = (queries.iter())
            .map(|q| {
                let [x, y, z] = point(q)?;
                Some(Tip {
                    // In the plane, the program compares the turtle's x and z.
                    at: if self.three_d { [x, y, z] } else { [x, z, 0.0] },
                    vigor: *q.params.first()?,
                    group: q.params.get(1).map_or(0, |&g| g as i64),
                })
            })
            .collect();
        let grid = Grid::new(&tips, self.radius2.sqrt());
        tips.iter()
            .enumerate()
            .map(|(i, tip)| match tip {
                None => Vec::new(),
                Some(t) => vec![Some(if grid.blocked(i, t, &tips, self.radius2) {
                    0.0
                } else {
                    1.0
                })],
            })
            .collect()
    }
}

/// The tips in cells as wide as the radius, so that a tip is held against
/// the tips of the cells around it, not against every tip (the program
/// compares all pairs; the answers are the same).
struct Grid {
    cell: f32,
    cells: HashMap<[i64; 3], Vec<usize>>,
}

impl Grid {
    fn new(tips: &[Option<Tip>], radius: f32) -> Grid {
        // A radius of 0 blocks only tips at the same point: any cell size
        // keeps those together.
        let cell = if radius > 0.0 && radius.is_finite() {
            radius
        } else {
            1.0
        };
        let mut grid = Grid {
            cell,
            cells: HashMap::new(),
        };
        for (i, t) in tips.iter().enumerate() {
            if let Some(t) = t {
                grid.cells.entry(grid.key(t.at)).or_default().push(i);
            }
        }
        grid
    }

    fn key(&self, p: [f32; 3]) -> [i64; 3] {
        // `as` saturates: a point too far to count keeps a cell of its own.
        p.map(|c| (c / self.cell).floor() as i64)
    }

    /// Whether another tip of `t`'s group, at least as vigorous, is within
    /// the radius of `t` (the `i`-th query).
    fn blocked(&self, i: usize, t: &Tip, tips: &[Option<Tip>], radius2: f32) -> bool {
        let [kx, ky, kz] = self.key(t.at);
        let near = |k: i64| k.saturating_sub(1)..=k.saturating_add(1);
        near(kx).any(|x| {
            near(ky).any(|y| {
                near(kz).any(|z| {
                    (self.cells.get(&[x, y, z]).into_iter().flatten()).any(|&j| {
                        let o = tips[j].as_ref().expect("only tips are in cells");
                        j != i
                            && o.group == t.group
                            && t.vigor <= o.vigor
                            && distance2(t.at, o.at) <= radius2
                    })
                })
            })
        })
    }
}

fn distance2(a: [f32; 3], b: [f32; 3]) -> f32 {
    let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::enviro::query_at as q;

    fn answers(three_d: bool, radius: f64, queries: &[Query]) -> Vec<Answer> {
        Honda81::new(&Density { radius, three_d }).answer(queries)
    }

    #[test]
    fn the_more_vigorous_of_two_near_tips_grows_and_equals_block_each_other() {
        let got = answers(
            true,
            1.0,
            &[
                q(0.5, [0.0; 3]),
                q(0.9, [0.5, 0.5, 0.0]),
                q(0.5, [5.0, 0.0, 0.0]),
            ],
        );
        assert_eq!(got, vec![vec![Some(0.0)], vec![Some(1.0)], vec![Some(1.0)]]);
        let got = answers(true, 1.0, &[q(0.5, [0.0; 3]), q(0.5, [1.0, 0.0, 0.0])]);
        assert_eq!(
            got,
            vec![vec![Some(0.0)], vec![Some(0.0)]],
            "at the radius exactly"
        );
    }

    #[test]
    fn in_the_plane_y_is_not_compared_but_z_is() {
        let got = answers(
            false,
            1.0,
            &[q(0.5, [0.0, 0.0, 0.0]), q(0.5, [0.0, 9.0, 0.0])],
        );
        assert_eq!(got[0], vec![Some(0.0)]);
        let got = answers(
            false,
            1.0,
            &[q(0.5, [0.0, 0.0, 0.0]), q(0.5, [0.0, 0.0, 9.0])],
        );
        assert_eq!(got[0], vec![Some(1.0)]);
    }

    #[test]
    fn groups_never_meet_and_queries_without_a_point_get_no_answer() {
        let mut a = q(0.5, [0.0; 3]);
        a.params.push(1.0);
        let got = answers(
            true,
            1.0,
            &[
                a,
                q(0.5, [0.0; 3]),
                Query {
                    params: vec![1.0],
                    position: vec![0.0, 0.0],
                },
            ],
        );
        assert_eq!(got, vec![vec![Some(1.0)], vec![Some(1.0)], vec![]]);
    }

    #[test]
    fn the_grid_answers_as_all_pairs_do() {
        // A lattice of tips at spacings around the radius.
        let queries: Vec<Query> = (0..400)
            .map(|k| {
                q(
                    ((k * 7) % 5) as f32 * 0.1,
                    [(k % 20) as f32 * 0.37, (k / 20) as f32 * 0.41, 0.0],
                )
            })
            .collect();
        let radius2 = 0.5f32 * 0.5;
        let brute: Vec<Answer> = (queries.iter().enumerate())
            .map(|(i, a)| {
                let hit = (queries.iter().enumerate()).any(|(j, b)| {
                    let (pa, pb) = (point(a).unwrap(), point(b).unwrap());
                    j != i && a.params[0] <= b.params[0] && distance2(pa, pb) <= radius2
                });
                vec![Some(if hit { 0.0 } else { 1.0 })]
            })
            .collect();
        assert_eq!(answers(true, 0.5, &queries), brute);
    }
}
