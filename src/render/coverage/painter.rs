//! The second pass over a flat line drawing, on every thread: the word's
//! pieces are interpreted a round at a time, each piece on a thread into
//! its segments projected to the picture ([`Lines`]); then every thread
//! draws the round's lines, in order, into its own stripes of the picture
//! ([`Coverage`] shares). Each sample sees the lines it sees when one
//! thread draws the whole word, in the same order, so the picture is the
//! same on any number of threads.

use super::{png_of_shares, Coverage, Survey};
use crate::ir::Rgb;
use crate::render::camera::Projector;
use crate::render::shade::Paint;
use crate::render::{Fit, RenderOptions};
use crate::turtle::{Disc, Pieced, Polygon, Segment, Sink};

/// Pixel rows in a stripe of a thread's share of the picture.
const STRIPE: u32 = 8;

/// A segment in the picture plane: its ends, its width as the turtle
/// drew it, and its colour.
#[derive(Clone, Copy, Debug)]
struct Line {
    a: [f64; 2],
    b: [f64; 2],
    width: f64,
    colour: Rgb,
}

/// A piece's segments projected into the picture plane, and the range of
/// the drawing across its principal axis.
struct Lines {
    proj: Projector,
    /// Every line black (`--palette mono`).
    mono: bool,
    /// The direction across the drawing's principal axis.
    across: (f64, f64),
    range: (f64, f64),
    lines: Vec<Line>,
}

impl Sink for Lines {
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
        self.lines.push(Line {
            a,
            b,
            width: s.width,
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

    /// Draws every piece of `word`, a round of pieces at a time, on
    /// `threads` threads.
    pub fn draw(&mut self, word: &dyn Pieced, threads: usize) {
        let threads = crate::parallel::threads(threads);
        let round = 2 * threads;
        let pieces = word.count();
        let empty = Lines {
            proj: self.proj,
            mono: self.mono,
            across: self.across,
            range: (f64::INFINITY, f64::NEG_INFINITY),
            lines: Vec::new(),
        };
        for first in (0..pieces).step_by(round) {
            let lines = crate::parallel::map_in_order(
                round.min(pieces - first),
                threads,
                |k| {
                    let mut lines = Lines {
                        lines: Vec::new(),
                        ..empty
                    };
                    word.run(first + k, &mut lines);
                    lines
                },
                |_| {},
            );
            self.paint(&lines);
        }
    }

    /// Each share draws every line of `pieces`, in order, on a thread of
    /// its own (the first on this one).
    fn paint(&mut self, pieces: &[Lines]) {
        let (fit, world_widths) = (&self.fit, self.world_widths);
        let draw = |share: &mut Coverage| {
            let mut overflow = false;
            for line in pieces.iter().flat_map(|p| &p.lines) {
                let width = fit.line_width(line.width, world_widths);
                match share.paint(line.colour) {
                    Some(k) => share.line(fit.to_px(line.a), fit.to_px(line.b), width, k),
                    None => overflow = true,
                }
            }
            overflow
        };
        let overflow = std::thread::scope(|scope| {
            let (first, rest) = self.shares.split_at_mut(1);
            let others: Vec<_> = rest
                .iter_mut()
                .map(|s| scope.spawn(move || draw(s)))
                .collect();
            let mut overflow = first.iter_mut().any(draw);
            for t in others {
                overflow |= t.join().unwrap_or(true);
            }
            overflow
        });
        self.overflow |= overflow;
        for p in pieces {
            self.range = (self.range.0.min(p.range.0), self.range.1.max(p.range.1));
            self.drawn += p.lines.len() as u64;
        }
        (self.progress)(self.drawn.min(self.total), self.total);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::turtle::Geometry;

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
            painter.draw(&g.in_parts(most), threads);
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
