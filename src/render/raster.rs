//! A software z-buffer renderer for lit looks (cpfg objects): what cpfg
//! draws with OpenGL, drawn here the same way.
//!
//! Everything becomes screen-space triangles with a depth and a colour per
//! vertex (lighting per vertex, as OpenGL's fixed function lights), drawn
//! into a supersampled colour and depth buffer (the nearer sample wins; on
//! a tie the first drawn) and box-filtered down. Lines are drawn by the
//! look's line style: screen-space lines of a pixel width, flat ribbons
//! facing the viewer, or cylinders; spheres (`@O`) are lit per sample.
//!
//! Nothing drawn needs storing: a z-buffer needs no order. What is drawn
//! comes from a [`Drawing`], replayed: once to survey its framing, then
//! once per thread for each band of rows, each thread drawing every other
//! stripe of rows into its own buffers. The buffers cover a band at a time,
//! so that memory stays bounded at any picture size ([`MAX_BAND_SAMPLES`]);
//! each band's rows go to the PNG encoder as they are done. Every sample is
//! drawn from the same things in the same order whichever band, stripe or
//! thread holds it: the same input gives the same bytes on any machine.

use super::camera::{cross, dot, sub, unit, Projector};
use super::shade::{to_colour, Colour, Kind, Paint, Shader};
use super::{Fit, Palette, RenderOptions};
use crate::ir::look::{Lighting, LineStyle, Shading};
use crate::ir::Rgb;
use crate::turtle::{Disc, Geometry, Polygon, Segment, Sink, Vec3};
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::sync::atomic::{AtomicU64, Ordering};

/// Samples (colour and depth, 8 bytes each) held at once: 64 MB.
const MAX_BAND_SAMPLES: usize = 8 << 20;

/// Polygons with more corners than this are fanned instead of ear-clipped
/// (ear clipping takes a time quadratic in the corners).
const MAX_EAR_CLIPPED: usize = 4096;

/// Samples across a pixel, each way: more in small pictures, where a pixel
/// is a larger share of the picture.
fn samples_per_pixel(width: u32, height: u32) -> u32 {
    match width.max(height) {
        0..=512 => 3,
        513..=2048 => 2,
        _ => 1,
    }
}

/// A vertex in samples (x right, y down), with its depth (smaller is
/// nearer) and colour.
#[derive(Clone, Copy, Debug)]
struct SVert {
    x: f64,
    y: f64,
    z: f64,
    c: Colour,
}

/// A band of sample rows, or one thread's share of it: the band's rows
/// are dealt out in stripes of `stripe` rows to `shares` targets, and this
/// one holds the stripes of share `share` (colour and depth), so that
/// threads drawing a plant share its dense parts alike.
struct Target {
    /// First sample row of the band, and its rows.
    y0: i64,
    rows: i64,
    width: i64,
    stripe: i64,
    shares: i64,
    share: i64,
    colour: Vec<u32>,
    depth: Vec<f32>,
}

/// An opaque colour as `0xAARRGGBB`.
fn pack(c: Colour) -> u32 {
    let q = |x: f32| (x.clamp(0.0, 1.0) * 255.0 + 0.5) as u32;
    (255 << 24) | (q(c[0]) << 16) | (q(c[1]) << 8) | q(c[2])
}

/// Twice the signed area of (a, b, p); swapping a and b negates it exactly,
/// so triangles sharing an edge leave no gap along it.
fn edge(a: &SVert, b: &SVert, px: f64, py: f64) -> f64 {
    (a.x - px) * (b.y - py) - (a.y - py) * (b.x - px)
}

impl Target {
    /// Share `share` of `shares` of the band, in stripes of `stripe` rows.
    fn share(
        y0: i64,
        rows: i64,
        width: i64,
        (background, alpha): (Rgb, u8),
        (stripe, shares, share): (i64, i64, i64),
    ) -> Target {
        let mut t = Target {
            y0,
            rows,
            width,
            stripe,
            shares,
            share,
            colour: Vec::new(),
            depth: Vec::new(),
        };
        let held = (0..rows).filter(|r| t.owns(y0 + r)).count();
        let n = held * width.max(0) as usize;
        let bg = pack(to_colour(background)) & 0x00ff_ffff | u32::from(alpha) << 24;
        t.colour = vec![bg; n];
        t.depth = vec![f32::INFINITY; n];
        t
    }

    /// Whether sample row `y` is held here.
    fn owns(&self, y: i64) -> bool {
        let r = y - self.y0;
        (0..self.rows).contains(&r) && (r / self.stripe) % self.shares == self.share
    }

    /// Where held row `y` is stored.
    fn local(&self, y: i64) -> i64 {
        let r = y - self.y0;
        r / self.stripe / self.shares * self.stripe + r % self.stripe
    }

    /// Whether sample rows `lo..=hi` meet the band.
    fn meets(&self, lo: f64, hi: f64) -> bool {
        hi >= self.y0 as f64 - 1.0 && lo <= (self.y0 + self.rows) as f64 + 1.0
    }

    fn plot(&mut self, x: i64, y: i64, z: f64, c: Colour) {
        let i = (self.local(y) * self.width + x) as usize;
        let z = z as f32;
        if z < self.depth[i] {
            self.depth[i] = z;
            self.colour[i] = pack(c);
        }
    }

    /// The rows of samples whose centres lie in `lo..=hi`, in the band
    /// (those held here: [`Target::owns`]).
    fn rows_between(&self, lo: f64, hi: f64) -> std::ops::Range<i64> {
        let first = ((lo - 0.5).ceil() as i64).max(self.y0);
        let last = ((hi - 0.5).floor() as i64).min(self.y0 + self.rows - 1);
        first..last + 1
    }

    fn triangle(&mut self, v: [SVert; 3]) {
        if v.iter()
            .any(|p| !(p.x.is_finite() && p.y.is_finite() && p.z.is_finite()))
        {
            return;
        }
        let area = edge(&v[0], &v[1], v[2].x, v[2].y);
        // NaN-safe: a NaN area is not above the bound either.
        if area.abs().partial_cmp(&1e-12) != Some(std::cmp::Ordering::Greater) {
            return;
        }
        let v = if area < 0.0 { [v[0], v[2], v[1]] } else { v };
        let area = area.abs();
        let lo = v.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
        let hi = v.iter().map(|p| p.y).fold(f64::NEG_INFINITY, f64::max);
        for y in self.rows_between(lo, hi) {
            if !self.owns(y) {
                continue;
            }
            let yc = y as f64 + 0.5;
            let Some((xl, xr)) = span(&v, yc) else {
                continue;
            };
            let first = ((xl - 0.5).ceil() as i64 - 1).max(0);
            let last = ((xr - 0.5).floor() as i64 + 1).min(self.width - 1);
            for x in first..=last {
                let xc = x as f64 + 0.5;
                let w0 = edge(&v[1], &v[2], xc, yc);
                let w1 = edge(&v[2], &v[0], xc, yc);
                let w2 = edge(&v[0], &v[1], xc, yc);
                if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                    continue;
                }
                let (b0, b1, b2) = (w0 / area, w1 / area, w2 / area);
                let z = b0 * v[0].z + b1 * v[1].z + b2 * v[2].z;
                let (b0, b1, b2) = (b0 as f32, b1 as f32, b2 as f32);
                let c = [0, 1, 2].map(|k| b0 * v[0].c[k] + b1 * v[1].c[k] + b2 * v[2].c[k]);
                self.plot(x, y, z, c);
            }
        }
    }

    /// A line between `a` and `b` (samples) `width` samples wide, with
    /// square ends reaching half its width past them, in one colour.
    fn line(&mut self, a: [f64; 3], b: [f64; 3], width: f64, c: Colour) {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = (dx * dx + dy * dy).sqrt();
        if len.partial_cmp(&1e-9) != Some(std::cmp::Ordering::Greater) || !width.is_finite() {
            return;
        }
        let h = width.clamp(1.0, 1e6) / 2.0;
        let (tx, ty) = (dx / len * h, dy / len * h);
        let (nx, ny) = (-ty, tx);
        let at = |p: [f64; 3], s: f64, side: f64| SVert {
            x: p[0] + s * tx + side * nx,
            y: p[1] + s * ty + side * ny,
            z: p[2],
            c,
        };
        let q = [
            at(a, -1.0, -1.0),
            at(a, -1.0, 1.0),
            at(b, 1.0, 1.0),
            at(b, 1.0, -1.0),
        ];
        self.triangle([q[0], q[1], q[2]]);
        self.triangle([q[0], q[2], q[3]]);
    }
}

/// Where the row at `yc` crosses the triangle `v`: its leftmost and
/// rightmost x.
fn span(v: &[SVert; 3], yc: f64) -> Option<(f64, f64)> {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for (p, q) in [(&v[0], &v[1]), (&v[1], &v[2]), (&v[2], &v[0])] {
        let (y0, y1) = (p.y.min(q.y), p.y.max(q.y));
        if yc < y0 || yc > y1 {
            continue;
        }
        let x = if y1 - y0 > 1e-12 {
            p.x + (yc - p.y) * (q.x - p.x) / (q.y - p.y)
        } else {
            lo = lo.min(p.x.min(q.x));
            p.x.max(q.x)
        };
        lo = lo.min(x);
        hi = hi.max(x);
    }
    (lo <= hi).then_some((lo, hi))
}

/// What a lit picture is drawn from: everything drawn, given to a sink in
/// the same order each time it is replayed (once to find the framing, then
/// once per band of rows, bands on several threads). A stored [`Geometry`]
/// replays itself; the driver replays the turtle, so that nothing drawn is
/// stored.
pub struct Drawing<'d> {
    source: Source<'d>,
    /// Whether segment widths are in turtle units ([`Geometry::world_widths`]).
    world_widths: bool,
}

enum Source<'d> {
    Stored(&'d Geometry),
    /// Gives everything to the sink; returns the deepest branch nesting.
    Replayed(&'d (dyn Fn(&mut dyn Sink) -> usize + Sync)),
}

impl<'d> Drawing<'d> {
    pub fn stored(g: &'d Geometry) -> Self {
        Drawing {
            source: Source::Stored(g),
            world_widths: g.world_widths,
        }
    }

    /// The drawing `replay` gives each time it is called (the same each
    /// time), its widths in turtle units when `world_widths`.
    pub fn replayed(
        replay: &'d (dyn Fn(&mut dyn Sink) -> usize + Sync),
        world_widths: bool,
    ) -> Self {
        Drawing {
            source: Source::Replayed(replay),
            world_widths,
        }
    }

    /// Gives everything drawn to `sink`; the deepest branch nesting.
    fn replay(&self, sink: &mut dyn Sink) -> usize {
        match self.source {
            Source::Stored(g) => {
                g.replay(sink);
                g.max_depth
            }
            Source::Replayed(f) => f(sink),
        }
    }
}

/// What a lit picture is drawn with: the projection, the fit, the shading.
struct Scene<'a> {
    lighting: &'a Lighting,
    shader: Shader<'a>,
    proj: Projector,
    fit: Fit,
    /// Samples per pixel each way.
    ss: f64,
    /// The style's line colours (`--palette`), instead of the system's.
    palette: Option<Palette>,
    world_widths: bool,
    /// Segments in the drawing and its deepest nesting (for `--palette`).
    segments: usize,
    max_depth: usize,
}

/// Draws `g` as its look `lighting` says, `palette` its colour map (never
/// empty), into PNG bytes; `None` for a picture of no pixels or when the
/// encoder fails. `progress(done, total)` is told as things are drawn.
pub fn png(
    g: &Geometry,
    lighting: &Lighting,
    palette: &[Rgb],
    opts: &RenderOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Option<Vec<u8>> {
    let drawing = Drawing::stored(g);
    let survey = survey(&drawing, lighting, opts);
    png_surveyed(&drawing, &survey, lighting, palette, opts, progress)
}

/// The first pass over `drawing` ([`Survey`]).
pub fn survey(drawing: &Drawing<'_>, lighting: &Lighting, opts: &RenderOptions) -> Survey {
    Survey::of(drawing, lighting, opts)
}

/// [`png`] of a drawing replayed ([`Drawing`]), its first pass done
/// (`survey`, which found its framing): drawn into each band of rows as it
/// comes; only the bands and a run of polygons ([`MAX_RUN`]) are held.
pub fn png_surveyed(
    drawing: &Drawing<'_>,
    survey: &Survey,
    lighting: &Lighting,
    palette: &[Rgb],
    opts: &RenderOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Option<Vec<u8>> {
    if palette.is_empty() {
        return None;
    }
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get().clamp(1, MAX_THREADS));
    let scene = Scene::new(survey, drawing.world_widths, lighting, palette, opts);
    png_in_bands(drawing, &scene, survey.drawn, opts, threads, progress)
}

/// Draws `scene` (`drawn` things, replayed from `drawing`) in bands on
/// `threads` threads, into PNG bytes.
fn png_in_bands(
    drawing: &Drawing<'_>,
    scene: &Scene<'_>,
    drawn_each: u64,
    opts: &RenderOptions,
    threads: usize,
    progress: &mut dyn FnMut(u64, u64),
) -> Option<Vec<u8>> {
    let (w, h) = (opts.width, opts.height);
    if w == 0 || h == 0 {
        return None;
    }
    let ss = samples_per_pixel(w, h);
    let bands = Bands::new(w, h, ss);
    let total = drawn_each.saturating_mul((bands.count() * threads) as u64);
    let mut out = Vec::new();
    let mut encoder = ::png::Encoder::new(&mut out, w, h);
    encoder.set_color(::png::ColorType::Rgba);
    encoder.set_depth(::png::BitDepth::Eight);
    let mut writer = encoder.write_header().ok()?;
    let mut stream = writer.stream_writer().ok()?;
    let drawn = AtomicU64::new(0);
    let stripe = i64::from(STRIPE_PIXELS * ss);
    for i in 0..bands.count() {
        let (row, rows) = bands.band(i);
        let share_of = |share: usize| {
            Target::share(
                i64::from(row * ss),
                i64::from(rows * ss),
                i64::from(w * ss),
                (opts.background, opts.background_alpha),
                (stripe, threads as i64, share as i64),
            )
        };
        let paint = |target, progress| {
            let mut painter = Painter::new(scene, target, &drawn, progress);
            drawing.replay(&mut painter);
            downsample(&painter.finish(), w, ss)
        };
        // This thread draws share 0 (and tells the progress); the others
        // the rest.
        let shares: Vec<Vec<u8>> = std::thread::scope(|scope| {
            let others: Vec<_> = (1..threads)
                .map(|k| scope.spawn(move || paint(share_of(k), None)))
                .collect();
            let first = paint(share_of(0), Some((&mut *progress, total)));
            std::iter::once(first)
                .chain(others.into_iter().map(|t| t.join().unwrap_or_default()))
                .collect()
        });
        let pixels = interleave(
            &shares,
            (w * 4) as usize,
            rows as usize,
            STRIPE_PIXELS as usize,
        );
        std::io::Write::write_all(&mut stream, &pixels?).ok()?;
    }
    progress(total, total);
    stream.finish().ok()?;
    drop(writer);
    Some(out)
}

/// Threads drawing a band at once, at most.
const MAX_THREADS: usize = 8;

/// Pixel rows in a stripe of a thread's share of a band ([`Target`]).
const STRIPE_PIXELS: u32 = 4;

/// The rows of a band of `rows` rows of `row_bytes` from its shares, each
/// holding every `shares.len()`th stripe of `stripe` rows; `None` when a
/// share is short (its thread failed).
fn interleave(shares: &[Vec<u8>], row_bytes: usize, rows: usize, stripe: usize) -> Option<Vec<u8>> {
    let mut out = Vec::with_capacity(rows * row_bytes);
    let mut next = vec![0; shares.len()];
    for r in 0..rows {
        let k = (r / stripe) % shares.len();
        let row = shares[k].get(next[k]..next[k] + row_bytes)?;
        out.extend_from_slice(row);
        next[k] += row_bytes;
    }
    Some(out)
}

/// The bands of rows a picture is drawn in, one after another: each at most
/// [`MAX_BAND_SAMPLES`] samples (all threads' shares together). A sample's
/// colour does not depend on which band or share holds it, so neither do
/// the picture's bytes.
struct Bands {
    h: u32,
    rows: u32,
}

impl Bands {
    fn new(w: u32, h: u32, ss: u32) -> Self {
        let row_samples = w as usize * (ss * ss) as usize;
        let rows = (MAX_BAND_SAMPLES / row_samples).clamp(1, h as usize) as u32;
        Bands { h, rows }
    }

    fn count(&self) -> usize {
        self.h.div_ceil(self.rows) as usize
    }

    /// Band `i`'s first row and its number of rows.
    fn band(&self, i: usize) -> (u32, u32) {
        let row = i as u32 * self.rows;
        (row, self.rows.min(self.h - row))
    }
}

/// The framing [`png`] gives `g` lit by `lighting` (its extent includes
/// cylinders' and spheres' radii).
pub fn framing(g: &Geometry, lighting: &Lighting, opts: &RenderOptions) -> super::Framing {
    Survey::of(&Drawing::stored(g), lighting, opts)
        .fit(opts)
        .framing
}

/// The pixels of the rows `t` holds, RGBA, each the mean of its samples.
fn downsample(t: &Target, w: u32, ss: u32) -> Vec<u8> {
    let (w, ss) = (w as usize, ss as usize);
    let rows = t.colour.len() / (t.width.max(1) as usize * ss);
    let n = (ss * ss) as u32;
    let mut out = Vec::with_capacity(w * rows * 4);
    for y in 0..rows {
        for x in 0..w {
            // Colours weighed by their opacity, so that a transparent
            // background's colour does not tint the edges.
            let mut sum = [0u32; 4];
            for sy in 0..ss {
                let base = (y * ss + sy) * t.width as usize + x * ss;
                for c in &t.colour[base..base + ss] {
                    let a = c >> 24;
                    sum[0] += ((c >> 16) & 255) * a;
                    sum[1] += ((c >> 8) & 255) * a;
                    sum[2] += (c & 255) * a;
                    sum[3] += a;
                }
            }
            let a = sum[3].max(1);
            out.extend(sum[..3].iter().map(|s| ((s + a / 2) / a) as u8));
            out.push(((sum[3] + n / 2) / n) as u8);
        }
    }
    out
}

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
    segments: usize,
    /// Everything drawn (for progress).
    drawn: u64,
    max_depth: usize,
}

impl Survey {
    pub(super) fn of(drawing: &Drawing<'_>, lighting: &Lighting, opts: &RenderOptions) -> Self {
        let turn = opts.style.rotate.to_radians().sin_cos();
        let mut survey = Survey {
            proj: Projector::new(opts),
            world_lines: lighting.line_style != LineStyle::Pixel,
            turn: (turn.1, turn.0),
            extremes: [([0.0; 2], f64::NEG_INFINITY); 6],
            bbox: None,
            segments: 0,
            drawn: 0,
            max_depth: 0,
        };
        survey.max_depth = drawing.replay(&mut survey);
        survey
    }

    /// The fit of everything surveyed into the picture of `opts`.
    pub(super) fn fit(&self, opts: &RenderOptions) -> Fit {
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
    pub(super) fn centre(&self) -> Vec3 {
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
            let t = super::rotate(q, self.turn);
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

/// A polygon's triangles (corner indices), its normal and, when shading is
/// smooth, the normal at each corner.
struct Tessellated {
    triangles: Vec<[usize; 3]>,
    normal: Vec3,
    corner_normals: Option<Vec<Vec3>>,
}

/// Polygons whose smooth normals are shared, at most: a surface's or a
/// cylinder's triangles come one after another, and are smoothed together.
const MAX_RUN: usize = 1 << 14;

/// Whom to tell how much is drawn, and of what total.
type Progress<'p> = (&'p mut dyn FnMut(u64, u64), u64);

/// The second pass: everything drawn into a band as it comes. Polygons
/// that come one after another (a run) are held until the run ends, so
/// that their shared corners get one normal; a segment is held until the
/// next, whose width a tapered look ends it with.
struct Painter<'s, 'p> {
    scene: &'s Scene<'s>,
    target: Target,
    run: Vec<Polygon>,
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
    /// Whom to tell of `drawn` (of a total), on one thread.
    progress: Option<Progress<'p>>,
}

impl<'s, 'p> Painter<'s, 'p> {
    fn new(
        scene: &'s Scene<'s>,
        target: Target,
        drawn: &'p AtomicU64,
        progress: Option<Progress<'p>>,
    ) -> Self {
        Painter {
            scene,
            target,
            run: Vec::new(),
            normals: Normals::default(),
            shown: Vec::new(),
            corners: Vec::new(),
            held: None,
            segments: 0,
            uncounted: 0,
            drawn,
            progress,
        }
    }

    fn tick(&mut self) {
        self.uncounted += 1;
        if self.uncounted == 1 << 14 {
            let all = self.drawn.fetch_add(self.uncounted, Ordering::Relaxed) + self.uncounted;
            self.uncounted = 0;
            if let Some((progress, total)) = &mut self.progress {
                progress(all, *total);
            }
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

    /// The band, with everything drawn.
    fn finish(mut self) -> Target {
        self.drawn.fetch_add(self.uncounted, Ordering::Relaxed);
        self.flush_run();
        self.draw_held(None);
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

impl<'a> Scene<'a> {
    fn new(
        survey: &Survey,
        world_widths: bool,
        lighting: &'a Lighting,
        palette: &'a [Rgb],
        opts: &RenderOptions,
    ) -> Scene<'a> {
        let proj = Projector::new(opts);
        Scene {
            lighting,
            shader: Shader::new(lighting, palette, proj.towards_viewer(survey.centre())),
            proj,
            fit: survey.fit(opts),
            ss: f64::from(samples_per_pixel(opts.width, opts.height)),
            palette: opts.style.palette,
            world_widths,
            segments: survey.segments,
            max_depth: survey.max_depth,
        }
    }

    /// The paint of segment `s`, the `i`th drawn: its own, or the style's.
    fn segment_paint(&self, s: &Segment, i: usize) -> Paint {
        Palette::paint_of(self.palette, s, i, self.segments, self.max_depth)
    }

    /// `p` in samples, with its depth; `None` behind a perspective's eye.
    fn to_samples(&self, p: Vec3) -> Option<[f64; 3]> {
        let (xy, z) = self.proj.project(p)?;
        let px = self.fit.to_px(xy);
        let depth = if self.proj.perspective() { -1.0 / z } else { z };
        Some([px[0] * self.ss, px[1] * self.ss, depth])
    }

    fn vert(&self, p: Vec3, c: Colour) -> Option<SVert> {
        let [x, y, z] = self.to_samples(p)?;
        Some(SVert { x, y, z, c })
    }

    /// Samples per world unit at `p`.
    fn samples_per_unit(&self, p: Vec3) -> f64 {
        let z = self.proj.project(p).map_or(1.0, |r| r.1);
        self.proj.pixels_per_unit(&self.fit, z) * self.ss
    }

    /// A colour for a primitive lit with normal `n` at `p`, by the look's
    /// shading.
    fn colour(&self, kind: Kind, paint: Paint, p: Vec3, n: Vec3) -> Colour {
        match self.lighting.shading {
            Shading::Filled | Shading::Wireframe => self.shader.flat(paint),
            Shading::Flat | Shading::Smooth => {
                let v = self.proj.towards_viewer(p);
                self.shader.shade(kind, paint, p, n, v)
            }
        }
    }

    /// A screen-space line `pixels` wide, unlit.
    fn pixel_line(&self, t: &mut Target, a: Vec3, b: Vec3, pixels: f64, c: Colour) {
        let (Some(pa), Some(pb)) = (self.to_samples(a), self.to_samples(b)) else {
            return;
        };
        let half = pixels * self.ss / 2.0 + 1.0;
        if t.meets(pa[1].min(pb[1]) - half, pa[1].max(pb[1]) + half) {
            t.line(pa, pb, pixels * self.ss, c);
        }
    }
}

/// Newell's normal of a polygon (length: twice its area); zero for a
/// degenerate one.
pub(super) fn newell(points: &[Vec3]) -> Vec3 {
    let mut n = [0.0; 3];
    for (i, a) in points.iter().enumerate() {
        let b = points[(i + 1) % points.len()];
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    n
}

/// Summed normals by corner position ([`key`]).
type Normals = HashMap<[u64; 3], Vec3, BuildHasherDefault<PointHasher>>;

/// A multiplicative hash of a corner's bits: a run's corners are looked up
/// a dozen times per polygon, where a keyed hash (SipHash) or a tree would
/// cost more than drawing. Lookups only; nothing iterates the map, so its
/// order cannot reach the picture.
#[derive(Default)]
struct PointHasher(u64);

impl Hasher for PointHasher {
    fn write(&mut self, bytes: &[u8]) {
        // A key's three words come here as one slice of bytes.
        for word in bytes.chunks(8) {
            let mut b = [0u8; 8];
            b[..word.len()].copy_from_slice(word);
            self.write_u64(u64::from_le_bytes(b));
        }
    }
    fn write_u64(&mut self, n: u64) {
        self.0 = (self.0.rotate_left(5) ^ n).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
    fn finish(&self) -> u64 {
        self.0
    }
}

fn key(p: Vec3) -> [u64; 3] {
    p.map(f64::to_bits)
}

/// Each polygon corner's summed face normals over the polygons that share
/// it (same position), each face turned to agree with the sum so far: the
/// smooth normals of a surface given as separate triangles.
fn shared_normals(polygons: &[Polygon], sums: &mut Normals) {
    sums.clear();
    for p in polygons {
        let Some(n) = unit(newell(&p.points)) else {
            continue;
        };
        for &q in &p.points {
            let sum = sums.entry(key(q)).or_insert([0.0; 3]);
            let s = if dot(*sum, n) < 0.0 { -1.0 } else { 1.0 };
            for k in 0..3 {
                sum[k] += s * n[k];
            }
        }
    }
}

/// A polygon's triangles and normals.
fn tessellate(p: &Polygon, shared: Option<&Normals>) -> Tessellated {
    let finite = p.points.iter().all(|q| q.iter().all(|c| c.is_finite()));
    let normal = if finite {
        unit(newell(&p.points))
    } else {
        None
    };
    let Some(normal) = normal.filter(|_| p.points.len() >= 3) else {
        return Tessellated {
            triangles: Vec::new(),
            normal: [0.0, 0.0, 1.0],
            corner_normals: None,
        };
    };
    let corner_normals = shared.map(|sums| {
        p.points
            .iter()
            .map(|&q| {
                let n = sums.get(&key(q)).and_then(|&s| unit(s)).unwrap_or(normal);
                let n = if dot(n, normal) < 0.0 {
                    n.map(|c| -c)
                } else {
                    n
                };
                // A crease (over 60°) keeps the face's own normal.
                if dot(n, normal) < 0.5 {
                    normal
                } else {
                    n
                }
            })
            .collect()
    });
    Tessellated {
        triangles: ear_clip(&p.points, normal),
        normal,
        corner_normals,
    }
}

/// Triangles covering the polygon `pts` (concave allowed), by ear
/// clipping in the plane across its normal `n`.
fn ear_clip(pts: &[Vec3], n: Vec3) -> Vec<[usize; 3]> {
    let count = pts.len();
    if count == 3 || count > MAX_EAR_CLIPPED {
        return (1..count - 1).map(|i| [0, i, i + 1]).collect();
    }
    // Drop the axis the normal is most along; keep the turn direction.
    let axis = (0..3)
        .max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
        .unwrap_or(2);
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    let flat: Vec<[f64; 2]> = pts.iter().map(|p| [p[u], p[v]]).collect();
    let turn = if n[axis] < 0.0 { -1.0 } else { 1.0 };
    let cross2 = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        turn * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
    };
    let mut left: Vec<usize> = (0..count).collect();
    let mut out = Vec::with_capacity(count - 2);
    let mut misses = 0;
    let mut i = 0;
    while left.len() > 3 {
        let m = left.len();
        let (a, b, c) = (left[(i + m - 1) % m], left[i % m], left[(i + 1) % m]);
        let convex = cross2(flat[a], flat[b], flat[c]) > 0.0;
        let empty = || {
            left.iter().all(|&k| {
                k == a
                    || k == b
                    || k == c
                    || cross2(flat[a], flat[b], flat[k]) < 0.0
                    || cross2(flat[b], flat[c], flat[k]) < 0.0
                    || cross2(flat[c], flat[a], flat[k]) < 0.0
            })
        };
        // After a whole round without an ear (a self-crossing or
        // degenerate polygon) any corner is clipped, so this ends.
        if (convex && empty()) || misses > m {
            out.push([a, b, c]);
            left.remove(i % m);
            misses = 0;
        } else {
            i += 1;
            misses += 1;
        }
        i %= left.len();
    }
    out.push([left[0], left[1], left[2]]);
    out
}

/// Polygons, lines and discs.
impl Scene<'_> {
    /// Adds to `out` where `p`'s corners fall in samples, when it can show
    /// in the band `t` (else adds nothing and says so): every corner in front of the eye, and some sample's centre
    /// within its box (a triangle is drawn at the centres it covers, so one
    /// between centres draws nothing). A wireframe's outlines are lines of
    /// a pixel or more: every polygon shows (with no corners given).
    fn corners_shown(&self, t: &Target, p: &Polygon, out: &mut Vec<[f64; 3]>) -> bool {
        if self.lighting.shading == Shading::Wireframe {
            return true;
        }
        let at = out.len();
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for &q in &p.points {
            let Some(c) = self.to_samples(q) else {
                out.truncate(at);
                return false;
            };
            for k in 0..2 {
                lo[k] = lo[k].min(c[k]);
                hi[k] = hi[k].max(c[k]);
            }
            out.push(c);
        }
        let first_x = ((lo[0] - 0.5).ceil() as i64).max(0);
        let last_x = ((hi[0] - 0.5).floor() as i64).min(t.width - 1);
        let mut rows = t.rows_between(lo[1], hi[1]);
        let shown = first_x <= last_x && rows.any(|y| t.owns(y));
        if !shown {
            out.truncate(at);
        }
        shown
    }

    /// Draws `p`, its corners in samples `corners` ([`Scene::corners_shown`];
    /// none for a wireframe).
    fn polygon(&self, t: &mut Target, p: &Polygon, tess: &Tessellated, corners: &[[f64; 3]]) {
        if tess.triangles.is_empty() {
            return;
        }
        let pts = &p.points;
        if self.lighting.shading == Shading::Wireframe {
            let c = self.shader.unlit(p.colour, p.index);
            let width = self.fit.line_width(1.0, false);
            for (i, &a) in pts.iter().enumerate() {
                self.pixel_line(t, a, pts[(i + 1) % pts.len()], width, c);
            }
            return;
        }
        // Two-sided: the face's normal turned towards the viewer.
        let centre = pts
            .iter()
            .fold([0.0; 3], |s, q| [s[0] + q[0], s[1] + q[1], s[2] + q[2]]);
        let centre = centre.map(|c| c / pts.len() as f64);
        let facing = dot(tess.normal, self.proj.towards_viewer(centre)) >= 0.0;
        let turn = |n: Vec3| if facing { n } else { n.map(|c| -c) };
        let paint = Paint::own(p.colour, p.index);
        let colours: Vec<Colour> = match &tess.corner_normals {
            Some(normals) => pts
                .iter()
                .zip(normals)
                .map(|(&q, &n)| self.colour(Kind::of(p), paint, q, turn(n)))
                .collect(),
            None => {
                let c = self.colour(Kind::of(p), paint, centre, turn(tess.normal));
                vec![c; pts.len()]
            }
        };
        let vert = |i: usize| SVert {
            x: corners[i][0],
            y: corners[i][1],
            z: corners[i][2],
            c: colours[i],
        };
        for &[a, b, c] in &tess.triangles {
            t.triangle([vert(a), vert(b), vert(c)]);
        }
    }

    fn segment(&self, t: &mut Target, s: &Segment, paint: Paint, end_width: f64) {
        if self.lighting.shading == Shading::Wireframe {
            let c = self.shader.flat(paint);
            return self.pixel_line(t, s.a, s.b, self.fit.line_width(1.0, false), c);
        }
        match self.lighting.line_style {
            LineStyle::Pixel => {
                let c = self.shader.flat(paint);
                let width = self.fit.line_width(s.width, self.world_widths);
                self.pixel_line(t, s.a, s.b, width, c);
            }
            LineStyle::Polygon => self.ribbon(t, s, paint, end_width),
            LineStyle::Cylinder => {
                let r = s.width.max(end_width).abs() / 2.0;
                if r * self.samples_per_unit(s.a) < 1.5 {
                    self.ribbon(t, s, paint, end_width);
                } else {
                    self.cylinder(t, s, paint, end_width);
                }
            }
        }
    }

    /// A flat band of the segment's width facing the viewer (cpfg's
    /// `polygon` line style; also a cylinder too thin to show its sides).
    fn ribbon(&self, t: &mut Target, s: &Segment, paint: Paint, end_width: f64) {
        let Some(axis) = unit(sub(s.b, s.a)) else {
            return;
        };
        let mid = [0, 1, 2].map(|k| (s.a[k] + s.b[k]) / 2.0);
        let v = self.proj.towards_viewer(mid);
        // Seen end on, a ribbon shows nothing (as in cpfg).
        let Some(side) = unit(cross(axis, v)) else {
            return;
        };
        let n = cross(side, axis);
        let c = self.colour(Kind::Line, paint, mid, n);
        let (ra, rb) = (s.width.abs() / 2.0, end_width.abs() / 2.0);
        let at = |p: Vec3, r: f64| {
            (
                self.vert([0, 1, 2].map(|k| p[k] - side[k] * r), c),
                self.vert([0, 1, 2].map(|k| p[k] + side[k] * r), c),
            )
        };
        let ((Some(a0), Some(a1)), (Some(b0), Some(b1))) = (at(s.a, ra), at(s.b, rb)) else {
            return;
        };
        let lo = [a0.y, a1.y, b0.y, b1.y]
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        let hi = [a0.y, a1.y, b0.y, b1.y]
            .into_iter()
            .fold(f64::NEG_INFINITY, f64::max);
        if t.meets(lo, hi) {
            t.triangle([a0, a1, b1]);
            t.triangle([a0, b1, b0]);
        }
    }

    /// A cylinder (a cone when tapered) from the segment's width to
    /// `end_width`, its sides lit smooth around the axis (or one colour per
    /// side when shading is flat); sides facing away are not drawn.
    fn cylinder(&self, t: &mut Target, s: &Segment, paint: Paint, end_width: f64) {
        let Some(axis) = unit(sub(s.b, s.a)) else {
            return;
        };
        let (Some(pa), Some(pb)) = (self.to_samples(s.a), self.to_samples(s.b)) else {
            return;
        };
        let (ra, rb) = (s.width.abs() / 2.0, end_width.abs() / 2.0);
        let reach = ra.max(rb) * self.samples_per_unit(s.a).max(self.samples_per_unit(s.b));
        if !t.meets(pa[1].min(pb[1]) - reach, pa[1].max(pb[1]) + reach) {
            return;
        }
        let helper = if axis[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let Some(u) = unit(cross(axis, helper)) else {
            return;
        };
        let w = cross(axis, u);
        let sides = if reach < 8.0 { 8 } else { 12 };
        let around = |k: f64| {
            let (sn, cs) = (k * std::f64::consts::TAU / sides as f64).sin_cos();
            [0, 1, 2].map(|i| u[i] * cs + w[i] * sn)
        };
        let mid = [0, 1, 2].map(|k| (s.a[k] + s.b[k]) / 2.0);
        let v = self.proj.towards_viewer(mid);
        let smooth = self.lighting.shading == Shading::Smooth;
        let ring = |p: Vec3, r: f64, k: usize, n: Vec3| {
            let q = [0, 1, 2].map(|i| p[i] + around(k as f64)[i] * r);
            self.vert(q, self.colour(Kind::Line, paint, q, n))
        };
        for k in 0..sides {
            let face = around(k as f64 + 0.5);
            if dot(face, v) < -0.3 {
                continue;
            }
            let (n0, n1) = if smooth {
                (around(k as f64), around(k as f64 + 1.0))
            } else {
                (face, face)
            };
            let corners = (
                ring(s.a, ra, k, n0),
                ring(s.a, ra, k + 1, n1),
                ring(s.b, rb, k + 1, n1),
                ring(s.b, rb, k, n0),
            );
            if let (Some(a0), Some(a1), Some(b1), Some(b0)) = corners {
                t.triangle([a0, a1, b1]);
                t.triangle([a0, b1, b0]);
            }
        }
    }

    fn disc(&self, t: &mut Target, d: &Disc) {
        let Some(c) = self.to_samples(d.centre) else {
            return;
        };
        let r_world = d.diameter.abs() / 2.0;
        let r = if d.pixels {
            r_world * self.fit.line_unit * self.ss
        } else {
            r_world * self.samples_per_unit(d.centre)
        };
        if !r.is_finite() || r <= 0.0 || !t.meets(c[1] - r, c[1] + r) {
            return;
        }
        let unlit = self.shader.unlit(d.colour, d.index);
        let lit = matches!(self.lighting.shading, Shading::Flat | Shading::Smooth);
        if self.lighting.shading == Shading::Wireframe {
            let width = self.fit.line_width(1.0, false) * self.ss;
            let n = 32;
            for k in 0..n {
                let at = |k: usize| {
                    let (sn, cs) = (k as f64 * std::f64::consts::TAU / n as f64).sin_cos();
                    [c[0] + r * cs, c[1] + r * sn, c[2]]
                };
                t.line(at(k), at(k + 1), width, unlit);
            }
        } else if d.pixels || !lit {
            flat_disc(t, c, r, unlit);
        } else {
            self.sphere(t, d, c, r, r_world);
        }
    }

    /// A lit sphere of world radius `r_world` around `d.centre`, at `c` (samples)
    /// and `r` samples across: a normal and a depth per sample.
    fn sphere(&self, t: &mut Target, d: &Disc, c: [f64; 3], r: f64, r_world: f64) {
        let (right, up) = self.proj.screen_axes(d.centre);
        let back = self.proj.towards_viewer(d.centre);
        let centre_z = self.proj.project(d.centre).map_or(0.0, |p| p.1);
        let perspective = self.proj.perspective();
        for y in t.rows_between(c[1] - r, c[1] + r) {
            if !t.owns(y) {
                continue;
            }
            let dy = (y as f64 + 0.5 - c[1]) / r;
            let half = (1.0 - dy * dy).max(0.0).sqrt() * r;
            let first = ((c[0] - half - 0.5).ceil() as i64).max(0);
            let last = ((c[0] + half - 0.5).floor() as i64).min(t.width - 1);
            for x in first..=last {
                let dx = (x as f64 + 0.5 - c[0]) / r;
                let q = 1.0 - dx * dx - dy * dy;
                if q < 0.0 {
                    continue;
                }
                let nz = q.sqrt();
                let n = [0, 1, 2].map(|k| right[k] * dx - up[k] * dy + back[k] * nz);
                let p = [0, 1, 2].map(|k| d.centre[k] + n[k] * r_world);
                let z = if perspective {
                    -1.0 / (centre_z - nz * r_world).max(1e-300)
                } else {
                    c[2] - nz * r_world
                };
                let colour = self.colour(Kind::Line, Paint::own(d.colour, d.index), p, n);
                t.plot(x, y, z, colour);
            }
        }
    }
}

/// A flat disc at `c` (samples, depth), `r` samples across.
fn flat_disc(t: &mut Target, c: [f64; 3], r: f64, colour: Colour) {
    let n = ((r * 2.0).ceil() as usize).clamp(8, 64);
    let centre = SVert {
        x: c[0],
        y: c[1],
        z: c[2],
        c: colour,
    };
    let at = |k: usize| {
        let (sn, cs) = (k as f64 * std::f64::consts::TAU / n as f64).sin_cos();
        SVert {
            x: c[0] + r * cs,
            y: c[1] + r * sn,
            ..centre
        }
    };
    for k in 0..n {
        t.triangle([centre, at(k), at(k + 1)]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::look::{Camera, Light, Material};

    const BLACK: Rgb = Rgb(0, 0, 0);

    fn lighting(shading: Shading, line_style: LineStyle) -> Lighting {
        Lighting {
            shading,
            line_style,
            ..Lighting::default()
        }
    }

    fn draw(g: &Geometry, l: &Lighting, opts: &RenderOptions) -> tiny_skia::Pixmap {
        let palette: Vec<Rgb> = (0..=255).map(|i| Rgb(i as u8, i as u8, i as u8)).collect();
        let bytes = png(g, l, &palette, opts, &mut |_, _| {}).expect("a picture");
        tiny_skia::Pixmap::decode_png(&bytes).expect("a PNG")
    }

    fn small(size: u32) -> RenderOptions {
        RenderOptions {
            width: size,
            height: size,
            background: BLACK,
            ..RenderOptions::default()
        }
    }

    fn rgb(pm: &tiny_skia::Pixmap, x: u32, y: u32) -> [u8; 3] {
        let p = pm.pixel(x, y).unwrap().demultiply();
        [p.red(), p.green(), p.blue()]
    }

    fn square(z: f64, half: f64, grey: u8) -> Polygon {
        Polygon {
            points: vec![
                [-half, -half, z],
                [half, -half, z],
                [half, half, z],
                [-half, half, z],
            ],
            colour: Rgb(grey, grey, grey),
            index: grey as u16,
            surface: false,
        }
    }

    #[test]
    fn the_nearer_triangle_wins_whatever_the_order() {
        let filled = lighting(Shading::Filled, LineStyle::Pixel);
        let (near, far) = (square(1.0, 1.0, 200), square(-1.0, 2.0, 100));
        for polygons in [vec![near.clone(), far.clone()], vec![far, near]] {
            let g = Geometry {
                polygons,
                ..Geometry::default()
            };
            let pm = draw(&g, &filled, &small(60));
            assert_eq!(rgb(&pm, 30, 30), [200; 3]);
            assert_eq!(rgb(&pm, 5, 5), [100; 3]);
        }
    }

    #[test]
    fn a_concave_polygon_covers_its_area() {
        // An L of area 3 in a 2×2 box, and a point so the fit is known.
        let l_shape = Polygon {
            points: vec![
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [2.0, 1.0, 0.0],
                [1.0, 1.0, 0.0],
                [1.0, 2.0, 0.0],
                [0.0, 2.0, 0.0],
            ],
            colour: Rgb(255, 255, 255),
            index: 255,
            surface: false,
        };
        let g = Geometry {
            polygons: vec![l_shape],
            ..Geometry::default()
        };
        let size = 100;
        let pm = draw(
            &g,
            &lighting(Shading::Filled, LineStyle::Pixel),
            &small(size),
        );
        let covered: f64 = pm.pixels().iter().map(|p| f64::from(p.red()) / 255.0).sum();
        // The 2×2 box fills 90% of the picture each way.
        let unit = (0.9 * f64::from(size) / 2.0).powi(2);
        let area = covered / unit;
        assert!((area - 3.0).abs() < 0.09, "area {area}");
    }

    #[test]
    fn a_lit_sphere_is_brighter_towards_the_light() {
        let mut l = lighting(Shading::Smooth, LineStyle::Cylinder);
        l.lights = vec![Light {
            vector: [1.0, 0.0, 0.0],
            directional: true,
            ambient: [0.0; 3],
            ..Light::default()
        }];
        l.materials = vec![Some(Material::CPFG_DEFAULT)];
        let g = Geometry {
            discs: vec![Disc {
                centre: [0.0; 3],
                diameter: 2.0,
                pixels: false,
                colour: Rgb(255, 255, 255),
                index: 0,
            }],
            ..Geometry::default()
        };
        let pm = draw(&g, &l, &small(60));
        let (right, left) = (rgb(&pm, 45, 30)[0], rgb(&pm, 15, 30)[0]);
        assert!(right > 100 && left < 20, "right {right}, left {left}");
    }

    #[test]
    fn colour_map_cylinders_move_the_index_around_the_axis() {
        let mut l = lighting(Shading::Smooth, LineStyle::Cylinder);
        l.lights = vec![Light {
            vector: [1.0, 0.0, 0.0],
            directional: true,
            ..Light::default()
        }];
        l.index_shift = 50.0;
        let g = Geometry {
            segments: vec![Segment {
                a: [0.0, -2.0, 0.0],
                b: [0.0, 2.0, 0.0],
                width: 2.0,
                colour: Rgb(100, 100, 100),
                index: 100,
                depth: 0,
            }],
            ..Geometry::default()
        };
        let pm = draw(&g, &l, &small(60));
        // Seen face on, the cylinder spans x = 30 ± 9 pixels: lit towards
        // +x (index up to 150), darker towards −x (down to 50); 5 pixels
        // off the axis N·L is ±0.6.
        let (right, middle, left) = (
            rgb(&pm, 35, 30)[0],
            rgb(&pm, 30, 30)[0],
            rgb(&pm, 25, 30)[0],
        );
        assert!(right > 120 && left < 80, "{left} {middle} {right}");
        assert!((95..=105).contains(&middle), "{middle}");
    }

    #[test]
    fn the_background_fills_what_nothing_covers() {
        let g = Geometry {
            polygons: vec![square(0.0, 1.0, 255)],
            discs: vec![Disc {
                centre: [5.0, 5.0, 0.0],
                diameter: 0.0,
                pixels: true,
                colour: Rgb(255, 255, 255),
                index: 255,
            }],
            ..Geometry::default()
        };
        let opts = RenderOptions {
            background: Rgb(10, 20, 30),
            ..small(40)
        };
        let pm = draw(&g, &lighting(Shading::Filled, LineStyle::Pixel), &opts);
        let bg = pm
            .pixels()
            .iter()
            .filter(|p| [p.red(), p.green(), p.blue()] == [10, 20, 30]);
        // The fit holds −1..5 each way in 36 pixels: the square covers
        // 12 × 12 pixels.
        let n = bg.count();
        assert!((40 * 40 - 170..=40 * 40 - 120).contains(&n), "{n}");
        let empty = draw(
            &Geometry::default(),
            &lighting(Shading::Flat, LineStyle::Cylinder),
            &opts,
        );
        assert!(empty
            .pixels()
            .iter()
            .all(|p| [p.red(), p.green(), p.blue()] == [10, 20, 30]));
    }

    #[test]
    fn a_transparent_background_stays_transparent_around_what_is_drawn() {
        let g = Geometry {
            polygons: vec![square(0.0, 1.0, 255)],
            ..Geometry::default()
        };
        let opts = RenderOptions {
            background: Rgb(10, 20, 30),
            background_alpha: 0,
            ..small(40)
        };
        let pm = draw(&g, &lighting(Shading::Filled, LineStyle::Pixel), &opts);
        let alphas: Vec<u8> = pm.pixels().iter().map(|p| p.alpha()).collect();
        assert_eq!(alphas[0], 0);
        assert!(alphas.contains(&255));
        // An edge pixel half covered is the square's colour, half opaque:
        // no tint of the transparent background's colour.
        let inside = pm.pixel(20, 20).unwrap();
        assert_eq!(inside.alpha(), 255);
        let near = |a: u8, b: u8| a.abs_diff(b) <= 3;
        for p in pm.pixels().iter().filter(|p| (1..255).contains(&p.alpha())) {
            let c = p.demultiply();
            assert!(
                near(c.red(), inside.red()) && near(c.blue(), inside.blue()),
                "{c:?} {inside:?}"
            );
        }
    }

    #[test]
    fn a_camera_puts_its_target_at_the_centre() {
        // A small square at the target and a bigger one off to the side.
        let target = [3.0, 1.0, 0.0];
        let mut off = square(0.0, 0.5, 100);
        for p in &mut off.points {
            p[0] += 3.0 + 4.0;
            p[1] += 1.0 + 1.0;
        }
        let mut mark = square(0.0, 0.2, 255);
        for p in &mut mark.points {
            p[0] += target[0];
            p[1] += target[1];
        }
        let g = Geometry {
            polygons: vec![mark, off],
            ..Geometry::default()
        };
        let opts = RenderOptions {
            camera: Some(Camera {
                eye: [3.0, 1.0, 20.0],
                target,
                up: [0.0, 1.0, 0.0],
                perspective: Some(30.0),
            }),
            ..small(81)
        };
        let pm = draw(&g, &lighting(Shading::Filled, LineStyle::Pixel), &opts);
        assert_eq!(rgb(&pm, 40, 40), [255; 3]);
        // The mark is 0.4 wide against an extent of ±4.5: ~3.6 pixels.
        assert_eq!(rgb(&pm, 40, 34), [0; 3]);
        assert_eq!(rgb(&pm, 46, 40), [0; 3]);
    }

    #[test]
    fn the_same_input_gives_the_same_bytes() {
        let g = Geometry {
            segments: (0..50)
                .map(|i| {
                    let t = f64::from(i) * 0.3;
                    Segment {
                        a: [t.cos(), t, t.sin()],
                        b: [(t + 0.3).cos(), t + 0.3, (t + 0.3).sin()],
                        width: 0.2,
                        colour: Rgb(90, 90, 90),
                        index: 90,
                        depth: 0,
                    }
                })
                .collect(),
            polygons: vec![square(0.5, 1.0, 50)],
            ..Geometry::default()
        };
        let l = lighting(Shading::Smooth, LineStyle::Cylinder);
        let palette = [Rgb(1, 2, 3), Rgb(200, 100, 50)];
        let once = png(&g, &l, &palette, &small(70), &mut |_, _| {});
        let twice = png(&g, &l, &palette, &small(70), &mut |_, _| {});
        assert!(once.is_some());
        assert_eq!(once, twice);
    }

    /// A helix of tapered cylinders through a smooth surface of quads and
    /// spheres, drawn in any number of bands on any number of threads:
    /// the same bytes, since a sample's colour does not depend on its band.
    #[test]
    fn bands_and_threads_do_not_change_the_picture() {
        let mut g = Geometry::default();
        for i in 0..40 {
            let t = f64::from(i) * 0.3;
            g.segment(Segment {
                a: [t.cos(), t / 3.0, t.sin()],
                b: [(t + 0.3).cos(), (t + 0.3) / 3.0, (t + 0.3).sin()],
                width: 0.3 - f64::from(i) * 0.005,
                colour: Rgb(90, 90, 90),
                index: 90,
                depth: 0,
            });
            if i % 10 == 0 {
                for k in 0..6 {
                    let (a, b) = (f64::from(k) * 0.2, f64::from(k + 1) * 0.2);
                    g.polygon(Polygon {
                        points: vec![
                            [a, t / 3.0, a * a],
                            [b, t / 3.0, b * b],
                            [b, t / 3.0 + 0.4, b * b],
                            [a, t / 3.0 + 0.4, a * a],
                        ],
                        colour: Rgb(40, 160, 40),
                        index: 40,
                        surface: true,
                    });
                }
                g.disc(Disc {
                    centre: [0.0, t / 3.0, 0.0],
                    diameter: 0.5,
                    colour: Rgb(200, 30, 30),
                    pixels: false,
                    index: 200,
                });
            }
        }
        let l = Lighting {
            tapered: true,
            ..lighting(Shading::Smooth, LineStyle::Cylinder)
        };
        let palette = [Rgb(1, 2, 3), Rgb(200, 100, 50)];
        let opts = RenderOptions {
            width: 60,
            height: 301,
            ..small(60)
        };
        let drawing = Drawing::stored(&g);
        let survey = survey(&drawing, &l, &opts);
        let scene = Scene::new(&survey, false, &l, &palette, &opts);
        let draw = |threads| {
            png_in_bands(
                &drawing,
                &scene,
                survey.drawn,
                &opts,
                threads,
                &mut |_, _| {},
            )
            .expect("a picture")
        };
        let one = draw(1);
        for threads in [2, 3, 7] {
            assert!(
                draw(threads) == one,
                "{threads} threads draw another picture"
            );
        }
        // And the picture is not blank: a band drawn twice or not at all
        // would show.
        let pm = tiny_skia::Pixmap::decode_png(&one).unwrap();
        let lit = (0..301)
            .filter(|&y| (0..60).any(|x| rgb(&pm, x, y) != [0, 0, 0]))
            .count();
        assert!(lit > 60, "{lit} rows drawn");
    }

    #[test]
    fn empty_and_degenerate_geometry_draws_without_panicking() {
        let seg = |a: Vec3, b: Vec3, width: f64| Segment {
            a,
            b,
            width,
            colour: BLACK,
            index: 0,
            depth: 0,
        };
        let g = Geometry {
            segments: vec![
                seg([0.0; 3], [0.0; 3], 1.0),
                seg([0.0; 3], [0.0, 1.0, 0.0], f64::NAN),
                seg([0.0; 3], [0.0, 0.0, 5.0], 1.0),
                seg([f64::NAN; 3], [0.0; 3], 1.0),
                seg([0.0; 3], [1e300, 0.0, 0.0], 1e300),
            ],
            polygons: vec![
                Polygon {
                    points: vec![[0.0; 3], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0], [3.0, 3.0, 3.0]],
                    colour: BLACK,
                    index: 0,
                    surface: false,
                },
                Polygon {
                    points: vec![[0.0; 3], [1.0, 0.0, 0.0]],
                    colour: BLACK,
                    index: 0,
                    surface: false,
                },
                // A bow tie: crosses itself.
                Polygon {
                    points: vec![[0.0; 3], [1.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
                    colour: BLACK,
                    index: 7,
                    surface: false,
                },
            ],
            discs: vec![Disc {
                centre: [0.0; 3],
                diameter: f64::INFINITY,
                pixels: false,
                colour: BLACK,
                index: 300,
            }],
            ..Geometry::default()
        };
        for shading in [
            Shading::Filled,
            Shading::Wireframe,
            Shading::Flat,
            Shading::Smooth,
        ] {
            for style in [LineStyle::Pixel, LineStyle::Polygon, LineStyle::Cylinder] {
                let l = lighting(shading, style);
                for size in [1, 7] {
                    draw(&g, &l, &small(size));
                    draw(&Geometry::default(), &l, &small(size));
                }
                let zero = RenderOptions {
                    width: 0,
                    ..small(5)
                };
                assert!(png(&g, &l, &[BLACK], &zero, &mut |_, _| {}).is_none());
            }
        }
    }

    #[test]
    fn ear_clipping_covers_a_concave_polygon_once() {
        let pts = [
            [0.0, 0.0, 0.0],
            [4.0, 0.0, 0.0],
            [4.0, 4.0, 0.0],
            [2.0, 1.0, 0.0],
            [0.0, 4.0, 0.0],
        ];
        let tris = ear_clip(&pts, [0.0, 0.0, 1.0]);
        assert_eq!(tris.len(), 3);
        let area: f64 = tris
            .iter()
            .map(|&[a, b, c]| {
                let (p, q, r) = (pts[a], pts[b], pts[c]);
                ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])).abs() / 2.0
            })
            .sum();
        assert!((area - 10.0).abs() < 1e-9, "{area}");
    }
}
