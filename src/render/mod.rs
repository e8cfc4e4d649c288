//! Rendering [`Geometry`] to pictures: an orthographic projection from a
//! view, fitted into the picture with a margin, then PNG ([`png`], tiny-skia)
//! or SVG ([`svg`]).

pub mod png;
pub mod svg;

use crate::ir::Rgb;
use crate::turtle::{Geometry, Vec3};

/// A view direction: azimuth about the y axis, then elevation about the x
/// axis, in degrees. (0, 0) looks down −z with x to the right and y up.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct View {
    pub azimuth: f64,
    pub elevation: f64,
}

/// Picture settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderOptions {
    pub width: u32,
    pub height: u32,
    pub view: View,
    /// Share of the picture the figure fills, 0..=100 (pfg scale factor).
    pub scale: f64,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 1024,
            height: 1024,
            view: View::default(),
            scale: 100.0,
        }
    }
}

/// A run of segments with one colour and width, as pixel polylines.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    pub colour: Rgb,
    /// Stroke width in pixels.
    pub width: f64,
    /// Polylines: each a list of points (pixels, y down).
    pub lines: Vec<Vec<[f64; 2]>>,
}

/// Geometry projected and fitted into the picture.
#[derive(Clone, Debug, PartialEq)]
pub struct Picture {
    pub width: u32,
    pub height: u32,
    pub runs: Vec<Run>,
    pub polygons: Vec<(Rgb, Vec<[f64; 2]>)>,
}

fn project(p: Vec3, view: View) -> [f64; 2] {
    let (sa, ca) = view.azimuth.to_radians().sin_cos();
    let (se, ce) = view.elevation.to_radians().sin_cos();
    let x = p[0] * ca + p[2] * sa;
    let z = -p[0] * sa + p[2] * ca;
    let y = p[1] * ce - z * se;
    [x, y]
}

/// Projects and fits `g` into a `width` × `height` picture.
pub fn layout(g: &Geometry, opts: &RenderOptions) -> Picture {
    let view = opts.view;
    let segs: Vec<([f64; 2], [f64; 2])> = g
        .segments
        .iter()
        .map(|s| (project(s.a, view), project(s.b, view)))
        .collect();
    let polys: Vec<Vec<[f64; 2]>> = g
        .polygons
        .iter()
        .map(|p| p.points.iter().map(|&q| project(q, view)).collect())
        .collect();
    let mut min = [f64::INFINITY; 2];
    let mut max = [f64::NEG_INFINITY; 2];
    for p in segs
        .iter()
        .flat_map(|(a, b)| [a, b])
        .chain(polys.iter().flatten())
    {
        for k in 0..2 {
            min[k] = min[k].min(p[k]);
            max[k] = max[k].max(p[k]);
        }
    }
    let (w, h) = (opts.width as f64, opts.height as f64);
    let fill = 0.9 * opts.scale.clamp(1.0, 100.0) / 100.0;
    let (bw, bh) = (max[0] - min[0], max[1] - min[1]);
    let sx = if bw > 0.0 {
        w * fill / bw
    } else {
        f64::INFINITY
    };
    let sy = if bh > 0.0 {
        h * fill / bh
    } else {
        f64::INFINITY
    };
    let mut s = sx.min(sy);
    if !s.is_finite() {
        s = 1.0;
    }
    let (cx, cy) = ((min[0] + max[0]) / 2.0, (min[1] + max[1]) / 2.0);
    let to_px = |p: [f64; 2]| [w / 2.0 + (p[0] - cx) * s, h / 2.0 - (p[1] - cy) * s];
    let base = (w.min(h) / 600.0).max(1.0);

    let mut runs: Vec<Run> = Vec::new();
    let mut last_end: Option<[f64; 2]> = None;
    for (seg, (a, b)) in g.segments.iter().zip(&segs) {
        let (pa, pb) = (to_px(*a), to_px(*b));
        let width = base * seg.width;
        let same = runs
            .last()
            .is_some_and(|r| r.colour == seg.colour && r.width == width);
        if !same {
            runs.push(Run {
                colour: seg.colour,
                width,
                lines: Vec::new(),
            });
            last_end = None;
        }
        let run = runs.last_mut().expect("just pushed");
        match (last_end, run.lines.last_mut()) {
            (Some(end), Some(line)) if end == pa => line.push(pb),
            _ => run.lines.push(vec![pa, pb]),
        }
        last_end = Some(pb);
    }
    let polygons = g
        .polygons
        .iter()
        .zip(polys)
        .map(|(p, pts)| (p.colour, pts.into_iter().map(to_px).collect()))
        .collect();
    Picture {
        width: opts.width,
        height: opts.height,
        runs,
        polygons,
    }
}
