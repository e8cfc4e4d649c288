//! Rendering [`Geometry`] to pictures: a projection from a view or a
//! camera ([`camera`]), fitted into the picture with a margin, then PNG
//! ([`png`], tiny-skia, flat colours in the painter's order, or [`raster`],
//! a z-buffer with lights for systems whose look is lit) or SVG ([`svg`]).

pub mod animate;
pub mod attractor;
pub mod axes;
pub mod camera;
pub mod coverage;
pub mod png;
pub mod raster;
mod shade;
pub mod shared;
pub mod simplify;
pub mod svg;
pub mod text;

use crate::ir::look::Camera;
use crate::ir::Rgb;
use crate::turtle::{Geometry, Segment, Vec3};
use camera::Projector;

/// The background of a picture whose look names none.
pub const WHITE: Rgb = Rgb(255, 255, 255);

/// A view direction: azimuth about the y axis, then elevation about the x
/// axis, in radians. (0, 0) looks down −z with x to the right and y up.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct View {
    pub azimuth: f64,
    pub elevation: f64,
}

impl View {
    /// The view of `azimuth` and `elevation` given in degrees.
    pub fn degrees(azimuth: f64, elevation: f64) -> Self {
        View {
            azimuth: azimuth.to_radians(),
            elevation: elevation.to_radians(),
        }
    }
}

/// Picture settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderOptions {
    pub width: u32,
    pub height: u32,
    pub view: View,
    /// Share of the picture the figure fills, 0..=100 (pfg scale factor).
    pub scale: f64,
    /// Draw each turtle path ([`Geometry::paths`]) as a uniform cubic
    /// B-spline with the turtle positions as control points (the book's
    /// Fig. 2.10, 2.11 and kolams), instead of the segments.
    pub spline: bool,
    /// Whether `view` was asked for (`--view`): it then overrides the
    /// file's camera.
    pub view_given: bool,
    /// The file's camera ([`crate::ir::look::Look::camera`]), used instead
    /// of `view` when given.
    pub camera: Option<Camera>,
    /// The background.
    pub background: Rgb,
    /// The background's opacity: 0 transparent (PNG alpha 0, no SVG
    /// background), 255 opaque.
    pub background_alpha: u8,
    /// The line width a stroke width is relative to: the system's initial
    /// width ([`crate::ir::Settings::width`]).
    pub base_width: f64,
    /// What the command line asks of the picture's style.
    pub style: Style,
    /// A fixed framing instead of fitting what is drawn: the frames of an
    /// animation all take the last frame's ([`framing`]).
    pub framing: Option<Framing>,
    /// What an SVG keeps of detail finer than its pixels.
    pub detail: Detail,
    /// Whether a dense drawing's lines are thinned to show its density
    /// ([`Fit::thinned`]): for pixels (PNG). An SVG keeps its widths: it is
    /// drawn at any zoom, and merging (`detail`) drops the overlapping
    /// strokes whose sum would show density.
    pub thin_dense: bool,
    /// Whether the picture keeps, per part, which module of the word drew
    /// it (the geometry's [`Origins`](crate::turtle::Origins)): a picture
    /// linked to its source ([`Links`]). Runs of lines are then split where
    /// the module changes.
    pub linked: bool,
    /// Threads that draw; 0 for every core. The picture is the same for
    /// every count.
    pub threads: usize,
}

/// What an SVG keeps of detail finer than half a pixel at its size
/// (`--detail`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Detail {
    /// Lines that add nothing visible left out, nearly collinear points
    /// merged ([`simplify`]).
    #[default]
    Merged,
    /// Every segment as the turtle drew it.
    Full,
}

impl Detail {
    pub const NAMES: [&'static str; 2] = ["merged", "full"];

    pub fn from_name(name: &str) -> Option<Detail> {
        match name {
            "merged" => Some(Detail::Merged),
            "full" => Some(Detail::Full),
            _ => None,
        }
    }
}

/// Where a fit puts the picture plane, as [`layout`] found it for one
/// geometry: the bounds of what is drawn (turned by the style's rotation)
/// and the pad kept within a margin. Given in [`RenderOptions::framing`],
/// it fits every picture the same way, whatever it draws.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Framing {
    lo: [f64; 2],
    hi: [f64; 2],
    pad: f64,
}

/// The framing [`layout`] gives `g` with `opts`.
pub fn framing(g: &Geometry, opts: &RenderOptions) -> Framing {
    let proj = Projector::new(opts);
    let p = projected(g, opts, &proj);
    let pad = half_widest(&p.segments, opts, g.world_widths);
    let unframed = RenderOptions {
        framing: None,
        ..*opts
    };
    proj.fit_padded(&p.extent, &unframed, pad).framing
}

/// Style options every drawing tool has (`graftal render --background`,
/// `--stroke-width`, `--margin`, `--rotate`, `--palette`); `None` keeps the
/// system's own.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Style {
    /// The background instead of the look's (or white).
    pub background: Option<crate::ir::colours::Rgba>,
    /// Pixels of a line of the system's initial width; other widths scale
    /// with it (a line twice as wide is twice as many pixels).
    pub stroke_width: Option<f64>,
    /// The blank border the fit keeps on every side.
    pub margin: Option<Margin>,
    /// Degrees the picture turns (counterclockwise) before it is fitted.
    pub rotate: f64,
    /// Line colours instead of the system's.
    pub palette: Option<Palette>,
}

/// A blank border: pixels, or a share of the picture's width (left and
/// right) and height (top and bottom).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Margin {
    Pixels(f64),
    Fraction(f64),
}

impl Margin {
    /// `50` (pixels), `5%` or `0.05` (a share: a number below 1).
    pub fn parse(s: &str) -> Result<Margin, String> {
        let t = s.trim();
        let (number, percent) = match t.strip_suffix('%') {
            Some(n) => (n, true),
            None => (t, false),
        };
        let v: f64 = number
            .trim()
            .parse()
            .ok()
            .filter(|v: &f64| v.is_finite() && *v >= 0.0)
            .ok_or_else(|| {
                format!("`{s}` is not a margin: pixels (`50`) or a share (`5%`, `0.05`)")
            })?;
        let margin = match (percent, v < 1.0) {
            (true, _) => Margin::Fraction(v / 100.0),
            (false, true) => Margin::Fraction(v),
            (false, false) => Margin::Pixels(v),
        };
        match margin {
            Margin::Fraction(f) if f >= 0.5 => {
                Err(format!("margin `{s}` leaves no room: below 50%"))
            }
            m => Ok(m),
        }
    }

    /// The margins left and right, top and bottom, of a `w` × `h` picture.
    fn pixels(self, w: f64, h: f64) -> (f64, f64) {
        match self {
            Margin::Pixels(p) => (p, p),
            Margin::Fraction(f) => (w * f, h * f),
        }
    }
}

/// Line colours for systems without their own (`--palette`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Palette {
    /// Every line black.
    Mono,
    /// By branch depth: brown at the trunk to green at the deepest tips.
    Depth,
    /// Along the turtle's path: the hues of the rainbow, red to violet.
    Rainbow,
}

impl Palette {
    pub const NAMES: [&'static str; 3] = ["mono", "depth", "rainbow"];

    pub fn from_name(name: &str) -> Option<Palette> {
        match name {
            "mono" => Some(Palette::Mono),
            "depth" => Some(Palette::Depth),
            "rainbow" => Some(Palette::Rainbow),
            _ => None,
        }
    }

    /// What segment `i` of `g` is painted with: its own colour without a
    /// palette. Polygons and discs keep theirs in every path.
    pub(crate) fn segment_paint(palette: Option<Palette>, g: &Geometry, i: usize) -> shade::Paint {
        Palette::paint_of(palette, &g.segments[i], i, g.segments.len(), g.max_depth)
    }

    /// The paint of `s`, segment `i` of `n` of a drawing nested at most
    /// `max_depth` deep: its own, or the style's.
    pub(crate) fn paint_of(
        palette: Option<Palette>,
        s: &Segment,
        i: usize,
        n: usize,
        max_depth: usize,
    ) -> shade::Paint {
        match palette {
            Some(p) => shade::Paint::Style(p.colour(i, n, s.depth, max_depth)),
            None => shade::Paint::own(s.colour, s.index),
        }
    }

    /// The colour of segment `i` of `n`, at branch depth `depth` of
    /// `max_depth`.
    fn colour(self, i: usize, n: usize, depth: u16, max_depth: usize) -> Rgb {
        let share = |k: f64, of: f64| {
            if of > 0.0 {
                (k / of).clamp(0.0, 1.0)
            } else {
                0.0
            }
        };
        match self {
            Palette::Mono => Rgb(0, 0, 0),
            Palette::Depth => {
                let t = share(f64::from(depth), max_depth as f64);
                let mix = |a: f64, b: f64| (a + (b - a) * t).round() as u8;
                Rgb(mix(101.0, 60.0), mix(67.0, 179.0), mix(33.0, 60.0))
            }
            Palette::Rainbow => hue(0.8 * share(i as f64, n.saturating_sub(1) as f64)),
        }
    }
}

/// The fully saturated colour of hue `h` (0 red, 1/3 green, 2/3 blue).
fn hue(h: f64) -> Rgb {
    let channel = |offset: f64| {
        let x = ((h * 6.0 + offset) % 6.0 - 3.0).abs() - 1.0;
        (x.clamp(0.0, 1.0) * 255.0).round() as u8
    };
    Rgb(channel(0.0), channel(4.0), channel(2.0))
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 1024,
            height: 1024,
            view: View::default(),
            scale: 100.0,
            spline: false,
            view_given: false,
            camera: None,
            background: WHITE,
            background_alpha: 255,
            base_width: 1.0,
            style: Style::default(),
            framing: None,
            detail: Detail::Merged,
            thin_dense: true,
            linked: false,
            threads: 0,
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
    pub background: Rgb,
    /// The background's opacity ([`RenderOptions::background_alpha`]).
    pub background_alpha: u8,
    pub runs: Vec<Run>,
    pub polygons: Vec<(Rgb, Vec<[f64; 2]>)>,
    /// Text written over the rest (cpfg labels).
    pub labels: Vec<text::Placed>,
    /// What drew each part, in a linked picture.
    pub links: Links,
}

/// Which module of the word drew each part of a picture
/// ([`RenderOptions::linked`]): per run and per polygon its position in
/// the word ([`UNTAGGED`] for a part no module drew), and `names`, what
/// the SVG says of each position (its `data-src`); all empty unless
/// linked.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Links {
    pub runs: Vec<u32>,
    pub polygons: Vec<u32>,
    pub names: Vec<String>,
}

/// The tag of a part drawn by no module (a layout, a scene).
pub const UNTAGGED: u32 = u32::MAX;

impl Links {
    /// What the SVG says of a part tagged `tag`: its `data-src`, if named.
    pub fn name(&self, tag: Option<&u32>) -> Option<&str> {
        self.names.get(*tag? as usize).map(String::as_str)
    }
}

/// How near `p` is to the viewer (larger is nearer): the coordinate along
/// the view direction, towards the eye.
fn depth(p: Vec3, t: Turn) -> f64 {
    let z = -p[0] * t.sa + p[2] * t.ca;
    p[1] * t.se + z * t.ce
}

/// A view's sines and cosines (azimuth, elevation), found once rather than
/// for every point projected.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Turn {
    sa: f64,
    ca: f64,
    se: f64,
    ce: f64,
}

impl Turn {
    pub fn of(view: View) -> Turn {
        let (sa, ca) = view.azimuth.sin_cos();
        let (se, ce) = view.elevation.sin_cos();
        Turn { sa, ca, se, ce }
    }
}

/// The order in which to draw `g`'s segments: farther first, so that nearer
/// segments cover farther ones (the painter's algorithm, by midpoint
/// depth). A flat picture seen face on keeps the turtle's order.
fn depth_order(g: &Geometry, proj: &Projector) -> Option<Vec<usize>> {
    let depths: Vec<f64> = g
        .segments
        .iter()
        .map(|s| {
            let mid = [
                (s.a[0] + s.b[0]) / 2.0,
                (s.a[1] + s.b[1]) / 2.0,
                (s.a[2] + s.b[2]) / 2.0,
            ];
            proj.project(mid).map_or(f64::NEG_INFINITY, |(_, z)| -z)
        })
        .collect();
    let (lo, hi) = depths
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &d| {
            (lo.min(d), hi.max(d))
        });
    if depths.is_empty() || hi - lo <= 1e-9 * (1.0 + hi.abs().max(lo.abs())) {
        return None;
    }
    let mut order: Vec<usize> = (0..depths.len()).collect();
    order.sort_by(|&a, &b| depths[a].total_cmp(&depths[b]));
    Some(order)
}

fn project(p: Vec3, t: Turn) -> [f64; 2] {
    let x = p[0] * t.ca + p[2] * t.sa;
    let z = -p[0] * t.sa + p[2] * t.ca;
    let y = p[1] * t.ce - z * t.se;
    [x, y]
}

/// Samples per control-point span of a spline.
const SPLINE_SAMPLES: usize = 8;

/// The uniform cubic B-spline with control points `ctrl`, sampled; the end
/// points are tripled so the curve starts and ends at them, and a closed
/// path (last point = first) is closed smoothly.
pub fn bspline(ctrl: &[[f64; 2]]) -> Vec<[f64; 2]> {
    if ctrl.len() < 3 {
        return ctrl.to_vec();
    }
    let (first, last) = (ctrl[0], ctrl[ctrl.len() - 1]);
    let extent = ctrl
        .iter()
        .map(|p| (p[0] - first[0]).abs().max((p[1] - first[1]).abs()))
        .fold(0.0, f64::max);
    let closed = (first[0] - last[0]).abs().max((first[1] - last[1]).abs()) <= 1e-9 * extent;
    let pts: Vec<[f64; 2]> = if closed {
        let body = &ctrl[..ctrl.len() - 1];
        let n = body.len();
        (0..n + 3).map(|i| body[i % n]).collect()
    } else {
        [first, first]
            .into_iter()
            .chain(ctrl.iter().copied())
            .chain([last, last])
            .collect()
    };
    let mut out = Vec::with_capacity((pts.len() - 3) * SPLINE_SAMPLES + 1);
    for w in pts.windows(4) {
        for k in 0..SPLINE_SAMPLES {
            let t = k as f64 / SPLINE_SAMPLES as f64;
            let (t2, t3) = (t * t, t * t * t);
            let b0 = (1.0 - t).powi(3) / 6.0;
            let b1 = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
            let b2 = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
            let b3 = t3 / 6.0;
            out.push([
                b0 * w[0][0] + b1 * w[1][0] + b2 * w[2][0] + b3 * w[3][0],
                b0 * w[0][1] + b1 * w[1][1] + b2 * w[2][1] + b3 * w[3][1],
            ]);
        }
    }
    let w = &pts[pts.len() - 4..];
    out.push([
        (w[1][0] + 4.0 * w[2][0] + w[3][0]) / 6.0,
        (w[1][1] + 4.0 * w[2][1] + w[3][1]) / 6.0,
    ]);
    out
}

/// What `g` draws, projected onto the picture plane but not yet fitted:
/// lines, polygons, discs, and the points whose bounds the fit covers.
struct Projected {
    segments: Vec<FlatSegment>,
    polys: Vec<(Rgb, Vec<[f64; 2]>)>,
    /// Colour, radius in pixels or not, centre, radius.
    discs: Vec<(Rgb, bool, [f64; 2], f64)>,
    extent: Vec<[f64; 2]>,
}

/// Projects `g` with `proj` ([`layout`] then fits it).
fn projected(g: &Geometry, opts: &RenderOptions, proj: &Projector) -> Projected {
    let segments = flat_segments(g, opts, proj);
    // Polygons with a corner behind a perspective's eye are left out.
    let polys: Vec<(Rgb, Vec<[f64; 2]>)> = g
        .polygons
        .iter()
        .filter_map(|p| {
            let pts: Option<Vec<[f64; 2]>> = p
                .points
                .iter()
                .map(|&q| proj.project(q).map(|r| r.0))
                .collect();
            pts.map(|pts| (p.colour, pts))
        })
        .collect();
    // Discs: centre and radius in picture units; a radius in pixels is
    // scaled after fitting.
    let discs: Vec<(Rgb, bool, [f64; 2], f64)> = g
        .discs
        .iter()
        .filter_map(|d| {
            let (c, z) = proj.project(d.centre)?;
            let r = d.diameter / 2.0;
            let r = if proj.perspective() && !d.pixels {
                r / z
            } else {
                r
            };
            Some((d.colour, d.pixels, c, r))
        })
        .collect();
    let disc_extent: Vec<[f64; 2]> = discs
        .iter()
        .flat_map(|&(_, pixels, c, r)| {
            let r = if pixels { 0.0 } else { r };
            [[c[0] - r, c[1] - r], [c[0] + r, c[1] + r]]
        })
        .collect();
    let extent: Vec<[f64; 2]> = segments
        .iter()
        .flat_map(|s| [s.a, s.b])
        .chain(polys.iter().flat_map(|p| p.1.iter().copied()))
        .chain(disc_extent)
        .collect();
    Projected {
        segments,
        polys,
        discs,
        extent,
    }
}

/// How much of the picture a drawing covers, in pixels: its extent along
/// the direction it spreads most (`length`) and across it (`width`). A
/// width under a pixel or two is a line at this view and size, a length
/// that small a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spread {
    pub length: f64,
    pub width: f64,
}

/// The [`Spread`] of what `g` draws, fitted into the picture of `opts` as
/// [`layout`] fits it.
pub fn drawn_spread(g: &Geometry, opts: &RenderOptions) -> Spread {
    let proj = Projector::new(opts);
    let p = projected(g, opts, &proj);
    let fit = proj.fit(&p.extent, opts);
    let px: Vec<[f64; 2]> = p.extent.iter().map(|&q| fit.to_px(q)).collect();
    spread(&px)
}

/// The [`Spread`] of a picture already laid out: its lines' and
/// polygons' points, in pixels.
pub fn picture_spread(pic: &Picture) -> Spread {
    let px: Vec<[f64; 2]> = pic
        .runs
        .iter()
        .flat_map(|r| r.lines.iter().flatten().copied())
        .chain(pic.polygons.iter().flat_map(|p| p.1.iter().copied()))
        .collect();
    spread(&px)
}

/// The extent of `points` along their principal axis and across it (so
/// that a slanted line is as thin as a level one).
fn spread(points: &[[f64; 2]]) -> Spread {
    let n = points.len().max(1) as f64;
    let mean = [0, 1].map(|k| points.iter().map(|p| p[k]).sum::<f64>() / n);
    let (mut xx, mut xy, mut yy) = (0.0, 0.0, 0.0);
    for p in points {
        let (dx, dy) = (p[0] - mean[0], p[1] - mean[1]);
        xx += dx * dx;
        xy += dx * dy;
        yy += dy * dy;
    }
    let angle = 0.5 * (2.0 * xy).atan2(xx - yy);
    let (s, c) = angle.sin_cos();
    let range = |f: &dyn Fn(&[f64; 2]) -> f64| {
        let (lo, hi) = points
            .iter()
            .map(f)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            });
        (hi - lo).max(0.0)
    };
    Spread {
        length: range(&|p| p[0] * c + p[1] * s),
        width: range(&|p| p[1] * c - p[0] * s),
    }
}

/// Projects and fits `g` into a `width` × `height` picture.
pub fn layout(g: &Geometry, opts: &RenderOptions) -> Picture {
    let proj = Projector::new(opts);
    let Projected {
        segments,
        polys,
        discs,
        extent,
    } = projected(g, opts, &proj);
    let ink = segments
        .iter()
        .map(|s| (s.b[0] - s.a[0]).hypot(s.b[1] - s.a[1]) * s.width.abs())
        .filter(|i| i.is_finite())
        .sum();
    let widest = segments.iter().map(|s| s.width.abs()).fold(0.0, f64::max);
    let fit = proj
        .fit_padded(&extent, opts, half_widest(&segments, opts, g.world_widths))
        .thinned(ink, widest, g.world_widths || !opts.thin_dense);
    let (runs, run_tags) = runs(&segments, &fit, g.world_widths);
    let mut polygons: Vec<(Rgb, Vec<[f64; 2]>)> = polys
        .into_iter()
        .map(|(c, pts)| (c, pts.into_iter().map(|q| fit.to_px(q)).collect()))
        .collect();
    let mut links = Links::default();
    if opts.linked {
        let tag = |o: Option<&usize>| o.map_or(UNTAGGED, |&o| o.min(UNTAGGED as usize) as u32);
        links.runs = run_tags;
        links.polygons = (0..polygons.len())
            .map(|i| tag(g.origins.polygons.get(i)))
            .chain((0..discs.len()).map(|i| tag(g.origins.discs.get(i))))
            .collect();
    }
    for (colour, pixels, c, r) in discs {
        let r = if pixels {
            r * fit.line_unit
        } else {
            r * fit.scale
        };
        polygons.push((colour, disc_outline(fit.to_px(c), r)));
    }
    let labels = g
        .labels
        .iter()
        .filter_map(|l| {
            Some(text::Placed {
                at: fit.to_px(proj.project(l.at)?.0),
                text: l.text.clone(),
                colour: l.colour,
            })
        })
        .collect();
    Picture {
        width: opts.width,
        height: opts.height,
        background: opts.background,
        background_alpha: opts.background_alpha,
        runs,
        polygons,
        labels,
        links,
    }
}

/// Half the widest of `segments` in pixels, where that does not depend
/// on the fit (widths in pixels, or `--stroke-width`): what an asked-for
/// margin keeps free besides, so that round caps and their anti-aliased
/// edge stay inside it.
fn half_widest(segments: &[FlatSegment], opts: &RenderOptions, world_widths: bool) -> f64 {
    let widest = segments.iter().map(|s| s.width.abs()).fold(0.0, f64::max);
    margin_pad(widest, opts, world_widths)
}

/// [`half_widest`] of lines at most `widest` wide.
pub(crate) fn margin_pad(widest: f64, opts: &RenderOptions, world_widths: bool) -> f64 {
    if opts.style.margin.is_none() || (world_widths && opts.style.stroke_width.is_none()) {
        return 0.0;
    }
    let probe = Fit::new(std::iter::empty(), opts);
    // And a pixel that anti-aliasing touches.
    let half = probe.line_width(widest, world_widths) / 2.0 + 1.0;
    if half.is_finite() {
        half
    } else {
        0.0
    }
}

/// A segment in the picture plane, before fitting.
struct FlatSegment {
    a: [f64; 2],
    b: [f64; 2],
    colour: Rgb,
    width: f64,
    /// The position in the word of the module that drew it, in a linked
    /// picture; else [`UNTAGGED`].
    tag: u32,
}

/// What `g` draws as lines, in the picture plane and in drawing order:
/// with `opts.spline` the B-splines through its paths, else its segments,
/// farther first. Lines reaching behind a perspective's eye are left out.
fn flat_segments(g: &Geometry, opts: &RenderOptions, proj: &Projector) -> Vec<FlatSegment> {
    let mut flat = Vec::new();
    let on_plane = |p: Vec3| proj.project(p).map(|r| r.0);
    if opts.spline {
        for (k, path) in g.paths.iter().enumerate() {
            let Some(ctrl) = path
                .points
                .iter()
                .map(|&p| on_plane(p))
                .collect::<Option<Vec<_>>>()
            else {
                continue;
            };
            let curve = bspline(&ctrl);
            let colour = match opts.style.palette {
                Some(p) => p.colour(k, g.paths.len(), path.depth, g.max_depth),
                None => path.colour,
            };
            flat.extend(curve.windows(2).map(|w| FlatSegment {
                a: w[0],
                b: w[1],
                colour,
                width: path.width,
                tag: UNTAGGED,
            }));
        }
    } else {
        let n = g.segments.len();
        let project_segment = |i: usize| {
            let s = &g.segments[i];
            Some(FlatSegment {
                a: on_plane(s.a)?,
                b: on_plane(s.b)?,
                colour: Palette::segment_paint(opts.style.palette, g, i).colour(),
                width: s.width,
                tag: (g.origins.segments.get(i))
                    .filter(|_| opts.linked)
                    .map_or(UNTAGGED, |&o| o.min(UNTAGGED as usize) as u32),
            })
        };
        match depth_order(g, proj) {
            Some(order) => flat.extend(order.into_iter().filter_map(project_segment)),
            None => flat.extend((0..n).filter_map(project_segment)),
        }
    }
    flat
}

/// The picture plane fitted into the picture: what it draws, turned by
/// the style's rotation, centred, filling the share of the picture the
/// options ask for inside the margin.
pub(crate) struct Fit {
    /// Pixels per picture-plane unit.
    pub(crate) scale: f64,
    centre: [f64; 2],
    width: f64,
    height: f64,
    /// Pixels per pixel of line width: lines are thicker in pictures more
    /// than 600 pixels across, so that they look the same.
    line_unit: f64,
    /// Cosine and sine of the rotation.
    turn: (f64, f64),
    /// `--stroke-width` per unit of the system's initial width.
    stroke_per_width: Option<f64>,
    /// The share of their width that lines in pixels are drawn at
    /// ([`Fit::thinned`]): 1 unless the drawing is dense.
    thin: f64,
    /// What the fit was made from.
    framing: Framing,
}

impl Fit {
    /// The fit of everything at `points` into the picture of `opts`.
    pub(crate) fn new<'p>(
        points: impl Iterator<Item = &'p [f64; 2]>,
        opts: &RenderOptions,
    ) -> Self {
        Fit::padded(points, opts, 0.0)
    }

    /// [`Fit::new`] keeping `pad` more pixels free within an asked-for
    /// margin: half the widest line, so that its caps stay inside.
    pub(crate) fn padded<'p>(
        points: impl Iterator<Item = &'p [f64; 2]>,
        opts: &RenderOptions,
        pad: f64,
    ) -> Self {
        let turn = opts.style.rotate.to_radians().sin_cos();
        let turn = (turn.1, turn.0);
        let mut min = [f64::INFINITY; 2];
        let mut max = [f64::NEG_INFINITY; 2];
        for p in points {
            let p = rotate(*p, turn);
            for k in 0..2 {
                min[k] = min[k].min(p[k]);
                max[k] = max[k].max(p[k]);
            }
        }
        // An animation's frames keep one framing, whatever each draws.
        let pad = opts.framing.map_or(pad, |f| f.pad);
        if let Some(f) = opts.framing {
            (min, max) = (f.lo, f.hi);
        }
        let (w, h) = (opts.width as f64, opts.height as f64);
        let share = opts.scale.clamp(1.0, 100.0) / 100.0;
        // Without a margin the figure fills 90% of each side, as pfg's.
        let (mx, my) = opts.style.margin.map_or((0.05 * w, 0.05 * h), |m| {
            let (mx, my) = m.pixels(w, h);
            (mx + pad, my + pad)
        });
        let (room_w, room_h) = ((w - 2.0 * mx).max(1.0), (h - 2.0 * my).max(1.0));
        let (bw, bh) = (max[0] - min[0], max[1] - min[1]);
        let sx = if bw > 0.0 {
            room_w * share / bw
        } else {
            f64::INFINITY
        };
        let sy = if bh > 0.0 {
            room_h * share / bh
        } else {
            f64::INFINITY
        };
        let mut s = sx.min(sy);
        if !s.is_finite() {
            s = 1.0;
        }
        let centre = [(min[0] + max[0]) / 2.0, (min[1] + max[1]) / 2.0];
        Fit {
            framing: Framing {
                lo: min,
                hi: max,
                pad,
            },
            ..Fit::around(centre, s, opts, pad)
        }
    }

    /// The fit with `scale` pixels a picture-plane unit and `centre` at the
    /// middle of the picture of `opts`.
    pub(crate) fn around(centre: [f64; 2], scale: f64, opts: &RenderOptions, pad: f64) -> Self {
        let (w, h) = (opts.width as f64, opts.height as f64);
        let (sin, cos) = opts.style.rotate.to_radians().sin_cos();
        let base = Some(opts.base_width.abs()).filter(|b| b.is_finite() && *b > 0.0);
        let half = [w / 2.0 / scale, h / 2.0 / scale];
        Fit {
            scale,
            centre,
            width: w,
            height: h,
            line_unit: (w.min(h) / 600.0).max(1.0),
            turn: (cos, sin),
            stroke_per_width: opts.style.stroke_width.map(|sw| sw / base.unwrap_or(1.0)),
            thin: 1.0,
            framing: Framing {
                lo: [centre[0] - half[0], centre[1] - half[1]],
                hi: [centre[0] + half[0], centre[1] + half[1]],
                pad,
            },
        }
    }

    /// A line of `width` in pixels: `--stroke-width` scaled by the width's
    /// share of the initial one, else turtle units scaled with the picture,
    /// or pixels that grow with pictures over 600 pixels.
    pub(crate) fn line_width(&self, width: f64, world_widths: bool) -> f64 {
        if let Some(per) = self.stroke_per_width {
            per * width
        } else if world_widths {
            (width * self.scale).max(0.5)
        } else {
            self.line_unit * width * self.thin
        }
    }

    /// The fit with lines in pixels thinned so that their ink (length
    /// times width, `ink` in plane units times widths) is at most half the
    /// area of the drawing's box (a plant fills about half its box): a dense crown of lines drawn at their
    /// default width would cover its box many times over and show as a
    /// solid mass; thinned, lines narrower than a pixel are drawn as
    /// hairlines whose coverage is their width, so the picture's grey shows
    /// how dense the drawing is. Widths the model gives in its own units or
    /// asked for with `--stroke-width` are kept.
    pub(crate) fn thinned(mut self, ink: f64, widest: f64, keep_widths: bool) -> Self {
        if keep_widths || self.stroke_per_width.is_some() {
            return self;
        }
        let Framing { lo, hi, .. } = self.framing;
        let unit = self.line_unit * widest.abs();
        // A box at least a line wide, so that a straight line keeps its width.
        let area = ((hi[0] - lo[0]) * self.scale + unit) * ((hi[1] - lo[1]) * self.scale + unit);
        let ink = ink * self.scale * self.line_unit;
        let room = area / 2.0;
        if ink > room && room > 0.0 && ink.is_finite() {
            self.thin = room / ink;
        }
        self
    }

    /// `p` in pixels (y down).
    pub(crate) fn to_px(&self, p: [f64; 2]) -> [f64; 2] {
        let [cx, cy] = self.centre;
        let p = rotate(p, self.turn);
        [
            self.width / 2.0 + (p[0] - cx) * self.scale,
            self.height / 2.0 - (p[1] - cy) * self.scale,
        ]
    }
}

/// `p` turned by the angle of cosine and sine `turn` about the origin.
fn rotate(p: [f64; 2], (c, s): (f64, f64)) -> [f64; 2] {
    if (c, s) == (1.0, 0.0) {
        return p;
    }
    [p[0] * c - p[1] * s, p[0] * s + p[1] * c]
}

/// `segments` in pixels, as runs of one colour and width in which
/// segments that continue one another make one polyline.
fn runs(segments: &[FlatSegment], fit: &Fit, world_widths: bool) -> (Vec<Run>, Vec<u32>) {
    let mut runs: Vec<Run> = Vec::new();
    let mut tags: Vec<u32> = Vec::new();
    let mut last_end: Option<[f64; 2]> = None;
    for seg in segments {
        let (pa, pb) = (fit.to_px(seg.a), fit.to_px(seg.b));
        let width = fit.line_width(seg.width, world_widths);
        let same = runs
            .last()
            .is_some_and(|r| r.colour == seg.colour && r.width == width)
            && tags.last() == Some(&seg.tag);
        if !same {
            runs.push(Run {
                colour: seg.colour,
                width,
                lines: Vec::new(),
            });
            tags.push(seg.tag);
            last_end = None;
        }
        let run = runs.last_mut().expect("just pushed");
        match (last_end, run.lines.last_mut()) {
            (Some(end), Some(line)) if end == pa => line.push(pb),
            _ => run.lines.push(vec![pa, pb]),
        }
        last_end = Some(pb);
    }
    // Unlinked pictures keep no tags.
    if tags.iter().all(|&t| t == UNTAGGED) {
        tags.clear();
    }
    (runs, tags)
}

/// A disc of radius `r` around `c` (pixels) as a polygon: a point per
/// pixel of its diameter, at least 8 and at most 64.
fn disc_outline(c: [f64; 2], r: f64) -> Vec<[f64; 2]> {
    let n = ((r * 2.0).ceil() as usize).clamp(8, 64);
    (0..n)
        .map(|k| {
            let (sn, cs) = (k as f64 * std::f64::consts::TAU / n as f64).sin_cos();
            [c[0] + r * cs, c[1] + r * sn]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::turtle::Segment;

    fn seg(a: Vec3, b: Vec3, c: u8) -> Segment {
        Segment {
            a,
            b,
            width: 1.0,
            colour: Rgb(c, c, c),
            index: 0,
            depth: 0,
        }
    }

    #[test]
    fn nearer_segments_are_drawn_last() {
        // A far segment (z = −1) drawn after a near one (z = +1) by the
        // turtle, crossing it in the picture.
        let g = Geometry {
            segments: vec![
                seg([-1.0, 0.0, 1.0], [1.0, 0.0, 1.0], 1),
                seg([0.0, -1.0, -1.0], [0.0, 1.0, -1.0], 2),
            ],
            ..Geometry::default()
        };
        let colours = |view: View| -> Vec<u8> {
            let opts = RenderOptions {
                view,
                ..RenderOptions::default()
            };
            layout(&g, &opts).runs.iter().map(|r| r.colour.0).collect()
        };
        // Seen from +z (the default view) the z = +1 segment is nearer.
        assert_eq!(colours(View::default()), [2, 1]);
        // Seen from −z (azimuth 180°) the other one is.
        let behind = View {
            azimuth: 180.0,
            elevation: 0.0,
        };
        assert_eq!(colours(behind), [1, 2]);
        // Seen from above (elevation 90°) both are at the same height: the
        // turtle's order stays.
        let above = View {
            azimuth: 0.0,
            elevation: 90.0,
        };
        assert_eq!(colours(above), [1, 2]);
    }

    #[test]
    fn open_spline_starts_and_ends_at_the_end_points() {
        let ctrl = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let c = bspline(&ctrl);
        assert_eq!(c.len(), 5 * SPLINE_SAMPLES + 1);
        let near =
            |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).abs() < 1e-12 && (p[1] - q[1]).abs() < 1e-12;
        assert!(near(c[0], ctrl[0]));
        assert!(near(*c.last().unwrap(), ctrl[3]));
        // The curve stays inside the control polygon's hull.
        assert!(c
            .iter()
            .all(|p| (0.0..=1.0).contains(&p[0]) && (0.0..=1.0).contains(&p[1])));
    }

    #[test]
    fn closed_spline_is_closed_and_smooth() {
        let ctrl = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [0.0, 0.0]];
        let c = bspline(&ctrl);
        let (a, b) = (c[0], *c.last().unwrap());
        assert!((a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12);
        // A B-spline of a square's corners cuts the corners: no sample is a corner.
        assert!(!c.iter().any(|p| p == &[0.0, 0.0] || p == &[2.0, 2.0]));
    }
}
