//! Generalized cylinders with a cross-section (cpfg `@#(id)` then `@Gs`,
//! `@Gc`, `@Ge`): the contour is swept along the Hermite curve between two
//! control points as a mesh of quadrilaterals, as cpfg's
//! `interpolate_connection` does.
//!
//! At each of the `pieces + 1` rings the frame follows the curve's tangent
//! with the least rotation from the first control point's frame, plus the
//! share `t` of the twist that brings it onto the second control point's
//! frame (cpfg's `twist of cylinders: on`); the radius goes linearly from
//! half the first point's width to half the second's, and the cross-section
//! from the first point's contour to the second's. A contour point
//! (x, y, z) lies at `r (x U − y L) + r z H / d`, `r` the radius and `d` the
//! distance between the control points.

use super::{add_scaled, cross, dot, normalised, Vec3};
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
    let ring = |k: usize| -> Vec<Vec3> {
        let t = k as f64 / pieces as f64;
        let (pos, tangent) = hermite_at(a.pos, t0, b.pos, t1, t);
        let h = if dot(tangent, tangent) > 1e-24 {
            normalised(tangent)
        } else {
            a.h
        };
        let u = roll(transport(a.u, a.h, h), h, twist * t);
        let l = cross(u, h);
        let r = a.radius + (b.radius - a.radius) * t;
        (0..m)
            .map(|i| {
                let p: Vec3 =
                    std::array::from_fn(|c| r * (from[i][c] + (to[i][c] - from[i][c]) * t));
                std::array::from_fn(|c| pos[c] + p[0] * u[c] - p[1] * l[c] + p[2] * h[c] / d)
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
        // (x goes along U), as wide as the radius says.
        let flat = [[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
        let quads = sweep(
            &end([0.0; 3], 0.5),
            &end([0.0, 2.0, 0.0], 0.25),
            (1.2, 1.2),
            4,
            &flat,
            &flat,
        );
        assert_eq!(quads.len(), 4);
        let first = quads[0];
        assert!((first[0][2] + 0.5).abs() < 1e-9 && (first[1][2] - 0.5).abs() < 1e-9);
        let last = quads[3];
        assert!((last[2][2] - 0.25).abs() < 1e-9 && (last[2][1] - 2.0).abs() < 1e-9);
        // y of the contour goes along −L = +x.
        let side = [[0.0, 1.0, 0.0], [0.0, 2.0, 0.0]];
        let q = sweep(
            &end([0.0; 3], 1.0),
            &end([0.0, 1.0, 0.0], 1.0),
            (1.2, 1.2),
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
        let q = sweep(&a, &b, (1.2, 1.2), 2, &dot_x, &dot_x);
        let mid = q[0][3];
        let eighth = std::f64::consts::FRAC_PI_4;
        assert!((mid[2] - eighth.cos()).abs() < 1e-9, "{mid:?}");
        assert!((mid[0] + eighth.sin()).abs() < 1e-9, "{mid:?}");
        assert!((q[1][3][0] + 1.0).abs() < 1e-9, "{:?}", q[1][3]);
    }

    #[test]
    fn coincident_points_draw_nothing() {
        let c = circle();
        assert_eq!(c.len(), CONTOUR_SAMPLES + 1);
        assert!(sweep(
            &end([0.0; 3], 1.0),
            &end([0.0; 3], 1.0),
            (1.2, 1.2),
            4,
            &c,
            &c
        )
        .is_empty());
    }
}
