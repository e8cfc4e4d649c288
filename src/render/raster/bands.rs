//! A lit picture drawn band by band: the bands of sample rows that bound
//! the memory held, the threads that each draw every other stripe of a
//! band, and the band's rows box-filtered down to pixels and handed to the
//! PNG encoder as they are done.

use super::painter::Painter;
use super::target::Target;
use super::{samples_per_pixel, Drawing, Scene};
use crate::render::RenderOptions;
use std::sync::atomic::AtomicU64;

/// Samples (colour and depth, 8 bytes each) held at once: 64 MB.
const MAX_BAND_SAMPLES: usize = 8 << 20;

/// Draws `scene` (`drawn` things, replayed from `drawing`) in bands on
/// `threads` threads, into PNG bytes.
pub(super) fn png_in_bands(
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
    let labels = scene.placed_labels(drawing);
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
        let mut pixels = interleave(
            &shares,
            (w * 4) as usize,
            rows as usize,
            STRIPE_PIXELS as usize,
        )?;
        // Labels over everything, as cpfg writes its bitmaps.
        for l in &labels {
            crate::render::text::write(&mut pixels, w, row, l);
        }
        std::io::Write::write_all(&mut stream, &pixels).ok()?;
    }
    progress(total, total);
    stream.finish().ok()?;
    drop(writer);
    Some(out)
}

/// Threads drawing a band at once, at most.
pub(super) const MAX_THREADS: usize = 8;

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
