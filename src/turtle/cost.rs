//! What a word will draw, counted before the turtle draws it, so that the
//! driver can refuse a word whose geometry would not fit in memory (E0303)
//! instead of running out of it: cpfg surfaces and generalized cylinders
//! make many primitives from one module, which counting moves misses.

use super::interpret::pieces;
use crate::ir::look::ContourRole;
use crate::ir::{System, TurtleOp, Word};

/// The primitives `word` makes: a segment per move, a point per polygon
/// vertex, a surface's triangles, and per cylinder control point its pieces
/// times the widest cross-section's points (the quadrilaterals of a swept
/// contour, or the axis's segments without one).
pub fn drawn_cost(sys: &System, word: &Word) -> u64 {
    let costs = Costs::of(sys);
    let params = word.has_params().then_some(word);
    let first = |i: usize| params.and_then(|w| w.args(i).first().copied());
    let mut cost = 0u64;
    for (i, &s) in word.0.iter().enumerate() {
        cost += costs.drawn(sys.op(s), || first(i));
    }
    cost
}

/// What each module draws, as [`drawn_cost`] counts it.
pub(super) struct Costs<'s> {
    sys: &'s System,
    /// The points of the widest cross-section, if there is one.
    ring: Option<u64>,
}

impl<'s> Costs<'s> {
    pub(super) fn of(sys: &'s System) -> Self {
        let ring = sys
            .contours
            .iter()
            .filter(|c| c.role == ContourRole::CrossSection)
            .map(|c| c.points.len() as u64)
            .max();
        Costs { sys, ring }
    }

    /// The primitives a module with `op` draws, `first` its first
    /// parameter (asked for only where it counts).
    #[inline]
    pub(super) fn drawn(&self, op: Option<TurtleOp>, first: impl FnOnce() -> Option<f64>) -> u64 {
        // A cylinder draws at least 4 pieces of axis, or its pieces of mesh.
        let cylinder = |n: f64| match self.ring {
            Some(r) => pieces(n) as u64 * r,
            None => pieces(n).max(4) as u64,
        };
        match op {
            Some(TurtleOp::Forward { .. } | TurtleOp::ForwardReal { .. }) => 1,
            Some(TurtleOp::Surface(k)) => self
                .sys
                .surfaces
                .get(usize::from(k))
                .map_or(0, |m| m.triangles.len() as u64),
            Some(TurtleOp::CylinderPoint { .. }) => cylinder(first().unwrap_or(1.0)),
            Some(TurtleOp::PolygonVertex) => first().map_or(1, cylinder),
            Some(TurtleOp::PolygonEnd) => first().map_or(0, |_| cylinder(4.0)),
            _ => 0,
        }
    }
}
