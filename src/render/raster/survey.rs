//! The first pass over a lit drawing: where it lies in the picture
//! (its framing) and how much it draws.

use super::Drawing;
use crate::ir::look::{Lighting, LineStyle};
use crate::render::camera::Projector;
use crate::render::{Fit, RenderOptions};
use crate::turtle::{Disc, Polygon, Segment, Sink, Vec3};

/// The first pass over a lit drawing: the points of the picture plane
/// that bound it (every corner, and the reach of world-wide lines and
/// spheres), its box in space, and how much it draws.
pub struct Survey {
    proj: Projector,
    world_lines: bool,
    /// The style's rotation, as [`Fit::padded`] turns points.
    turn: (f64, f64),
    /// The points that are furthest each way, turned (least and most x and
    /// y) and unturned (largest |x| and |y|): a fit of these is the fit of
    /// every point.
    extremes: [([f64; 2], f64); 6],
    bbox: Option<[f64; 6]>,
    pub(super) segments: usize,
    /// The segments each piece of the drawing draws (where a thread
    /// starting at a piece starts counting, for `--palette`).
    pub(super) piece_segments: Vec<usize>,
    /// Everything drawn (for progress).
    pub(super) drawn: u64,
    pub(super) max_depth: usize,
}

impl Survey {
    pub(in crate::render) fn of(
        drawing: &Drawing<'_>,
        lighting: &Lighting,
        opts: &RenderOptions,
    ) -> Self {
        let turn = opts.style.rotate.to_radians().sin_cos();
        let empty = || Survey {
            proj: Projector::new(opts),
            world_lines: lighting.line_style != LineStyle::Pixel,
            turn: (turn.1, turn.0),
            extremes: [([0.0; 2], f64::NEG_INFINITY); 6],
            bbox: None,
            segments: 0,
            piece_segments: Vec::new(),
            drawn: 0,
            max_depth: 0,
        };
        let threads = crate::parallel::threads(opts.threads);
        let (parts, depth) = crate::turtle::pieces::each(drawing.pieced(), threads, empty);
        let mut survey = empty();
        for part in parts {
            survey.piece_segments.push(part.segments);
            survey.add(part);
        }
        survey.max_depth = depth;
        survey
    }

    /// Adds what `later` surveyed, as if it had come after what this
    /// survey saw: the same survey as one pass over both.
    fn add(&mut self, later: Survey) {
        for (e, l) in self.extremes.iter_mut().zip(later.extremes) {
            // The first point furthest out wins a tie, as in one pass.
            if l.1 > e.1 {
                *e = l;
            }
        }
        crate::turtle::join_boxes(&mut self.bbox, later.bbox);
        self.segments += later.segments;
        self.drawn += later.drawn;
    }

    /// The fit of everything surveyed into the picture of `opts`.
    pub(in crate::render) fn fit(&self, opts: &RenderOptions) -> Fit {
        let pts: Vec<[f64; 2]> = (self.extremes.iter())
            .filter(|e| e.1 > f64::NEG_INFINITY)
            .map(|e| e.0)
            .collect();
        self.proj.fit(&pts, opts)
    }

    /// How many pixels the drawing spans in the picture of `opts`, the
    /// lesser of its width and height (0 when nothing is drawn).
    pub fn pixels_across(&self, opts: &RenderOptions) -> f64 {
        if self.drawn == 0 {
            return 0.0;
        }
        let fit = self.fit(opts);
        let e = &self.extremes;
        let across = (e[1].1 + e[0].1).min(e[3].1 + e[2].1) * fit.scale;
        if across.is_finite() {
            across
        } else {
            0.0
        }
    }

    /// The middle of the drawing's box in space (where the shader looks
    /// from, for a perspective).
    pub(in crate::render) fn centre(&self) -> Vec3 {
        self.bbox.map_or([0.0; 3], |b| {
            [
                (b[0] + b[3]) / 2.0,
                (b[1] + b[4]) / 2.0,
                (b[2] + b[5]) / 2.0,
            ]
        })
    }

    /// `p` and the reach `r` (world units) around it.
    fn reach(&mut self, p: Vec3, r: f64) {
        crate::turtle::grow_box(&mut self.bbox, p);
        let Some((xy, z)) = self.proj.project(p) else {
            return;
        };
        let r = if self.proj.perspective() { r / z } else { r };
        let r = if r.is_finite() { r.abs() } else { 0.0 };
        for q in [[xy[0] - r, xy[1] - r], [xy[0] + r, xy[1] + r]] {
            let t = crate::render::rotate(q, self.turn);
            let keys = [-t[0], t[0], -t[1], t[1], q[0].abs(), q[1].abs()];
            for (e, key) in self.extremes.iter_mut().zip(keys) {
                // NaN never wins, as in the fit's min and max.
                if key > e.1 {
                    *e = (q, key);
                }
            }
        }
    }
}

impl Sink for Survey {
    fn segment(&mut self, s: Segment) {
        let r = if self.world_lines { s.width / 2.0 } else { 0.0 };
        self.reach(s.a, r);
        self.reach(s.b, r);
        self.segments += 1;
        self.drawn += 1;
    }
    fn polygon(&mut self, p: Polygon) {
        for &q in &p.points {
            self.reach(q, 0.0);
        }
        self.drawn += 1;
    }
    fn disc(&mut self, d: Disc) {
        self.reach(d.centre, if d.pixels { 0.0 } else { d.diameter / 2.0 });
        self.drawn += 1;
    }
}
