//! Layout shapes ([`Shape`]): their outlines (for drawing and for
//! containment) and the exact test "does this stem stay inside the union of
//! the shapes", the geometry of a growth constraint that any front end may
//! state and the driver draws.
//!
//! Coordinates are stem units with the origin at the root and y up. The
//! starting point of Rectangle, RoundRect and Ellipse is the lower-left
//! corner of the bounding box. A RoundRect's corner parameter is the size
//! of the corner's quarter-ellipse (Delphi's `RoundRect` X3/Y3: the corner
//! radius is half of it); corners are outlined with 8 segments each, both
//! where drawn and where growth tests containment, so what is drawn is what
//! is tested.
//!
//! Containment of a stem (a segment) in the union is exact, not sampled:
//! each shape meets the segment's line in a set of parameter intervals
//! (an ellipse by a quadratic, a polygon by its edge crossings and an
//! even-odd test of each piece), and the stem is inside when these
//! intervals cover all of `[0, 1]`.

use crate::ir::{Rgb, Shape};

/// Tolerance of the containment tests, relative to the layout's size.
const EPS: f64 = 1e-9;

/// Segments per RoundRect corner.
const CORNER_SEGMENTS: usize = 8;

/// Points of an ellipse's outline when drawn.
const ELLIPSE_POINTS: usize = 96;

/// The shape's colour.
pub fn colour(shape: &Shape) -> Rgb {
    match shape {
        Shape::Rectangle { colour, .. }
        | Shape::RoundRect { colour, .. }
        | Shape::Ellipse { colour, .. }
        | Shape::Polygon { colour, .. } => *colour,
    }
}

/// The outline of a shape as a closed polygon (first point not repeated).
pub fn outline(shape: &Shape) -> Vec<[f64; 2]> {
    match *shape {
        Shape::Rectangle { x, y, w, h, .. } => {
            vec![[x, y], [x + w, y], [x + w, y + h], [x, y + h]]
        }
        Shape::Ellipse { x, y, w, h, .. } => {
            let (cx, cy, rx, ry) = (x + w / 2.0, y + h / 2.0, w / 2.0, h / 2.0);
            (0..ELLIPSE_POINTS)
                .map(|i| {
                    let a = std::f64::consts::TAU * i as f64 / ELLIPSE_POINTS as f64;
                    [cx + rx * a.cos(), cy + ry * a.sin()]
                })
                .collect()
        }
        Shape::RoundRect {
            x, y, w, h, corner, ..
        } => {
            let rx = (corner / 2.0).min(w / 2.0).max(0.0);
            let ry = (corner / 2.0).min(h / 2.0).max(0.0);
            // Corner centres, counter-clockwise from the lower right.
            let centres = [
                (x + w - rx, y + ry, -90.0f64),
                (x + w - rx, y + h - ry, 0.0),
                (x + rx, y + h - ry, 90.0),
                (x + rx, y + ry, 180.0),
            ];
            let mut pts = Vec::new();
            for (cx, cy, start) in centres {
                for k in 0..=CORNER_SEGMENTS {
                    let a = (start + 90.0 * k as f64 / CORNER_SEGMENTS as f64).to_radians();
                    pts.push([cx + rx * a.cos(), cy + ry * a.sin()]);
                }
            }
            pts
        }
        Shape::Polygon { ref points, .. } => points.iter().map(|&(x, y)| [x, y]).collect(),
    }
}

/// `[minx, miny, maxx, maxy]` of all shapes, or `None` without shapes.
pub fn bounds(shapes: &[Shape]) -> Option<[f64; 4]> {
    let mut b: Option<[f64; 4]> = None;
    for s in shapes {
        for p in outline(s) {
            let bb = b.get_or_insert([p[0], p[1], p[0], p[1]]);
            bb[0] = bb[0].min(p[0]);
            bb[1] = bb[1].min(p[1]);
            bb[2] = bb[2].max(p[0]);
            bb[3] = bb[3].max(p[1]);
        }
    }
    b
}

/// A shape prepared for containment tests.
#[derive(Clone, Debug)]
enum Region {
    Ellipse { cx: f64, cy: f64, rx: f64, ry: f64 },
    Polygon(Vec<[f64; 2]>),
}

/// The union of the layout's shapes, ready for containment tests.
#[derive(Clone, Debug)]
pub struct Outline {
    regions: Vec<Region>,
    /// Absolute tolerance (relative [`EPS`] times the layout's size).
    eps: f64,
}

impl Outline {
    pub fn new(shapes: &[Shape]) -> Self {
        let size = bounds(shapes).map_or(1.0, |b| (b[2] - b[0]).max(b[3] - b[1]).max(1e-300));
        let regions = shapes
            .iter()
            .map(|s| match *s {
                Shape::Ellipse { x, y, w, h, .. } => Region::Ellipse {
                    cx: x + w / 2.0,
                    cy: y + h / 2.0,
                    rx: w / 2.0,
                    ry: h / 2.0,
                },
                _ => Region::Polygon(outline(s)),
            })
            .collect();
        Outline {
            regions,
            eps: EPS * size,
        }
    }

    /// Whether the point is inside (or on the boundary of) the union.
    pub fn contains_point(&self, p: [f64; 2]) -> bool {
        self.regions.iter().any(|r| match r {
            Region::Ellipse { cx, cy, rx, ry } => {
                if *rx <= 0.0 || *ry <= 0.0 {
                    return false;
                }
                let (u, v) = ((p[0] - cx) / rx, (p[1] - cy) / ry);
                u * u + v * v <= 1.0 + 2.0 * self.eps / rx.min(*ry)
            }
            Region::Polygon(pts) => in_polygon(pts, p, self.eps),
        })
    }

    /// Whether the whole segment `a`–`b` lies inside the union.
    pub fn contains_segment(&self, a: [f64; 2], b: [f64; 2]) -> bool {
        let d = [b[0] - a[0], b[1] - a[1]];
        let mut intervals: Vec<(f64, f64)> = Vec::new();
        for r in &self.regions {
            match r {
                Region::Ellipse { cx, cy, rx, ry } => {
                    if *rx <= 0.0 || *ry <= 0.0 {
                        continue;
                    }
                    let (ox, oy) = ((a[0] - cx) / rx, (a[1] - cy) / ry);
                    let (dx, dy) = (d[0] / rx, d[1] / ry);
                    let qa = dx * dx + dy * dy;
                    let tol = 2.0 * self.eps / rx.min(*ry);
                    let qc = ox * ox + oy * oy - 1.0 - tol;
                    if qa == 0.0 {
                        if qc <= 0.0 {
                            intervals.push((0.0, 1.0));
                        }
                        continue;
                    }
                    let qb = 2.0 * (ox * dx + oy * dy);
                    let disc = qb * qb - 4.0 * qa * qc;
                    if disc < 0.0 {
                        continue;
                    }
                    let s = disc.sqrt();
                    intervals.push(((-qb - s) / (2.0 * qa), (-qb + s) / (2.0 * qa)));
                }
                Region::Polygon(pts) => polygon_intervals(pts, a, d, self.eps, &mut intervals),
            }
        }
        covers(&mut intervals)
    }
}

/// Whether the intervals cover `[0, 1]` (up to a tiny gap).
fn covers(intervals: &mut [(f64, f64)]) -> bool {
    intervals.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut reach = 0.0f64;
    for &(s, e) in intervals.iter() {
        if s > reach + 1e-9 {
            break;
        }
        reach = reach.max(e);
        if reach >= 1.0 - 1e-9 {
            return true;
        }
    }
    reach >= 1.0 - 1e-9
}

/// Even-odd point-in-polygon, counting points within `eps` of an edge as
/// inside.
fn in_polygon(pts: &[[f64; 2]], p: [f64; 2], eps: f64) -> bool {
    let n = pts.len();
    if n < 3 {
        return false;
    }
    let mut inside = false;
    for i in 0..n {
        let (u, v) = (pts[i], pts[(i + 1) % n]);
        if point_segment_distance(p, u, v) <= eps {
            return true;
        }
        if (u[1] > p[1]) != (v[1] > p[1]) {
            let x = u[0] + (p[1] - u[1]) / (v[1] - u[1]) * (v[0] - u[0]);
            if p[0] < x {
                inside = !inside;
            }
        }
    }
    inside
}

/// The parameter intervals of `a + t·d`, t in [0, 1], inside the polygon.
fn polygon_intervals(
    pts: &[[f64; 2]],
    a: [f64; 2],
    d: [f64; 2],
    eps: f64,
    out: &mut Vec<(f64, f64)>,
) {
    let n = pts.len();
    if n < 3 {
        return;
    }
    let mut ts = vec![0.0, 1.0];
    for i in 0..n {
        let (u, v) = (pts[i], pts[(i + 1) % n]);
        let e = [v[0] - u[0], v[1] - u[1]];
        let den = d[0] * e[1] - d[1] * e[0];
        if den.abs() < 1e-300 {
            continue;
        }
        let w = [u[0] - a[0], u[1] - a[1]];
        let t = (w[0] * e[1] - w[1] * e[0]) / den;
        let s = (w[0] * d[1] - w[1] * d[0]) / den;
        if (-1e-12..=1.0 + 1e-12).contains(&s) && t > 0.0 && t < 1.0 {
            ts.push(t);
        }
    }
    ts.sort_by(f64::total_cmp);
    let at = |t: f64| [a[0] + d[0] * t, a[1] + d[1] * t];
    for w in ts.windows(2) {
        let (t0, t1) = (w[0], w[1]);
        let mid = at((t0 + t1) / 2.0);
        if in_polygon(pts, mid, eps) || (t1 - t0 < 1e-12 && in_polygon(pts, at(t0), eps)) {
            out.push((t0, t1));
        }
    }
}

/// Distance from `p` to the segment `u`–`v`.
pub fn point_segment_distance(p: [f64; 2], u: [f64; 2], v: [f64; 2]) -> f64 {
    let e = [v[0] - u[0], v[1] - u[1]];
    let len2 = e[0] * e[0] + e[1] * e[1];
    let t = if len2 > 0.0 {
        (((p[0] - u[0]) * e[0] + (p[1] - u[1]) * e[1]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let q = [u[0] + e[0] * t - p[0], u[1] + e[1] * t - p[1]];
    (q[0] * q[0] + q[1] * q[1]).sqrt()
}

/// Distance between segments `a`–`b` and `c`–`d`.
pub fn segment_distance(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> f64 {
    let cross = |o: [f64; 2], p: [f64; 2], q: [f64; 2]| {
        (p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0])
    };
    let (d1, d2) = (cross(a, b, c), cross(a, b, d));
    let (d3, d4) = (cross(c, d, a), cross(c, d, b));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return 0.0;
    }
    point_segment_distance(a, c, d)
        .min(point_segment_distance(b, c, d))
        .min(point_segment_distance(c, a, b))
        .min(point_segment_distance(d, a, b))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ellipse() -> Shape {
        Shape::Ellipse {
            colour: Rgb(0, 0, 0),
            x: -100.0,
            y: 0.0,
            w: 200.0,
            h: 100.0,
        }
    }

    #[test]
    fn segments_inside_an_ellipse_and_across_a_union() {
        let o = Outline::new(&[ellipse()]);
        assert!(o.contains_segment([0.0, 0.0], [0.0, 100.0]));
        assert!(!o.contains_segment([0.0, 50.0], [0.0, 101.0]));
        // A concave L-shaped polygon: the segment across the notch is out.
        let l = Shape::Polygon {
            colour: Rgb(0, 0, 0),
            points: vec![
                (0.0, 0.0),
                (10.0, 0.0),
                (10.0, 2.0),
                (2.0, 2.0),
                (2.0, 10.0),
                (0.0, 10.0),
            ],
        };
        let o = Outline::new(std::slice::from_ref(&l));
        assert!(o.contains_segment([1.0, 1.0], [9.0, 1.0]));
        assert!(o.contains_segment([1.0, 1.0], [1.0, 9.0]));
        assert!(!o.contains_segment([9.0, 1.0], [1.0, 9.0]));
        // Filling the notch with a rectangle makes it inside the union.
        let r = Shape::Rectangle {
            colour: Rgb(0, 0, 0),
            x: 1.0,
            y: 1.0,
            w: 9.0,
            h: 9.0,
        };
        assert!(Outline::new(&[l, r]).contains_segment([9.0, 1.0], [1.0, 9.0]));
    }

    #[test]
    fn distances_between_segments() {
        assert_eq!(
            segment_distance([0.0, 0.0], [2.0, 2.0], [0.0, 2.0], [2.0, 0.0]),
            0.0
        );
        let d = segment_distance([0.0, 0.0], [1.0, 0.0], [0.0, 3.0], [1.0, 3.0]);
        assert!((d - 3.0).abs() < 1e-12);
    }

    #[test]
    fn round_rect_outline_is_closed_and_inside_its_box() {
        let s = Shape::RoundRect {
            colour: Rgb(0, 0, 0),
            x: 0.0,
            y: 0.0,
            w: 100.0,
            h: 50.0,
            corner: 20.0,
        };
        let pts = outline(&s);
        assert_eq!(pts.len(), 4 * (CORNER_SEGMENTS + 1));
        assert!(pts.iter().all(
            |p| (-1e-9..=100.0 + 1e-9).contains(&p[0]) && (-1e-9..=50.0 + 1e-9).contains(&p[1])
        ));
        let o = Outline::new(&[s]);
        assert!(o.contains_point([50.0, 25.0]) && !o.contains_point([0.5, 0.5]));
    }
}
