//! vlab's `chiba`: light through spherical leaf clusters (after Chiba et
//! al.). Each query is a cluster: a sphere at the turtle's position whose
//! radius is its first parameter (the spec's radius when that is not
//! positive). A cluster's light is summed over the sources (or, with none,
//! over samples of a sky): each ray leaves the cluster's centre towards
//! the light through a voxel grid fitted around the pass's clusters, and
//! every other cluster it meets takes its share, by the area of their
//! discs' overlap or by the chord the ray cuts through it. The answer is
//! the light (p1) and, to a `?E` of four parameters or more, the
//! direction the light mostly comes from (p2..p4).
//!
//! Computed in `f32` where the program computes in `float`, and in `f64`
//! where C promotes to `double` (constants like `0.5`, `M_PI`, `acos`,
//! `pow`), so that the answers round as the program's do. Only the
//! current pass's clusters count: nothing is kept between steps.

use super::{point, Answer, Pass, Query};
use crate::ir::environment::{Light, LightSource};
use std::f64::consts::PI;

/// The most voxels a grid may have: a larger spec is halved along its
/// longest axis until it fits (the program would allocate any size).
const MAX_CELLS: u64 = 1 << 24;
/// The finest sky: 8·4⁷ = 131072 samples (the program would make any).
const MAX_LEVEL: i32 = 8;
/// The most (cluster, voxel) pairs a pass may test while filling its grid;
/// past it the pass answers nothing rather than grow without bound.
const MAX_VISITS: u64 = 1 << 25;

pub struct Chiba {
    size: [usize; 3],
    transmittance: f32,
    /// The beam's radius, in radii of the lit cluster (1 when estimating
    /// areas, as the program forces it).
    beam: f32,
    /// A cluster's radius when its query gives none.
    radius: f32,
    estimate_area: bool,
    /// The sources, or else the sky's samples, normalized.
    lights: Vec<Sample>,
}

/// A direction light comes from (unit length) and its share of the light.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Sample {
    dir: [f32; 3],
    intensity: f32,
}

impl Chiba {
    pub fn new(l: &Light) -> Chiba {
        Chiba {
            size: grid_size(l.grid),
            transmittance: l.transmittance as f32,
            beam: if l.estimate_area {
                1.0
            } else {
                l.beam_radius as f32
            },
            radius: l.radius as f32,
            estimate_area: l.estimate_area,
            lights: if l.sources.is_empty() {
                sky(l.samples, l.lower_to_upper as f32, l.cie)
            } else {
                sources(&l.sources)
            },
        }
    }
}

/// The spec's grid, each axis at least 1 and at most [`MAX_CELLS`] in
/// all (halving the longest axis until it fits).
fn grid_size(spec: [u32; 3]) -> [usize; 3] {
    let mut n = spec.map(|k| u64::from(k.max(1)));
    while n[0].saturating_mul(n[1]).saturating_mul(n[2]) > MAX_CELLS {
        let longest = (0..3).max_by_key(|&c| (n[c], 3 - c)).unwrap_or(0);
        n[longest] = n[longest].div_ceil(2);
    }
    n.map(|k| k as usize)
}

/// The given sources, directions normalized and intensities scaled to a
/// sum of 1. Where the program would divide by a zero sum, or walk a ray
/// of no direction, the source gives no light.
fn sources(given: &[LightSource]) -> Vec<Sample> {
    let total = (given.iter()).fold(0f32, |t, s| t + s.intensity as f32);
    let usable = total != 0.0 && total.is_finite();
    (given.iter())
        .map(|s| {
            let dir = normalize(s.direction.map(|c| c as f32));
            let lights = usable && dir.iter().all(|c| c.is_finite()) && dir != [0.0; 3];
            Sample {
                dir,
                intensity: if lights {
                    s.intensity as f32 / total
                } else {
                    0.0
                },
            }
        })
        .collect()
}

/// The subdivision level of the sky for `samples` asked: the program's
/// `ceil(log(n/8)/log 4) + 1` (so 20 asks level 2, 128 level 3), at least
/// 1 (fewer than 3 samples would overrun the program's arrays) and at
/// most [`MAX_LEVEL`].
fn level(samples: u32) -> i32 {
    let l = ((f64::from(samples) / 8.0).ln() / 4f64.ln()).ceil() + 1.0;
    l.clamp(1.0, f64::from(MAX_LEVEL)) as i32
}

/// The sky: one sample through the middle of each triangle of the
/// subdivided octahedron. Without the CIE formula, the upper samples
/// (y >= 0) share 1/(1+LtoU) and the lower ones LtoU/(1+LtoU).
fn sky(samples: u32, lower_to_upper: f32, cie: bool) -> Vec<Sample> {
    let dirs: Vec<[f32; 3]> = sphere(level(samples)).iter().map(centre).collect();
    if cie {
        return overcast(&dirs);
    }
    let up = dirs.iter().filter(|d| d[1] >= 0.0).count() as f32;
    let down = dirs.len() as f32 - up;
    let share = 1.0 + f64::from(lower_to_upper);
    let up_each = (1.0 / f64::from(up) / share) as f32;
    // `LtoU/(float)n` is a float division in the program; the rest double.
    let down_each = (f64::from(lower_to_upper / down) / share) as f32;
    (dirs.iter())
        .map(|&dir| Sample {
            dir,
            intensity: if dir[1] >= 0.0 { up_each } else { down_each },
        })
        .collect()
}

/// The CIE overcast sky over `dirs`, normalized to sum 1; nothing from
/// below the horizon (y <= 0). The program takes the cosine of the angle
/// from the zenith as y/√(x²+y²), leaving z out; so does this.
fn overcast(dirs: &[[f32; 3]]) -> Vec<Sample> {
    let luminance = |[x, y, _]: [f32; 3]| {
        let c = f64::from(y) / f64::from(x * x + y * y).sqrt();
        ((1.0 + c) / 3.0 * (8.6 * c + 0.123) / 0.203) as f32
    };
    let mut sky: Vec<Sample> = (dirs.iter())
        .map(|&dir| Sample {
            dir,
            intensity: if dir[1] <= 0.0 { 0.0 } else { luminance(dir) },
        })
        .collect();
    let total = sky.iter().fold(0f32, |t, s| t + s.intensity);
    for s in &mut sky {
        s.intensity /= total;
    }
    sky
}

type Triangle = [[f64; 3]; 3];

/// Jon Leech's sphere (vlab's `sphere.c`): the octahedron, each triangle's
/// first and last vertices swapped, subdivided `level - 1` times, each
/// triangle [0,1,2] into [0,b,a], [b,1,c], [a,b,c], [a,c,2] with a, b, c
/// the normalized middles of 0–2, 0–1 and 1–2. The order is the program's
/// and fixes the order its samples' light is summed in.
fn sphere(level: i32) -> Vec<Triangle> {
    const X: [f64; 3] = [1.0, 0.0, 0.0];
    const Y: [f64; 3] = [0.0, 1.0, 0.0];
    const Z: [f64; 3] = [0.0, 0.0, 1.0];
    let neg = |v: [f64; 3]| v.map(|c| -c);
    let octahedron = [
        [X, Z, Y],
        [Y, Z, neg(X)],
        [neg(X), Z, neg(Y)],
        [neg(Y), Z, X],
        [X, Y, neg(Z)],
        [Y, neg(X), neg(Z)],
        [neg(X), neg(Y), neg(Z)],
        [neg(Y), X, neg(Z)],
    ];
    let mut tris: Vec<Triangle> = octahedron.iter().map(|&[p, q, r]| [r, q, p]).collect();
    for _ in 1..level {
        tris = tris.iter().flat_map(split).collect();
    }
    tris
}

fn split(&[p0, p1, p2]: &Triangle) -> [Triangle; 4] {
    let mid = |u: [f64; 3], v: [f64; 3]| {
        let m = [0, 1, 2].map(|c| (u[c] + v[c]) * 0.5);
        let mag = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];
        // The program scales by the inverse root rather than dividing.
        let inv = if mag != 0.0 { 1.0 / mag.sqrt() } else { 1.0 };
        m.map(|c| c * inv)
    };
    let (a, b, c) = (mid(p0, p2), mid(p0, p1), mid(p1, p2));
    [[p0, b, a], [b, p1, c], [a, b, c], [a, c, p2]]
}

/// A triangle's sample direction: its vertices as `float`, their mean,
/// normalized.
fn centre(t: &Triangle) -> [f32; 3] {
    let v = t.map(|p| p.map(|c| c as f32));
    normalize([0, 1, 2].map(|c| (f64::from(v[0][c] + v[1][c] + v[2][c]) / 3.0) as f32))
}

/// `v` scaled to unit length; a zero vector stays zero.
fn normalize(v: [f32; 3]) -> [f32; 3] {
    let len = dot(v, v).sqrt();
    if len > 0.0 {
        v.map(|c| c / len)
    } else {
        v
    }
}

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn sub(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// A leaf cluster: a sphere and the area of its disc.
#[derive(Clone, Copy, Debug)]
struct Cluster {
    at: [f32; 3],
    radius: f32,
    area: f32,
}

impl Chiba {
    /// The cluster `q` stands for. The program takes a `?E` of one
    /// parameter or of four and more; its radius is p1 when positive.
    /// Clusters the program could not place (a coordinate or radius not a
    /// finite number, a negative radius) are not answered.
    fn cluster(&self, q: &Query) -> Option<Cluster> {
        if q.params.len() != 1 && q.params.len() < 4 {
            return None;
        }
        let at = point(q)?;
        let radius = if q.params[0] > 0.0 {
            q.params[0]
        } else {
            self.radius
        };
        let placed = at.iter().all(|c| c.is_finite()) && radius.is_finite() && radius >= 0.0;
        placed.then(|| Cluster {
            at,
            radius,
            area: (PI * f64::from(radius) * f64::from(radius)) as f32,
        })
    }
}

/// Where the grid lies and how clusters are spread over its voxels.
#[derive(Clone, Copy, Debug)]
struct Frame {
    size: [usize; 3],
    /// The lower corner and the extent of the union of the clusters' boxes.
    pos: [f32; 3],
    range: [f32; 3],
    /// How much further than its radius a cluster may shade: the largest
    /// radius times the beam's.
    reach: f32,
    /// Half a voxel's diagonal.
    half: f32,
}

impl Frame {
    /// The frame of `clusters`, as the program fits it query by query;
    /// `None` when there are none, or the box is flat or not finite (where
    /// the program would divide by zero).
    fn fit(clusters: &[Cluster], size: [usize; 3], beam: f32) -> Option<Frame> {
        let (first, rest) = clusters.split_first()?;
        let mut pos = first.at.map(|c| c - first.radius);
        let mut range = [2.0 * first.radius; 3];
        let mut max_radius = first.radius;
        for k in rest {
            for c in 0..3 {
                let below = pos[c] - (k.at[c] - k.radius);
                if below > 0.0 {
                    pos[c] -= below;
                    range[c] += below;
                }
                let above = (k.at[c] + k.radius) - (pos[c] + range[c]);
                if above > 0.0 {
                    range[c] += above;
                }
            }
            max_radius = max_radius.max(k.radius);
        }
        let sound = (0..3).all(|c| pos[c].is_finite() && range[c].is_finite() && range[c] > 0.0);
        let voxel2 = (0..3).fold(0f32, |h, c| {
            let v = range[c] / size[c] as f32;
            h + v * v
        });
        sound.then(|| Frame {
            size,
            pos,
            range,
            reach: max_radius * beam,
            half: (0.5 * f64::from(voxel2).sqrt()) as f32,
        })
    }

    /// The voxel, per axis, that `x` falls in (not clamped).
    fn node(&self, c: usize, x: f32) -> i64 {
        ((x - self.pos[c]) / self.range[c] * self.size[c] as f32).floor() as i64
    }

    /// Per axis, the voxels that may hold `k`: one more each side than its
    /// inflated box covers, clamped to the grid (possibly empty).
    fn span(&self, k: &Cluster) -> [(usize, usize); 3] {
        [0, 1, 2].map(|c| {
            let n = self.size[c] as f32;
            let scale = |x: f32| (x - self.pos[c]) / self.range[c] * n;
            let lo = (scale(k.at[c] - k.radius - self.reach)).floor() - 1.0;
            let hi = 1.0 + (scale(k.at[c] + k.radius + self.reach)).floor();
            let lo = if lo < 0.0 { 0.0 } else { lo };
            let hi = if hi >= n { n - 1.0 } else { hi };
            // `as` saturates; a NaN bound (a NaN beam) gives voxel 0, whose
            // distance test then admits nothing.
            (lo as usize, hi as usize)
        })
    }

    /// How many voxels [`Frame::span`] gives `k`.
    fn visits(&self, k: &Cluster) -> u64 {
        (self.span(k).iter()).fold(1u64, |v, &(lo, hi)| {
            v.saturating_mul((hi + 1).saturating_sub(lo) as u64)
        })
    }

    /// Calls `f` with each voxel (flat index) whose centre lies within the
    /// cluster's inflated radius plus half a voxel's diagonal.
    fn each_voxel(&self, k: &Cluster, mut f: impl FnMut(usize)) {
        let [sx, sy, sz] = self.span(k);
        let r = k.radius + self.reach + self.half;
        for z in sz.0..=sz.1 {
            for y in sy.0..=sy.1 {
                for x in sx.0..=sx.1 {
                    let pt = [self.centre(0, x), self.centre(1, y), self.centre(2, z)];
                    let v = sub(k.at, pt);
                    if dot(v, v) <= r * r {
                        f(self.flat([x, y, z]));
                    }
                }
            }
        }
    }

    /// The centre of voxel `i` along axis `c` (summed in `double`, as the
    /// program's `0.5` makes it).
    fn centre(&self, c: usize, i: usize) -> f32 {
        let n = f64::from(self.size[c] as f32);
        (f64::from(self.pos[c]) + (f64::from(i as f32) + 0.5) / n * f64::from(self.range[c])) as f32
    }

    fn flat(&self, [x, y, z]: [usize; 3]) -> usize {
        (z * self.size[1] + y) * self.size[0] + x
    }

    fn cells(&self) -> usize {
        self.size.iter().product()
    }
}

/// The clusters each voxel may hold, in descending order (the program
/// prepends to its lists, and the order rounds the products of shares).
struct Grid {
    frame: Frame,
    /// Voxel `v`'s clusters are `members[starts[v]..starts[v + 1]]`.
    starts: Vec<u32>,
    members: Vec<u32>,
}

impl Grid {
    /// `None` when filling it would test more than [`MAX_VISITS`] pairs.
    fn new(frame: Frame, clusters: &[Cluster]) -> Option<Grid> {
        let visits = (clusters.iter()).fold(0u64, |v, k| v.saturating_add(frame.visits(k)));
        if visits > MAX_VISITS {
            return None;
        }
        let cells = frame.cells();
        // Count, make the counts running ends, then fill each voxel from
        // its end down, so that the later clusters come first.
        let mut starts = vec![0u32; cells + 1];
        for k in clusters {
            frame.each_voxel(k, |v| starts[v] += 1);
        }
        let mut total = 0;
        for s in &mut starts[..cells] {
            total += *s;
            *s = total;
        }
        starts[cells] = total;
        let mut members = vec![0u32; total as usize];
        for (i, k) in clusters.iter().enumerate() {
            frame.each_voxel(k, |v| {
                starts[v] -= 1;
                members[starts[v] as usize] = i as u32;
            });
        }
        Some(Grid {
            frame,
            starts,
            members,
        })
    }

    /// The clusters of voxel `cell`; none outside the grid.
    fn list(&self, cell: i64) -> &[u32] {
        match usize::try_from(cell) {
            Ok(v) if v < self.frame.cells() => {
                &self.members[self.starts[v] as usize..self.starts[v + 1] as usize]
            }
            _ => &[],
        }
    }
}

/// A ray's walk from voxel to voxel, as the program takes it. **Its quirk
/// is kept:** the voxel's middle is reckoned without the grid's corner
/// while the ray's origin is absolute, so the face the ray is taken to
/// cross next is off by the corner; the walk goes as the program's does.
struct Walk {
    origin: [f32; 3],
    dir: [f32; 3],
    size: [i64; 3],
    node: [i64; 3],
    middle: [f32; 3],
    /// Half a voxel, signed with the direction.
    half: [f32; 3],
    /// The program's cell pointer and how far it moves per axis.
    cell: i64,
    stride: [i64; 3],
}

impl Walk {
    fn start(f: &Frame, origin: [f32; 3], dir: [f32; 3]) -> Walk {
        let size = f.size.map(|n| n as i64);
        let mut stride = [1, size[0], size[0] * size[1]];
        let mut half = [0.0; 3];
        let mut node = [0; 3];
        let mut middle = [0.0; 3];
        for c in 0..3 {
            let n = f64::from(f.size[c] as f32);
            half[c] = (0.5 * f64::from(f.range[c]) / n) as f32;
            if dir[c] < 0.0 {
                half[c] = -half[c];
                stride[c] = -stride[c];
            }
            node[c] = f.node(c, origin[c]);
            middle[c] = ((node[c] as f32 as f64 + 0.5) / n * f64::from(f.range[c])) as f32;
        }
        // The first voxel is clamped into the grid; the node is not.
        let at = [0, 1, 2].map(|c| node[c].clamp(0, size[c] - 1));
        Walk {
            origin,
            dir,
            size,
            node,
            middle,
            half,
            cell: (at[2] * size[1] + at[1]) * size[0] + at[0],
            stride,
        }
    }

    /// Crosses into the next voxel; `false` once the ray leaves the grid.
    /// Ties keep the lower axis. Every axis moves one way only, so a walk
    /// takes at most the grid's three sizes (plus a few) steps.
    fn advance(&mut self) -> bool {
        let face = |c: usize| self.middle[c] + self.half[c] - self.origin[c];
        let (mut ind, mut nearest) = (0, face(0).abs());
        for c in 1..3 {
            let aux = face(c);
            if (aux * self.dir[ind]).abs() < (nearest * self.dir[c]).abs() {
                (ind, nearest) = (c, aux);
            }
        }
        self.middle[ind] += 2.0 * self.half[ind];
        self.cell += self.stride[ind];
        // An axis of no direction steps down, as the program's does (its
        // cell pointer then steps up). Saturating: a node at the end of
        // `i64` just stays outside.
        let step = if self.dir[ind] > 0.0 { 1 } else { -1 };
        self.node[ind] = self.node[ind].saturating_add(step);
        (0..self.size[ind]).contains(&self.node[ind])
    }
}

/// One pass's clusters in their grid, and the marks of the clusters a ray
/// has already been shaded by.
struct Scene {
    clusters: Vec<Cluster>,
    grid: Grid,
    marks: Vec<u64>,
    ray: u64,
}

impl Chiba {
    /// The light cluster `l` receives from `s`.
    fn light(&self, scene: &mut Scene, l: usize, s: &Sample) -> f32 {
        if s.intensity == 0.0 {
            return 0.0;
        }
        let leaf = scene.clusters[l];
        let mut walk = Walk::start(&scene.grid.frame, leaf.at, s.dir);
        scene.ray += 1;
        scene.marks[l] = scene.ray;
        let mut reduction = 1f32;
        loop {
            for &k in scene.grid.list(walk.cell) {
                let k = k as usize;
                if scene.marks[k] == scene.ray {
                    continue;
                }
                // A cluster that takes nothing stays unmarked, retested
                // (with the same result) in the next voxel that holds it.
                if let Some(r) = self.shade(reduction, &leaf, s.dir, &scene.clusters[k]) {
                    scene.marks[k] = scene.ray;
                    reduction = r;
                }
            }
            if !walk.advance() {
                return s.intensity * reduction;
            }
        }
    }

    /// `reduction` after cluster `k` shades `leaf` along `dir`; `None`
    /// when it does not.
    fn shade(&self, reduction: f32, leaf: &Cluster, dir: [f32; 3], k: &Cluster) -> Option<f32> {
        let t = self.transmittance;
        if self.estimate_area {
            let covered = covered_area(leaf.at, dir, k, leaf.radius);
            (covered > 0.0).then(|| reduction * (1.0 - (1.0 - t) * covered / leaf.area))
        } else {
            let reach = k.radius + self.beam * leaf.radius;
            let chord = chord(leaf.at, dir, k, reach);
            // `2.0` and `pow` are double in the program.
            let power = || f64::from(t).powf(f64::from(chord) / (2.0 * f64::from(reach)));
            (chord > 0.0).then(|| (f64::from(reduction) * power()) as f32)
        }
    }
}

/// The area of the overlap of `k`'s disc and the lit cluster's (radius
/// `radius`, at `p`), both square to the ray `dir`; 0 when `k` lies
/// behind `p` (away from the light) or the discs are apart. NaN where
/// rounding makes the squared distance negative, as in the program (and
/// so, as there, no shade).
fn covered_area(p: [f32; 3], dir: [f32; 3], k: &Cluster, radius: f32) -> f32 {
    let w = sub(p, k.at);
    let along = dot(dir, w);
    if along > 0.0 {
        return 0.0;
    }
    let d2 = dot(w, w) - along * along;
    let apart = k.radius + radius;
    if d2 < apart * apart {
        let (r1, r2) = if k.radius < radius {
            (radius, k.radius)
        } else {
            (k.radius, radius)
        };
        lens(r1, r2, d2.sqrt())
    } else {
        0.0
    }
}

/// The overlap of discs of radii `r1 >= r2` whose centres are `d` apart
/// (less than `r1 + r2`).
fn lens(r1: f32, r2: f32, d: f32) -> f32 {
    let (r1s, r2s) = (r1 * r1, r2 * r2);
    if d + r2 <= r1 {
        return (PI * f64::from(r2s)) as f32;
    }
    let x1 = (r1s + d * d - r2s) / (2.0 * d);
    let x2 = (r2s + d * d - r1s) / (2.0 * d);
    let y = (r2s - x2 * x2).sqrt();
    let caps =
        f64::from(r1s) * f64::from(x1 / r1).acos() + f64::from(r2s) * f64::from(x2 / r2).acos();
    (caps - f64::from(y * d)) as f32
}

/// The length of the ray from `p` along `dir` inside `k`'s sphere grown to
/// radius `reach`, ahead of `p` only: the whole chord when the sphere is
/// ahead, from `p` on when `p` is inside, 0 when it is behind or missed.
fn chord(p: [f32; 3], dir: [f32; 3], k: &Cluster, reach: f32) -> f32 {
    let w = sub(p, k.at);
    let along = dot(dir, w);
    let disc = along * along - dot(w, w) + reach * reach;
    if disc < 0.0 || disc.is_nan() {
        return 0.0;
    }
    let d = disc.sqrt();
    match (-along + d > 0.0, -along - d >= 0.0) {
        (true, true) => 2.0 * d,
        (true, false) => -along + d,
        _ => 0.0,
    }
}

impl Chiba {
    /// The answer to cluster `l`: its light, and to a `?E` of four
    /// parameters or more, the direction most of it comes from.
    fn respond(&self, scene: &mut Scene, l: usize, brightest: bool) -> Answer {
        let mut sum = 0f32;
        let mut towards = [0f32; 3];
        for s in &self.lights {
            let a = self.light(scene, l, s);
            sum += a;
            for (t, d) in towards.iter_mut().zip(s.dir) {
                *t += a * d;
            }
        }
        let mut answer = vec![Some(sum)];
        if brightest {
            answer.extend(normalize(towards).map(Some));
        }
        answer
    }

    /// The pass's clusters in their grid, and which query each is; `None`
    /// when the pass cannot be framed or would cost too much.
    fn scene(&self, queries: &[Query]) -> Option<(Scene, Vec<Option<usize>>)> {
        let mut clusters = Vec::new();
        let slots = (queries.iter())
            .map(|q| {
                let k = self.cluster(q)?;
                clusters.push(k);
                Some(clusters.len() - 1)
            })
            .collect();
        let frame = Frame::fit(&clusters, self.size, self.beam)?;
        let grid = Grid::new(frame, &clusters)?;
        let marks = vec![0; clusters.len()];
        let scene = Scene {
            clusters,
            grid,
            marks,
            ray: 0,
        };
        Some((scene, slots))
    }
}

impl Pass for Chiba {
    fn answer(&mut self, queries: &[Query]) -> Vec<Answer> {
        let Some((mut scene, slots)) = self.scene(queries) else {
            return vec![Vec::new(); queries.len()];
        };
        (queries.iter().zip(slots))
            .map(|(q, slot)| match slot {
                Some(l) => self.respond(&mut scene, l, q.params.len() >= 4),
                None => Vec::new(),
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 07-Open-10's spec: a 32³ grid, opaque clusters, areas estimated,
    /// the 128-sample sky with nothing from below, unless sources given.
    fn spec(sources: &[([f64; 3], f64)]) -> Light {
        Light {
            grid: [32; 3],
            transmittance: 0.0,
            lower_to_upper: 0.0,
            samples: 128,
            radius: 25.0,
            beam_radius: 0.0,
            sources: (sources.iter())
                .map(|&(direction, intensity)| LightSource {
                    direction,
                    intensity,
                })
                .collect(),
            estimate_area: true,
            cie: false,
        }
    }

    fn q(radius: f32, at: [f32; 3]) -> Query {
        Query {
            params: vec![radius],
            position: at.to_vec(),
        }
    }

    /// Each query's light (p1).
    fn lights(l: &Light, queries: &[Query]) -> Vec<f32> {
        (Chiba::new(l).answer(queries).iter())
            .map(|a| a[0].expect("p1 is set"))
            .collect()
    }

    const UP: [f64; 3] = [0.0, 1.0, 0.0];

    fn near(got: f32, want: f64, what: &str) {
        assert!(
            (f64::from(got) - want).abs() < 1e-5,
            "{what}: got {got}, want {want}"
        );
    }

    #[test]
    fn a_lone_cluster_gets_all_of_one_source() {
        let got = lights(
            &spec(&[([50.0, 100.0, 0.0], 4.0)]),
            &[q(0.9, [3.0, -2.0, 7.0])],
        );
        assert_eq!(got, vec![1.0]);
    }

    #[test]
    fn an_opaque_cluster_straight_above_takes_all_and_is_not_shaded_from_below() {
        let got = lights(
            &spec(&[(UP, 1.0)]),
            &[q(0.5, [0.0; 3]), q(0.5, [0.0, 2.0, 0.0])],
        );
        assert_eq!(got, vec![0.0, 1.0]);
    }

    #[test]
    fn the_lens_area_is_the_overlap_of_two_discs() {
        // Unit discs one apart: 2·acos(1/2) − (1/2)·√3 = 2π/3 − √3/2.
        near(lens(1.0, 1.0, 1.0), 1.228_370, "equal discs");
        // Radii 1 and 0.5, one apart: acos(7/8) + acos(1/4)/4 − √15/8.
        near(lens(1.0, 0.5, 1.0), 0.350_767, "unequal discs");
        // The smaller inside the larger: all of it, π/4.
        near(
            lens(1.0, 0.5, 0.25),
            std::f64::consts::FRAC_PI_4,
            "nested discs",
        );
    }

    #[test]
    fn partly_overlapping_discs_shade_by_the_lens() {
        // The upper cluster's centre is 1 off the ray: a unit lens.
        let got = lights(
            &spec(&[(UP, 1.0)]),
            &[q(1.0, [0.0; 3]), q(1.0, [1.0, 3.0, 0.0])],
        );
        near(got[0], 1.0 - 1.228_370 / std::f64::consts::PI, "lit");
        // Half transparent: half the lens's share is taken.
        let mut half = spec(&[(UP, 1.0)]);
        half.transmittance = 0.5;
        let got = lights(&half, &[q(1.0, [0.0; 3]), q(1.0, [1.0, 3.0, 0.0])]);
        near(got[0], 1.0 - 0.5 * 1.228_370 / std::f64::consts::PI, "half");
    }

    #[test]
    fn without_areas_the_chord_sets_the_transmittance() {
        let mut l = spec(&[(UP, 1.0)]);
        (l.estimate_area, l.transmittance) = (false, 0.5);
        // Through the middle: the whole diameter, t¹.
        let got = lights(&l, &[q(1.0, [0.0; 3]), q(1.0, [0.0, 3.0, 0.0])]);
        assert_eq!(got, vec![0.5, 1.0]);
        // 0.6 off the middle: a chord of 2·0.8, t^0.8.
        let got = lights(&l, &[q(1.0, [0.0; 3]), q(1.0, [0.6, 3.0, 0.0])]);
        near(got[0], 0.5f64.powf(0.8), "chord");
        // A beam as wide as half the lit cluster widens the shading sphere
        // to 1.5: 0.6 off, the chord is 2·√(1.5² − 0.6²) of 3.
        l.beam_radius = 0.5;
        let got = lights(&l, &[q(1.0, [0.0; 3]), q(1.0, [0.6, 3.0, 0.0])]);
        near(got[0], 0.5f64.powf((2.25f64 - 0.36).sqrt() / 1.5), "beam");
    }

    #[test]
    fn the_sky_has_the_programs_number_of_samples() {
        let count = |n: u32| sky(n, 0.7, false).len();
        assert_eq!((count(20), count(128)), (32, 128));
        // 8 and under: the octahedron itself; just over 128: the next level.
        assert_eq!((count(0), count(3), count(8), count(129)), (8, 8, 8, 512));
        assert_eq!(count(u32::MAX), 8 << 14, "capped at level 8");
    }

    #[test]
    fn the_sphere_is_subdivided_in_the_programs_order() {
        let s = sphere(2);
        let (x, y, z) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
        // The program scales by the inverse root: 0.5·(1/√0.5), one ulp
        // under √0.5.
        let r = 0.5 * (1.0 / 0.5f64.sqrt());
        assert_ne!(r, 0.5f64.sqrt());
        // The first face, swapped, is (+Y, +Z, +X); its first child is
        // [0, b, a]: +Y, then the middles of +Y+Z and +Y+X.
        assert_eq!(s[0], [y, [0.0, r, r], [r, r, 0.0]]);
        assert_eq!(s[1][1], z);
        assert_eq!(s[3][2], x);
        assert_eq!(centre(&sphere(1)[0]), [1.0 / 3f32.sqrt(); 3]);
    }

    #[test]
    fn the_sky_above_shares_one_and_the_lower_part_its_ratio() {
        let up = |s: &[Sample]| s.iter().filter(|s| s.dir[1] >= 0.0).count();
        let dark = sky(128, 0.0, false);
        assert_eq!(up(&dark), 64);
        assert!(dark
            .iter()
            .all(|s| s.intensity == if s.dir[1] >= 0.0 { 1.0 / 64.0 } else { 0.0 }));
        let dim = sky(20, 0.7, false);
        let (hi, lo) = (dim[0].intensity, dim[31].intensity);
        assert_eq!((dim[0].dir[1] >= 0.0, dim[31].dir[1] < 0.0), (true, true));
        near(hi, 1.0 / 16.0 / 1.7, "up");
        near(lo, 0.7 / 16.0 / 1.7, "down");
        let cie = sky(128, 0.0, true);
        let total: f32 = cie.iter().map(|s| s.intensity).sum();
        near(total, 1.0, "CIE sum");
        assert!(cie.iter().all(|s| s.dir[1] > 0.0 || s.intensity == 0.0));
        // Brightest at the zenith, dimmest low towards ±x; but the
        // program's cosine leaves z out, so the same elevation towards ±z
        // is seven times as bright: 0.615 of the most against 0.083.
        let lit: Vec<&Sample> = cie.iter().filter(|s| s.dir[1] > 0.0).collect();
        let most = lit.iter().map(|s| s.intensity).fold(0f32, f32::max);
        let low = |axis: usize| {
            let s = lit.iter().find(|s| s.dir[1] < 0.2 && s.dir[axis] > 0.98);
            s.expect("a sample near the horizon").intensity / most
        };
        near(low(0), 0.083_488, "towards x");
        near(low(2), 0.615_198, "towards z");
    }

    #[test]
    fn a_lone_cluster_under_the_sky_gets_all_of_it() {
        assert_eq!(lights(&spec(&[]), &[q(1.0, [0.0; 3])]), vec![1.0]);
        let mut l = spec(&[]);
        (l.samples, l.lower_to_upper) = (20, 0.7);
        near(lights(&l, &[q(1.0, [5.0; 3])])[0], 1.0, "upper and lower");
    }

    #[test]
    fn four_parameters_ask_for_the_brightest_direction() {
        let mut four = q(0.9, [0.0; 3]);
        four.params = vec![0.9, 0.0, 0.0, 0.0, 7.0];
        let got = Chiba::new(&spec(&[([50.0, 100.0, 0.0], 4.0)])).answer(&[four]);
        let [sum, x, y, z] = got[0][..] else {
            panic!("four values: {got:?}")
        };
        assert_eq!(sum, Some(1.0));
        let d = [x, y, z].map(|c| c.unwrap());
        near(dot(d, d), 1.0, "unit");
        near(d[0], 50.0 / 12500f64.sqrt(), "x");
        near(d[1], 100.0 / 12500f64.sqrt(), "y");
        assert_eq!(d[2], 0.0);
    }

    #[test]
    fn queries_of_zero_two_or_three_parameters_or_no_point_get_no_answer() {
        let with = |params: Vec<f32>, position: Vec<f32>| Query { params, position };
        let got = Chiba::new(&spec(&[(UP, 1.0)])).answer(&[
            with(vec![], vec![0.0; 3]),
            with(vec![1.0; 2], vec![0.0; 3]),
            with(vec![1.0; 3], vec![0.0; 3]),
            with(vec![1.0], vec![0.0; 2]),
            with(vec![1.0], vec![5.0; 3]),
        ]);
        assert_eq!(got, vec![vec![], vec![], vec![], vec![], vec![Some(1.0)]]);
    }

    /// The lens of two discs of radius `r` whose centres lie `w` apart
    /// seen along `dir` (computed in f64), over the disc's area.
    fn share(dir: [f64; 3], w: [f64; 3], r: f64) -> f64 {
        let n = dot64(dir, dir).sqrt();
        let along = dot64(dir, w) / n;
        let d = (dot64(w, w) - along * along).sqrt();
        if d >= 2.0 * r {
            return 0.0;
        }
        let x = d / 2.0;
        (2.0 * r * r * (x / r).acos() - (r * r - x * x).sqrt() * d) / (std::f64::consts::PI * r * r)
    }

    fn dot64(a: [f64; 3], b: [f64; 3]) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    #[test]
    fn three_spheres_in_a_column_07_open_10() {
        // `?E(0.9)f(1)?E(0.9)f(1)?E(0.9)` up the y axis, one source.
        let sun = [50.0, 100.0, 0.0];
        let column: Vec<Query> = (0..3).map(|k| q(0.9, [0.0, k as f32, 0.0])).collect();
        let got = lights(&spec(&[(sun, 4.0)]), &column);
        let by = |k: f64| 1.0 - share(sun, [0.0, k, 0.0], 0.9);
        near(got[2], 1.0, "top");
        near(got[1], by(1.0), "middle, under the top's lens");
        near(got[0], by(1.0) * by(2.0), "bottom, under both");
        assert!(got[2] > got[1] && got[1] > got[0], "{got:?}");
        // The figures: 1, 0.31305, 0.18958.
        near(got[0], 0.189_579, "bottom");
    }

    /// 07-Open-11's sixty-four touching unit spheres, corners of a
    /// Sierpinski tetrahedron of side 16 along +z, −x and +y.
    fn sierpinski() -> Vec<[f32; 3]> {
        let corner = |k: usize, s: f32| match k {
            1 => [0.0, 0.0, s],
            2 => [-s, 0.0, 0.0],
            3 => [0.0, s, 0.0],
            _ => [0.0; 3],
        };
        (0..64)
            .map(|i| {
                let parts = [(i / 16, 8.0), (i / 4 % 4, 4.0), (i % 4, 2.0)];
                (parts.iter()).fold([0.0; 3], |p, &(k, s)| {
                    let c = corner(k, s);
                    [p[0] + c[0], p[1] + c[1], p[2] + c[2]]
                })
            })
            .collect()
    }

    #[test]
    fn the_sierpinski_spheres_under_the_sky_07_open_11() {
        let at = sierpinski();
        let queries: Vec<Query> = at.iter().map(|&p| q(1.0, p)).collect();
        let got = lights(&spec(&[]), &queries);
        // The apex sees the whole upper sky: touching spheres at 45° or
        // lower cannot cover a ray above the horizon.
        assert_eq!(got[63], 1.0);
        assert!(got.iter().all(|&g| (0.45..=1.0).contains(&g)), "{got:?}");
        // The bottom layer is shaded more than the upper half.
        let mean = |keep: &dyn Fn(f32) -> bool| {
            let (sum, n) = (at.iter().zip(&got))
                .filter(|(p, _)| keep(p[1]))
                .fold((0.0, 0.0), |(s, n), (_, g)| (s + g, n + 1.0));
            sum / n
        };
        let (bottom, upper) = (mean(&|y| y == 0.0), mean(&|y| y >= 8.0));
        assert!(bottom + 0.1 < upper, "{bottom} vs {upper}");
        near(got[0], 0.609_924, "the origin's");
    }

    /// 07-Open-12's nine sources, a quarter let through.
    fn two_trees() -> Light {
        let mut l = spec(&[
            ([0.0, 100.0, 0.0], 4.0),
            ([40.0, 100.0, 0.0], 3.0),
            ([-40.0, 100.0, 0.0], 3.0),
            ([0.0, 100.0, -40.0], 3.0),
            ([0.0, 100.0, 40.0], 3.0),
            ([80.0, 75.0, 0.0], 2.0),
            ([-80.0, 75.0, 0.0], 2.0),
            ([0.0, 75.0, 80.0], 2.0),
            ([0.0, 75.0, -80.0], 2.0),
        ]);
        l.transmittance = 0.25;
        l
    }

    #[test]
    fn nine_sources_sum_to_one_and_shade_through_the_walk_07_open_12() {
        let l = two_trees();
        let weights: Vec<f32> = Chiba::new(&l).lights.iter().map(|s| s.intensity).collect();
        assert_eq!(weights[..3], [1.0 / 6.0, 0.125, 0.125]);
        assert_eq!(weights[8], 1.0 / 12.0);
        near(lights(&l, &[q(0.5, [0.0; 3])])[0], 1.0, "lone");
        let got = lights(&l, &[q(0.5, [0.0; 3]), q(0.5, [0.0, 2.0, 0.0])]);
        let oblique = 1.0 - 0.75 * share([40.0, 100.0, 0.0], [0.0, 2.0, 0.0], 0.5);
        // The zenith's sixth is cut to a quarter; the low sources miss.
        // Of the four oblique ones only +x and +z are shaded: the walks
        // towards −x and −z run sideways out of the grid (the program's
        // middle without the corner) before the voxels of the upper
        // cluster, so those two arrive whole.
        let want = 0.25 / 6.0 + 2.0 * 0.125 * oblique + 2.0 * 0.125 + 4.0 / 12.0;
        near(got[0], want, "shaded");
        near(got[0], 0.846_798, "the figure");
        near(got[1], 1.0, "above");
    }

    #[test]
    fn the_walk_reckons_faces_without_the_grid_corner() {
        let l = two_trees();
        let c = Chiba::new(&l);
        let (scene, _) = c
            .scene(&[q(0.5, [0.0; 3]), q(0.5, [0.0, 2.0, 0.0])])
            .unwrap();
        let frame = scene.grid.frame;
        assert_eq!((frame.pos, frame.range), ([-0.5; 3], [1.0, 3.0, 1.0]));
        let mut walk = Walk::start(&frame, [0.0; 3], c.lights[2].dir);
        assert_eq!(walk.node, [16, 5, 16]);
        let mut highest = walk.node[1];
        while walk.advance() {
            highest = highest.max(walk.node[1]);
        }
        // The true ray rises to row 15 before it leaves by x = −0.5; the
        // walk leaves at row 13, through column −1.
        assert_eq!((walk.node, highest), ([-1, 13, 16], 13));
    }

    #[test]
    fn absurd_specs_and_queries_are_answered_safely() {
        let sizes = grid_size([0, u32::MAX, u32::MAX]);
        assert!(sizes.iter().all(|&n| n >= 1));
        assert!(sizes.iter().product::<usize>() as u64 <= MAX_CELLS);
        let mut l = spec(&[(UP, 1.0)]);
        l.grid = [0; 3];
        // One voxel: the walk still finds the cluster above.
        assert_eq!(
            lights(&l, &[q(0.5, [0.0; 3]), q(0.5, [0.0, 2.0, 0.0])]),
            vec![0.0, 1.0]
        );
        let nowhere = |p: Query| Chiba::new(&spec(&[(UP, 1.0)])).answer(&[p, q(1.0, [0.0; 3])]);
        // No finite point or radius: that query is not answered.
        assert_eq!(
            nowhere(q(1.0, [f32::NAN, 0.0, 0.0])),
            vec![vec![], vec![Some(1.0)]]
        );
        assert_eq!(
            nowhere(q(f32::INFINITY, [0.0; 3])),
            vec![vec![], vec![Some(1.0)]]
        );
        // A lone point cluster frames a flat grid: the pass answers nothing.
        l.radius = 0.0;
        assert_eq!(
            Chiba::new(&l).answer(&[q(0.0, [1.0; 3])]),
            vec![Vec::<Option<f32>>::new()]
        );
        // Clusters grown by a vast beam over a 256³ grid, three times over:
        // past the budget, nothing is built and nothing answered.
        let mut vast = spec(&[(UP, 1.0)]);
        (vast.grid, vast.estimate_area, vast.beam_radius) = ([256; 3], false, 1e30);
        let three: Vec<Query> = (0..3).map(|k| q(1.0, [k as f32; 3])).collect();
        assert_eq!(
            Chiba::new(&vast).answer(&three),
            vec![Vec::<Option<f32>>::new(); 3]
        );
        // Sources of no direction or no weight give no light.
        let dark = spec(&[([0.0; 3], 1.0)]);
        assert_eq!(lights(&dark, &[q(1.0, [0.0; 3])]), vec![0.0]);
        let weightless = spec(&[(UP, 0.0)]);
        assert_eq!(lights(&weightless, &[q(1.0, [0.0; 3])]), vec![0.0]);
    }

    #[test]
    fn a_pass_of_thousands_of_clusters_is_quick() {
        // 4000 clusters in a 20×10×20 block under the nine sources.
        let queries: Vec<Query> = (0..4000)
            .map(|k| {
                q(
                    0.3,
                    [(k % 20) as f32, (k / 400) as f32, (k / 20 % 20) as f32],
                )
            })
            .collect();
        let t = std::time::Instant::now();
        let got = lights(&two_trees(), &queries);
        assert!(t.elapsed().as_secs() < 20, "{:?}", t.elapsed());
        // The top layer is lit more than the bottom one.
        let mean = |r: std::ops::Range<usize>| got[r].iter().sum::<f32>() / 400.0;
        assert!(mean(3600..4000) > mean(0..400));
    }
}
