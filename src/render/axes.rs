//! The principal axes of a drawing's points, and the view that looks
//! along one: what says a picture lies in a plane seen edge-on, and which
//! view sees it face on.

use crate::turtle::{self, Geometry};

/// The points a picture of `g` is made of: segment ends and polygon
/// corners, or with `spline` the turtle's positions the curves pass by.
pub fn world_points(g: &Geometry, spline: bool) -> Vec<turtle::Vec3> {
    if spline {
        return g
            .paths
            .iter()
            .flat_map(|p| p.points.iter().copied())
            .collect();
    }
    g.segments
        .iter()
        .flat_map(|s| [s.a, s.b])
        .chain(g.polygons.iter().flat_map(|p| p.points.iter().copied()))
        .chain(g.discs.iter().map(|d| d.centre))
        .collect()
}

/// The variances of `points` along their principal axes, largest first,
/// each with its axis (a unit vector): the eigenvalues and eigenvectors of
/// their covariance, by Jacobi rotations.
pub fn principal_spreads(points: &[turtle::Vec3]) -> [(f64, turtle::Vec3); 3] {
    let n = points.len().max(1) as f64;
    let mean = [0, 1, 2].map(|k| points.iter().map(|p| p[k]).sum::<f64>() / n);
    let mut c = [[0.0f64; 3]; 3];
    for p in points {
        let d = [0, 1, 2].map(|k| p[k] - mean[k]);
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] += d[i] * d[j] / n;
            }
        }
    }
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..50 {
        let (p, q) = [(0, 1), (0, 2), (1, 2)]
            .into_iter()
            .max_by(|a, b| c[a.0][a.1].abs().total_cmp(&c[b.0][b.1].abs()))
            .unwrap_or((0, 1));
        if c[p][q].abs() <= 1e-300 {
            break;
        }
        let theta = 0.5 * (2.0 * c[p][q]).atan2(c[q][q] - c[p][p]);
        let (s, co) = theta.sin_cos();
        // c = Jᵀ c J and v = v J for the rotation J in the (p, q) plane:
        // turning the rows of c gives c J, whose transpose is Jᵀ c (c is
        // symmetric), and turning that again gives Jᵀ c J.
        let turn = |row: &mut [f64; 3]| {
            let (a, b) = (row[p], row[q]);
            row[p] = co * a - s * b;
            row[q] = s * a + co * b;
        };
        c.iter_mut().for_each(turn);
        c = [0, 1, 2].map(|i| [c[0][i], c[1][i], c[2][i]]);
        c.iter_mut().for_each(turn);
        v.iter_mut().for_each(turn);
    }
    let mut out = [0, 1, 2].map(|k| (c[k][k].max(0.0), [v[0][k], v[1][k], v[2][k]]));
    out.sort_by(|a, b| b.0.total_cmp(&a.0));
    out
}

/// The view (azimuth, elevation in degrees) that looks along `normal`:
/// the direction [`super`]'s parallel view looks from is
/// (-sin az cos el, sin el, cos az cos el).
pub fn view_along(normal: turtle::Vec3) -> (f64, f64) {
    let n = if normal[2] < 0.0 {
        normal.map(|x| -x)
    } else {
        normal
    };
    let el = n[1].clamp(-1.0, 1.0).asin().to_degrees();
    let az = (-n[0]).atan2(n[2]).to_degrees();
    // No `-0` in the suggestion.
    (az.round() + 0.0, el.round() + 0.0)
}
