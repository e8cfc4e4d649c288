//! The attractor of a planar IFS drawn at pixel resolution, the same
//! pixels every run: no chaos game, no noise.
//!
//! An IFS `{w1 … wn}` of maps that shrink has one attractor A, the
//! figure made of its own images: A = w1(A) ∪ … ∪ wn(A) (Bekaert &
//! Willems §2.3.1; the graph of one symbol, rule `A -> w1(A) … wn(A)`).
//! It is drawn in three steps:
//!
//! 1. **A disc that holds A**: a centre c and the radius R = max |wi(c) − c|
//!    / (1 − ri), ri the most wi stretches (its largest singular value),
//!    which every wi maps into itself; of the maps' fixed points and their
//!    centroid, the centre with the smallest R.
//! 2. **A's extent**, along the picture's axes (turned by `--rotate`), by
//!    branch and bound over the couples w = wσ1 ∘ … ∘ wσk: the image w(D)
//!    of the disc bounds what A has there from above, the image of a fixed
//!    point (a point of A) from below, and the couple with the highest
//!    bound is split until the two meet within a millionth of R. The box is
//!    fitted into the picture as every 2D picture is ([`super::Fit`]: the
//!    margin, the share it fills).
//! 3. **The pixels**, by the minimal plotting algorithm (Dubuc & Elqortobi):
//!    a grid of cells (a pixel split 4 x 4 up to 1024 x 1024) holds
//!    one point of A per cell reached, starting from the maps' fixed
//!    points; each point's images under every map are computed once, and
//!    an image whose cell is already set goes no further. Each cell is set
//!    at most once, so the work is bounded by cells times maps (Fractint's
//!    64 at most; past a budget the cells are made coarser), and every
//!    pixel set holds a point of A. A pixel is set when one of its cells
//!    is.
//!
//! Nothing depends on threads or the clock: the same graph and options
//! give the same bytes.

use super::{Fit, RenderOptions};
use crate::ir::graph::{stretch_2d, Affine, InstancingGraph};
use crate::ir::Rgb;
use std::collections::BinaryHeap;
use std::fmt::Write as _;

/// A map of the plane: rows `[a b e]`, `[c d f]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Map2([[f64; 3]; 2]);

impl Map2 {
    const IDENTITY: Map2 = Map2([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);

    fn of(a: &Affine) -> Map2 {
        let m = &a.0;
        Map2([[m[0][0], m[0][1], m[0][3]], [m[1][0], m[1][1], m[1][3]]])
    }

    pub fn apply(&self, p: [f64; 2]) -> [f64; 2] {
        let m = &self.0;
        [
            m[0][0] * p[0] + m[0][1] * p[1] + m[0][2],
            m[1][0] * p[0] + m[1][1] * p[1] + m[1][2],
        ]
    }

    /// `self ∘ other`: `other` first.
    fn after(&self, other: &Map2) -> Map2 {
        let (a, b) = (&self.0, &other.0);
        let row = |i: usize| {
            [
                a[i][0] * b[0][0] + a[i][1] * b[1][0],
                a[i][0] * b[0][1] + a[i][1] * b[1][1],
                a[i][0] * b[0][2] + a[i][1] * b[1][2] + a[i][2],
            ]
        };
        Map2([row(0), row(1)])
    }

    fn stretch(&self) -> f64 {
        let m = &self.0;
        stretch_2d(m[0][0], m[0][1], m[1][0], m[1][1])
    }

    fn inverse(&self) -> Option<Map2> {
        let m = &self.0;
        let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let (a, b, c, d) = (m[1][1] / det, -m[0][1] / det, -m[1][0] / det, m[0][0] / det);
        Some(Map2([
            [a, b, -(a * m[0][2] + b * m[1][2])],
            [c, d, -(c * m[0][2] + d * m[1][2])],
        ]))
    }

    /// The point the map leaves where it is (it shrinks, so there is one).
    fn fixed_point(&self) -> Option<[f64; 2]> {
        let m = &self.0;
        let i_minus = Map2([
            [1.0 - m[0][0], -m[0][1], 0.0],
            [-m[1][0], 1.0 - m[1][1], 0.0],
        ]);
        let inv = i_minus.inverse()?;
        let p = inv.apply([m[0][2], m[1][2]]);
        (p[0].is_finite() && p[1].is_finite()).then_some(p)
    }

    /// `|Mᵀ d|`: how far the image of the unit disc reaches along `d`.
    fn reach(&self, d: [f64; 2]) -> f64 {
        let m = &self.0;
        (m[0][0] * d[0] + m[1][0] * d[1]).hypot(m[0][1] * d[0] + m[1][1] * d[1])
    }
}

/// Why an attractor is not drawn.
#[derive(Clone, Debug, PartialEq)]
pub enum NotDrawn {
    /// The graph is not an IFS of maps of the plane: several symbols,
    /// geometries, or maps that leave the plane.
    NotAnIfs,
    /// A map does not shrink: there is no attractor.
    NotContractive,
    /// The axiom's transform flattens the plane, or the numbers overflow.
    Degenerate,
    /// More pixels than a grid of cells is made for (4 billion).
    TooLarge,
}

impl std::fmt::Display for NotDrawn {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            NotDrawn::NotAnIfs => {
                "only a planar graph of one symbol without geometry (an IFS) is drawn flat"
            }
            NotDrawn::NotContractive => "a map of the IFS does not shrink: it has no attractor",
            NotDrawn::Degenerate => "the IFS's numbers flatten or overflow the plane",
            NotDrawn::TooLarge => "the picture has too many pixels for an attractor",
        })
    }
}

/// The IFS a graph is, in the plane of the picture: the maps of its one
/// symbol seen through the axiom's one transform (`w ∘ wi ∘ w⁻¹`, whose
/// attractor is w(A)).
pub fn planar_ifs(graph: &InstancingGraph) -> Result<Vec<Map2>, NotDrawn> {
    let [symbol] = graph.symbols.as_slice() else {
        return Err(NotDrawn::NotAnIfs);
    };
    let [axiom] = graph.axiom.as_slice() else {
        return Err(NotDrawn::NotAnIfs);
    };
    let rule = symbol.rule.as_deref().unwrap_or(&[]);
    if graph.has_geometry() || rule.is_empty() || !graph.is_planar() {
        return Err(NotDrawn::NotAnIfs);
    }
    let w = Map2::of(&axiom.transform);
    let w_inv = w.inverse().ok_or(NotDrawn::Degenerate)?;
    let maps: Vec<Map2> = rule
        .iter()
        .map(|i| w.after(&Map2::of(&i.transform)).after(&w_inv))
        .collect();
    if maps
        .iter()
        .any(|m| m.0.iter().flatten().any(|x| !x.is_finite()))
    {
        return Err(NotDrawn::Degenerate);
    }
    // At the IR's own threshold (`InstancingGraph::divergent_cycles`).
    if rule
        .iter()
        .any(|i| i.transform.contraction().is_nan() || i.transform.contraction() >= 1.0 - 1e-12)
    {
        return Err(NotDrawn::NotContractive);
    }
    Ok(maps)
}

/// A disc every map sends into itself, so that it holds the attractor:
/// its centre and radius.
fn bounding_disc(maps: &[Map2]) -> ([f64; 2], f64) {
    let fixed: Vec<[f64; 2]> = maps.iter().filter_map(Map2::fixed_point).collect();
    let n = fixed.len().max(1) as f64;
    let centroid = [0, 1].map(|k| fixed.iter().map(|p| p[k]).sum::<f64>() / n);
    let radius = |c: [f64; 2]| {
        maps.iter()
            .map(|m| {
                let q = m.apply(c);
                (q[0] - c[0]).hypot(q[1] - c[1]) / (1.0 - m.stretch())
            })
            .fold(0.0, f64::max)
    };
    let mut best = (centroid, radius(centroid));
    for c in fixed {
        let r = radius(c);
        if r < best.1 {
            best = (c, r);
        }
    }
    best
}

/// A couple under consideration: its map and the most it can reach.
struct Node {
    bound: f64,
    order: u64,
    map: Map2,
}

impl PartialEq for Node {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == std::cmp::Ordering::Equal
    }
}
impl Eq for Node {}
impl PartialOrd for Node {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Node {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        // The highest bound first; of equal ones the earliest found.
        (self.bound.total_cmp(&other.bound)).then(other.order.cmp(&self.order))
    }
}

/// The most couples made (a map applied to a couple), and kept to be
/// split, to find one side of the attractor's extent: a few milliseconds
/// and megabytes. Past them the extent is the highest bound left, still
/// one that holds A (an IFS of maps that shrink by 0.999 gets there).
const MAX_MADE: usize = 1_000_000;
const MAX_KEPT: usize = 200_000;

/// How far along `d` (a unit vector) the attractor reaches: at least the
/// true extent, and within `tolerance` of it unless [`MAX_MADE`] ran out.
fn support(
    maps: &[Map2],
    disc: ([f64; 2], f64),
    point: [f64; 2],
    d: [f64; 2],
    tolerance: f64,
) -> f64 {
    let (c, r) = disc;
    let dot = |p: [f64; 2]| p[0] * d[0] + p[1] * d[1];
    let bound = |m: &Map2| dot(m.apply(c)) + r * m.reach(d);
    let mut best = dot(point);
    let mut heap = BinaryHeap::new();
    let mut order = 0u64;
    heap.push(Node {
        bound: bound(&Map2::IDENTITY),
        order,
        map: Map2::IDENTITY,
    });
    // The highest bound of the couples not kept (past MAX_KEPT).
    let mut dropped = f64::NEG_INFINITY;
    for _ in 0..MAX_MADE / maps.len().max(1) {
        let Some(top) = heap.pop() else {
            return best.max(dropped);
        };
        if top.bound - best <= tolerance {
            return top.bound.max(dropped);
        }
        for m in maps {
            let child = top.map.after(m);
            best = best.max(dot(child.apply(point)));
            let b = bound(&child);
            if b <= best {
                continue;
            }
            if heap.len() < MAX_KEPT {
                order += 1;
                heap.push(Node {
                    bound: b,
                    order,
                    map: child,
                });
            } else {
                dropped = dropped.max(b);
            }
        }
    }
    heap.peek().map_or(best, |n| n.bound.max(best)).max(dropped)
}

/// The extent is found within this share of the attractor's size: a
/// tenth of a pixel in a picture 5000 pixels wide. Finer, the couples
/// along a straight edge of the attractor (a side of Sierpinski's
/// triangle) would be split into millions.
const TOLERANCE: f64 = 2e-5;

/// A size of the attractor from points of it (the maps' fixed points and
/// their images under every map): at most its diameter, and close to it.
fn spread(maps: &[Map2]) -> f64 {
    let fixed: Vec<[f64; 2]> = maps.iter().filter_map(Map2::fixed_point).collect();
    let points: Vec<[f64; 2]> = (fixed.iter())
        .flat_map(|p| maps.iter().map(move |m| m.apply(*p)))
        .chain(fixed.iter().copied())
        .collect();
    let range = |k: usize| {
        let (lo, hi) = (points.iter()).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p[k]), hi.max(p[k]))
        });
        (hi - lo).max(0.0)
    };
    range(0).max(range(1))
}

/// The picture's pixels the attractor touches, row by row.
#[derive(Clone, Debug, PartialEq)]
pub struct Pixels {
    pub width: u32,
    pub height: u32,
    /// `set[y * width + x]`, y down.
    pub set: Vec<bool>,
}

impl Pixels {
    pub fn count(&self) -> usize {
        self.set.iter().filter(|&&s| s).count()
    }
}

/// The most cells a grid has when its pixels are split: a pixel is split
/// into 4 x 4 cells up to 1024 x 1024 pixels, 2 x 2 up to 2048 x 2048,
/// and not at all beyond (the work and memory then grow with the pixels
/// alone). Finer cells find more of the pixels that a sliver of the
/// attractor touches: against a chaos game of 50 million points, 4 x 4
/// misses about 1.5% of Sierpinski's triangle's pixels at 1024 x 1024,
/// 2 x 2 about 5%; every pixel set holds a point of the attractor.
const MOST_CELLS: u64 = 1 << 24;

/// Cells of border kept around the picture, so that an extent found a
/// hair short cuts nothing off that the margin would show.
const BORDER: i64 = 4;

/// Where the attractor of `maps` goes in the picture of `opts`: the map
/// of the plane to pixels (x right, y down) that fits its extent as every
/// 2D picture is fitted (its margin, rotation and share).
pub fn frame(maps: &[Map2], opts: &RenderOptions) -> Result<Map2, NotDrawn> {
    let disc = bounding_disc(maps);
    if !(disc.1.is_finite() && disc.0.iter().all(|v| v.is_finite())) {
        return Err(NotDrawn::Degenerate);
    }
    let point = maps
        .iter()
        .find_map(Map2::fixed_point)
        .ok_or(NotDrawn::Degenerate)?;
    // The picture's axes in the plane: x' = p·(c, −s), y' = p·(s, c).
    let (s, c) = opts.style.rotate.to_radians().sin_cos();
    let (ax, ay) = ([c, -s], [s, c]);
    let tolerance = TOLERANCE * spread(maps).max(1e-6 * disc.1).max(f64::MIN_POSITIVE);
    let side = |d: [f64; 2]| support(maps, disc, point, d, tolerance);
    let (x_hi, y_hi) = (side(ax), side(ay));
    let (x_lo, y_lo) = (-side([-ax[0], -ax[1]]), -side([-ay[0], -ay[1]]));
    // The box's corners back in the plane, which the fit turns again.
    let corners: Vec<[f64; 2]> = [[x_lo, y_lo], [x_hi, y_lo], [x_hi, y_hi], [x_lo, y_hi]]
        .iter()
        .map(|&[x, y]| [x * c + y * s, -x * s + y * c])
        .collect();
    let fit = Fit::new(corners.iter(), opts);
    // The plane to pixels, found from the fit (it is affine).
    let o = fit.to_px([0.0, 0.0]);
    let ex = fit.to_px([1.0, 0.0]);
    let ey = fit.to_px([0.0, 1.0]);
    let m = Map2([
        [ex[0] - o[0], ey[0] - o[0], o[0]],
        [ex[1] - o[1], ey[1] - o[1], o[1]],
    ]);
    match m.0.iter().flatten().all(|v| v.is_finite()) {
        true => Ok(m),
        false => Err(NotDrawn::Degenerate),
    }
}

/// The pixels of the attractor of `maps`, fitted into the picture of
/// `opts` ([`frame`]).
pub fn pixels(maps: &[Map2], opts: &RenderOptions) -> Result<Pixels, NotDrawn> {
    let (w, h) = (opts.width, opts.height);
    let to_px = frame(maps, opts)?;
    let area = u64::from(w) * u64::from(h);
    let mut k = [4u32, 2, 1]
        .into_iter()
        .find(|k| area * u64::from(k * k) <= MOST_CELLS)
        .unwrap_or(1);
    loop {
        let kf = f64::from(k);
        let b = BORDER as f64;
        let to_grid = Map2([[kf, 0.0, b], [0.0, kf, b]]).after(&to_px);
        let from_grid = to_grid.inverse().ok_or(NotDrawn::Degenerate)?;
        let grid_maps: Vec<Map2> = maps
            .iter()
            .map(|m| to_grid.after(m).after(&from_grid))
            .collect();
        let cols = i64::from(w) * i64::from(k) + 2 * BORDER;
        let rows = i64::from(h) * i64::from(k) + 2 * BORDER;
        if cols.saturating_mul(rows) > i64::from(u32::MAX) {
            return Err(NotDrawn::TooLarge);
        }
        // Split pixels only while the work stays within its budget.
        let budget = if k > 1 { MOST_WORK } else { u64::MAX };
        let Some(cells) = plot(&grid_maps, cols, rows, budget) else {
            k /= 2;
            continue;
        };
        let k = i64::from(k);
        let mut set = vec![false; w as usize * h as usize];
        for (i, px) in set.iter_mut().enumerate() {
            let (x, y) = ((i % w as usize) as i64, (i / w as usize) as i64);
            *px = (0..k * k).any(|j| {
                let (cx, cy) = (BORDER + x * k + j % k, BORDER + y * k + j / k);
                cells
                    .get((cy * cols + cx) as usize)
                    .copied()
                    .unwrap_or(false)
            });
        }
        return Ok(Pixels {
            width: w,
            height: h,
            set,
        });
    }
}

/// The most maps applied to points while pixels are split into cells
/// (about half a second): an attractor that fills its picture under many
/// maps (Fractint's 64) is plotted in coarser cells instead.
const MOST_WORK: u64 = 1 << 27;

/// A point of the attractor in the grid: its cell, and where it is in
/// the cell in 65536ths (8 bytes, as fine everywhere in the grid).
#[derive(Clone, Copy)]
struct Point {
    cell: u32,
    fx: u16,
    fy: u16,
}

/// The minimal plotting algorithm on a `cols` x `rows` grid: the cells
/// that points of the attractor of `maps` (in grid units) fall in; `None`
/// when that takes more than `budget` maps applied.
fn plot(maps: &[Map2], cols: i64, rows: i64, budget: u64) -> Option<Vec<bool>> {
    let mut set = vec![false; (cols * rows).max(0) as usize];
    let mut stack: Vec<Point> = Vec::new();
    let visit = |p: [f64; 2], set: &mut Vec<bool>, stack: &mut Vec<Point>| {
        let (fx, fy) = (p[0].floor(), p[1].floor());
        if !(fx >= 0.0 && fy >= 0.0 && fx < cols as f64 && fy < rows as f64) {
            return;
        }
        let cell = fy as i64 * cols + fx as i64;
        if std::mem::replace(&mut set[cell as usize], true) {
            return;
        }
        let frac = |v: f64, f: f64| ((v - f) * 65536.0).clamp(0.0, 65535.0) as u16;
        stack.push(Point {
            cell: cell as u32,
            fx: frac(p[0], fx),
            fy: frac(p[1], fy),
        });
    };
    for m in maps {
        if let Some(p) = m.fixed_point() {
            visit(p, &mut set, &mut stack);
        }
    }
    let mut work = 0u64;
    while let Some(q) = stack.pop() {
        work += maps.len() as u64;
        if work > budget {
            return None;
        }
        let cell = i64::from(q.cell);
        let p = [
            (cell % cols) as f64 + (f64::from(q.fx) + 0.5) / 65536.0,
            (cell / cols) as f64 + (f64::from(q.fy) + 0.5) / 65536.0,
        ];
        for m in maps {
            visit(m.apply(p), &mut set, &mut stack);
        }
    }
    Some(set)
}

/// The pixels as a PNG: `ink` where set, else the background of `opts`.
pub fn png(px: &Pixels, ink: Rgb, opts: &RenderOptions) -> Option<Vec<u8>> {
    if px.width == 0 || px.height == 0 {
        return None;
    }
    let mut out = Vec::new();
    let mut encoder = ::png::Encoder::new(&mut out, px.width, px.height);
    encoder.set_color(::png::ColorType::Rgba);
    encoder.set_depth(::png::BitDepth::Eight);
    let mut writer = encoder.write_header().ok()?;
    let mut stream = writer.stream_writer().ok()?;
    let bg = opts.background;
    let back = [bg.0, bg.1, bg.2, opts.background_alpha];
    let fore = [ink.0, ink.1, ink.2, 255];
    let mut row = Vec::with_capacity(px.width as usize * 4);
    for line in px.set.chunks(px.width as usize) {
        row.clear();
        for &s in line {
            row.extend_from_slice(if s { &fore } else { &back });
        }
        std::io::Write::write_all(&mut stream, &row).ok()?;
    }
    stream.finish().ok()?;
    drop(writer);
    Some(out)
}

/// The pixels as an SVG: the background, then one path of the runs of
/// set pixels, row by row, with crisp edges.
pub fn svg(px: &Pixels, ink: Rgb, opts: &RenderOptions) -> String {
    let (w, h) = (px.width, px.height);
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" shape-rendering="crispEdges">"#
    );
    let bg = opts.background;
    match opts.background_alpha {
        0 => {}
        a => {
            let opacity = match a {
                255 => String::new(),
                a => format!(r#" fill-opacity="{:.3}""#, f64::from(a) / 255.0),
            };
            let _ = writeln!(
                out,
                r##"<rect width="{w}" height="{h}" fill="#{:02x}{:02x}{:02x}"{opacity}/>"##,
                bg.0, bg.1, bg.2
            );
        }
    }
    let mut d = String::new();
    for (y, line) in px.set.chunks(w.max(1) as usize).enumerate() {
        let mut x = 0;
        while x < line.len() {
            if !line[x] {
                x += 1;
                continue;
            }
            let start = x;
            while x < line.len() && line[x] {
                x += 1;
            }
            let n = x - start;
            let _ = write!(d, "M{start} {y}h{n}v1h-{n}z");
        }
    }
    if !d.is_empty() {
        let _ = writeln!(
            out,
            r##"<path d="{d}" fill="#{:02x}{:02x}{:02x}"/>"##,
            ink.0, ink.1, ink.2
        );
    }
    out.push_str("</svg>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn halves(corners: &[[f64; 2]]) -> Vec<Map2> {
        corners
            .iter()
            .map(|c| Map2([[0.5, 0.0, 0.5 * c[0]], [0.0, 0.5, 0.5 * c[1]]]))
            .collect()
    }

    fn opts(w: u32, h: u32) -> RenderOptions {
        RenderOptions {
            width: w,
            height: h,
            ..RenderOptions::default()
        }
    }

    #[test]
    fn the_extent_is_found_from_the_maps() {
        let maps = halves(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        let disc = bounding_disc(&maps);
        let p = maps[0].fixed_point().unwrap();
        for (d, want) in [([1.0, 0.0], 1.0), ([-1.0, 0.0], 0.0), ([0.0, 1.0], 1.0)] {
            let got = support(&maps, disc, p, d, 1e-5);
            assert!(got >= want && got - want <= 1e-5, "{d:?}: {got}");
        }
        // The disc holds the attractor.
        for q in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]] {
            assert!((q[0] - disc.0[0]).hypot(q[1] - disc.0[1]) <= disc.1 + 1e-12);
        }
    }

    #[test]
    fn four_halves_to_the_corners_fill_the_square() {
        let maps = halves(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]);
        let px = pixels(&maps, &opts(100, 100)).unwrap();
        // The 5% margin on each side: a 90 x 90 square.
        let n = px.count();
        assert!((90 * 90..=91 * 91).contains(&n), "{n}");
        assert!(px.set[50 * 100 + 50] && !px.set[2 * 100 + 2]);
    }

    #[test]
    fn the_same_pixels_every_time_and_a_png_of_them() {
        let maps = halves(&[[0.0, 0.0], [1.0, 0.0], [0.5, 0.8]]);
        let a = pixels(&maps, &opts(64, 48)).unwrap();
        assert_eq!(a, pixels(&maps, &opts(64, 48)).unwrap());
        let bytes = png(&a, Rgb(0, 0, 0), &opts(64, 48)).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
        let svg = svg(&a, Rgb(0, 0, 0), &opts(64, 48));
        assert!(svg.contains("<path d=\"M") && svg.ends_with("</svg>\n"));
    }
}
