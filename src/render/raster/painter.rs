//! The second pass over a lit drawing: everything drawn into a band of
//! samples as it comes, polygons held in runs that share smooth normals.

use super::target::Target;
use super::tessellate::{shared_normals, tessellate, Normals};
use super::Scene;
use crate::ir::look::Shading;
use crate::turtle::{Disc, Polygon, Segment, Sink};
use std::sync::atomic::{AtomicU64, Ordering};

/// Polygons whose smooth normals are shared, at most: a surface's or a
/// cylinder's triangles come one after another, and are smoothed together.
const MAX_RUN: usize = 1 << 14;

/// The second pass: everything drawn into a band as it comes. Polygons
/// that come one after another (a run) are held until the run ends, so
/// that their shared corners get one normal; a segment is held until the
/// next, whose width a tapered look ends it with.
pub(super) struct Painter<'s, 'p> {
    scene: &'s Scene<'s>,
    target: Target,
    run: Vec<Polygon>,
    /// Polygons of translucent materials, drawn after everything else.
    translucent: Vec<Polygon>,
    /// Scratch for a run: the shared normals, the polygons shown and their
    /// corners in samples (kept to save allocating them each run).
    normals: Normals,
    shown: Vec<(usize, usize)>,
    corners: Vec<[f64; 3]>,
    held: Option<Segment>,
    /// Segments drawn so far (their index, for `--palette`).
    segments: usize,
    /// Drawn and not yet counted in `drawn`, which all threads count in.
    uncounted: u64,
    drawn: &'p AtomicU64,
}

impl<'s, 'p> Painter<'s, 'p> {
    pub(super) fn new(
        scene: &'s Scene<'s>,
        target: Target,
        drawn: &'p AtomicU64,
        first_segment: usize,
    ) -> Self {
        Painter {
            scene,
            target,
            run: Vec::new(),
            translucent: Vec::new(),
            normals: Normals::default(),
            shown: Vec::new(),
            corners: Vec::new(),
            held: None,
            segments: first_segment,
            uncounted: 0,
            drawn,
        }
    }

    fn tick(&mut self) {
        self.uncounted += 1;
        if self.uncounted == 1 << 14 {
            self.drawn.fetch_add(self.uncounted, Ordering::Relaxed);
            self.uncounted = 0;
        }
    }

    /// Draws the run of polygons held.
    fn flush_run(&mut self) {
        if self.run.is_empty() {
            return;
        }
        let scene = self.scene;
        // Each polygon shown, with where its corners start in `corners`.
        let (mut shown, mut corners) = (
            std::mem::take(&mut self.shown),
            std::mem::take(&mut self.corners),
        );
        for (i, p) in self.run.iter().enumerate() {
            let at = corners.len();
            if scene.corners_shown(&self.target, p, &mut corners) {
                shown.push((i, at));
            }
        }
        // Most polygons of a dense plant fall between samples: those cost
        // no normals, no tessellation and no shading.
        if !shown.is_empty() {
            let smooth = scene.lighting.shading == Shading::Smooth;
            if smooth {
                shared_normals(&self.run, &mut self.normals);
            }
            let shared = smooth.then_some(&self.normals);
            for &(i, at) in &shown {
                let p = &self.run[i];
                let tess = tessellate(p, shared);
                let end = (at + p.points.len()).min(corners.len());
                scene.polygon(&mut self.target, p, &tess, &corners[at..end]);
            }
        }
        self.run.clear();
        shown.clear();
        corners.clear();
        (self.shown, self.corners) = (shown, corners);
    }

    /// Draws the segment held, ending with `end_width` when the look tapers.
    fn draw_held(&mut self, next: Option<&Segment>) {
        let Some(s) = self.held.take() else {
            return;
        };
        let end_width = match next {
            Some(next) if self.scene.lighting.tapered && next.a == s.b => next.width,
            _ => s.width,
        };
        let paint = self.scene.segment_paint(&s, self.segments);
        self.segments += 1;
        self.scene.segment(&mut self.target, &s, paint, end_width);
    }

    /// The end of a piece of the drawing: what is held is drawn, so that
    /// each piece draws the same whichever thread draws what follows it.
    pub(super) fn end_piece(&mut self) {
        self.flush_run();
        self.draw_held(None);
        self.drawn.fetch_add(self.uncounted, Ordering::Relaxed);
        self.uncounted = 0;
    }

    /// The band with everything opaque drawn, and the translucent polygons
    /// held to be drawn over it (over every thread's band, merged).
    pub(super) fn opaque(mut self) -> (Target, Vec<Polygon>) {
        self.end_piece();
        (self.target, self.translucent)
    }

    /// `target` with `translucent` blended over it one by one, in order.
    pub(super) fn blend(mut self, translucent: Vec<Polygon>) -> Target {
        for p in translucent {
            self.target.opacity = Some(self.scene.opacity(&p));
            self.run.push(p);
            self.flush_run();
        }
        self.target.opacity = None;
        self.target
    }
}

impl Sink for Painter<'_, '_> {
    fn segment(&mut self, s: Segment) {
        self.flush_run();
        self.draw_held(Some(&s));
        self.held = Some(s);
        self.tick();
    }
    fn polygon(&mut self, p: Polygon) {
        if self.scene.opacity(&p) < 1.0 {
            self.translucent.push(p);
            return self.tick();
        }
        self.run.push(p);
        if self.run.len() >= MAX_RUN {
            self.flush_run();
        }
        self.tick();
    }
    fn disc(&mut self, d: Disc) {
        self.flush_run();
        self.scene.disc(&mut self.target, &d);
        self.tick();
    }
}
