//! Where a ray meets each primitive: closed forms, in the primitive's own
//! coordinates. A ray is `o + t d` with `d` of any length (an affine
//! transform of a ray keeps `t`), and a hit is the smallest `t` in
//! `(t_min, t_max)` with the surface's normal there (of any length, facing
//! either way: shading turns it towards the eye).

use super::vec::{add, cross, dot, mad, mul, normalize, sub, V3};
use crate::ir::graph::Primitive;

/// A ray: origin and direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: V3,
    pub dir: V3,
}

impl Ray {
    pub fn at(&self, t: f64) -> V3 {
        mad(self.origin, self.dir, t)
    }
}

/// A hit: the ray's parameter and the surface normal there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f64,
    pub normal: V3,
}

/// The nearest hit of `ray` on `p` with `t` in `(t_min, t_max)`.
pub fn intersect(p: &Primitive, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
    let hit = match p {
        Primitive::Sphere { centre, radius } => sphere(*centre, *radius, ray, t_min, t_max),
        Primitive::Box { min, max } => aabb(*min, *max, ray, t_min, t_max),
        Primitive::Cylinder { base, top, radius } => {
            cone(*base, *top, *radius, *radius, ray, t_min, t_max)
        }
        Primitive::Cone {
            base,
            top,
            base_radius,
            top_radius,
        } => cone(*base, *top, *base_radius, *top_radius, ray, t_min, t_max),
        Primitive::Disc {
            centre,
            normal,
            radius,
        } => disc(*centre, *normal, *radius, ray, t_min, t_max),
        Primitive::Triangle([a, b, c]) => triangle(*a, *b, *c, ray, t_min, t_max),
        Primitive::Polygon(points) => polygon(points, ray, t_min, t_max),
    };
    hit.filter(|h| h.t.is_finite())
}

/// The smaller root of `a t² + 2 b t + c` in `(t_min, t_max)`, else the
/// larger, by the numerically stable form.
fn roots(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    let disc = b * b - a * c;
    if disc < 0.0 || a == 0.0 {
        return None;
    }
    let q = -(b + b.signum() * disc.sqrt());
    let (r1, r2) = (q / a, if q != 0.0 { c / q } else { q / a });
    Some((r1.min(r2), r1.max(r2)))
}

pub fn sphere(c: V3, r: f64, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
    let oc = sub(ray.origin, c);
    let (t0, t1) = roots(dot(ray.dir, ray.dir), dot(oc, ray.dir), dot(oc, oc) - r * r)?;
    let t = [t0, t1].into_iter().find(|t| *t > t_min && *t < t_max)?;
    Some(Hit {
        t,
        normal: sub(ray.at(t), c),
    })
}

/// The interval of `t` over which the ray is inside the box, with the
/// normals of the faces it enters and leaves by.
pub fn slabs(min: V3, max: V3, ray: &Ray) -> Option<(f64, f64, V3, V3)> {
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    let (mut n0, mut n1) = ([0.0; 3], [0.0; 3]);
    for k in 0..3 {
        let d = ray.dir[k];
        if d == 0.0 {
            if ray.origin[k] < min[k] || ray.origin[k] > max[k] {
                return None;
            }
            continue;
        }
        let (mut a, mut b) = ((min[k] - ray.origin[k]) / d, (max[k] - ray.origin[k]) / d);
        let mut face = [0.0; 3];
        face[k] = -1.0;
        if a > b {
            std::mem::swap(&mut a, &mut b);
            face[k] = 1.0;
        }
        if a > t0 {
            t0 = a;
            n0 = face;
        }
        if b < t1 {
            t1 = b;
            n1 = mul(face, -1.0);
        }
    }
    (t0 <= t1).then_some((t0, t1, n0, n1))
}

pub fn aabb(min: V3, max: V3, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
    let (t0, t1, n0, n1) = slabs(min, max, ray)?;
    if t0 > t_min && t0 < t_max {
        Some(Hit { t: t0, normal: n0 })
    } else if t1 > t_min && t1 < t_max {
        Some(Hit { t: t1, normal: n1 })
    } else {
        None
    }
}

/// A closed, possibly truncated cone (a cylinder when the radii agree):
/// its side, where `|perp|² = r(s)²` with `r` linear along the axis, and
/// its two end discs.
fn cone(base: V3, top: V3, r0: f64, r1: f64, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
    let axis = sub(top, base);
    let h = dot(axis, axis).sqrt();
    if h.is_nan() || h <= 0.0 {
        return None;
    }
    let u = mul(axis, 1.0 / h);
    let k = (r1 - r0) / h;
    let w = sub(ray.origin, base);
    let (ws, ds) = (dot(w, u), dot(ray.dir, u));
    let p = mad(w, u, -ws);
    let q = mad(ray.dir, u, -ds);
    let r_w = r0 + k * ws;
    let mut best: Option<Hit> = None;
    let mut consider = |hit: Hit| {
        if hit.t > t_min && hit.t < t_max && best.is_none_or(|b| hit.t < b.t) {
            best = Some(hit);
        }
    };
    let a = dot(q, q) - k * k * ds * ds;
    let b = dot(p, q) - k * ds * r_w;
    let c = dot(p, p) - r_w * r_w;
    if let Some((t0, t1)) = roots(a, b, c) {
        for t in [t0, t1] {
            let s = ws + t * ds;
            if (0.0..=h).contains(&s) && r0 + k * s >= 0.0 {
                let perp = add(p, mul(q, t));
                let normal = sub(perp, mul(u, (r0 + k * s) * k));
                consider(Hit { t, normal });
            }
        }
    }
    for (centre, radius, normal) in [(base, r0, mul(u, -1.0)), (top, r1, u)] {
        if let Some(hit) = disc(centre, normal, radius, ray, t_min, t_max) {
            consider(hit);
        }
    }
    best
}

pub fn disc(c: V3, n: V3, r: f64, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
    let denom = dot(n, ray.dir);
    if denom == 0.0 || r <= 0.0 {
        return None;
    }
    let t = dot(n, sub(c, ray.origin)) / denom;
    if !(t > t_min && t < t_max) {
        return None;
    }
    let off = sub(ray.at(t), c);
    let n2 = dot(n, n);
    let in_plane = sub(off, mul(n, dot(off, n) / n2));
    (dot(in_plane, in_plane) <= r * r).then_some(Hit { t, normal: n })
}

/// Möller and Trumbore's test.
pub fn triangle(a: V3, b: V3, c: V3, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
    let (e1, e2) = (sub(b, a), sub(c, a));
    let pv = cross(ray.dir, e2);
    let det = dot(e1, pv);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let inv = 1.0 / det;
    let tv = sub(ray.origin, a);
    let u = dot(tv, pv) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let qv = cross(tv, e1);
    let v = dot(ray.dir, qv) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = dot(e2, qv) * inv;
    (t > t_min && t < t_max).then(|| Hit {
        t,
        normal: cross(e1, e2),
    })
}

fn polygon(points: &[V3], ray: &Ray, t_min: f64, mut t_max: f64) -> Option<Hit> {
    let first = *points.first()?;
    let mut best = None;
    for pair in points[1..].windows(2) {
        if let Some(hit) = triangle(first, pair[0], pair[1], ray, t_min, t_max) {
            t_max = hit.t;
            best = Some(hit);
        }
    }
    best
}

/// The unit normal of a hit facing the ray's origin.
pub fn facing(normal: V3, dir: V3) -> V3 {
    let n = normalize(normal);
    if dot(n, dir) > 0.0 {
        mul(n, -1.0)
    } else {
        n
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: V3, d: V3) -> Ray {
        Ray { origin: o, dir: d }
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn a_sphere_is_met_where_the_closed_form_says() {
        // From (0,0,5) down -z onto the unit sphere at (0,0,0) offset 0.6 in x:
        // it meets z = sqrt(1 - 0.36) = 0.8, so t = 5 - 0.8.
        let s = Primitive::Sphere {
            centre: [0.0; 3],
            radius: 1.0,
        };
        let h = intersect(&s, &ray([0.6, 0.0, 5.0], [0.0, 0.0, -1.0]), 0.0, 1e9).unwrap();
        assert!(close(h.t, 4.2));
        assert!(close(normalize(h.normal)[2], 0.8));
        // A direction of length 2 halves t.
        let h2 = intersect(&s, &ray([0.6, 0.0, 5.0], [0.0, 0.0, -2.0]), 0.0, 1e9).unwrap();
        assert!(close(h2.t, 2.1));
        assert!(intersect(&s, &ray([1.01, 0.0, 5.0], [0.0, 0.0, -1.0]), 0.0, 1e9).is_none());
        // From inside, the far wall.
        let h3 = intersect(&s, &ray([0.0; 3], [1.0, 0.0, 0.0]), 1e-9, 1e9).unwrap();
        assert!(close(h3.t, 1.0));
    }

    #[test]
    fn a_box_is_met_on_the_face_the_ray_enters() {
        let b = Primitive::Box {
            min: [-1.0, -2.0, -3.0],
            max: [1.0, 2.0, 3.0],
        };
        let h = intersect(&b, &ray([0.5, 10.0, 0.0], [0.0, -1.0, 0.0]), 0.0, 1e9).unwrap();
        assert!(close(h.t, 8.0));
        assert_eq!(h.normal, [0.0, 1.0, 0.0]);
        let diag = ray([-5.0, -5.0, 0.0], [1.0, 1.0, 0.0]);
        let h = intersect(&b, &diag, 0.0, 1e9).unwrap();
        assert!(close(h.t, 4.0), "enters by x = -1 at t = 4, got {}", h.t);
        assert!(intersect(&b, &ray([2.0, 0.0, 0.0], [0.0, 1.0, 0.0]), 0.0, 1e9).is_none());
    }

    #[test]
    fn a_cylinder_is_met_on_its_side_and_its_caps() {
        let c = Primitive::Cylinder {
            base: [0.0; 3],
            top: [0.0, 2.0, 0.0],
            radius: 0.5,
        };
        let side = intersect(&c, &ray([3.0, 1.0, 0.0], [-1.0, 0.0, 0.0]), 0.0, 1e9).unwrap();
        assert!(close(side.t, 2.5));
        assert!(close(normalize(side.normal)[0], 1.0));
        let cap = intersect(&c, &ray([0.2, 5.0, 0.0], [0.0, -1.0, 0.0]), 0.0, 1e9).unwrap();
        assert!(close(cap.t, 3.0));
        assert!(close(normalize(cap.normal)[1], 1.0));
        assert!(intersect(&c, &ray([3.0, 2.5, 0.0], [-1.0, 0.0, 0.0]), 0.0, 1e9).is_none());
    }

    #[test]
    fn a_cone_narrows_linearly() {
        // Radius 1 at y = 0 to 0 at y = 2: at y = 1 the radius is 0.5.
        let c = Primitive::Cone {
            base: [0.0; 3],
            top: [0.0, 2.0, 0.0],
            base_radius: 1.0,
            top_radius: 0.0,
        };
        let h = intersect(&c, &ray([3.0, 1.0, 0.0], [-1.0, 0.0, 0.0]), 0.0, 1e9).unwrap();
        assert!(close(h.t, 2.5), "got {}", h.t);
        // The normal leans up: the side faces out and up.
        let n = normalize(h.normal);
        assert!(n[0] > 0.0 && n[1] > 0.0 && close(n[1] / n[0], 0.5));
    }

    #[test]
    fn discs_and_triangles_are_met_inside_only() {
        let d = Primitive::Disc {
            centre: [0.0; 3],
            normal: [0.0, 0.0, 1.0],
            radius: 1.0,
        };
        assert!(close(
            intersect(&d, &ray([0.5, 0.5, 2.0], [0.0, 0.0, -1.0]), 0.0, 1e9)
                .unwrap()
                .t,
            2.0
        ));
        assert!(intersect(&d, &ray([0.8, 0.8, 2.0], [0.0, 0.0, -1.0]), 0.0, 1e9).is_none());
        let t = Primitive::Triangle([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        assert!(close(
            intersect(&t, &ray([0.2, 0.2, 3.0], [0.0, 0.0, -1.0]), 0.0, 1e9)
                .unwrap()
                .t,
            3.0
        ));
        assert!(intersect(&t, &ray([0.6, 0.6, 3.0], [0.0, 0.0, -1.0]), 0.0, 1e9).is_none());
        let square = Primitive::Polygon(vec![
            [0.0; 3],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ]);
        assert!(intersect(&square, &ray([0.9, 0.9, 1.0], [0.0, 0.0, -1.0]), 0.0, 1e9).is_some());
        // t_max cuts.
        assert!(intersect(&square, &ray([0.9, 0.9, 1.0], [0.0, 0.0, -1.0]), 0.0, 0.5).is_none());
    }
}
