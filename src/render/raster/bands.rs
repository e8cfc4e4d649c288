//! A lit picture drawn band by band: the bands of sample rows that bound
//! the memory held; in each, every thread draws a run of the drawing's
//! pieces into a band of its own, and the bands are laid together nearer
//! over farther (the earlier piece on a tie), which is what one thread
//! drawing every piece in order into one band gives. The band's rows are
//! box-filtered down to pixels and handed to the PNG encoder as they are
//! done.

use super::painter::Painter;
use super::target::Target;
use super::{samples_per_pixel, Drawing, Scene};
use crate::render::RenderOptions;
use crate::turtle::Polygon;
use std::ops::Range;
use std::sync::atomic::{AtomicU64, Ordering};

/// Samples (colour and depth, 8 bytes each) held at once by each thread:
/// 32 MB, and 64 MB on one thread.
const THREAD_BAND_SAMPLES: usize = 4 << 20;

/// Draws `scene` (`drawn_each` things, from `drawing`) in bands on
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
    let pieces = drawing.pieced().count();
    let threads = threads.clamp(1, pieces.max(1));
    let ss = samples_per_pixel(w, h);
    let bands = Bands::new(w, h, ss, threads);
    let total = drawn_each.saturating_mul(bands.count() as u64);
    let mut out = Vec::new();
    let mut encoder = ::png::Encoder::new(&mut out, w, h);
    encoder.set_color(::png::ColorType::Rgba);
    encoder.set_depth(::png::BitDepth::Eight);
    let mut writer = encoder.write_header().ok()?;
    let mut stream = writer.stream_writer().ok()?;
    let drawn = AtomicU64::new(0);
    let labels = scene.placed_labels(drawing);
    let runs: Vec<Range<usize>> = (0..threads)
        .map(|t| t * pieces / threads..(t + 1) * pieces / threads)
        .collect();
    for i in 0..bands.count() {
        let (row, rows) = bands.band(i);
        let band = || {
            let (y0, rows, width) = (row * ss, rows * ss, w * ss);
            let background = (opts.background, opts.background_alpha);
            Target::band(i64::from(y0), i64::from(rows), i64::from(width), background)
        };
        let paint = |run: Range<usize>, progress: &mut dyn FnMut(u64, u64)| {
            let first = scene.first_segments.get(run.start).copied().unwrap_or(0);
            let mut painter = Painter::new(scene, band(), &drawn, first);
            for k in run {
                drawing.pieced().run(k, &mut painter);
                painter.end_piece();
                progress(drawn.load(Ordering::Relaxed), total);
            }
            painter.opaque()
        };
        let painted: Vec<(Target, Vec<Polygon>)> = std::thread::scope(|scope| {
            let others: Vec<_> = (runs[1..].iter().cloned())
                .map(|run| scope.spawn(move || paint(run, &mut |_, _| {})))
                .collect();
            let first = paint(runs[0].clone(), &mut *progress);
            std::iter::once(Some(first))
                .chain(others.into_iter().map(|t| t.join().ok()))
                .collect::<Option<Vec<_>>>()
        })?;
        let target = merged(scene, &drawn, painted)?;
        let mut pixels = downsample(&target, w, ss, threads);
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

/// The threads' bands laid together in the order of their pieces, and
/// every thread's translucent polygons blended over the whole, in order.
fn merged(
    scene: &Scene<'_>,
    drawn: &AtomicU64,
    painted: Vec<(Target, Vec<Polygon>)>,
) -> Option<Target> {
    let mut painted = painted.into_iter();
    let (mut target, mut translucent) = painted.next()?;
    let (later, more): (Vec<Target>, Vec<Vec<Polygon>>) = painted.unzip();
    target.merge(&later);
    drop(later);
    translucent.extend(more.into_iter().flatten());
    Some(Painter::new(scene, target, drawn, 0).blend(translucent))
}

/// Threads drawing a band at once, at most.
pub(super) const MAX_THREADS: usize = 64;

/// The bands of rows a picture is drawn in, one after another: each at most
/// [`THREAD_BAND_SAMPLES`] samples a thread (twice that on one). A
/// sample's colour does not depend on which band holds it, so neither do
/// the picture's bytes.
struct Bands {
    h: u32,
    rows: u32,
}

impl Bands {
    fn new(w: u32, h: u32, ss: u32, threads: usize) -> Self {
        let row_samples = w as usize * (ss * ss) as usize;
        let samples = THREAD_BAND_SAMPLES * if threads == 1 { 2 } else { 1 };
        let rows = (samples / row_samples).clamp(1, h as usize) as u32;
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

/// The pixels of the rows `t` holds, RGBA, each the mean of its samples:
/// the rows shared among `threads` threads.
fn downsample(t: &Target, w: u32, ss: u32, threads: usize) -> Vec<u8> {
    let (w, ss) = (w as usize, ss as usize);
    let rows = t.colour.len() / (t.width.max(1) as usize * ss);
    let mut out = vec![0u8; w * rows * 4];
    let share = rows.div_ceil(threads.max(1)).max(1) * w * 4;
    let shares = out.chunks_mut(share).enumerate();
    crate::parallel::on_own_threads(shares, |(k, pixels)| {
        let first = k * share / (w * 4);
        for (i, row) in pixels.chunks_mut(w * 4).enumerate() {
            downsample_row(t, first + i, ss, row);
        }
    });
    out
}

/// Pixel row `y` of `t` into `row`.
fn downsample_row(t: &Target, y: usize, ss: usize, row: &mut [u8]) {
    let n = (ss * ss) as u32;
    for (x, pixel) in row.chunks_mut(4).enumerate() {
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
        for (p, s) in pixel.iter_mut().zip(&sum[..3]) {
            *p = ((s + a / 2) / a) as u8;
        }
        pixel[3] = ((sum[3] + n / 2) / n) as u8;
    }
}
