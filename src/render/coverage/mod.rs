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

mod painter;

use super::camera::Projector;
use super::shade::Paint;
use super::{Fit, RenderOptions};
use crate::ir::Rgb;
use crate::turtle::{Disc, Polygon, Segment, Sink};

pub use painter::Painter;

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

/// A pixel row another share of the picture keeps.
const NOT_HELD: u32 = u32::MAX;

/// A picture as paint indices per sample (0 the background), or a share
/// of one: its pixel rows dealt out in stripes to threads, each holding
/// its own stripes and drawing into them every line that reaches them, in
/// order (so that each sample sees the lines it would see in the whole
/// picture).
pub struct Coverage {
    width: u32,
    height: u32,
    ss: u32,
    /// Pixel rows per stripe (the stripes are dealt out to the shares in
    /// turn).
    stripe: u32,
    /// Where each pixel row is kept here ([`NOT_HELD`] where another share
    /// keeps it): a look-up, not divisions, for every pixel a line covers.
    rows: Vec<u32>,
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
        Coverage::share(
            width,
            height,
            (background, background_alpha),
            (height, 1, 0),
        )
    }

    /// Share `share` of `shares` of an empty picture, its pixel rows dealt
    /// out in stripes of `stripe`; `None` when it has no pixels.
    fn share(
        width: u32,
        height: u32,
        (background, background_alpha): (Rgb, u8),
        (stripe, shares, share): (u32, u32, u32),
    ) -> Option<Self> {
        if width == 0 || height == 0 || stripe == 0 || share >= shares {
            return None;
        }
        let ss = samples_per_pixel(width, height);
        let (sw, sh) = (i64::from(width * ss), i64::from(height * ss));
        let mut c = Coverage {
            width,
            height,
            ss,
            stripe,
            rows: Vec::new(),
            sw,
            sh,
            samples: Vec::new(),
            paints: Vec::new(),
            background,
            background_alpha,
            hairlines: Vec::new(),
        };
        let mut held = 0;
        c.rows = (0..height)
            .map(|y| match (y / stripe) % shares == share {
                true => {
                    held += 1;
                    held - 1
                }
                false => NOT_HELD,
            })
            .collect();
        c.samples = vec![0; usize::try_from(sw).ok()? * held as usize * ss as usize];
        Some(c)
    }

    /// Where pixel row `y` is kept here, if this share holds it.
    #[inline]
    fn local(&self, y: i64) -> Option<usize> {
        let at = *self.rows.get(usize::try_from(y).ok()?)?;
        (at != NOT_HELD).then_some(at as usize)
    }

    /// The pixel rows this share holds.
    fn held(&self) -> usize {
        self.samples.len() / (self.sw as usize * self.ss as usize).max(1)
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
        let ss = i64::from(self.ss);
        let mut row = top;
        while row <= bottom {
            let Some(local) = self.local(row / ss) else {
                // On to the first row of the next stripe.
                row = (row / ss / i64::from(self.stripe) + 1) * i64::from(self.stripe) * ss;
                continue;
            };
            let at = (local as i64 * ss + row % ss) * self.sw;
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
                let at = at as usize;
                self.samples[at + first as usize..=at + last as usize].fill(k);
            }
            row += 1;
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
            let n = self.width as usize * self.held();
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
                    false => (col as usize, r as i64),
                    true => (r as usize, col),
                };
                let Some(y) = self.local(y) else {
                    continue;
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

    /// Pixel row `y` of the picture (held here), RGBA, each pixel the mean
    /// of its samples weighed by their opacity (so that a transparent
    /// background does not tint the edges), onto `out`.
    fn rgba_row(&self, y: u32, out: &mut Vec<u8>) {
        let Some(y) = self.local(i64::from(y)) else {
            return;
        };
        let ss = self.ss as usize;
        let n = (ss * ss) as u32;
        let bg = self.background;
        let colour = |k: u8| -> (Rgb, u32) {
            match k {
                0 => (bg, u32::from(self.background_alpha)),
                k => (self.paints[k as usize - 1], 255),
            }
        };
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

    /// Each of `rows` (a pixel row of the picture held here, and room for
    /// it) in RGBA ([`Self::rgba_row`]).
    fn rgba_rows(&self, rows: Vec<(u32, &mut [u8])>) {
        let mut one = Vec::with_capacity(self.width as usize * 4);
        for (y, pixels) in rows {
            one.clear();
            self.rgba_row(y, &mut one);
            let n = one.len().min(pixels.len());
            pixels[..n].copy_from_slice(&one[..n]);
        }
    }

    /// The picture, RGBA, row by row.
    pub fn rgba(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.width as usize * self.height as usize * 4);
        for y in 0..self.height {
            self.rgba_row(y, &mut out);
        }
        out
    }

    /// The picture as PNG bytes, encoded a band of rows at a time.
    pub fn png(&self) -> Option<Vec<u8>> {
        png_of_shares(std::slice::from_ref(self))
    }
}

/// The picture whose shares are `shares` (every share of it, in order) as
/// PNG bytes, encoded a band of rows at a time: each share turns its rows
/// of a band into RGBA on a thread of its own, then the band is
/// compressed.
fn png_of_shares(shares: &[Coverage]) -> Option<Vec<u8>> {
    let first = shares.first()?;
    let (w, h, stripe) = (first.width, first.height, first.stripe);
    let mut out = Vec::new();
    let mut encoder = ::png::Encoder::new(&mut out, w, h);
    encoder.set_color(::png::ColorType::Rgba);
    encoder.set_depth(::png::BitDepth::Eight);
    encoder.set_compression(::png::Compression::Fast);
    let mut writer = encoder.write_header().ok()?;
    let mut stream = writer.stream_writer().ok()?;
    let row = w as usize * 4;
    // Four stripes a share: few bands, each held briefly.
    let band_rows = (stripe as usize * shares.len() * 4).min(h as usize);
    let mut band = vec![0u8; row * band_rows];
    for top in (0..h as usize).step_by(band_rows.max(1)) {
        let rows = band_rows.min(h as usize - top);
        let band = &mut band[..row * rows];
        // Each row of the band goes to the share holding its stripe.
        let mut held: Vec<Vec<(u32, &mut [u8])>> = shares.iter().map(|_| Vec::new()).collect();
        for (i, pixels) in band.chunks_mut(row).enumerate() {
            let y = (top + i) as u32;
            held[(y / stripe) as usize % shares.len()].push((y, pixels));
        }
        crate::parallel::on_own_threads(shares.iter().zip(held), |(share, rows)| {
            share.rgba_rows(rows)
        });
        std::io::Write::write_all(&mut stream, band).ok()?;
    }
    stream.finish().ok()?;
    drop(writer);
    Some(out)
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

    /// Adds what `later` surveyed, as if it had come after what this
    /// survey saw (the sums for the principal axis moved to this survey's
    /// first point).
    pub fn add(&mut self, later: Survey) {
        self.lo = [self.lo[0].min(later.lo[0]), self.lo[1].min(later.lo[1])];
        self.hi = [self.hi[0].max(later.hi[0]), self.hi[1].max(later.hi[1])];
        self.depth = (
            self.depth.0.min(later.depth.0),
            self.depth.1.max(later.depth.1),
        );
        self.segments += later.segments;
        self.widest = self.widest.max(later.widest);
        self.ink += later.ink;
        for colour in later.colours {
            if !self.colours.contains(&colour) {
                self.stored |= self.colours.len() >= 255;
                self.colours.push(colour);
            }
        }
        self.stored |= later.stored;
        let Some(theirs) = later.origin else {
            return;
        };
        let ours = *self.origin.get_or_insert(theirs);
        let [n, x, y, xx, xy, yy] = later.sums;
        let (dx, dy) = (theirs[0] - ours[0], theirs[1] - ours[1]);
        let moved = [
            n,
            x + n * dx,
            y + n * dy,
            xx + 2.0 * dx * x + n * dx * dx,
            xy + dx * y + dy * x + n * dx * dy,
            yy + 2.0 * dy * y + n * dy * dy,
        ];
        for (sum, m) in self.sums.iter_mut().zip(moved) {
            *sum += m;
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn surveys_of_parts_added_in_order_are_the_survey_of_the_whole() {
        let segment = |i: u32| Segment {
            a: [f64::from(i) * 0.5, f64::from(i % 5), 0.0],
            b: [f64::from(i) * 0.5 + 3.0, f64::from(i % 5) * 2.0 + 1.0, 0.0],
            width: f64::from(i % 4),
            colour: Rgb((i % 3) as u8, 0, 0),
            index: 0,
            depth: 0,
        };
        let opts = RenderOptions::default();
        let mut whole = Survey::new(&opts);
        let mut parts = Survey::new(&opts);
        for part in [0..7, 7..8, 8..30] {
            let mut survey = Survey::new(&opts);
            for i in part {
                whole.segment(segment(i));
                survey.segment(segment(i));
            }
            parts.add(survey);
        }
        parts.add(Survey::new(&opts));
        assert_eq!((parts.lo, parts.hi), (whole.lo, whole.hi));
        assert_eq!(
            (parts.segments, parts.widest),
            (whole.segments, whole.widest)
        );
        assert_eq!(parts.colours, whole.colours);
        assert_eq!(parts.origin, whole.origin);
        for (p, w) in parts.sums.iter().zip(whole.sums) {
            assert!((p - w).abs() <= 1e-9 * w.abs().max(1.0), "{p} against {w}");
        }
        assert!((parts.ink - whole.ink).abs() < 1e-9);
    }
}
