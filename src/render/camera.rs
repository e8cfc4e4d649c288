//! Where a picture is seen from: a file's camera (eye, target, up, parallel
//! or perspective, [`Camera`]) or the azimuth/elevation [`View`].
//!
//! A [`Projector`] takes world points to the picture plane (x right, y up,
//! in world units for a parallel projection and in units of the tangent of
//! the angle off the view axis for a perspective one) and a distance away
//! from the viewer, which the z-buffer compares.

use super::{depth, project, Fit, RenderOptions, Turn};
use crate::ir::look::Camera;
use crate::turtle::Vec3;

/// A projection of world points onto the picture plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projector {
    /// The azimuth/elevation view: parallel, exactly today's formulas
    /// ([`super::project`]), so pictures without a camera stay the same.
    View(Turn),
    /// A camera's frame.
    Camera(Frame),
}

/// A camera as an orthonormal frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    eye: Vec3,
    right: Vec3,
    up: Vec3,
    /// From the eye towards the target.
    forward: Vec3,
    perspective: bool,
    /// Perspective: the tangent of half the view angle, which spans the
    /// picture's height (`gluPerspective`'s).
    half_tan: f64,
    /// Perspective: nearer than this (along `forward`) is not drawn.
    near: f64,
}

pub(crate) fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(crate) fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `v` of length 1, or `None` when it has no direction (or is not finite).
pub(crate) fn unit(v: Vec3) -> Option<Vec3> {
    let n = dot(v, v).sqrt();
    (n > 1e-300 && n.is_finite()).then(|| [v[0] / n, v[1] / n, v[2] / n])
}

impl Frame {
    /// The frame of `cam`; a degenerate camera (eye on the target, up along
    /// the view) falls back to looking down −z, and an up along the view
    /// to another up.
    pub fn new(cam: &Camera) -> Frame {
        let forward = unit(sub(cam.target, cam.eye)).unwrap_or([0.0, 0.0, -1.0]);
        let right = [cam.up, [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]]
            .into_iter()
            .find_map(|up| unit(cross(forward, up)).filter(|r| dot(*r, *r) > 0.5))
            .unwrap_or([1.0, 0.0, 0.0]);
        let up = cross(right, forward);
        let distance = dot(sub(cam.target, cam.eye), forward);
        let angle = cam.perspective.filter(|a| a.is_finite() && *a > 0.0);
        Frame {
            eye: if cam.eye.iter().all(|c| c.is_finite()) {
                cam.eye
            } else {
                [0.0; 3]
            },
            right,
            up,
            forward,
            perspective: angle.is_some(),
            half_tan: angle.map_or(1.0, |a| (a.min(179.0).to_radians() / 2.0).tan()),
            near: (distance.abs() * 1e-3).max(1e-9),
        }
    }
}

impl Projector {
    /// The projector of `opts`: its camera when it has one, else its view.
    pub fn new(opts: &RenderOptions) -> Projector {
        match &opts.camera {
            Some(cam) => Projector::Camera(Frame::new(cam)),
            None => Projector::View(Turn::of(opts.view)),
        }
    }

    /// Whether nearer things look larger.
    pub fn perspective(&self) -> bool {
        matches!(self, Projector::Camera(f) if f.perspective)
    }

    /// `p` on the picture plane and its distance away from the viewer
    /// (larger is farther); `None` behind the near plane of a perspective.
    pub fn project(&self, p: Vec3) -> Option<([f64; 2], f64)> {
        match self {
            Projector::View(t) => Some((project(p, *t), -depth(p, *t))),
            Projector::Camera(f) => {
                let d = sub(p, f.eye);
                let (x, y, z) = (dot(d, f.right), dot(d, f.up), dot(d, f.forward));
                if !f.perspective {
                    return Some(([x, y], z));
                }
                (z >= f.near).then(|| ([x / z, y / z], z))
            }
        }
    }

    /// Pixels per world unit at distance `z` for a fit of `fit`.
    pub(crate) fn pixels_per_unit(&self, fit: &Fit, z: f64) -> f64 {
        if self.perspective() {
            fit.scale / z.max(1e-300)
        } else {
            fit.scale
        }
    }

    /// The unit vector from `p` towards the viewer.
    pub fn towards_viewer(&self, p: Vec3) -> Vec3 {
        match self {
            Projector::View(t) => [-t.sa * t.ce, t.se, t.ca * t.ce],
            Projector::Camera(f) if f.perspective => {
                unit(sub(f.eye, p)).unwrap_or([-f.forward[0], -f.forward[1], -f.forward[2]])
            }
            Projector::Camera(f) => [-f.forward[0], -f.forward[1], -f.forward[2]],
        }
    }

    /// The picture's right and up directions in the world (at `p`, for a
    /// perspective: perpendicular to the line of sight there).
    pub fn screen_axes(&self, p: Vec3) -> (Vec3, Vec3) {
        let back = self.towards_viewer(p);
        let up = match self {
            Projector::View(t) => [t.sa * t.se, t.ce, -t.ca * t.se],
            Projector::Camera(f) => f.up,
        };
        let right = unit(cross(up, back)).unwrap_or([1.0, 0.0, 0.0]);
        (right, cross(back, right))
    }

    /// The fit of picture-plane points `pts` into the picture of `opts`: a
    /// parallel projection centres what is drawn (cpfg's auto-centring); a
    /// perspective is its camera's alone, nothing fitted: the view axis at
    /// the centre and the view angle across the picture's height, as
    /// cpfg's `gluPerspective` (and graftal's ray tracer) has it.
    pub(crate) fn fit(&self, pts: &[[f64; 2]], opts: &RenderOptions) -> Fit {
        self.fit_padded(pts, opts, 0.0)
    }

    /// [`Projector::fit`] keeping `pad` more pixels within an asked-for
    /// margin ([`Fit::padded`]).
    pub(crate) fn fit_padded(&self, pts: &[[f64; 2]], opts: &RenderOptions, pad: f64) -> Fit {
        match self {
            Projector::Camera(f) if f.perspective => {
                let scale = opts.height.max(1) as f64 / 2.0 / f.half_tan;
                Fit::around([0.0, 0.0], scale, opts, pad)
            }
            _ => Fit::padded(pts.iter(), opts, pad),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::View;

    fn camera(eye: Vec3, target: Vec3, perspective: Option<f64>) -> RenderOptions {
        RenderOptions {
            camera: Some(Camera {
                eye,
                target,
                up: [0.0, 1.0, 0.0],
                perspective,
            }),
            ..RenderOptions::default()
        }
    }

    #[test]
    fn the_view_projects_as_before() {
        let view = View::degrees(30.0, 20.0);
        let p = [1.5, -2.0, 0.25];
        let opts = RenderOptions {
            view,
            ..RenderOptions::default()
        };
        let (xy, z) = Projector::new(&opts).project(p).unwrap();
        assert_eq!(xy, project(p, Turn::of(view)));
        assert_eq!(z, -depth(p, Turn::of(view)));
        // The direction towards the viewer is the one depth grows along.
        let v = Projector::new(&opts).towards_viewer(p);
        let t = Turn::of(view);
        let d = depth([p[0] + v[0], p[1] + v[1], p[2] + v[2]], t) - depth(p, t);
        assert!((d - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_camera_looks_from_its_eye_at_its_target() {
        // A viewer at +x looking towards −x, y up, has −z on the right.
        let opts = camera([10.0, 0.0, 0.0], [0.0; 3], None);
        let pr = Projector::new(&opts);
        let (xy, z) = pr.project([0.0, 2.0, -1.0]).unwrap();
        assert!((xy[0] - 1.0).abs() < 1e-12 && (xy[1] - 2.0).abs() < 1e-12);
        assert!((z - 10.0).abs() < 1e-12);
        assert!(pr.project([5.0, 0.0, 0.0]).unwrap().1 < z);
    }

    #[test]
    fn a_perspective_shrinks_far_things_and_drops_what_is_behind() {
        let opts = camera([0.0, 0.0, 10.0], [0.0; 3], Some(45.0));
        let pr = Projector::new(&opts);
        let near = pr.project([1.0, 0.0, 5.0]).unwrap().0;
        let far = pr.project([1.0, 0.0, -5.0]).unwrap().0;
        assert!(near[0] > far[0] && far[0] > 0.0);
        assert!(pr.project([0.0, 0.0, 11.0]).is_none());
    }

    #[test]
    fn degenerate_cameras_still_project() {
        for (eye, up) in [
            ([0.0; 3], [0.0, 1.0, 0.0]),
            ([0.0, 5.0, 0.0], [0.0, 1.0, 0.0]),
        ] {
            let mut opts = camera(eye, [0.0; 3], None);
            if let Some(c) = opts.camera.as_mut() {
                c.up = up;
            }
            let (xy, z) = Projector::new(&opts).project([1.0, 2.0, 3.0]).unwrap();
            assert!(xy[0].is_finite() && xy[1].is_finite() && z.is_finite());
        }
    }
}
