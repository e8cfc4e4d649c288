//! Tropisms: the pulls that bend the turtle's frame at every step
//! ([`crate::ir::look::Tropism`]), as cpfg's movements do them (R. Měch,
//! 1994) and as the book's §2.4 states them: a heading H pulled by a
//! vector T turns about `H × T` by `e |H × T|`, e the elasticity.
//!
//! What bends keeps a state beside the turtle's own: the elasticity of
//! each tropism, and the frame at the last drawn step, from which U and L
//! follow a bent heading without twisting about it. Branches save and
//! restore it with the turtle's state. A system without tropisms has none
//! of it and draws as before.

use super::state::{cross, dot, normalised, State};
use super::Vec3;
use crate::ir::look::{Tropism, TropismKind};
use crate::ir::ElasticityChange;

/// The most tropisms a system bends by (cpfg allows ten); the front end
/// warns about more.
pub const MAX_TROPISMS: usize = 16;

/// Below this, a cross product is taken for parallel vectors: no turn.
const PARALLEL: f64 = 1e-6;

/// What bends with the turtle: the elasticities, and the frame at the last
/// drawn step.
#[derive(Clone, Copy, Debug)]
struct Bending {
    elasticity: [f64; MAX_TROPISMS],
    prev_h: Vec3,
    prev_u: Vec3,
}

/// The tropisms of a system while a word is interpreted.
#[derive(Clone)]
pub(super) struct Tropisms<'a> {
    list: &'a [Tropism],
    /// Each tropism's pull: its unit vector times its intensity.
    pulls: [Vec3; MAX_TROPISMS],
    now: Bending,
    saved: Vec<Bending>,
}

/// `v` turned about the unit `axis` by `angle` (Rodrigues).
pub(super) fn turned(v: Vec3, axis: Vec3, angle: f64) -> Vec3 {
    let (s, c) = angle.sin_cos();
    let k_v = cross(axis, v);
    let along = dot(axis, v) * (1.0 - c);
    std::array::from_fn(|i| v[i] * c + k_v[i] * s + axis[i] * along)
}

fn scaled(v: Vec3, k: f64) -> Vec3 {
    v.map(|x| x * k)
}

fn plus(a: Vec3, b: Vec3) -> Vec3 {
    std::array::from_fn(|i| a[i] + b[i])
}

fn length(v: Vec3) -> f64 {
    dot(v, v).sqrt()
}

impl<'a> Tropisms<'a> {
    /// The tropisms of `list` (the first [`MAX_TROPISMS`]) for a turtle in
    /// state `st`; `None` when there are none.
    pub(super) fn new(list: &'a [Tropism], st: &State) -> Option<Self> {
        if list.is_empty() {
            return None;
        }
        let list = &list[..list.len().min(MAX_TROPISMS)];
        let mut pulls = [[0.0; 3]; MAX_TROPISMS];
        let mut elasticity = [0.0; MAX_TROPISMS];
        for (k, t) in list.iter().enumerate() {
            let n = length(t.vector);
            if n > 0.0 && n.is_finite() && t.intensity.is_finite() {
                pulls[k] = scaled(t.vector, t.intensity / n);
            }
            elasticity[k] = if t.elasticity.is_finite() {
                t.elasticity
            } else {
                0.0
            };
        }
        Some(Tropisms {
            list,
            pulls,
            now: Bending {
                elasticity,
                prev_h: st.h,
                prev_u: st.u,
            },
            saved: Vec::new(),
        })
    }

    pub(super) fn push(&mut self) {
        self.saved.push(self.now);
    }

    pub(super) fn pop(&mut self) {
        if let Some(b) = self.saved.pop() {
            self.now = b;
        }
    }

    /// Before a step: the bending tropisms turn H, then the torques twist
    /// U about it.
    pub(super) fn before_step(&mut self, st: &mut State) {
        self.bend(st);
        self.twist(st);
    }

    /// The summed pull of the [`TropismKind::Bend`] tropisms on heading
    /// `h` (`l` stands in for `H × T` when H lies along T): each is its
    /// elasticity times its pull, tilted from the pull by its angle
    /// towards H.
    fn pull(&self, h: Vec3, l: Vec3) -> Vec3 {
        let mut d = [0.0; 3];
        for (k, t) in self.list.iter().enumerate() {
            if t.kind != TropismKind::Bend {
                continue;
            }
            let (e, p) = (self.now.elasticity[k], self.pulls[k]);
            let (sin, cos) = t.angle.to_radians().sin_cos();
            d = plus(d, scaled(p, e * cos));
            if sin.abs() > 1e-12 {
                let across = cross(h, p);
                let n = length(across);
                let (across, n) = if n < PARALLEL * 0.1 {
                    (l, 1.0)
                } else {
                    (across, n)
                };
                // T × (H × T) / |H × T|: across T, towards H.
                d = plus(d, scaled(cross(p, across), e * sin / n));
            }
        }
        d
    }

    /// cpfg's orthotropism and plagiotropism together: H turns towards
    /// the summed pull D about `H × D` by `|H × D|` radians (at most one);
    /// U and L follow without twisting.
    fn bend(&mut self, st: &mut State) {
        let d = self.pull(st.h, st.l);
        let axis = cross(st.h, d);
        let n = length(axis);
        if !(PARALLEL..f64::INFINITY).contains(&n) {
            return;
        }
        st.h = normalised(turned(st.h, scaled(axis, 1.0 / n), n.min(1.0)));
        self.untwist(st);
    }

    /// cpfg's torque: cpfg's up turns about `up × D'` by `|up × D'|`
    /// radians (at most one) away from D', D' being the torques' summed
    /// pull across H scaled by its size; H stays. cpfg's up is the
    /// turtle's −U, so U turns towards D'.
    fn twist(&mut self, st: &mut State) {
        let mut w = [0.0; 3];
        for (k, t) in self.list.iter().enumerate() {
            if t.kind == TropismKind::Torque {
                w = plus(w, scaled(self.pulls[k], self.now.elasticity[k]));
            }
        }
        let size = length(w);
        if !(size > 0.0 && size.is_finite()) {
            return;
        }
        let across = cross(st.h, scaled(w, 1.0 / size));
        if dot(across, across) <= 1e-8 {
            return;
        }
        let target = scaled(cross(across, st.h), size);
        let axis = cross(st.u, target);
        let n = length(axis);
        if n < PARALLEL * 0.1 {
            return;
        }
        st.u = normalised(turned(st.u, scaled(axis, 1.0 / n), n.min(1.0)));
        st.l = normalised(cross(st.u, st.h));
        st.u = cross(st.h, st.l);
        self.keep_twist(st);
    }

    /// After a step: the older tropisms turn H in the HU plane, then in
    /// the HL plane.
    pub(super) fn after_step(&mut self, st: &mut State) {
        for (k, t) in self.list.iter().enumerate() {
            let e = self.now.elasticity[k];
            if t.kind != TropismKind::BendAfterStep || e == 0.0 {
                continue;
            }
            let p = self.pulls[k];
            let s = (e * dot(p, st.u)).clamp(-1.0, 1.0);
            let c = (1.0 - s * s).sqrt();
            (st.h, st.u) = (
                plus(scaled(st.h, c), scaled(st.u, s)),
                plus(scaled(st.u, c), scaled(st.h, -s)),
            );
            let s = (e * dot(p, st.l)).clamp(-1.0, 1.0);
            let c = (1.0 - s * s).sqrt();
            (st.h, st.l) = (
                plus(scaled(st.h, c), scaled(st.l, s)),
                plus(scaled(st.l, c), scaled(st.h, -s)),
            );
        }
    }

    /// A drawn step: the frame untwisting starts from from now on.
    pub(super) fn drawn_step(&mut self, st: &State) {
        self.keep_twist(st);
    }

    /// cpfg `@Tf`.
    pub(super) fn keep_twist(&mut self, st: &State) {
        self.now.prev_h = st.h;
        self.now.prev_u = st.u;
    }

    /// cpfg's no-twist adjustment (`@Tp`, and after every bend): U is the
    /// U of the last drawn step turned by the rotation that takes that
    /// step's heading to the current one; L follows.
    pub(super) fn untwist(&mut self, st: &mut State) {
        let (ph, pu) = (self.now.prev_h, self.now.prev_u);
        let axis = cross(ph, st.h);
        let n = length(axis);
        if n > PARALLEL {
            let mut angle = n.min(1.0).asin();
            if dot(ph, st.h) < 0.0 {
                angle = std::f64::consts::PI - angle;
            }
            st.u = turned(pu, scaled(axis, 1.0 / n), angle);
        }
        let l = cross(st.u, st.h);
        if dot(l, l) > 1e-18 {
            st.l = normalised(l);
            st.u = cross(st.h, st.l);
        }
    }

    /// `@Ts`, `@Ti`, `@Td`, `_`: the elasticity of tropism `k` changed by
    /// `value` as `change` says (by the tropism's step without one).
    pub(super) fn change(&mut self, k: usize, change: ElasticityChange, value: Option<f64>) {
        let Some(t) = self.list.get(k) else {
            return;
        };
        let e = &mut self.now.elasticity[k];
        *e = match (change, value) {
            (ElasticityChange::Set | ElasticityChange::SetOrIncrease, Some(v)) => v,
            (ElasticityChange::Set, None) => 0.0,
            (ElasticityChange::Increase, Some(v)) => *e + v,
            (ElasticityChange::Decrease, Some(v)) => *e - v,
            (ElasticityChange::Increase | ElasticityChange::SetOrIncrease, None) => *e + t.step,
            (ElasticityChange::Decrease, None) => *e - t.step,
        };
        if !e.is_finite() {
            *e = 0.0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::turtle::{Geometry, Run};

    fn tropism(vector: Vec3, elasticity: f64, kind: TropismKind) -> Tropism {
        Tropism {
            vector,
            angle: 0.0,
            intensity: 1.0,
            elasticity,
            step: 0.0,
            kind,
        }
    }

    /// `word` of a cpfg L-system drawn with `tropisms`.
    fn draw(word: &str, tropisms: Vec<Tropism>) -> Geometry {
        let src = format!("lsystem: 1\nderivation length: 0\naxiom: {word}\nendlsystem\n");
        let mut sys = crate::front::cpfg::read_ok(&src);
        sys.settings.delta = 90f64.to_radians();
        sys.settings.tropisms = tropisms;
        let word = crate::driver::derive(&sys, &crate::driver::RunOptions::default()).unwrap();
        Run::word(&sys, &word, 0).geometry()
    }

    fn direction(g: &Geometry, k: usize) -> Vec3 {
        let s = &g.segments[k];
        normalised(std::array::from_fn(|i| s.b[i] - s.a[i]))
    }

    fn close(a: Vec3, b: Vec3) -> bool {
        (0..3).all(|i| (a[i] - b[i]).abs() < 1e-9)
    }

    #[test]
    fn orthotropism_turns_by_elasticity_times_h_cross_t_before_the_step() {
        // Heading +x (cpfg `-` turns right), pulled down: α = e |H × T| = 0.1.
        let g = draw(
            "-FF",
            vec![tropism([0.0, -2.0, 0.0], 0.1, TropismKind::Bend)],
        );
        let (s, c) = 0.1f64.sin_cos();
        assert!(
            close(direction(&g, 0), [c, -s, 0.0]),
            "{:?}",
            direction(&g, 0)
        );
        // The second step is bent again, by e |H × T| = 0.1 cos 0.1.
        let a = 0.1 + 0.1 * c;
        assert!(close(direction(&g, 1), [a.cos(), -a.sin(), 0.0]));
    }

    #[test]
    fn a_bend_is_at_most_one_radian_and_none_along_the_vector() {
        let g = draw(
            "-F",
            vec![tropism([0.0, -1.0, 0.0], 5.0, TropismKind::Bend)],
        );
        assert!(close(direction(&g, 0), [1f64.cos(), -1f64.sin(), 0.0]));
        let g = draw("F", vec![tropism([0.0, 1.0, 0.0], 5.0, TropismKind::Bend)]);
        assert!(close(direction(&g, 0), [0.0, 1.0, 0.0]));
    }

    #[test]
    fn plagiotropism_brings_the_heading_across_the_vector() {
        let mut t = tropism([0.0, 1.0, 0.0], 0.3, TropismKind::Bend);
        t.angle = 90.0;
        let g = draw(&format!("-(45){}", "F".repeat(40)), vec![t]);
        let first = direction(&g, 0);
        let last = direction(&g, 39);
        assert!(first[1] > 0.5 && last[1].abs() < 1e-3, "{first:?} {last:?}");
        assert!(last[0] > 0.99);
    }

    #[test]
    fn elasticity_modules_change_it_and_branches_restore_it() {
        let t = || tropism([0.0, -1.0, 0.0], 0.0, TropismKind::Bend);
        // E 0 draws straight; @Ts sets it inside the branch only.
        let g = draw("-F[@Ts(1,0.2)F]F", vec![t()]);
        assert!(close(direction(&g, 0), [1.0, 0.0, 0.0]));
        assert!(direction(&g, 1)[1] < -0.19);
        assert!(close(direction(&g, 2), [1.0, 0.0, 0.0]));
        // @Ti and @Td step it; without an id nothing changes.
        let g = draw("-@Ti(1,0.3)@Td(1,0.1)F@Ts@Ti(0.5)F", vec![t()]);
        let y = direction(&g, 0)[1];
        assert!((y + 0.2f64.sin()).abs() < 1e-9, "{y}");
        assert!(direction(&g, 1)[1] < y);
    }

    #[test]
    fn the_older_tropism_bends_after_the_step() {
        let mut t = tropism([0.0, -1.0, 0.0], 0.5, TropismKind::BendAfterStep);
        t.step = -0.5;
        // Heading +x, U = +z, L = +y after `-`: sin α = e (T·L) = -0.5, a
        // turn of 30° towards −y, after the first step.
        let g = draw("-FF", vec![t]);
        assert!(close(direction(&g, 0), [1.0, 0.0, 0.0]));
        let d = direction(&g, 1);
        assert!(close(d, [30f64.to_radians().cos(), -0.5, 0.0]), "{d:?}");
    }

    #[test]
    fn a_torque_twists_up_about_the_heading_only() {
        let g = draw(
            "&(90)FF-F",
            vec![tropism([1.0, 0.0, 0.0], 0.4, TropismKind::Torque)],
        );
        // H stays (−z after the pitch); the turn after the twist is not in
        // the untwisted plane.
        assert!(close(direction(&g, 1), direction(&g, 0)));
        let untwisted = draw("&(90)FF-F", vec![]);
        assert!(!close(direction(&g, 2), direction(&untwisted, 2)));
    }

    #[test]
    fn a_torque_turns_cpfgs_up_away_from_the_vector() {
        // cpfg: after `&(90)` H = −z and its up is −y; the torque towards
        // +x turns that up by 0.4 rad away from +x (movements.c rolls by
        // the inverse quaternion), to (−sin 0.4, −cos 0.4, 0); L = H × up
        // = (−cos 0.4, sin 0.4, 0), and `-` turns H onto −L.
        let g = draw(
            "&(90)F-F",
            vec![tropism([1.0, 0.0, 0.0], 0.4, TropismKind::Torque)],
        );
        assert!(close(direction(&g, 0), [0.0, 0.0, -1.0]));
        let (s, c) = 0.4f64.sin_cos();
        let d = direction(&g, 1);
        assert!(close(d, [c, -s, 0.0]), "{d:?}");
    }

    #[test]
    fn without_tropisms_nothing_changes() {
        let word = "-F/(30)+(20)F[&(10)F]F";
        let plain = draw(word, vec![]);
        let zero = draw(
            word,
            vec![tropism([0.0, -1.0, 0.0], 0.0, TropismKind::Bend)],
        );
        assert_eq!(plain.segments.len(), zero.segments.len());
        for k in 0..plain.segments.len() {
            assert!(close(direction(&plain, k), direction(&zero, k)));
        }
    }
}
