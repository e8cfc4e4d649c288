//! PNG output through tiny-skia: the picture's background (white unless
//! the look names one), anti-aliased strokes with
//! round caps and joins, filled polygons.

use super::Picture;
use crate::ir::Rgb;
use tiny_skia::{
    Color, FillRule, LineCap, LineJoin, Paint, PathBuilder, Pixmap, Stroke, Transform,
};

/// Segments per stroked path: long runs are split so the stroker's memory
/// stays bounded.
const CHUNK: usize = 20_000;

fn paint(c: Rgb) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color_rgba8(c.0, c.1, c.2, 255);
    p.anti_alias = true;
    p
}

/// Draws the picture; `None` only if the size is zero or too large for
/// tiny-skia.
pub fn draw(pic: &Picture) -> Option<Pixmap> {
    draw_with(pic, &mut |_, _| {})
}

/// [`draw`], calling `progress(drawn, total)` with the segments stroked so
/// far as it goes.
pub fn draw_with(pic: &Picture, progress: &mut dyn FnMut(u64, u64)) -> Option<Pixmap> {
    let total: u64 = pic
        .runs
        .iter()
        .flat_map(|r| &r.lines)
        .map(|l| l.len().saturating_sub(1) as u64)
        .sum();
    let mut drawn = 0u64;
    let mut pixmap = Pixmap::new(pic.width, pic.height)?;
    let bg = pic.background;
    pixmap.fill(Color::from_rgba8(bg.0, bg.1, bg.2, pic.background_alpha));
    for (colour, pts) in &pic.polygons {
        let mut pb = PathBuilder::new();
        let mut it = pts.iter();
        if let Some(p) = it.next() {
            pb.move_to(p[0] as f32, p[1] as f32);
        }
        for p in it {
            pb.line_to(p[0] as f32, p[1] as f32);
        }
        pb.close();
        if let Some(path) = pb.finish() {
            pixmap.fill_path(
                &path,
                &paint(*colour),
                FillRule::EvenOdd,
                Transform::identity(),
                None,
            );
        }
    }
    for run in &pic.runs {
        let stroke = Stroke {
            width: stroke_width(run.width, pic),
            line_cap: LineCap::Round,
            line_join: LineJoin::Round,
            ..Stroke::default()
        };
        let p = paint(run.colour);
        let mut pb = PathBuilder::new();
        let mut count = 0;
        for line in &run.lines {
            pb.move_to(line[0][0] as f32, line[0][1] as f32);
            for q in &line[1..] {
                pb.line_to(q[0] as f32, q[1] as f32);
                count += 1;
                if count >= CHUNK {
                    // A long polyline goes on in a new path from the same
                    // point: round caps meet as a round join would.
                    if let Some(path) = std::mem::take(&mut pb).finish() {
                        pixmap.stroke_path(&path, &p, &stroke, Transform::identity(), None);
                    }
                    pb.move_to(q[0] as f32, q[1] as f32);
                    drawn += count as u64;
                    progress(drawn, total);
                    count = 0;
                }
            }
        }
        if let Some(path) = pb.finish() {
            pixmap.stroke_path(&path, &p, &stroke, Transform::identity(), None);
        }
        drawn += count as u64;
        progress(drawn, total);
    }
    // Opaque label pixels are the same premultiplied.
    for l in &pic.labels {
        super::text::write(pixmap.data_mut(), pic.width, 0, l);
    }
    Some(pixmap)
}

/// A run's width as stroked: at most twice the picture's perimeter (a
/// wider line covers the picture all the same, and tiny-skia's scan
/// converter overflows on widths like 10^11 pixels); NaN draws hairlines.
fn stroke_width(width: f64, pic: &Picture) -> f32 {
    let widest = 4.0 * (f64::from(pic.width) + f64::from(pic.height));
    if width.is_nan() {
        return 0.0;
    }
    width.clamp(0.0, widest) as f32
}

/// The picture as PNG bytes.
pub fn encode(pic: &Picture) -> Option<Vec<u8>> {
    encode_with(pic, &mut |_, _| {})
}

/// [`encode`], reporting progress as [`draw_with`] does.
pub fn encode_with(pic: &Picture, progress: &mut dyn FnMut(u64, u64)) -> Option<Vec<u8>> {
    draw_with(pic, progress)?.encode_png().ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::Run;

    /// A width of 10^11 pixels (a view file's `initial line width`)
    /// made tiny-skia's scan converter panic; drawn at the widest that
    /// matters, it covers the picture.
    #[test]
    fn a_line_wider_than_the_picture_covers_it() {
        for width in [99_999_999_999.0, f64::INFINITY, f64::NAN, -5.0] {
            let pic = Picture {
                width: 32,
                height: 32,
                background: crate::render::WHITE,
                background_alpha: 255,
                runs: vec![Run {
                    colour: Rgb(0, 0, 0),
                    width,
                    lines: vec![vec![[10.0, 16.0], [22.0, 16.0]]],
                }],
                polygons: Vec::new(),
                labels: Vec::new(),
                links: Default::default(),
            };
            let pixmap = draw(&pic).unwrap();
            let dark = pixmap.pixels().iter().filter(|p| p.red() < 128).count();
            let covers = width.is_finite() && width > 0.0 || width == f64::INFINITY;
            assert_eq!(dark == 32 * 32, covers, "{width}: {dark} dark pixels");
        }
    }
}
