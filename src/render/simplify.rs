//! The lines of a [`Picture`] with what cannot be seen at its size merged
//! away, for the SVG of a big drawing (`--detail merged`, the default).
//!
//! Two steps, each within half a pixel, in the drawing order:
//! - a segment whose ink lands only on cells (half-pixel squares) that
//!   the same colour already covers, with nothing of another colour drawn
//!   over them since, adds nothing visible and is left out (the polyline
//!   it was part of is split there);
//! - in what is left, points that lie within half a pixel of the line
//!   between their neighbours kept are dropped, so that a chain of short
//!   nearly collinear segments becomes one.
//!
//! Like the streamed PNG path ([`super::coverage`]), a dense crown then
//! costs what its pixels cost, not what its segments cost.

use super::{Picture, Run};
use crate::ir::Rgb;

/// How far (pixels) a merged line may stray from the lines it replaces.
pub const TOLERANCE: f64 = 0.5;

/// The most cells held: 16 M (two bytes each).
const MAX_CELLS: f64 = 16.0 * 1024.0 * 1024.0;

/// The most points a merged stretch of a polyline checks against its
/// chord, so that merging stays linear in the number of points.
const MAX_STRETCH: usize = 32;

/// Which colour last covered each cell of the picture (0 none).
struct Cells {
    /// Pixels per cell.
    size: f64,
    cols: i64,
    rows: i64,
    last: Vec<u16>,
    colours: Vec<Rgb>,
}

impl Cells {
    fn new(pic: &Picture) -> Self {
        let (w, h) = (f64::from(pic.width), f64::from(pic.height));
        // Half a pixel, or larger where the picture would need too many.
        let size = (TOLERANCE).max((w * h / MAX_CELLS).sqrt());
        let (cols, rows) = ((w / size).ceil() as i64, (h / size).ceil() as i64);
        Cells {
            size,
            cols,
            rows,
            last: vec![0; (cols * rows).max(0) as usize],
            colours: Vec::new(),
        }
    }

    /// The index of `colour`; `None` past what a cell can name.
    fn paint(&mut self, colour: Rgb) -> Option<u16> {
        if let Some(k) = self.colours.iter().rposition(|&c| c == colour) {
            return Some(k as u16 + 1);
        }
        if self.colours.len() >= usize::from(u16::MAX) {
            return None;
        }
        self.colours.push(colour);
        Some(self.colours.len() as u16)
    }

    /// Paints the cells whose centre lies within `width / 2` of the
    /// segment `a`–`b` (pixels) with `k`; whether any of them changed. A
    /// segment thinner than a cell covers the cells it passes through.
    fn stroke(&mut self, a: [f64; 2], b: [f64; 2], width: f64, k: u16) -> bool {
        let s = self.size;
        let (a, b) = ([a[0] / s, a[1] / s], [b[0] / s, b[1] / s]);
        let r = (width / 2.0 / s).max(0.5);
        let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
        // Pieces of at most two cells, so that each piece's bounding box
        // is little more than its ink.
        let pieces = (len / 2.0).ceil().clamp(1.0, 1e6) as usize;
        let mut changed = false;
        for i in 0..pieces {
            let t = |j: usize| j as f64 / pieces as f64;
            let at = |t: f64| [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];
            changed |= self.capsule(at(t(i)), at(t(i + 1)), r, k);
        }
        changed
    }

    /// [`Cells::stroke`] of one short piece, in cell units.
    fn capsule(&mut self, a: [f64; 2], b: [f64; 2], r: f64, k: u16) -> bool {
        let lo = |i: usize| ((a[i].min(b[i]) - r - 0.5).ceil() as i64).max(0);
        let hi = |i: usize, n: i64| ((a[i].max(b[i]) + r - 0.5).floor() as i64).min(n - 1);
        let mut changed = false;
        for y in lo(1)..=hi(1, self.rows) {
            for x in lo(0)..=hi(0, self.cols) {
                let c = [x as f64 + 0.5, y as f64 + 0.5];
                if distance_squared(c, a, b) <= r * r {
                    let cell = &mut self.last[(y * self.cols + x) as usize];
                    changed |= *cell != k;
                    *cell = k;
                }
            }
        }
        changed
    }
}

/// The square of the distance from `p` to the segment `a`–`b`.
fn distance_squared(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (ex, ey) = (p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
    ex * ex + ey * ey
}

/// `line` without the points that lie within [`TOLERANCE`] of the chord
/// between the points kept around them; its ends are kept.
fn merge_collinear(line: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let Some((&first, rest)) = line.split_first() else {
        return Vec::new();
    };
    let mut out = vec![first];
    let mut stretch: Vec<[f64; 2]> = Vec::new();
    for &p in rest {
        let anchor = *out.last().expect("starts with the first point");
        let fits = stretch.len() < MAX_STRETCH
            && stretch
                .iter()
                .all(|&q| distance_squared(q, anchor, p) <= TOLERANCE * TOLERANCE);
        if !fits {
            if let Some(&prev) = stretch.last() {
                out.push(prev);
                stretch.clear();
            }
        }
        stretch.push(p);
    }
    if let Some(&last) = stretch.last() {
        out.push(last);
    }
    out
}

/// The pieces of `line` whose segments add something visible to `cells`
/// (in `colour`, `width` pixels wide), which it paints them into.
fn visible_pieces(
    cells: &mut Cells,
    line: &[[f64; 2]],
    colour: Rgb,
    width: f64,
) -> Vec<Vec<[f64; 2]>> {
    let paint = cells.paint(colour);
    let mut pieces: Vec<Vec<[f64; 2]>> = Vec::new();
    let mut open = false;
    for w in line.windows(2) {
        let finite = w.iter().flatten().all(|c| c.is_finite());
        let shows = match paint {
            Some(k) if finite => cells.stroke(w[0], w[1], width, k),
            _ => true,
        };
        match (shows, open) {
            (true, true) => pieces.last_mut().expect("open").push(w[1]),
            (true, false) => pieces.push(vec![w[0], w[1]]),
            (false, _) => {}
        }
        open = shows;
    }
    pieces
}

/// The picture's runs with sub-pixel detail merged away; `None` when
/// nothing merges (the picture is written as it is).
pub fn merged_runs(pic: &Picture) -> Option<Vec<Run>> {
    let mut cells = Cells::new(pic);
    let mut changed = false;
    let runs: Vec<Run> = pic
        .runs
        .iter()
        .map(|run| {
            let mut lines = Vec::new();
            for line in &run.lines {
                let pieces = visible_pieces(&mut cells, line, run.colour, run.width);
                changed |= pieces.len() != 1 || pieces[0].len() != line.len();
                for piece in pieces {
                    let merged = merge_collinear(&piece);
                    changed |= merged.len() != piece.len();
                    lines.push(merged);
                }
            }
            Run {
                colour: run.colour,
                width: run.width,
                lines,
            }
        })
        .collect();
    changed.then_some(runs)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn picture(lines: Vec<Vec<[f64; 2]>>) -> Picture {
        Picture {
            width: 100,
            height: 100,
            background: Rgb(255, 255, 255),
            background_alpha: 255,
            runs: vec![Run {
                colour: Rgb(0, 0, 0),
                width: 1.0,
                lines,
            }],
            polygons: Vec::new(),
            labels: Vec::new(),
            links: Default::default(),
        }
    }

    #[test]
    fn nearly_collinear_points_merge_and_corners_stay() {
        let line = [[0.0, 0.0], [1.0, 0.2], [2.0, -0.1], [3.0, 0.0], [3.0, 5.0]];
        assert_eq!(merge_collinear(&line), [[0.0, 0.0], [3.0, 0.0], [3.0, 5.0]]);
    }

    #[test]
    fn a_line_drawn_again_over_itself_is_left_out() {
        let there = vec![[10.0, 10.0], [40.0, 10.0]];
        let back = vec![[40.0, 10.0], [10.0, 10.0], [10.0, 60.0]];
        let runs = merged_runs(&picture(vec![there.clone(), back])).unwrap();
        assert_eq!(runs[0].lines, [there, vec![[10.0, 10.0], [10.0, 60.0]]]);
    }

    #[test]
    fn a_picture_without_sub_pixel_detail_is_kept() {
        let pic = picture(vec![vec![[10.0, 10.0], [40.0, 10.0], [40.0, 50.0]]]);
        assert_eq!(merged_runs(&pic), None);
    }
}
