//! Outline growth: the semantics of a growth constraint (the STL paper's
//! Graphics Developer, section IV), which turns a seed with growth points
//! inside layout shapes into explicit branching. A front end asks this
//! module for the stems of its seed ([`walk_seed`]) and for the growth
//! ([`grow`]); it walks no turtle of its own.
//!
//! Growth starts at the *growth points* of the seed (the STL front end's
//! lowering marks them):
//! each is a rule applied at a turtle state and a level. Applying a rule:
//!
//! * its top-level stems outside any branch (a "trunk", rare in practice)
//!   are always drawn;
//! * each top-level branch `[...]`, in the rule's order (its priority), is a
//!   *candidate*: it succeeds only if every stem it draws stays inside the
//!   union of the layout shapes ([`super::shapes::Outline`], an exact test)
//!   and keeps clear of every stem already grown. Two stems collide when the
//!   distance between their centre lines is less than the mean of their
//!   broadnesses (their strokes would overlap). Stems that share an end
//!   point (a joint: a stem and its parent, or siblings) are compared by the
//!   distance from each one's free end to the other instead, so a joint is
//!   not a collision but a branch folded onto its sibling is;
//! * a successful branch is kept and, while the rule has levels left (its
//!   self-resemblance count, else `LEVELS`), growth continues at its end
//!   with the same rule one level up; a failed branch is marked `~`.
//!
//! Breadth-first growth handles growth points in a queue (level by level,
//! and within a level in the order they were made); depth-first growth on a
//! stack, following each successful branch to its end before trying the
//! next branch. Growth is deterministic: the order is fixed by the seed and
//! the rules, so it needs no random tie-breaks.
//!
//! Stems already grown are kept in a uniform grid over the layout's
//! bounding box (cells about one stem long), so each candidate stem is
//! compared only with the stems in the few cells around it.

use super::shapes::{point_segment_distance, segment_distance, Outline};

/// The most stems growth makes.
pub const MAX_STEMS: usize = 1_000_000;

/// The most cells of the grid.
const MAX_CELLS: usize = 1 << 18;

/// A drawing component in a rule's expansion.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Comp {
    F,
    /// `L`
    L,
    /// `R`
    R,
    /// `+` (left)
    Plus,
    /// `-` (right)
    Minus,
    Open,
    Close,
}

impl Comp {
    /// +1 for a left turn, −1 for a right turn, 0 otherwise.
    pub fn turn(self) -> i64 {
        match self {
            Comp::L | Comp::Plus => 1,
            Comp::R | Comp::Minus => -1,
            _ => 0,
        }
    }
}

/// The expanded seed, as the growth walk reads it: drawing components,
/// changes of stem level, and growth points (with the front end's index).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SeedEvent {
    Component(Comp),
    Level(u32),
    Growth(usize),
}

/// The top-level branches of a string: index pairs of `[` and its `]`.
pub fn branches(comps: &[Comp]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut depth = 0usize;
    let mut open = 0;
    for (i, c) in comps.iter().enumerate() {
        match c {
            Comp::Open => {
                if depth == 0 {
                    open = i;
                }
                depth += 1;
            }
            Comp::Close => {
                depth = depth.saturating_sub(1);
                if depth == 0 {
                    out.push((open, i));
                }
            }
            _ => {}
        }
    }
    out
}

/// A turtle state in the plane: position and heading as a count of turns
/// by the angle (left positive; heading 0 is up).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    pub pos: [f64; 2],
    pub turns: i64,
}

/// One stem: its ends and half its broadness.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stem {
    pub a: [f64; 2],
    pub b: [f64; 2],
    pub half: f64,
}

/// A stem in a rule's own frame (unit length, root at the origin, facing up).
pub type LocalStem = ([f64; 2], [f64; 2]);

/// A rule's geometry for unit length at the origin facing up.
#[derive(Clone, Debug, Default)]
pub struct UnitGeom {
    pub trunk: Vec<LocalStem>,
    /// Per top-level branch: its stems and the pose at its end.
    pub branches: Vec<(Vec<LocalStem>, Pose)>,
}

/// The direction of a heading of `turns` turns by `delta` radians.
fn dir(turns: i64, delta: f64) -> [f64; 2] {
    let (s, c) = (turns as f64 * delta).sin_cos();
    [-s, c]
}

impl UnitGeom {
    pub fn new(comps: &[Comp], delta: f64) -> Self {
        let mut g = UnitGeom::default();
        let mut st = Pose {
            pos: [0.0, 0.0],
            turns: 0,
        };
        let mut stack: Vec<Pose> = Vec::new();
        for &c in comps {
            match c {
                Comp::F => {
                    let d = dir(st.turns, delta);
                    let b = [st.pos[0] + d[0], st.pos[1] + d[1]];
                    let seg = (st.pos, b);
                    if stack.is_empty() {
                        g.trunk.push(seg);
                    } else if let Some(br) = g.branches.last_mut() {
                        br.0.push(seg);
                    }
                    st.pos = b;
                }
                Comp::Open => {
                    if stack.is_empty() {
                        g.branches.push((Vec::new(), st));
                    }
                    stack.push(st);
                }
                Comp::Close => {
                    if stack.len() == 1 {
                        if let Some(br) = g.branches.last_mut() {
                            br.1 = st;
                        }
                    }
                    if let Some(s) = stack.pop() {
                        st = s;
                    }
                }
                _ => st.turns += c.turn(),
            }
        }
        g
    }
}

/// What growth needs to know besides the rules.
#[derive(Clone, Debug)]
pub struct Params {
    /// The turning angle in radians.
    pub delta: f64,
    pub depth_first: bool,
    /// Broadness and length at a level (already clamped).
    pub broadness: Vec<f64>,
    pub length: Vec<f64>,
    pub max_stems: usize,
}

/// A growth point: where a rule is applied.
#[derive(Clone, Copy, Debug)]
pub struct Point {
    /// The unit rule (index into the `units` given to [`grow`]).
    pub rule: usize,
    pub pose: Pose,
    /// The level of the stems this application draws.
    pub level: u32,
    /// Levels this chain may still grow, this one included.
    pub budget: u32,
}

/// An entry of a grown node.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Grown {
    Empty,
    Failed,
    Node(usize),
}

/// A rule applied during growth, with what became of each branch.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Node {
    pub rule: usize,
    pub entries: Vec<Grown>,
    /// When the node's trunk appeared: how many stems were made before it
    /// (`u32::MAX` until it is drawn), so that growth can be replayed in
    /// order (an animation's frames).
    pub trunk_at: u32,
    /// Per entry, how many stems were made before its branch's stems
    /// (`u32::MAX` for a branch that drew none).
    pub entries_at: Vec<u32>,
}

/// The result of growth.
#[derive(Clone, Debug, Default)]
pub struct Outcome {
    /// Nodes; node `i < roots` is the root of growth point `i`.
    pub nodes: Vec<Node>,
    /// Every stem (the seed's and grown), in the order made.
    pub stems: Vec<Stem>,
    /// Set when growth stopped at [`Params::max_stems`].
    pub truncated: bool,
}

/// A uniform grid of stem indices.
struct Grid {
    min: [f64; 2],
    cell: f64,
    nx: usize,
    ny: usize,
    cells: Vec<Vec<u32>>,
    /// Per stem: the query that last saw it (to visit each once).
    seen: Vec<u32>,
    query: u32,
}

impl Grid {
    fn new(bounds: [f64; 4], cell: f64) -> Self {
        let (w, h) = (
            (bounds[2] - bounds[0]).max(1e-300),
            (bounds[3] - bounds[1]).max(1e-300),
        );
        let mut cell = if cell.is_finite() && cell > 0.0 {
            cell
        } else {
            w.max(h)
        };
        if (w / cell).ceil() * (h / cell).ceil() > MAX_CELLS as f64 {
            cell = (w * h / MAX_CELLS as f64).sqrt() * 1.01;
        }
        let nx = ((w / cell).ceil() as usize).clamp(1, MAX_CELLS);
        let ny = ((h / cell).ceil() as usize)
            .clamp(1, MAX_CELLS / nx.max(1))
            .max(1);
        Grid {
            min: [bounds[0], bounds[1]],
            cell,
            nx,
            ny,
            cells: vec![Vec::new(); nx * ny],
            seen: Vec::new(),
            query: 0,
        }
    }

    fn range(&self, lo: [f64; 2], hi: [f64; 2]) -> (usize, usize, usize, usize) {
        let idx = |v: f64, m: f64, n: usize| {
            let i = ((v - m) / self.cell).floor();
            if i.is_nan() || i < 0.0 {
                0
            } else {
                (i as usize).min(n - 1)
            }
        };
        (
            idx(lo[0], self.min[0], self.nx),
            idx(hi[0], self.min[0], self.nx),
            idx(lo[1], self.min[1], self.ny),
            idx(hi[1], self.min[1], self.ny),
        )
    }

    fn insert(&mut self, id: u32, s: &Stem) {
        let (x0, x1, y0, y1) = self.range(
            [s.a[0].min(s.b[0]) - s.half, s.a[1].min(s.b[1]) - s.half],
            [s.a[0].max(s.b[0]) + s.half, s.a[1].max(s.b[1]) + s.half],
        );
        for y in y0..=y1 {
            for x in x0..=x1 {
                self.cells[y * self.nx + x].push(id);
            }
        }
        self.seen.push(0);
    }
}

/// Whether the stems `s` and `t` keep clear of each other.
///
/// Stems never cross or lie on each other, even with no broadness: the
/// least clearance is `eps` (a billionth of the layout's size).
fn clear(s: &Stem, t: &Stem, eps: f64) -> bool {
    let need = (s.half + t.half).max(2.0 * eps);
    let close = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).abs() <= eps && (p[1] - q[1]).abs() <= eps;
    let shared = [(s.a, t.a), (s.a, t.b), (s.b, t.a), (s.b, t.b)]
        .iter()
        .position(|&(p, q)| close(p, q));
    let d = match shared {
        Some(k) => {
            let s_free = if k < 2 { s.b } else { s.a };
            let t_free = if k % 2 == 0 { t.b } else { t.a };
            point_segment_distance(s_free, t.a, t.b).min(point_segment_distance(t_free, s.a, s.b))
        }
        None => segment_distance(s.a, s.b, t.a, t.b),
    };
    d >= need - eps
}

struct Grower<'a> {
    units: &'a [UnitGeom],
    params: &'a Params,
    outline: &'a Outline,
    grid: Grid,
    out: Outcome,
    eps: f64,
}

impl Grower<'_> {
    fn level_value(v: &[f64], level: u32) -> f64 {
        v.get(level as usize).or(v.last()).copied().unwrap_or(1.0)
    }

    fn place(&self, p: &Point, local: ([f64; 2], [f64; 2]), len: f64, half: f64) -> Stem {
        let (s, c) = (p.pose.turns as f64 * self.params.delta).sin_cos();
        let tr = |q: [f64; 2]| {
            [
                p.pose.pos[0] + len * (q[0] * c - q[1] * s),
                p.pose.pos[1] + len * (q[0] * s + q[1] * c),
            ]
        };
        Stem {
            a: tr(local.0),
            b: tr(local.1),
            half,
        }
    }

    fn add(&mut self, s: Stem) {
        let id = self.out.stems.len() as u32;
        self.grid.insert(id, &s);
        self.out.stems.push(s);
    }

    /// Whether `s` is inside the layout and clear of every stem (and of the
    /// candidate's own earlier stems `own`).
    fn fits(&mut self, s: &Stem, own: &[Stem]) -> bool {
        if !self.outline.contains_segment(s.a, s.b) {
            return false;
        }
        if own.iter().any(|t| !clear(s, t, self.eps)) {
            return false;
        }
        let reach = s.half + self.params.broadness.first().copied().unwrap_or(0.0) / 2.0;
        let (x0, x1, y0, y1) = self.grid.range(
            [s.a[0].min(s.b[0]) - reach, s.a[1].min(s.b[1]) - reach],
            [s.a[0].max(s.b[0]) + reach, s.a[1].max(s.b[1]) + reach],
        );
        self.grid.query = self.grid.query.wrapping_add(1);
        let q = self.grid.query;
        for y in y0..=y1 {
            for x in x0..=x1 {
                for &id in &self.grid.cells[y * self.grid.nx + x] {
                    let seen = &mut self.grid.seen[id as usize];
                    if *seen == q {
                        continue;
                    }
                    *seen = q;
                    if !clear(s, &self.out.stems[id as usize], self.eps) {
                        return false;
                    }
                }
            }
        }
        true
    }

    /// Applies the rule of growth point `p` to node `node`: draws the trunk
    /// and decides branch `k`; returns the child growth point when branch
    /// `k` succeeded and may grow on.
    fn trunk(&mut self, p: &Point, node: usize) {
        self.out.nodes[node].trunk_at = self.appeared();
        let unit = &self.units[p.rule];
        let len = Self::level_value(&self.params.length, p.level);
        let half = Self::level_value(&self.params.broadness, p.level) / 2.0;
        let stems: Vec<Stem> = unit
            .trunk
            .iter()
            .map(|&l| self.place(p, l, len, half))
            .collect();
        for s in stems {
            self.add(s);
        }
    }

    fn branch(&mut self, p: &Point, node: usize, k: usize) -> Option<Point> {
        if self.out.stems.len() >= self.params.max_stems {
            self.out.truncated = true;
            self.out.nodes[node].entries[k] = Grown::Empty;
            return None;
        }
        let units = self.units;
        let (locals, end) = &units[p.rule].branches[k];
        let len = Self::level_value(&self.params.length, p.level);
        let half = Self::level_value(&self.params.broadness, p.level) / 2.0;
        let mut own: Vec<Stem> = Vec::with_capacity(locals.len());
        for &l in locals {
            let s = self.place(p, l, len, half);
            if !self.fits(&s, &own) {
                self.out.nodes[node].entries[k] = Grown::Failed;
                return None;
            }
            own.push(s);
        }
        self.out.nodes[node].entries_at[k] = self.appeared();
        for s in own {
            self.add(s);
        }
        if p.budget <= 1 {
            self.out.nodes[node].entries[k] = Grown::Empty;
            return None;
        }
        let (s, c) = (p.pose.turns as f64 * self.params.delta).sin_cos();
        let pos = [
            p.pose.pos[0] + len * (end.pos[0] * c - end.pos[1] * s),
            p.pose.pos[1] + len * (end.pos[0] * s + end.pos[1] * c),
        ];
        Some(Point {
            rule: p.rule,
            pose: Pose {
                pos,
                turns: p.pose.turns + end.turns,
            },
            level: p.level + 1,
            budget: p.budget - 1,
        })
    }

    /// How many stems were made so far: when what is made next appears.
    fn appeared(&self) -> u32 {
        u32::try_from(self.out.stems.len()).unwrap_or(u32::MAX)
    }

    fn new_node(&mut self, rule: usize) -> usize {
        let n = self.units[rule].branches.len();
        self.out.nodes.push(Node {
            rule,
            entries: vec![Grown::Empty; n],
            trunk_at: u32::MAX,
            entries_at: vec![u32::MAX; n],
        });
        self.out.nodes.len() - 1
    }
}

/// Grows the growth points `points` (node `i` of the outcome belongs to
/// point `i`), with the seed's own stems `seed_stems` already in place.
pub fn grow(
    units: &[UnitGeom],
    outline: &Outline,
    bounds: [f64; 4],
    params: &Params,
    seed_stems: &[Stem],
    points: &[Point],
) -> Outcome {
    let l0 = params.length.first().copied().unwrap_or(1.0);
    let b0 = params.broadness.first().copied().unwrap_or(0.0);
    let size = (bounds[2] - bounds[0])
        .abs()
        .max((bounds[3] - bounds[1]).abs());
    let mut g = Grower {
        units,
        params,
        outline,
        grid: Grid::new(bounds, l0.max(b0)),
        out: Outcome::default(),
        eps: 1e-9 * size.max(l0).max(1e-300),
    };
    for s in seed_stems {
        g.add(*s);
    }
    for p in points {
        g.new_node(p.rule);
    }
    if params.depth_first {
        // Frames: (point, node, next branch).
        for (i, p) in points.iter().enumerate() {
            g.trunk(p, i);
            let mut stack = vec![(*p, i, 0usize)];
            while let Some(top) = stack.last_mut() {
                let (p, node, k) = *top;
                if k >= units[p.rule].branches.len() {
                    stack.pop();
                    continue;
                }
                top.2 += 1;
                if let Some(child) = g.branch(&p, node, k) {
                    let c = g.new_node(child.rule);
                    g.out.nodes[node].entries[k] = Grown::Node(c);
                    g.trunk(&child, c);
                    stack.push((child, c, 0));
                }
            }
        }
    } else {
        // Level by level. A level's growth points are in the tree's order
        // (that of the rules' branches), which runs across the tree from
        // one side to the other; they are taken alternately from its two
        // ends, so that neither side of the tree claims the contested space
        // first (the paper's "stems in the same level share almost the same
        // probability to branch successfully").
        let mut level: Vec<(Point, usize)> = points.iter().copied().zip(0..).collect();
        while !level.is_empty() {
            let n = level.len();
            let order = (0..n).map(|i| if i % 2 == 0 { i / 2 } else { n - 1 - i / 2 });
            let mut next: Vec<Option<(Point, usize)>> = Vec::new();
            let mut slots: Vec<Vec<usize>> = vec![Vec::new(); n];
            for i in order {
                let (p, node) = level[i];
                g.trunk(&p, node);
                for k in 0..units[p.rule].branches.len() {
                    if let Some(child) = g.branch(&p, node, k) {
                        let c = g.new_node(child.rule);
                        g.out.nodes[node].entries[k] = Grown::Node(c);
                        slots[i].push(next.len());
                        next.push(Some((child, c)));
                    }
                }
            }
            // The next level in the tree's order.
            level = slots
                .into_iter()
                .flatten()
                .filter_map(|j| next[j].take())
                .collect();
        }
    }
    g.out
}

/// Walks the expanded seed: the seed's stems, and where each growth point
/// stands. `growing` gives each growth point's unit rule and budget, in the
/// order of the seed; `delta` is the turning angle, `defaults` the stem
/// length and broadness past the levels `lw` and `bw` give.
pub fn walk_seed(
    events: &[SeedEvent],
    growing: &[(usize, u32)],
    delta: f64,
    defaults: (f64, f64),
    bw: &[f64],
    lw: &[f64],
) -> (Vec<Stem>, Vec<Point>) {
    let mut stems = Vec::new();
    let mut points = Vec::new();
    let mut pose = Pose {
        pos: [0.0, 0.0],
        turns: 0,
    };
    let mut level = 0u32;
    let mut stack = Vec::new();
    let mut growing = growing.iter();
    for e in events {
        match *e {
            SeedEvent::Component(Comp::F) => {
                let d = [
                    -(pose.turns as f64 * delta).sin(),
                    (pose.turns as f64 * delta).cos(),
                ];
                let len = lw.get(level as usize).copied().unwrap_or(defaults.0);
                let b = [pose.pos[0] + len * d[0], pose.pos[1] + len * d[1]];
                stems.push(Stem {
                    a: pose.pos,
                    b,
                    half: bw.get(level as usize).copied().unwrap_or(defaults.1) / 2.0,
                });
                pose.pos = b;
            }
            SeedEvent::Component(Comp::Open) => stack.push(pose),
            SeedEvent::Component(Comp::Close) => {
                if let Some(p) = stack.pop() {
                    pose = p;
                }
            }
            SeedEvent::Component(c) => pose.turns += c.turn(),
            SeedEvent::Level(k) => level = k,
            SeedEvent::Growth(_) => {
                let &(rule, budget) = growing.next().expect("one per growth point");
                points.push(Point {
                    rule,
                    pose,
                    level,
                    budget,
                });
            }
        }
    }
    (stems, points)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::{Rgb, Shape};

    #[test]
    fn unit_geometry_finds_branch_ends() {
        use Comp::*;
        let g = UnitGeom::new(
            &[
                Open, F, Open, Plus, F, Close, F, Close, Open, Minus, F, Close,
            ],
            0.5,
        );
        assert_eq!(g.branches.len(), 2);
        assert_eq!(g.branches[0].0.len(), 3);
        // The first branch ends two steps up, facing up (the inner branch popped).
        assert_eq!(g.branches[0].1.turns, 0);
        assert!((g.branches[0].1.pos[1] - 2.0).abs() < 1e-12);
        assert_eq!(g.branches[1].1.turns, -1);
        assert_eq!(
            branches(&[F, Open, Open, Close, Close, Open, Close]),
            vec![(1, 4), (5, 6)]
        );
    }

    #[test]
    fn joints_are_not_collisions_but_overlaps_are() {
        let s = Stem {
            a: [0.0, 0.0],
            b: [0.0, 10.0],
            half: 1.0,
        };
        let sibling = Stem {
            a: [0.0, 0.0],
            b: [5.0, 8.66],
            half: 1.0,
        };
        assert!(clear(&s, &sibling, 1e-9));
        let folded = Stem {
            a: [0.0, 0.0],
            b: [0.5, 9.0],
            half: 1.0,
        };
        assert!(!clear(&s, &folded, 1e-9));
        let near = Stem {
            a: [1.5, 2.0],
            b: [1.5, 8.0],
            half: 1.0,
        };
        assert!(!clear(&s, &near, 1e-9));
    }

    #[test]
    fn growth_stays_in_a_box_and_stops_at_its_levels() {
        use Comp::*;
        let unit = UnitGeom::new(
            &[Open, Minus, F, Close, Open, Plus, F, Close],
            30f64.to_radians(),
        );
        let shapes = [Shape::Rectangle {
            colour: Rgb(0, 0, 0),
            x: -50.0,
            y: 0.0,
            w: 100.0,
            h: 100.0,
        }];
        let outline = Outline::new(&shapes);
        for depth_first in [false, true] {
            let params = Params {
                delta: 30f64.to_radians(),
                depth_first,
                broadness: vec![0.5; 20],
                length: vec![10.0; 20],
                max_stems: 100_000,
            };
            let p = Point {
                rule: 0,
                pose: Pose {
                    pos: [0.0, 10.0],
                    turns: 0,
                },
                level: 1,
                budget: 3,
            };
            let seed = [Stem {
                a: [0.0, 0.0],
                b: [0.0, 10.0],
                half: 0.25,
            }];
            let out = grow(
                std::slice::from_ref(&unit),
                &outline,
                [-50.0, 0.0, 50.0, 100.0],
                &params,
                &seed,
                &[p],
            );
            // Three levels of a binary rule with room for all: 2 + 4 + 8 stems.
            assert_eq!(out.stems.len(), 1 + 14, "{depth_first}");
            assert_eq!(out.nodes.len(), 1 + 2 + 4);
        }
    }
}
