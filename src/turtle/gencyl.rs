//! Generalized cylinders with a cross-section (cpfg `@#(id)` then `@Gs`,
//! `@Gc`, `@Ge`): the contour is swept along the Hermite curve between two
//! control points as a mesh of quadrilaterals, as cpfg's
//! `interpolate_connection` does.
//!
//! At each of the `pieces + 1` rings the frame follows the curve's tangent
//! with the least rotation from the first control point's frame, plus the
//! share `t` of the twist that brings it onto the second control point's
//! frame (cpfg's `twist of cylinders: on`); the cross-section goes from the
//! first point's contour to the second's. The rings are spaced and sized
//! by a second, planar Hermite curve (t, r) from (0, half the first
//! point's width) to (1, half the second's) whose tangents are cpfg's
//! radius tangents (`@Gr`, [`RadiusTangents`]); without them it is the
//! straight line, rings evenly spaced and the radius linear. A contour point
//! (x, y, z) lies at `r (−x U − y L) + r z H / d`, `r` the radius and `d`
//! the distance between the control points: cpfg's `x U − y L` with cpfg's
//! up, the turtle's −U.

use super::state::{add_scaled, cross, dot, normalised};
use super::Vec3;
use crate::ir::look::CONTOUR_SAMPLES;

/// A control point of a generalized cylinder: where it is, its frame (H
/// and U, unit and orthogonal) and the radius there.
#[derive(Clone, Copy, Debug)]
pub(super) struct End {
    pub pos: Vec3,
    pub h: Vec3,
    pub u: Vec3,
    pub radius: f64,
}

/// The tangents of the (t, r) curve at the start and the end of a piece of
/// cylinder, as cpfg's `@Gr` sets them: (dt, dr) per unit of the ring
/// parameter. A zero tangent means "the straight line": (1, r₁ − r₀).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct RadiusTangents {
    pub start: [f64; 2],
    pub end: [f64; 2],
}

impl RadiusTangents {
    /// The tangents actually used between radii `r0` and `r1`: a zero one
    /// replaced by the straight line's (cpfg's default).
    fn resolved(self, r0: f64, r1: f64) -> ([f64; 2], [f64; 2]) {
        let or_line = |v: [f64; 2]| {
            if v == [0.0, 0.0] {
                [1.0, r1 - r0]
            } else {
                v
            }
        };
        (or_line(self.start), or_line(self.end))
    }
}

/// The unit circle as a closed cross-section: `CONTOUR_SAMPLES + 1`
/// points starting on +x, the last the first.
pub(super) fn circle() -> Vec<Vec3> {
    (0..=CONTOUR_SAMPLES)
        .map(|k| {
            let a = std::f64::consts::TAU * (k % CONTOUR_SAMPLES) as f64 / CONTOUR_SAMPLES as f64;
            [a.cos(), a.sin(), 0.0]
        })
        .collect()
}

/// `v` turned by the least rotation taking unit `from` to unit `to`
/// (unchanged when they are parallel or opposite: no axis to turn about).
fn transport(v: Vec3, from: Vec3, to: Vec3) -> Vec3 {
    let axis = cross(from, to);
    let s = dot(axis, axis).sqrt();
    if s < 1e-12 {
        return v;
    }
    let k = axis.map(|x| x / s);
    let c = dot(from, to);
    // Rodrigues: v cos + (k × v) sin + k (k · v)(1 − cos).
    let kv = cross(k, v);
    let along = dot(k, v) * (1.0 - c);
    std::array::from_fn(|i| v[i] * c + kv[i] * s + k[i] * along)
}

/// `u` turned about unit `h` by `angle`, then made unit and orthogonal to
/// `h` (rounding and the transport leave it slightly off).
fn roll(u: Vec3, h: Vec3, angle: f64) -> Vec3 {
    let (s, c) = angle.sin_cos();
    let hu = cross(h, u);
    let turned: Vec3 = std::array::from_fn(|i| u[i] * c + hu[i] * s);
    let off = add_scaled(turned, h, -dot(turned, h));
    if dot(off, off) < 1e-24 {
        return u;
    }
    normalised(off)
}

/// The signed angle about unit `h` from `a` to `b` (both orthogonal to it).
fn angle_about(h: Vec3, a: Vec3, b: Vec3) -> f64 {
    dot(cross(a, b), h).atan2(dot(a, b))
}

/// The quadrilaterals of the piece of cylinder from `a` to `b`: `pieces`
/// rings after `a`, the cross-section going from `from` to `to` (point
/// lists of one length; the shorter one's length is used otherwise).
/// Nothing when the control points coincide (cpfg draws nothing either).
pub(super) fn sweep(
    a: &End,
    b: &End,
    tangents: (f64, f64),
    radius_tangents: RadiusTangents,
    pieces: usize,
    from: &[Vec3],
    to: &[Vec3],
) -> Vec<[Vec3; 4]> {
    let chord: Vec3 = std::array::from_fn(|i| b.pos[i] - a.pos[i]);
    let d = dot(chord, chord).sqrt();
    let m = from.len().min(to.len());
    if d < 1e-5 || !d.is_finite() || m < 2 || pieces == 0 {
        return Vec::new();
    }
    let t0 = a.h.map(|x| x * d * tangents.0);
    let t1 = b.h.map(|x| x * d * tangents.1);
    let twist = angle_about(b.h, transport(a.u, a.h, b.h), b.u);
    let (rt0, rt1) = radius_tangents.resolved(a.radius, b.radius);
    let ring = |k: usize| -> Vec<Vec3> {
        let s = k as f64 / pieces as f64;
        // Where along the axis the ring sits, and its radius.
        let t = hermite_1d(0.0, rt0[0], 1.0, rt1[0], s);
        let r = hermite_1d(a.radius, rt0[1], b.radius, rt1[1], s);
        let (pos, tangent) = hermite_at(a.pos, t0, b.pos, t1, t);
        let h = if dot(tangent, tangent) > 1e-24 {
            normalised(tangent)
        } else {
            a.h
        };
        let u = roll(transport(a.u, a.h, h), h, twist * t);
        let l = cross(u, h);
        (0..m)
            .map(|i| {
                let p: Vec3 =
                    std::array::from_fn(|c| r * (from[i][c] + (to[i][c] - from[i][c]) * t));
                std::array::from_fn(|c| pos[c] - p[0] * u[c] - p[1] * l[c] + p[2] * h[c] / d)
            })
            .collect()
    };
    let mut quads = Vec::with_capacity(pieces * (m - 1));
    let mut last = ring(0);
    for k in 1..=pieces {
        let next = ring(k);
        for i in 0..m - 1 {
            quads.push([last[i], last[i + 1], next[i + 1], next[i]]);
        }
        last = next;
    }
    quads
}

/// The value at `s` of the cubic Hermite function from `p0` (slope `m0`)
/// to `p1` (slope `m1`) over [0, 1].
fn hermite_1d(p0: f64, m0: f64, p1: f64, m1: f64, s: f64) -> f64 {
    let (s2, s3) = (s * s, s * s * s);
    (2.0 * s3 - 3.0 * s2 + 1.0) * p0
        + (s3 - 2.0 * s2 + s) * m0
        + (-2.0 * s3 + 3.0 * s2) * p1
        + (s3 - s2) * m1
}

/// The point and the derivative at `t` of the cubic Hermite curve from
/// `p0` (tangent `t0`) to `p1` (tangent `t1`).
fn hermite_at(p0: Vec3, t0: Vec3, p1: Vec3, t1: Vec3, t: f64) -> (Vec3, Vec3) {
    let (t2, t3) = (t * t, t * t * t);
    let h = [
        2.0 * t3 - 3.0 * t2 + 1.0,
        t3 - 2.0 * t2 + t,
        -2.0 * t3 + 3.0 * t2,
        t3 - t2,
    ];
    let dh = [
        6.0 * t2 - 6.0 * t,
        3.0 * t2 - 4.0 * t + 1.0,
        -6.0 * t2 + 6.0 * t,
        3.0 * t2 - 2.0 * t,
    ];
    let at = |w: [f64; 4]| -> Vec3 {
        std::array::from_fn(|i| w[0] * p0[i] + w[1] * t0[i] + w[2] * p1[i] + w[3] * t1[i])
    };
    (at(h), at(dh))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn end(pos: Vec3, radius: f64) -> End {
        End {
            pos,
            h: [0.0, 1.0, 0.0],
            u: [0.0, 0.0, 1.0],
            radius,
        }
    }

    #[test]
    fn a_straight_sweep_places_the_contour_in_the_frame() {
        // An open "contour" from (−1, 0) to (1, 0): a flat ribbon along U
        // (x goes along cpfg's up, −U), as wide as the radius says.
        let flat = [[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
        let quads = sweep(
            &end([0.0; 3], 0.5),
            &end([0.0, 2.0, 0.0], 0.25),
            (1.2, 1.2),
            RadiusTangents::default(),
            4,
            &flat,
            &flat,
        );
        assert_eq!(quads.len(), 4);
        let first = quads[0];
        assert!((first[0][2] - 0.5).abs() < 1e-9 && (first[1][2] + 0.5).abs() < 1e-9);
        let last = quads[3];
        assert!((last[2][2] + 0.25).abs() < 1e-9 && (last[2][1] - 2.0).abs() < 1e-9);
        // y of the contour goes along −L = +x.
        let side = [[0.0, 1.0, 0.0], [0.0, 2.0, 0.0]];
        let q = sweep(
            &end([0.0; 3], 1.0),
            &end([0.0, 1.0, 0.0], 1.0),
            (1.2, 1.2),
            RadiusTangents::default(),
            1,
            &side,
            &side,
        );
        assert!((q[0][0][0] - 1.0).abs() < 1e-9, "{:?}", q[0][0]);
    }

    #[test]
    fn the_twist_between_control_points_is_shared_out() {
        // The second point is rolled a quarter turn about H: the middle
        // ring is rolled by an eighth.
        let a = end([0.0; 3], 1.0);
        let b = End {
            u: [-1.0, 0.0, 0.0],
            ..end([0.0, 1.0, 0.0], 1.0)
        };
        let dot_x = [[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
        let q = sweep(
            &a,
            &b,
            (1.2, 1.2),
            RadiusTangents::default(),
            2,
            &dot_x,
            &dot_x,
        );
        let mid = q[0][3];
        let eighth = std::f64::consts::FRAC_PI_4;
        // The contour's x lies along −U.
        assert!((mid[2] + eighth.cos()).abs() < 1e-9, "{mid:?}");
        assert!((mid[0] - eighth.sin()).abs() < 1e-9, "{mid:?}");
        assert!((q[1][3][0] - 1.0).abs() < 1e-9, "{:?}", q[1][3]);
    }

    #[test]
    fn coincident_points_draw_nothing() {
        let c = circle();
        assert_eq!(c.len(), CONTOUR_SAMPLES + 1);
        assert!(sweep(
            &end([0.0; 3], 1.0),
            &end([0.0; 3], 1.0),
            (1.2, 1.2),
            RadiusTangents::default(),
            4,
            &c,
            &c
        )
        .is_empty());
    }

    #[test]
    fn radius_tangents_give_width_to_a_cylinder_without_end_widths() {
        // Radius 0 at both ends: without tangents every ring is a point;
        // with the radius rising at slope 1 and falling at slope 1 (and the
        // axis parameter still at both ends), the radius is s (1 − s), its
        // top 1/4 half way along the axis (the contour's x along −U).
        let dot_x = [[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
        let (a, b) = (end([0.0; 3], 0.0), end([0.0, 2.0, 0.0], 0.0));
        let widest = |rt: RadiusTangents| {
            let q = sweep(&a, &b, (1.0, 1.0), rt, 4, &dot_x, &dot_x);
            q.iter()
                .flat_map(|quad| quad.iter())
                .fold(
                    [0.0f64, 0.0],
                    |w, p| if -p[2] > w[0] { [-p[2], p[1]] } else { w },
                )
        };
        assert_eq!(widest(RadiusTangents::default()), [0.0, 0.0]);
        let bulge = RadiusTangents {
            start: [0.0, 1.0],
            end: [0.0, -1.0],
        };
        let [r, y] = widest(bulge);
        assert!(
            (r - 0.25).abs() < 1e-9 && (y - 1.0).abs() < 1e-9,
            "{r} at {y}"
        );
    }
}
