//! The second pass over a flat line drawing, on every thread: each of the
//! word's pieces is interpreted once, by whichever thread is free, into its
//! segments projected to the picture and dealt to the stripes they reach
//! ([`Lines`]); every thread draws the lines of every piece that reach its
//! own stripes of the picture, piece after piece ([`Coverage`] shares).
//! Each sample sees the lines it sees when one thread draws the whole word,
//! in the same order, so the picture is the same on any number of threads.

use super::{png_of_shares, Coverage, Survey};
use crate::ir::Rgb;
use crate::render::camera::Projector;
use crate::render::shade::Paint;
use crate::render::{Fit, RenderOptions};
use crate::turtle::{Disc, Pieced, Polygon, Segment, Sink};

/// Pixel rows in a stripe of a thread's share of the picture: tall enough
/// that few lines reach two stripes (each share then goes over them).
const STRIPE: u32 = 32;

/// A segment as the picture draws it: its ends and width in pixels, and
/// its colour.
#[derive(Clone, Copy, Debug)]
struct Line {
    a: [f64; 2],
    b: [f64; 2],
    width: f64,
    colour: Rgb,
}

/// A piece's segments projected into the picture, each dealt to the
/// shares whose stripes it can reach (so that a thread goes over its own
/// lines only), and the range of the drawing across its principal axis.
struct Lines<'f> {
    proj: Projector,
    fit: &'f Fit,
    world_widths: bool,
    /// Every line black (`--palette mono`).
    mono: bool,
    /// The direction across the drawing's principal axis.
    across: (f64, f64),
    range: (f64, f64),
    /// Per share of the picture, its lines in order.
    shares: Vec<Vec<Line>>,
    /// Lines made (once each, whatever the shares they went to).
    made: u64,
}

impl Lines<'_> {
    /// Gives `line` to each share holding a pixel row it can reach.
    fn deal(&mut self, line: Line) {
        let n = self.shares.len();
        if n == 1 {
            self.shares[0].push(line);
            return;
        }
        let reach = if line.width >= 1.0 {
            line.width / 2.0
        } else {
            0.0
        } + 1.0;
        let per_stripe = 1.0 / f64::from(STRIPE);
        let lo = (line.a[1].min(line.b[1]) - reach) * per_stripe;
        let hi = (line.a[1].max(line.b[1]) + reach) * per_stripe;
        // Spanning a stripe of every share, or not a number, or far off
        // the picture: every share draws it (and the drawing decides).
        if !(hi - lo < (n - 1) as f64 && lo > -LIMIT && hi < LIMIT) {
            for share in &mut self.shares {
                share.push(line);
            }
            return;
        }
        let (first, last) = (floor(lo), floor(hi));
        let mut share = first.rem_euclid(n as i64) as usize;
        for _ in first..=last {
            self.shares[share].push(line);
            share = if share + 1 == n { 0 } else { share + 1 };
        }
    }
}

/// Stripes as far off the picture as a line is dealt by: past them (2^52,
/// where an `f64` still holds every integer) every share draws it.
const LIMIT: f64 = 4_503_599_627_370_496.0;

/// `x` rounded down, for `x` within [`LIMIT`]: `f64::floor` is a call into
/// the maths library on the x86-64 baseline, and this is every line's.
fn floor(x: f64) -> i64 {
    let t = x as i64;
    t - i64::from(x < t as f64)
}

impl Sink for Lines<'_> {
    fn segment(&mut self, s: Segment) {
        let (Some((a, _)), Some((b, _))) = (self.proj.project(s.a), self.proj.project(s.b)) else {
            return;
        };
        for p in [a, b] {
            let v = p[0] * self.across.0 + p[1] * self.across.1;
            self.range = (self.range.0.min(v), self.range.1.max(v));
        }
        let colour = match self.mono {
            true => Rgb(0, 0, 0),
            false => Paint::own(s.colour, s.index).colour(),
        };
        self.made += 1;
        self.deal(Line {
            a: self.fit.to_px(a),
            b: self.fit.to_px(b),
            width: self.fit.line_width(s.width, self.world_widths),
            colour,
        });
    }
    fn polygon(&mut self, _: Polygon) {}
    fn disc(&mut self, _: Disc) {}
}

/// The second pass: every segment drawn into the picture, in order.
pub struct Painter<'p> {
    proj: Projector,
    fit: Fit,
    world_widths: bool,
    mono: bool,
    /// The picture, one share a thread.
    shares: Vec<Coverage>,
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
    /// The painter of what `survey` found, into the picture of `opts` in
    /// shares for `threads` threads; `None` when the picture has no
    /// pixels.
    pub fn new(
        survey: &Survey,
        opts: &RenderOptions,
        world_widths: bool,
        threads: usize,
        progress: &'p mut dyn FnMut(u64, u64),
    ) -> Option<Self> {
        let rows = opts.height.div_ceil(STRIPE) as usize;
        let shares = crate::parallel::threads(threads).clamp(1, rows.max(1)) as u32;
        let background = (opts.background, opts.background_alpha);
        let shares = (0..shares)
            .map(|k| Coverage::share(opts.width, opts.height, background, (STRIPE, shares, k)))
            .collect::<Option<Vec<_>>>()?;
        let (c, s) = survey.principal();
        Some(Painter {
            proj: Projector::new(opts),
            fit: survey.fit(opts, world_widths),
            world_widths,
            mono: opts.style.palette == Some(crate::render::Palette::Mono),
            shares,
            drawn: 0,
            total: survey.segments,
            progress,
            across: (-s, c),
            range: (f64::INFINITY, f64::NEG_INFINITY),
            overflow: false,
        })
    }

    /// Draws every piece of `word`: each thread draws its share of the
    /// picture, piece after piece, and interprets the next piece nobody
    /// has while it waits for its own next one
    /// ([`crate::parallel::feed_in_order`]).
    pub fn draw(&mut self, word: &dyn Pieced) {
        let shares = self.shares.len();
        let make = |k: usize| {
            let mut lines = Lines {
                proj: self.proj,
                fit: &self.fit,
                world_widths: self.world_widths,
                mono: self.mono,
                across: self.across,
                range: (f64::INFINITY, f64::NEG_INFINITY),
                shares: vec![Vec::new(); shares],
                made: 0,
            };
            word.run(k, &mut lines);
            lines
        };
        // Each share, its index, and whether a colour of it went past the
        // picture's 255.
        let mut eaters: Vec<_> = (self.shares.iter_mut().enumerate())
            .map(|(k, share)| (k, share, false))
            .collect();
        let (progress, total) = (&mut *self.progress, self.total);
        let (mut drawn, mut range) = (self.drawn, self.range);
        crate::parallel::feed_in_order(
            word.count(),
            2 * shares,
            &mut eaters,
            make,
            |(k, share, overflow), lines| *overflow |= paint(share, &lines.shares[*k]),
            |_, lines| {
                range = (range.0.min(lines.range.0), range.1.max(lines.range.1));
                drawn += lines.made;
                progress(drawn.min(total), total);
            },
        );
        self.overflow |= eaters.iter().any(|e| e.2);
        (self.drawn, self.range) = (drawn, range);
    }

    /// How wide the drawing is across the direction it spreads most, in
    /// pixels ([`crate::render::Spread::width`]).
    pub fn spread_width(&self) -> f64 {
        (self.range.1 - self.range.0).max(0.0) * self.fit.scale
    }

    /// The picture as PNG bytes.
    pub fn png(&self) -> Option<Vec<u8>> {
        png_of_shares(&self.shares)
    }
}

/// Draws `lines` into `share`, in order; whether a colour was past the
/// picture's 255.
fn paint(share: &mut Coverage, lines: &[Line]) -> bool {
    let mut overflow = false;
    for line in lines {
        match share.paint(line.colour) {
            Some(paint) => share.line(line.a, line.b, line.width, paint),
            None => overflow = true,
        }
    }
    overflow
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::turtle::Geometry;

    #[test]
    fn floor_rounds_down_on_both_sides_of_zero() {
        for (x, want) in [
            (2.7, 2),
            (2.0, 2),
            (0.0, 0),
            (-0.0, 0),
            (-0.5, -1),
            (-1.0, -1),
            (-7.25, -8),
        ] {
            assert_eq!(floor(x), want, "{x}");
            assert_eq!(floor(x), x.floor() as i64, "{x}");
        }
    }

    #[test]
    fn shares_of_the_picture_on_any_threads_draw_what_one_draws_whole() {
        // Crossing lines, thick and hairline, in colours that come and go,
        // cut into parts of a few lines: every thread count, and the
        // drawing in one part, give the same bytes.
        let mut g = Geometry::default();
        for i in 0..200u32 {
            let t = f64::from(i) * 0.37;
            g.segment(Segment {
                a: [t.cos() * 5.0, t.sin() * 3.0, 0.0],
                b: [(t * 1.7).sin() * 4.0, (t * 0.3).cos() * 6.0, 0.0],
                width: if i % 3 == 0 { 0.02 } else { 0.3 },
                colour: Rgb((i * 40 % 256) as u8, (i % 7 * 30) as u8, 90),
                index: 0,
                depth: 0,
            });
        }
        let opts = RenderOptions {
            width: 97,
            height: 83,
            ..RenderOptions::default()
        };
        let mut survey = Survey::new(&opts);
        g.replay(&mut survey);
        let draw = |threads: usize, most: usize| {
            let mut quiet = |_, _| {};
            let mut painter = Painter::new(&survey, &opts, true, threads, &mut quiet).unwrap();
            painter.draw(&g.in_parts(most));
            assert!(!painter.overflow);
            painter.png().unwrap()
        };
        let whole = draw(1, usize::MAX);
        for threads in [1, 2, 3, 7] {
            assert!(draw(threads, 7) == whole, "{threads} threads");
        }
        // Not blank: the lines are there.
        let pm = tiny_skia::Pixmap::decode_png(&whole).unwrap();
        let inked = pm
            .pixels()
            .iter()
            .filter(|p| p.alpha() > 0 && p.red() > 0)
            .count();
        assert!(inked > 500, "{inked} pixels inked");
    }
}
