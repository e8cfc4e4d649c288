//! Flat line drawings drawn as the turtle makes them: nothing of the
//! geometry is stored, only the picture.
//!
//! Two passes over the word: the first ([`Survey`]) finds what the fit
//! needs (the drawing's bounds, its widest line) and whether the drawing
//! can be drawn this way at all; the second ([`Painter`]) draws each
//! segment into a [`Coverage`] buffer as it comes. What needs storage is
//! drawn the stored way ([`super::layout`]): a drawing with depth (3D
//! seen from the side: the painter's order sorts every segment by depth),
//! polygons and discs (drawn under every line, so after them all), splines
//! (a whole path at a time), more than 255 colours or a palette by depth
//! or along the path (which needs the totals).
//!
//! Each pixel is a square of samples (4 × 4 in pictures up to 1024
//! pixels), each holding the paint of the last line that covered its
//! centre; a pixel is the mean of its samples. A line covers the samples
//! within half its width of it (round ends, as tiny-skia strokes them), so
//! lines thinner than a pixel, or many lines through one pixel, leave it
//! grey in proportion to how much of it they cover: a dense crown shows its
//! density instead of a solid mass.

use super::camera::Projector;
use super::shade::Paint;
use super::{Fit, RenderOptions};
use crate::ir::Rgb;
use crate::turtle::{Disc, Polygon, Segment, Sink};

/// The most samples held: 16 MB (one byte each).
const MAX_SAMPLES: u64 = 16 << 20;

/// Samples across a pixel, each way: 4 while the picture's samples fit in
/// [`MAX_SAMPLES`], fewer in larger pictures.
fn samples_per_pixel(width: u32, height: u32) -> u32 {
    let pixels = u64::from(width) * u64::from(height);
    (1..=4u32)
        .rev()
        .find(|s| pixels * u64::from(s * s) <= MAX_SAMPLES)
        .unwrap_or(1)
}

/// A picture as paint indices per sample (0 the background).
pub struct Coverage {
    width: u32,
    height: u32,
    ss: u32,
    /// Samples per row and rows of samples.
    sw: i64,
    sh: i64,
    samples: Vec<u8>,
    /// Paint `k` is `paints[k - 1]`.
    paints: Vec<Rgb>,
    background: Rgb,
    background_alpha: u8,
    /// Lines narrower than a pixel, per pixel: their colour laid over
    /// each other (premultiplied, 0..1) and the share of what is under
    /// them still showing; made at the first such line.
    hairlines: Vec<[f32; 4]>,
}

/// The interval of `x` where `lo <= c * x + e <= hi` (everything or
/// nothing when `c` is 0).
fn solve(c: f64, e: f64, lo: f64, hi: f64) -> (f64, f64) {
    if c.abs() < 1e-12 {
        return if (lo..=hi).contains(&e) {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            (f64::INFINITY, f64::NEG_INFINITY)
        };
    }
    let (a, b) = ((lo - e) / c, (hi - e) / c);
    (a.min(b), a.max(b))
}

/// The hairlines `h` of a pixel over its samples' sums `sum` (colour
/// times opacity, and opacity, of `n` samples), as straight RGBA.
fn over(h: &[f32; 4], sum: [u32; 4], n: u32) -> [u8; 4] {
    let n = n as f32 * 255.0;
    let alpha = (1.0 - h[3]) + h[3] * sum[3] as f32 / n;
    let mut out = [0u8; 4];
    for i in 0..3 {
        let premultiplied = h[i] + h[3] * sum[i] as f32 / (n * 255.0);
        out[i] = (255.0 * premultiplied / alpha.max(1e-6))
            .round()
            .clamp(0.0, 255.0) as u8;
    }
    out[3] = (255.0 * alpha).round().clamp(0.0, 255.0) as u8;
    out
}

impl Coverage {
    /// An empty picture; `None` when it has no pixels.
    pub fn new(width: u32, height: u32, background: Rgb, background_alpha: u8) -> Option<Self> {
        if width == 0 || height == 0 {
            return None;
        }
        let ss = samples_per_pixel(width, height);
        let (sw, sh) = (i64::from(width * ss), i64::from(height * ss));
        Some(Coverage {
            width,
            height,
            ss,
            sw,
            sh,
            samples: vec![0; usize::try_from(sw * sh).ok()?],
            paints: Vec::new(),
            background,
            background_alpha,
            hairlines: Vec::new(),
        })
    }

    /// The paint index of `colour`, added when new; `None` past 255.
    pub fn paint(&mut self, colour: Rgb) -> Option<u8> {
        if let Some(k) = self.paints.iter().rposition(|&c| c == colour) {
            return Some(k as u8 + 1);
        }
        if self.paints.len() >= 255 {
            return None;
        }
        self.paints.push(colour);
        Some(self.paints.len() as u8)
    }

    /// A line from `a` to `b` (pixels, y down) `width` pixels wide, with
    /// round ends, in paint `k`. A line narrower than a pixel is a hairline
    /// ([`Coverage::hairline`]) of its width's opacity, as tiny-skia strokes
    /// it; 0 or NaN wide, an opaque hairline.
    pub fn line(&mut self, a: [f64; 2], b: [f64; 2], width: f64, k: u8) {
        if width.is_nan() || width < 1.0 {
            let alpha = if width > 0.0 { width } else { 1.0 };
            return self.hairline(a, b, alpha as f32, k);
        }
        let ss = f64::from(self.ss);
        let widest = 4.0 * f64::from(self.width + self.height);
        let r = width.min(widest) * ss / 2.0;
        let (a, b) = ([a[0] * ss, a[1] * ss], [b[0] * ss, b[1] * ss]);
        if !(a.iter().chain(&b).all(|c| c.is_finite())) {
            return;
        }
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = (dx * dx + dy * dy).sqrt();
        let top = ((a[1].min(b[1]) - r - 0.5).ceil() as i64).max(0);
        let bottom = ((a[1].max(b[1]) + r - 0.5).floor() as i64).min(self.sh - 1);
        for row in top..=bottom {
            let yc = row as f64 + 0.5;
            let (mut xl, mut xr) = (f64::INFINITY, f64::NEG_INFINITY);
            for end in [a, b] {
                let h = r * r - (yc - end[1]) * (yc - end[1]);
                if h >= 0.0 {
                    let h = h.sqrt();
                    xl = xl.min(end[0] - h);
                    xr = xr.max(end[0] + h);
                }
            }
            if len > 1e-9 {
                // Along the segment: 0 <= (p - a)·d <= len²; across it:
                // |(p - a) × d| <= r·len, both linear in x on this row.
                let ey = yc - a[1];
                let along = solve(dx, ey * dy - a[0] * dx, 0.0, len * len);
                let across = solve(dy, -a[0] * dy - ey * dx, -r * len, r * len);
                let (l, h) = (along.0.max(across.0), along.1.min(across.1));
                if l <= h {
                    xl = xl.min(l);
                    xr = xr.max(h);
                }
            }
            let first = ((xl - 0.5).ceil() as i64).max(0);
            let last = ((xr - 0.5).floor() as i64).min(self.sw - 1);
            if first <= last {
                let at = (row * self.sw) as usize;
                self.samples[at + first as usize..=at + last as usize].fill(k);
            }
        }
    }

    /// A line a pixel wide of opacity `alpha` from `a` to `b`, anti-aliased
    /// as tiny-skia draws hairlines: along its longer axis, each pixel
    /// column (or row) it crosses gets `alpha` times the share of the column
    /// it spans, split between the two pixels nearest the line. Lines laid
    /// over each other add up as paint over paint, so many fine lines in a
    /// pixel darken it in proportion to their ink until it is covered.
    fn hairline(&mut self, a: [f64; 2], b: [f64; 2], alpha: f32, k: u8) {
        if !(a.iter().chain(&b).all(|c| c.is_finite())) {
            return;
        }
        if self.hairlines.is_empty() {
            let n = self.width as usize * self.height as usize;
            self.hairlines = vec![[0.0, 0.0, 0.0, 1.0]; n];
        }
        let c = self.paints[usize::from(k) - 1];
        let c = [c.0, c.1, c.2].map(|v| f32::from(v) / 255.0);
        // Along x when the line is wider than high, else along y (swapped).
        let steep = (b[1] - a[1]).abs() > (b[0] - a[0]).abs();
        let (mut p, mut q) = match steep {
            false => (a, b),
            true => ([a[1], a[0]], [b[1], b[0]]),
        };
        if p[0] > q[0] {
            std::mem::swap(&mut p, &mut q);
        }
        let (limit_u, limit_v) = match steep {
            false => (self.width, self.height),
            true => (self.height, self.width),
        };
        let (u0, u1) = (p[0].max(0.0), q[0].min(f64::from(limit_u)));
        if u0 >= u1 {
            return;
        }
        let slope = (q[1] - p[1]) / (q[0] - p[0]);
        for col in u0.floor() as i64..u1.ceil() as i64 {
            let (l, h) = ((col as f64).max(u0), ((col + 1) as f64).min(u1));
            let v = p[1] + slope * ((l + h) / 2.0 - p[0]) - 0.5;
            let (row, frac) = (v.floor(), v - v.floor());
            let share = (alpha as f64 * (h - l)) as f32;
            for (r, s) in [(row, 1.0 - frac), (row + 1.0, frac)] {
                if r < 0.0 || r >= f64::from(limit_v) {
                    continue;
                }
                let (x, y) = match steep {
                    false => (col as usize, r as usize),
                    true => (r as usize, col as usize),
                };
                let px = &mut self.hairlines[y * self.width as usize + x];
                let a = share * s as f32;
                for i in 0..3 {
                    px[i] = a * c[i] + (1.0 - a) * px[i];
                }
                px[3] *= 1.0 - a;
            }
        }
    }

    /// Rows `y0..y0 + rows` of the picture, RGBA, each pixel the mean of its
    /// samples weighed by their opacity (so that a transparent background
    /// does not tint the edges).
    fn rgba_rows(&self, y0: u32, rows: u32) -> Vec<u8> {
        let ss = self.ss as usize;
        let n = (ss * ss) as u32;
        let bg = self.background;
        let colour = |k: u8| -> (Rgb, u32) {
            match k {
                0 => (bg, u32::from(self.background_alpha)),
                k => (self.paints[k as usize - 1], 255),
            }
        };
        let mut out = Vec::with_capacity(self.width as usize * rows as usize * 4);
        for y in y0 as usize..(y0 + rows) as usize {
            for x in 0..self.width as usize {
                let mut sum = [0u32; 4];
                for sy in 0..ss {
                    let base = (y * ss + sy) * self.sw as usize + x * ss;
                    for &k in &self.samples[base..base + ss] {
                        let (c, a) = colour(k);
                        sum[0] += u32::from(c.0) * a;
                        sum[1] += u32::from(c.1) * a;
                        sum[2] += u32::from(c.2) * a;
                        sum[3] += a;
                    }
                }
                match self.hairlines.get(y * self.width as usize + x) {
                    None => {
                        let a = sum[3].max(1);
                        out.extend(sum[..3].iter().map(|s| ((s + a / 2) / a) as u8));
                        out.push(((sum[3] + n / 2) / n) as u8);
                    }
                    Some(h) => out.extend(over(h, sum, n)),
                }
            }
        }
        out
    }

    /// The picture, RGBA, row by row.
    pub fn rgba(&self) -> Vec<u8> {
        self.rgba_rows(0, self.height)
    }

    /// The picture as PNG bytes, encoded a band of rows at a time.
    pub fn png(&self) -> Option<Vec<u8>> {
        let mut out = Vec::new();
        let mut encoder = ::png::Encoder::new(&mut out, self.width, self.height);
        encoder.set_color(::png::ColorType::Rgba);
        encoder.set_depth(::png::BitDepth::Eight);
        encoder.set_compression(::png::Compression::Fast);
        let mut writer = encoder.write_header().ok()?;
        let mut stream = writer.stream_writer().ok()?;
        let mut row = 0;
        while row < self.height {
            let rows = 64.min(self.height - row);
            std::io::Write::write_all(&mut stream, &self.rgba_rows(row, rows)).ok()?;
            row += rows;
        }
        stream.finish().ok()?;
        drop(writer);
        Some(out)
    }
}

/// What the first pass finds: the bounds of the drawing in the picture
/// plane (turned by the style's rotation), its widest line, its colours,
/// and whether anything in it needs the stored way.
pub struct Survey {
    proj: Projector,
    /// Cosine and sine of the style's rotation.
    turn: (f64, f64),
    lo: [f64; 2],
    hi: [f64; 2],
    depth: (f64, f64),
    pub segments: u64,
    widest: f64,
    /// Length times width of every line ([`Fit::thinned`]).
    ink: f64,
    colours: Vec<Rgb>,
    /// Something that needs storage: a polygon, a disc, too many colours.
    stored: bool,
    /// Sums for the drawing's principal axis, about its first point.
    origin: Option<[f64; 2]>,
    sums: [f64; 6],
}

impl Survey {
    pub fn new(opts: &RenderOptions) -> Self {
        let (s, c) = opts.style.rotate.to_radians().sin_cos();
        Survey {
            proj: Projector::new(opts),
            turn: (c, s),
            lo: [f64::INFINITY; 2],
            hi: [f64::NEG_INFINITY; 2],
            depth: (f64::INFINITY, f64::NEG_INFINITY),
            segments: 0,
            widest: 0.0,
            ink: 0.0,
            colours: Vec::new(),
            stored: false,
            origin: None,
            sums: [0.0; 6],
        }
    }

    fn point(&mut self, p: [f64; 2]) {
        let q = super::rotate(p, self.turn);
        self.lo = [self.lo[0].min(q[0]), self.lo[1].min(q[1])];
        self.hi = [self.hi[0].max(q[0]), self.hi[1].max(q[1])];
        let o = *self.origin.get_or_insert(p);
        let (x, y) = (p[0] - o[0], p[1] - o[1]);
        for (sum, v) in self.sums.iter_mut().zip([1.0, x, y, x * x, x * y, y * y]) {
            *sum += v;
        }
    }

    /// Whether the drawing can be drawn streamed: something drawn, all of
    /// it lines at one depth, in at most 255 colours.
    pub fn streams(&self) -> bool {
        let (lo, hi) = self.depth;
        let flat = hi - lo <= 1e-9 * (1.0 + hi.abs().max(lo.abs()));
        !self.stored && self.segments > 0 && flat
    }

    /// The fit of the drawing into the picture of `opts`, as
    /// [`super::layout`] fits the stored drawing.
    pub(crate) fn fit(&self, opts: &RenderOptions, world_widths: bool) -> Fit {
        // The corners of the turned bounds, turned back: the fit turns them
        // again and finds the same bounds.
        let back = (self.turn.0, -self.turn.1);
        let corners = [self.lo, self.hi].map(|p| super::rotate(p, back));
        let pad = super::margin_pad(self.widest, opts, world_widths);
        Fit::padded(corners.iter(), opts, pad).thinned(self.ink, self.widest, world_widths)
    }

    /// The framing [`Survey::fit`] gives (what an animation keeps).
    pub fn framing(&self, opts: &RenderOptions, world_widths: bool) -> super::Framing {
        self.fit(opts, world_widths).framing
    }

    /// The direction (cosine, sine) the drawing spreads most along, as
    /// [`super::spread`] finds it.
    fn principal(&self) -> (f64, f64) {
        let [n, x, y, xx, xy, yy] = self.sums;
        let n = n.max(1.0);
        let (mx, my) = (x / n, y / n);
        let (cxx, cxy, cyy) = (xx - n * mx * mx, xy - n * mx * my, yy - n * my * my);
        let angle = 0.5 * (2.0 * cxy).atan2(cxx - cyy);
        let (s, c) = angle.sin_cos();
        (c, s)
    }
}

impl Sink for Survey {
    fn segment(&mut self, s: Segment) {
        let (Some((a, za)), Some((b, zb))) = (self.proj.project(s.a), self.proj.project(s.b))
        else {
            return;
        };
        self.segments += 1;
        self.point(a);
        self.point(b);
        let z = -(za + zb) / 2.0;
        self.depth = (self.depth.0.min(z), self.depth.1.max(z));
        self.widest = self.widest.max(s.width.abs());
        let ink = (b[0] - a[0]).hypot(b[1] - a[1]) * s.width.abs();
        if ink.is_finite() {
            self.ink += ink;
        }
        let colour = Paint::own(s.colour, s.index).colour();
        if !self.colours.contains(&colour) {
            self.stored |= self.colours.len() >= 255;
            self.colours.push(colour);
        }
    }
    fn polygon(&mut self, _: Polygon) {
        self.stored = true;
    }
    fn disc(&mut self, _: Disc) {
        self.stored = true;
    }
}

/// The second pass: each segment drawn into the picture as it comes.
pub struct Painter<'p> {
    proj: Projector,
    fit: Fit,
    world_widths: bool,
    /// Every line black (`--palette mono`).
    mono: bool,
    pub picture: Coverage,
    /// Drawn so far, of `total`, and whom to tell.
    drawn: u64,
    total: u64,
    progress: &'p mut dyn FnMut(u64, u64),
    /// The direction across the drawing's principal axis, and the range of
    /// the drawing along it (plane units).
    across: (f64, f64),
    range: (f64, f64),
    /// A colour past the picture's 255.
    pub overflow: bool,
}

impl<'p> Painter<'p> {
    /// The painter of what `survey` found, into the picture of `opts`;
    /// `None` when the picture has no pixels.
    pub fn new(
        survey: &Survey,
        opts: &RenderOptions,
        world_widths: bool,
        progress: &'p mut dyn FnMut(u64, u64),
    ) -> Option<Self> {
        let picture = Coverage::new(
            opts.width,
            opts.height,
            opts.background,
            opts.background_alpha,
        )?;
        let (c, s) = survey.principal();
        Some(Painter {
            proj: Projector::new(opts),
            fit: survey.fit(opts, world_widths),
            world_widths,
            mono: opts.style.palette == Some(super::Palette::Mono),
            picture,
            drawn: 0,
            total: survey.segments,
            progress,
            across: (-s, c),
            range: (f64::INFINITY, f64::NEG_INFINITY),
            overflow: false,
        })
    }

    /// How wide the drawing is across the direction it spreads most, in
    /// pixels ([`super::Spread::width`]).
    pub fn spread_width(&self) -> f64 {
        (self.range.1 - self.range.0).max(0.0) * self.fit.scale
    }

    fn across(&mut self, p: [f64; 2]) {
        let v = p[0] * self.across.0 + p[1] * self.across.1;
        self.range = (self.range.0.min(v), self.range.1.max(v));
    }
}

impl Sink for Painter<'_> {
    fn segment(&mut self, s: Segment) {
        let (Some((a, _)), Some((b, _))) = (self.proj.project(s.a), self.proj.project(s.b)) else {
            return;
        };
        self.across(a);
        self.across(b);
        let colour = match self.mono {
            true => Rgb(0, 0, 0),
            false => Paint::own(s.colour, s.index).colour(),
        };
        let Some(k) = self.picture.paint(colour) else {
            self.overflow = true;
            return;
        };
        let width = self.fit.line_width(s.width, self.world_widths);
        self.picture
            .line(self.fit.to_px(a), self.fit.to_px(b), width, k);
        self.drawn += 1;
        if self.drawn % (1 << 16) == 0 || self.drawn == self.total {
            (self.progress)(self.drawn, self.total);
        }
    }
    fn polygon(&mut self, _: Polygon) {}
    fn disc(&mut self, _: Disc) {}
}
