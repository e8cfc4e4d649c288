//! The turtle over shared subtrees: statistics and pictures of context-free
//! deterministic systems without deriving their words.
//!
//! Bekaert & Willems ("Ray tracing 3D linear graftals") draw a graftal by
//! instancing: every node `(s, n)` of the derivation tree ([`D0l`]) is
//! the same object wherever it occurs, placed by the turtle state it starts
//! in. The turtle is relative: what a subtree draws, seen from its start,
//! depends only on the frame it starts in (and whether turns are swapped),
//! not on where it is. When the frames a system can reach form a finite set
//! (turns by rational fractions of a full turn: every pfg and Fractint
//! system, LinF's right angles, …), a subtree is summarised once per
//! starting frame: where it ends, in which frame, how much it scales the
//! step, how many segments it draws, its deepest branching, and the box
//! around everything it draws. A parent's summary is composed from its
//! children's, so the table has `symbols × depth × frames` entries however
//! long the word is: the quadratic Koch island at 12 steps (2.7 × 10¹¹
//! segments) is counted and boxed exactly from 4 × 13 × 4 summaries.
//!
//! The summaries grow with the depth — the Koch island's by 4 a step, past
//! the largest `f64` at 512 steps — while the picture they make converges
//! in shape. So each level of the table keeps its lengths in its own unit,
//! a power of two chosen so that the level's largest is about 1: scaling
//! by a power of two is exact, so every figure is the same, bit for bit,
//! as in unit steps wherever those fit, and a picture of any depth is
//! drawn in the unit of its top level ([`Instanced::word_scaled`]).
//!
//! [`Instanced::picture`] draws with the "smaller than one pixel" criterion
//! of the same paper: a subtree whose box falls within half a pixel is
//! drawn as one line from where it starts to where it ends, and not
//! entered. The
//! picture then has about as many points as the curve is long in pixels.
//!
//! What is not instanced here — brackets that are rewritten, random or
//! parameter-given angles, frames that never repeat, absolute moves,
//! polygons, discs, two headings — is left to the streaming turtle (see
//! [`crate::driver::stats`]); [`Instanced::new`] says `None`.

use super::state::rotate;
use super::Vec3;
use crate::ir::{Angle, Axis, D0l, SymbolId, System, TurtleOp};
use std::collections::HashMap;

/// A subtree whose box is smaller than this many pixels across is drawn
/// as one line. The paper's criterion is one pixel; at one pixel the inked
/// pixels of the Koch island at 5 steps in 256² differed from drawing
/// every segment by 17%, at half a pixel by none (`tests/it/scale.rs`).
const WITHIN: f64 = 0.5;

/// The most frames a system may reach.
const MAX_FRAMES: usize = 4096;
/// The most summaries kept (about 100 bytes each).
const MAX_SUMMARIES: usize = 1 << 20;

/// An orthonormal turtle frame: heading, left, up.
type Frame = [Vec3; 3];

/// What one symbol does to the relative turtle state.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Act {
    /// Nothing that moves or turns the turtle (colours, widths, no op).
    Keep,
    Forward {
        draw: bool,
    },
    /// A rotation: index into [`Instanced::turns`].
    Turn(u16),
    Swap,
    Scale(f64),
    Push,
    Pop,
}

/// A rotation of the frame, as the turtle applies it.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Rotation {
    /// About `axis` by `angle` radians, negated when turns are swapped
    /// (unless `fixed`).
    About { axis: Axis, angle: f64, fixed: bool },
    /// LinF `Frenet`: torsion about H, then curvature about U, both
    /// negated when swapped.
    Frenet { torsion: f64, curvature: f64 },
}

/// A subtree seen from its start, for unit step length, its lengths in
/// the unit of its level: a power of two steps, one for each depth, that
/// brings the level's largest length to about 1 (see the module notes).
#[derive(Clone, Copy, Debug)]
pub struct Summary {
    /// Where it ends, relative to its start.
    pub end: Vec3,
    /// The state it ends in (frame index × 2 + swapped).
    state: u32,
    /// The factor it leaves on the step length.
    scale: f64,
    /// The box around the end points of everything it draws; `lo > hi`
    /// when it draws nothing.
    pub lo: Vec3,
    pub hi: Vec3,
    /// Saturates at `u128::MAX`: enough to choose what to walk into; the
    /// exact count is [`crate::eval::tree::Tree::count`]'s.
    pub segments: u128,
    /// The deepest branch nesting inside it, relative to its start.
    pub depth: u32,
}

impl Summary {
    fn identity(state: u32) -> Self {
        Summary {
            end: [0.0; 3],
            state,
            scale: 1.0,
            lo: [f64::INFINITY; 3],
            hi: [f64::NEG_INFINITY; 3],
            segments: 0,
            depth: 0,
        }
    }

    pub fn draws(&self) -> bool {
        self.segments > 0
    }

    /// Its lengths times `2^e`.
    fn rescaled(mut self, e: i64) -> Self {
        for v in [&mut self.end, &mut self.lo, &mut self.hi] {
            *v = v.map(|x| ldexp(x, e));
        }
        self
    }

    /// Its lengths times `k`.
    fn times(mut self, k: f64) -> Self {
        for v in [&mut self.end, &mut self.lo, &mut self.hi] {
            *v = v.map(|x| x * k);
        }
        self
    }

    /// Whether its lengths are all finite numbers (its box only when it
    /// draws).
    fn finite(&self) -> bool {
        let bounds = self.lo.iter().chain(&self.hi).filter(|_| self.draws());
        self.end.iter().chain(bounds).all(|v| v.is_finite())
    }

    /// The largest magnitude of its lengths that is finite (0 for none).
    fn largest(&self) -> f64 {
        let ends = self.end.iter();
        let bounds = self.lo.iter().chain(&self.hi).filter(|_| self.draws());
        ends.chain(bounds)
            .map(|v| v.abs())
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max)
    }
}

/// `x · 2^e`: exact unless the result is beyond `f64`'s range (then
/// infinite, or 0 and subnormals below).
pub fn ldexp(mut x: f64, e: i64) -> f64 {
    // Past ±2200 every finite non-zero `x` overflows or vanishes alike.
    let mut e = e.clamp(-2200, 2200);
    while e != 0 {
        let k = e.clamp(-1000, 1000);
        // 2^k, built from its exponent bits: exact.
        x *= f64::from_bits(((k + 1023) as u64) << 52);
        e -= k;
    }
    x
}

/// The power of two that brings `m` to within `[0.5, 1)`: 0 for 0 or a
/// number that is not finite.
fn exponent_of(m: f64) -> i64 {
    if m > 0.0 && m.is_finite() {
        m.log2().floor() as i64 + 1
    } else {
        0
    }
}

/// A system prepared for instanced interpretation.
pub struct Instanced<'a> {
    sys: &'a System,
    tree: D0l<'a>,
    acts: Vec<Act>,
    turns: Vec<Rotation>,
    frames: Vec<Frame>,
    /// `next[(state · turns) + t]`: the state after turn `t`.
    next: Vec<u32>,
    /// Whether any symbol changes colour or width (a picture then needs
    /// the streaming turtle).
    styled: bool,
    /// Summaries of rewritten symbols by (symbol, depth, state), each in
    /// the unit of its level.
    memo: HashMap<(u32, u64, u32), Summary>,
    /// `units[d]`: the unit of level `d`'s lengths is `2^units[d]` steps;
    /// known for the levels filled ([`Instanced::fill`]), `units[0] = 0`.
    units: Vec<i64>,
}

/// The frame the turtle starts in: H = +y, L = −x, U = +z.
const START: Frame = [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];

/// Snaps values within 1e-12 of a multiple of 1/2 to it, so frames at
/// right angles are exact and keys compare equal.
fn snap(v: f64) -> f64 {
    let r = (v * 2.0).round() / 2.0;
    if (v - r).abs() < 1e-12 {
        r
    } else {
        v
    }
}

fn key(f: &Frame) -> [i64; 9] {
    let mut k = [0i64; 9];
    for (i, x) in f.iter().flatten().enumerate() {
        k[i] = (x * 1e9).round() as i64;
    }
    k
}

fn turn(f: &Frame, axis: Axis, angle: f64) -> Frame {
    let (s, c) = angle.sin_cos();
    let [mut h, mut l, mut u] = *f;
    match axis {
        Axis::Up => (h, l) = rotate(h, l, c, s),
        Axis::Left => (u, h) = rotate(u, h, c, s),
        Axis::Heading => (u, l) = rotate(u, l, c, s),
    }
    [h, l, u].map(|v| v.map(snap))
}

impl Rotation {
    fn apply(&self, f: &Frame, swapped: bool) -> Frame {
        let sign = if swapped { -1.0 } else { 1.0 };
        match *self {
            Rotation::About { axis, angle, fixed } => {
                turn(f, axis, if fixed { angle } else { sign * angle })
            }
            Rotation::Frenet { torsion, curvature } => {
                let f = turn(f, Axis::Heading, -sign * torsion);
                turn(&f, Axis::Up, -sign * curvature)
            }
        }
    }
}

/// What the symbols of a system do, as [`Instanced::new`] finds them.
struct Acts {
    /// By symbol; `Keep` for the symbols no word holds.
    acts: Vec<Act>,
    /// The distinct rotations the symbols make.
    turns: Vec<Rotation>,
    /// Whether any symbol changes colour or width.
    styled: bool,
}

impl Acts {
    /// `None` when a symbol the words can hold does something instancing
    /// does not cover.
    fn of(sys: &System, tree: &D0l) -> Option<Self> {
        let mut found = Acts {
            acts: Vec::with_capacity(tree.symbol_count()),
            turns: Vec::new(),
            styled: false,
        };
        // Only the symbols the word can hold matter.
        for (i, used) in symbols_used(tree).into_iter().enumerate() {
            let s = SymbolId(i as u32);
            let act = match sys.op(s) {
                Some(op) if used => found.act(sys, op)?,
                _ => Act::Keep,
            };
            // A bracket that is rewritten would open or close branches
            // across subtrees.
            if matches!(act, Act::Push | Act::Pop) && tree.successor(s).is_some() {
                return None;
            }
            found.acts.push(act);
        }
        Some(found)
    }

    /// What `op` does; `None` when instancing does not cover it.
    fn act(&mut self, sys: &System, op: TurtleOp) -> Option<Act> {
        let fixed = |a: Angle| match a {
            Angle::Delta(f) => Some(f * sys.settings.delta),
            Angle::Radians(r) => Some(r),
            Angle::Uniform { .. } => None,
        };
        let act = match op {
            TurtleOp::Forward { draw } => Act::Forward { draw },
            TurtleOp::Rotate { axis, angle } => self.turn(Rotation::About {
                axis,
                angle: fixed(angle)?,
                fixed: false,
            }),
            TurtleOp::TurnUnswapped(angle) => self.turn(Rotation::About {
                axis: Axis::Up,
                angle: fixed(angle)?,
                fixed: false,
            }),
            TurtleOp::TurnAround => self.turn(Rotation::About {
                axis: Axis::Up,
                angle: std::f64::consts::PI,
                fixed: true,
            }),
            TurtleOp::Frenet { rotation, negate } => {
                let r = sys.rotations.get(rotation.0 as usize)?;
                let sign = if negate { -1.0 } else { 1.0 };
                self.turn(Rotation::Frenet {
                    torsion: sign * fixed(r.torsion)?,
                    curvature: sign * fixed(r.curvature)?,
                })
            }
            TurtleOp::SwapTurns => Act::Swap,
            TurtleOp::ScaleLength(f) if f > 0.0 && f.is_finite() => Act::Scale(f),
            TurtleOp::Push => Act::Push,
            TurtleOp::Pop => Act::Pop,
            TurtleOp::DecrementWidth
            | TurtleOp::NextColour
            | TurtleOp::PreviousColour
            | TurtleOp::SetColour(_)
            | TurtleOp::ShiftColour { .. }
            | TurtleOp::ColourIndex { .. }
            | TurtleOp::LineWidth { .. } => {
                self.styled = true;
                Act::Keep
            }
            _ => return None,
        };
        Some(act)
    }

    /// The turn by `r`, added to the rotations when it is new.
    fn turn(&mut self, r: Rotation) -> Act {
        let k = self.turns.iter().position(|&t| t == r).unwrap_or_else(|| {
            self.turns.push(r);
            self.turns.len() - 1
        });
        Act::Turn(k as u16)
    }
}

/// By symbol, whether the words of `tree` can hold it.
fn symbols_used(tree: &D0l) -> Vec<bool> {
    let mut used = vec![false; tree.symbol_count()];
    let mut todo: Vec<SymbolId> = tree.axiom().to_vec();
    while let Some(s) = todo.pop() {
        if !std::mem::replace(&mut used[s.index()], true) {
            todo.extend(tree.successor(s).unwrap_or(&[]));
        }
    }
    used
}

/// Whether every branch `w` opens, it closes, and none closes before it
/// opens.
fn balanced(acts: &[Act], w: &[SymbolId]) -> bool {
    let mut depth = 0i64;
    for s in w {
        match acts[s.index()] {
            Act::Push => depth += 1,
            Act::Pop => {
                depth -= 1;
                if depth < 0 {
                    return false;
                }
            }
            _ => {}
        }
    }
    depth == 0
}

/// Indices into a list of frames by the frames' [`key`].
type FrameIndex = HashMap<[i64; 9], u32>;

/// The frames reachable from the start by every turn, swapped or not, and
/// each one's index by its key; `None` past [`MAX_FRAMES`].
fn reachable_frames(turns: &[Rotation]) -> Option<(Vec<Frame>, FrameIndex)> {
    let mut frames: Vec<Frame> = vec![START];
    let mut index: FrameIndex = HashMap::from([(key(&START), 0)]);
    let mut i = 0;
    while i < frames.len() {
        for swapped in [false, true] {
            for t in turns {
                let f = t.apply(&frames[i], swapped);
                let k = key(&f);
                if let std::collections::hash_map::Entry::Vacant(e) = index.entry(k) {
                    if frames.len() >= MAX_FRAMES {
                        return None;
                    }
                    e.insert(frames.len() as u32);
                    frames.push(f);
                }
            }
        }
        i += 1;
    }
    Some((frames, index))
}

/// The state after each turn from each state (frame · 2 + swapped), as
/// [`Instanced::next`] holds them.
fn transitions(frames: &[Frame], index: &HashMap<[i64; 9], u32>, turns: &[Rotation]) -> Vec<u32> {
    let states = frames.len() * 2;
    let mut next: Vec<u32> = Vec::with_capacity(states * turns.len());
    for st in 0..states {
        let (f, sw) = (st / 2, st % 2 == 1);
        for t in turns {
            let g = t.apply(&frames[f], sw);
            let id = index[&key(&g)];
            next.push(id * 2 + sw as u32);
        }
    }
    next
}

impl<'a> Instanced<'a> {
    /// `None` when `sys` is not context-free and deterministic, or draws
    /// with something instancing does not cover (see the module notes).
    pub fn new(sys: &'a System) -> Option<Self> {
        // Tropisms bend each step by the frame it is taken in: no subtree
        // draws the same wherever it is.
        if sys.structure.is_some() || !sys.settings.tropisms.is_empty() {
            return None;
        }
        let tree = D0l::of(sys)?;
        let Acts {
            acts,
            turns,
            styled,
        } = Acts::of(sys, &tree)?;
        // Every successor and the axiom must be balanced, so that each
        // subtree's branches close inside it.
        let balanced = |w: &[SymbolId]| balanced(&acts, w);
        if !balanced(tree.axiom())
            || !(0..tree.symbol_count())
                .filter_map(|i| tree.successor(SymbolId(i as u32)))
                .all(balanced)
        {
            return None;
        }
        let (frames, index) = reachable_frames(&turns)?;
        let next = transitions(&frames, &index, &turns);
        Some(Instanced {
            sys,
            tree,
            acts,
            turns,
            frames,
            next,
            styled,
            memo: HashMap::new(),
            units: vec![0],
        })
    }

    fn states(&self) -> usize {
        self.frames.len() * 2
    }

    /// The summary of the subtree of `s` after `d` more steps, starting in
    /// `state`, in the unit of level `d` (of level 0 for a symbol that is
    /// not rewritten).
    fn summary(&mut self, s: SymbolId, d: u64, state: u32) -> Summary {
        match self.tree.successor(s) {
            Some(_) if d > 0 => {
                // The levels are filled bottom-up, whole, before they are
                // read: each level's unit needs all of it.
                self.fill(d);
                let x = self.memo.get(&(s.0, d, state));
                x.copied().unwrap_or_else(|| Summary::identity(state))
            }
            _ => self.leaf(s, state),
        }
    }

    /// The unit of the summary of `s` after `d` more steps: `2^this` steps.
    fn unit_of(&self, s: SymbolId, d: u64) -> i64 {
        match self.tree.successor(s) {
            Some(_) if d > 0 => self.units.get(d as usize).copied().unwrap_or(0),
            _ => 0,
        }
    }

    fn leaf(&self, s: SymbolId, state: u32) -> Summary {
        let mut x = Summary::identity(state);
        match self.acts[s.index()] {
            Act::Forward { draw } => {
                let h = self.frames[state as usize / 2][0];
                x.end = h;
                if draw {
                    x.segments = 1;
                    x.lo = h.map(|v| v.min(0.0));
                    x.hi = h.map(|v| v.max(0.0));
                }
            }
            Act::Turn(t) => x.state = self.next[state as usize * self.turns.len() + t as usize],
            Act::Swap => x.state = state ^ 1,
            Act::Scale(f) => x.scale = f,
            Act::Keep | Act::Push | Act::Pop => {}
        }
        x
    }

    /// The summary of the word `w` with every symbol `d` more steps deep,
    /// starting in `state`, in the unit of level `d`.
    fn compose(&mut self, w: &[SymbolId], d: u64, state: u32) -> Summary {
        let unit = self.units.get(d as usize).copied().unwrap_or(0);
        let mut acc = Summary::identity(state);
        // (end, state, scale) at each open branch.
        let mut stack: Vec<(Vec3, u32, f64)> = Vec::new();
        for &c in w {
            match self.acts[c.index()] {
                Act::Push if self.tree.successor(c).is_none() || d == 0 => {
                    stack.push((acc.end, acc.state, acc.scale));
                    acc.depth = acc.depth.max(stack.len() as u32);
                    continue;
                }
                Act::Pop if self.tree.successor(c).is_none() || d == 0 => {
                    if let Some((e, st, k)) = stack.pop() {
                        (acc.end, acc.state, acc.scale) = (e, st, k);
                    }
                    continue;
                }
                _ => {}
            }
            // A symbol that is not rewritten is one step long, in the
            // unit of the level: negligible far up, but not nothing.
            let x = self.summary(c, d, acc.state);
            let x = x.rescaled(self.unit_of(c, d) - unit);
            let k = acc.scale;
            if x.draws() {
                for i in 0..3 {
                    acc.lo[i] = acc.lo[i].min(acc.end[i] + k * x.lo[i]);
                    acc.hi[i] = acc.hi[i].max(acc.end[i] + k * x.hi[i]);
                }
            }
            acc.segments = acc.segments.saturating_add(x.segments);
            acc.depth = acc.depth.max(stack.len() as u32 + x.depth);
            for i in 0..3 {
                acc.end[i] += k * x.end[i];
            }
            acc.state = x.state;
            acc.scale *= x.scale;
        }
        acc
    }

    /// Fills the summaries of every level up to `steps` that is not yet,
    /// bottom-up and each from the one below, so that no recursion is
    /// deeper than one level; each level in its own unit, the power of two
    /// that brings its largest length to about 1.
    fn fill(&mut self, steps: u64) {
        if (self.units.len() as u64) > steps {
            return;
        }
        let rewritten: Vec<(SymbolId, &'a [SymbolId])> = (0..self.tree.symbol_count() as u32)
            .map(SymbolId)
            .filter_map(|s| Some((s, self.tree.successor(s)?)))
            .collect();
        let states = self.states() as u32;
        while (self.units.len() as u64) <= steps {
            let d = self.units.len() as u64;
            let mut level = Vec::with_capacity(rewritten.len() * states as usize);
            for &(s, w) in &rewritten {
                for st in 0..states {
                    level.push(((s.0, d, st), self.compose(w, d - 1, st)));
                }
            }
            let largest = level.iter().map(|(_, x)| x.largest()).fold(0.0, f64::max);
            let shift = exponent_of(largest);
            let below = self.units[d as usize - 1];
            self.units.push(below.saturating_add(shift));
            for (k, x) in level {
                self.memo.insert(k, x.rescaled(-shift));
            }
        }
    }

    /// The summary of the whole word after `steps` steps, in turtle units:
    /// infinite where it is beyond `f64` ([`Instanced::word_scaled`] is
    /// not).
    pub fn word(&mut self, steps: u64) -> Summary {
        let (x, unit) = self.word_in_units(steps);
        x.rescaled(unit).times(self.sys.settings.step)
    }

    /// The summary of the whole word after `steps` steps, its lengths in
    /// units of `2^k` turtle units, with `k`: 0 where turtle units hold
    /// them, else the unit of the top level. A picture is the same shape
    /// in any unit ([`Instanced::lines`] draws in this one).
    pub fn word_scaled(&mut self, steps: u64) -> (Summary, i64) {
        let (x, unit) = self.word_in_units(steps);
        let step = self.sys.settings.step;
        let turtle = x.rescaled(unit).times(step);
        // Turtle units hold it when nothing overflows, and nothing that
        // is not nothing vanishes into the subnormals.
        let tiny = f64::MIN_POSITIVE * f64::EPSILON.recip();
        let kept = x.largest() == 0.0 || turtle.largest() >= tiny;
        if unit == 0 || (turtle.finite() && kept) {
            (turtle, 0)
        } else {
            (x.times(step), unit)
        }
    }

    /// The whole word's summary in the unit of its top level, for unit
    /// steps, with that unit (`2^this` steps).
    fn word_in_units(&mut self, steps: u64) -> (Summary, i64) {
        self.fill(steps);
        let axiom = self.tree.axiom();
        let x = self.compose(axiom, steps, 0);
        (x, self.units[steps as usize])
    }

    /// Whether the memo would stay within bounds for `steps` steps.
    pub fn fits(&self, steps: u64) -> bool {
        let rewritten = (0..self.tree.symbol_count())
            .filter(|&i| self.tree.successor(SymbolId(i as u32)).is_some())
            .count();
        (rewritten as u128) * (self.states() as u128) * (steps as u128) <= MAX_SUMMARIES as u128
    }

    /// Whether [`Instanced::picture`] can draw the system: one colour and
    /// width throughout.
    pub fn can_draw(&self) -> bool {
        !self.styled
    }

    /// Walks the word after `steps` steps as lines through the shared
    /// subtrees, seen face on: a subtree whose box is within half a pixel
    /// (`pixels` per unit of `2^unit` turtle units) goes to `out` as one
    /// line from its start to its end, in those units; larger subtrees are
    /// walked into.
    pub fn lines(&mut self, steps: u64, pixels: f64, unit: i64, out: &mut dyn Lines) {
        self.walk_in(steps, unit, &mut Within { pixels, out });
    }

    /// Walks the word after `steps` steps through the shared subtrees:
    /// `walker` says which drawing subtrees to walk into, and receives the
    /// others whole, where they are placed.
    pub fn walk(&mut self, steps: u64, walker: &mut dyn Walker) {
        self.walk_in(steps, 0, walker);
    }

    /// [`Instanced::walk`] in units of `2^unit` turtle units.
    fn walk_in(&mut self, steps: u64, unit: i64, walker: &mut dyn Walker) {
        let start = Turtle {
            pos: [0.0; 3],
            state: 0,
            scale: self.sys.settings.step,
        };
        let axiom = self.tree.axiom();
        self.walk_from(axiom, steps, (start, unit), walker);
    }

    /// Walks `subtree` alone from the origin, in the start frame (turns
    /// swapped as it says) and with a unit step: what each of its
    /// placements draws, before it is placed.
    pub fn walk_subtree(&mut self, subtree: Subtree, walker: &mut dyn Walker) {
        let start = Turtle {
            pos: [0.0; 3],
            state: u32::from(subtree.swapped),
            scale: 1.0,
        };
        self.walk_from(&[subtree.symbol], subtree.depth, (start, 0), walker);
    }

    /// Walks `word` with every symbol `steps` more steps deep from the
    /// turtle `start`, in units of `2^unit` turtle units.
    fn walk_from(
        &mut self,
        word: &[SymbolId],
        steps: u64,
        (start, unit): (Turtle, i64),
        out: &mut dyn Walker,
    ) {
        let mut t = start;
        let mut branches: Vec<Turtle> = Vec::new();
        let mut stack: Vec<(&[SymbolId], u64)> = vec![(word, steps)];
        while let Some(top) = stack.last_mut() {
            let Some((&c, rest)) = top.0.split_first() else {
                stack.pop();
                continue;
            };
            top.0 = rest;
            let d = top.1;
            let rewritten = self.tree.successor(c).filter(|_| d > 0);
            match (self.acts[c.index()], rewritten) {
                (Act::Push, None) => {
                    branches.push(t);
                    continue;
                }
                (Act::Pop, None) => {
                    if let Some(b) = branches.pop() {
                        t = b;
                        out.lift();
                    }
                    continue;
                }
                _ => {}
            }
            let x = self.summary(c, d, t.state);
            // The step in the walk's units, times the summary's unit.
            let k = ldexp(t.scale, self.unit_of(c, d) - unit);
            if let Some(w) = rewritten {
                if x.draws() && out.enter(&x, k) {
                    stack.push((w, d - 1));
                    continue;
                }
            }
            let end = [
                t.pos[0] + k * x.end[0],
                t.pos[1] + k * x.end[1],
                t.pos[2] + k * x.end[2],
            ];
            if x.draws() {
                let subtree = Subtree {
                    symbol: c,
                    depth: if rewritten.is_some() { d } else { 0 },
                    swapped: t.state % 2 == 1,
                };
                let at = Placement {
                    pos: t.pos,
                    frame: self.frames[t.state as usize / 2],
                    scale: t.scale,
                };
                out.whole(subtree, &at, end);
            } else if end != t.pos {
                out.lift();
            }
            t.pos = end;
            t.state = x.state;
            t.scale *= x.scale;
        }
    }
}

/// A subtree of the derivation: `symbol` rewritten `depth` more times
/// (0: the symbol itself), its turns swapped or not. Every occurrence
/// draws the same, once placed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Subtree {
    pub symbol: SymbolId,
    pub depth: u64,
    pub swapped: bool,
}

/// Where a subtree starts: position, frame (heading, left, up) and step
/// length. What it draws there is what [`Instanced::walk_subtree`] draws,
/// turned from the start frame to `frame`, scaled by `scale` and moved
/// to `pos`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    pub pos: Vec3,
    pub frame: [Vec3; 3],
    pub scale: f64,
}

/// What [`Instanced::walk`] is walked for.
pub trait Walker {
    /// Whether to walk into the drawing subtree summarised by `x`, at
    /// step length `scale` (which takes `x`'s lengths, in the unit of its
    /// level, to the walk's units), rather than take it whole.
    fn enter(&mut self, x: &Summary, scale: f64) -> bool;
    /// A drawing subtree (or a single drawn step, `depth` 0) taken whole:
    /// placed at `at`, ending at `end`.
    fn whole(&mut self, subtree: Subtree, at: &Placement, end: Vec3);
    /// The turtle moved without drawing: what follows starts anew.
    fn lift(&mut self);
}

/// [`Instanced::lines`]' walker: subtrees within half a pixel are lines.
struct Within<'o> {
    pixels: f64,
    out: &'o mut dyn Lines,
}

impl Walker for Within<'_> {
    fn enter(&mut self, x: &Summary, scale: f64) -> bool {
        let extent = (0..2)
            .map(|i| (x.hi[i] - x.lo[i]) * scale * self.pixels)
            .fold(0.0, f64::max);
        extent >= WITHIN
    }

    fn whole(&mut self, _: Subtree, at: &Placement, end: Vec3) {
        self.out.line(at.pos, end);
    }

    fn lift(&mut self) {
        self.out.lift();
    }
}

/// Where [`Instanced::lines`] draws.
pub trait Lines {
    /// A line from `a` to `b` (turtle units).
    fn line(&mut self, a: Vec3, b: Vec3);
    /// The turtle moved without drawing: the next line starts anew.
    fn lift(&mut self);
}

/// Where the walk of [`Instanced::lines`] is: position, state, step.
#[derive(Clone, Copy)]
struct Turtle {
    pos: Vec3,
    state: u32,
    scale: f64,
}
