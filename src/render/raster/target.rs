//! The samples a lit picture is drawn into: a band of sample rows holding
//! a colour and a depth per sample, and the triangles and lines rasterised
//! into it (the nearer sample wins; on a tie the first drawn). Threads
//! draw successive parts of the drawing into bands of their own, which
//! [`Target::merge`] lays together by the same rule.

use crate::ir::texture::Texture;
use crate::ir::Rgb;
use crate::render::shade::{to_colour, Colour};

/// A vertex in samples (x right, y down), with its depth (smaller is
/// nearer), colour and texture coordinates (unused untextured).
#[derive(Clone, Copy, Debug)]
pub(super) struct SVert {
    pub(super) x: f64,
    pub(super) y: f64,
    pub(super) z: f64,
    pub(super) c: Colour,
    pub(super) uv: [f64; 2],
}

/// A band of sample rows: colour and depth per sample.
pub(super) struct Target {
    /// First sample row of the band, and its rows.
    y0: i64,
    rows: i64,
    pub(super) width: i64,
    pub(super) colour: Vec<u32>,
    depth: Vec<f32>,
    /// While translucent things are drawn (after everything opaque), their
    /// opacity: each sample in front is mixed over what is there, and the
    /// depth kept (OpenGL's blending with depth writes off, as cpfg draws
    /// translucent materials).
    pub(super) opacity: Option<f32>,
}

/// The colour of a packed opaque sample.
fn unpack(c: u32) -> Colour {
    [16, 8, 0].map(|s| ((c >> s) & 0xff) as f32 / 255.0)
}

/// An opaque colour as `0xAARRGGBB`.
fn pack(c: Colour) -> u32 {
    let q = |x: f32| (x.clamp(0.0, 1.0) * 255.0 + 0.5) as u32;
    (255 << 24) | (q(c[0]) << 16) | (q(c[1]) << 8) | q(c[2])
}

/// Whether samples on the edge from `a` to `b` belong to the triangle
/// that runs it this way (its neighbour runs it the other way).
fn owns_edge(a: &SVert, b: &SVert) -> bool {
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    dy > 0.0 || (dy == 0.0 && dx < 0.0)
}

/// Twice the signed area of (a, b, p); swapping a and b negates it exactly,
/// so triangles sharing an edge leave no gap along it.
fn edge(a: &SVert, b: &SVert, px: f64, py: f64) -> f64 {
    (a.x - px) * (b.y - py) - (a.y - py) * (b.x - px)
}

impl Target {
    /// The band of `rows` sample rows from `y0`, `width` samples wide,
    /// filled with the background.
    pub(super) fn band(y0: i64, rows: i64, width: i64, (background, alpha): (Rgb, u8)) -> Target {
        let n = (rows.max(0) * width.max(0)) as usize;
        let bg = pack(to_colour(background)) & 0x00ff_ffff | u32::from(alpha) << 24;
        Target {
            y0,
            rows,
            width,
            colour: vec![bg; n],
            depth: vec![f32::INFINITY; n],
            opacity: None,
        }
    }

    /// Lays each of `later` (the same band, each with what was drawn after
    /// what the one before holds) over this one in turn: each sample the
    /// nearest, the earliest on a tie, as if everything had been drawn
    /// into one band in order. Each sample's result depends on that sample
    /// alone, so the band is cut into a share of samples a thread (as many
    /// as drew it), each laid over by every later band.
    pub(super) fn merge(&mut self, later: &[Target]) {
        if later.is_empty() {
            return;
        }
        let share = self.depth.len().div_ceil(later.len() + 1).max(1);
        let shares = (self.depth.chunks_mut(share))
            .zip(self.colour.chunks_mut(share))
            .enumerate();
        crate::parallel::on_own_threads(shares, |(k, (depth, colour))| {
            let at = k * share..k * share + depth.len();
            for l in later {
                let samples = depth.iter_mut().zip(colour.iter_mut());
                let theirs = l.depth[at.clone()].iter().zip(&l.colour[at.clone()]);
                for ((d, c), (&ld, &lc)) in samples.zip(theirs) {
                    if ld < *d {
                        *d = ld;
                        *c = lc;
                    }
                }
            }
        });
    }

    /// Whether sample rows `lo..=hi` meet the band.
    #[inline]
    pub(super) fn meets(&self, lo: f64, hi: f64) -> bool {
        hi >= self.y0 as f64 - 1.0 && lo <= (self.y0 + self.rows) as f64 + 1.0
    }

    // Called per sample from the other rooms of the raster.
    #[inline]
    pub(super) fn plot(&mut self, x: i64, y: i64, z: f64, c: Colour) {
        let i = ((y - self.y0) * self.width + x) as usize;
        let z = z as f32;
        if z < self.depth[i] {
            match self.opacity {
                None => {
                    self.depth[i] = z;
                    self.colour[i] = pack(c);
                }
                Some(a) => {
                    let under = unpack(self.colour[i]);
                    let mixed = [0, 1, 2].map(|k| a * c[k] + (1.0 - a) * under[k]);
                    self.colour[i] = pack(mixed) & 0x00ff_ffff | self.colour[i] & 0xff00_0000;
                }
            }
        }
    }

    /// The rows of samples whose centres lie in `lo..=hi`, in the band.
    #[inline]
    pub(super) fn rows_between(&self, lo: f64, hi: f64) -> std::ops::Range<i64> {
        let first = ((lo - 0.5).ceil() as i64).max(self.y0);
        let last = ((hi - 0.5).floor() as i64).min(self.y0 + self.rows - 1);
        first..last + 1
    }

    pub(super) fn triangle(&mut self, v: [SVert; 3]) {
        self.fill(v, None);
    }

    /// A triangle wearing `texture`: each sample's lit colour combined
    /// with the texel at its texture coordinates (interpolated across the
    /// triangle as the colour is); a sample whose texel leaves it less than
    /// half opaque is not drawn (the transparent parts of a leaf's image
    /// cut its shape out of the surface).
    pub(super) fn textured_triangle(&mut self, v: [SVert; 3], texture: &Texture) {
        self.fill(v, Some(texture));
    }

    fn fill(&mut self, v: [SVert; 3], texture: Option<&Texture>) {
        if v.iter()
            .any(|p| !(p.x.is_finite() && p.y.is_finite() && p.z.is_finite()))
        {
            return;
        }
        let area = edge(&v[0], &v[1], v[2].x, v[2].y);
        // NaN-safe: a NaN area is not above the bound either.
        if area.abs().partial_cmp(&1e-12) != Some(std::cmp::Ordering::Greater) {
            return;
        }
        let v = if area < 0.0 { [v[0], v[2], v[1]] } else { v };
        let area = area.abs();
        let lo = v.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
        let hi = v.iter().map(|p| p.y).fold(f64::NEG_INFINITY, f64::max);
        for y in self.rows_between(lo, hi) {
            let yc = y as f64 + 0.5;
            let Some((xl, xr)) = span(&v, yc) else {
                continue;
            };
            let first = ((xl - 0.5).ceil() as i64 - 1).max(0);
            let last = ((xr - 0.5).floor() as i64 + 1).min(self.width - 1);
            for x in first..=last {
                let xc = x as f64 + 0.5;
                let w0 = edge(&v[1], &v[2], xc, yc);
                let w1 = edge(&v[2], &v[0], xc, yc);
                let w2 = edge(&v[0], &v[1], xc, yc);
                if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                    continue;
                }
                // A sample on an edge two blended triangles share is
                // theirs once: the one that runs the edge one way owns it.
                let on = [(w0, 1, 2), (w1, 2, 0), (w2, 0, 1)];
                if self.opacity.is_some()
                    && on
                        .iter()
                        .any(|&(w, a, b)| w == 0.0 && !owns_edge(&v[a], &v[b]))
                {
                    continue;
                }
                let (b0, b1, b2) = (w0 / area, w1 / area, w2 / area);
                let z = b0 * v[0].z + b1 * v[1].z + b2 * v[2].z;
                let (b0, b1, b2) = (b0 as f32, b1 as f32, b2 as f32);
                let mut c = [0, 1, 2].map(|k| b0 * v[0].c[k] + b1 * v[1].c[k] + b2 * v[2].c[k]);
                if let Some(texture) = texture {
                    let (b0, b1, b2) = (f64::from(b0), f64::from(b1), f64::from(b2));
                    let uv = [0, 1].map(|k| b0 * v[0].uv[k] + b1 * v[1].uv[k] + b2 * v[2].uv[k]);
                    let lit = [c[0], c[1], c[2], 1.0];
                    let shaded = texture.shade(lit, uv[0], uv[1]);
                    if shaded[3] < 0.5 {
                        continue;
                    }
                    c = [shaded[0], shaded[1], shaded[2]];
                }
                self.plot(x, y, z, c);
            }
        }
    }

    /// A line between `a` and `b` (samples) `width` samples wide, with
    /// square ends reaching half its width past them, in one colour.
    pub(super) fn line(&mut self, a: [f64; 3], b: [f64; 3], width: f64, c: Colour) {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = (dx * dx + dy * dy).sqrt();
        if len.partial_cmp(&1e-9) != Some(std::cmp::Ordering::Greater) || !width.is_finite() {
            return;
        }
        let h = width.clamp(1.0, 1e6) / 2.0;
        let (tx, ty) = (dx / len * h, dy / len * h);
        let (nx, ny) = (-ty, tx);
        let at = |p: [f64; 3], s: f64, side: f64| SVert {
            x: p[0] + s * tx + side * nx,
            y: p[1] + s * ty + side * ny,
            z: p[2],
            c,
            uv: [0.0; 2],
        };
        let q = [
            at(a, -1.0, -1.0),
            at(a, -1.0, 1.0),
            at(b, 1.0, 1.0),
            at(b, 1.0, -1.0),
        ];
        self.triangle([q[0], q[1], q[2]]);
        self.triangle([q[0], q[2], q[3]]);
    }
}

/// Where the row at `yc` crosses the triangle `v`: its leftmost and
/// rightmost x.
fn span(v: &[SVert; 3], yc: f64) -> Option<(f64, f64)> {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for (p, q) in [(&v[0], &v[1]), (&v[1], &v[2]), (&v[2], &v[0])] {
        let (y0, y1) = (p.y.min(q.y), p.y.max(q.y));
        if yc < y0 || yc > y1 {
            continue;
        }
        let x = if y1 - y0 > 1e-12 {
            p.x + (yc - p.y) * (q.x - p.x) / (q.y - p.y)
        } else {
            lo = lo.min(p.x.min(q.x));
            p.x.max(q.x)
        };
        lo = lo.min(x);
        hi = hi.max(x);
    }
    (lo <= hi).then_some((lo, hi))
}
