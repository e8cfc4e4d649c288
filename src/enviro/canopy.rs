//! vlab's `clover`: light over a plane, read from an image, shaded by the
//! leaves the queries lay on it (Měch & Prusinkiewicz 1996, white clover).
//!
//! The plane is a grid of cells; each cell has the light (the image's
//! green) and a ratio (its red) it was given at the start, and a count of
//! the leaves over it. A `?E(1,area)` lays a leaf disc of that area on
//! the grid, any other `?E(p1,area)` with p1 ≠ 0 takes one away; a
//! `?E(r)` or `?E(0,…)` asks for the light, which every leaf over its
//! cell cuts by the transmittance. The leaves of all steps stay on the
//! grid (unless the spec says to forget them each step), and the light is
//! answered after every leaf of the step is laid or lifted. Computed in
//! `f32`, as the program does.

use super::{Answer, Pass, Query};
use crate::ir::environment::Canopy;
use crate::ir::texture::Image;

/// The most cells along each side (as many as the largest image the
/// program decodes), so that odd settings cannot exhaust memory.
const MAX_CELLS: u32 = 4096;

/// What one cell of the plane holds (the program's bytes).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Cell {
    /// Leaves over the cell, 0..=255.
    leaves: u8,
    light: u8,
    ratio: u8,
}

pub struct Clover {
    size: [usize; 2],
    /// The world's lower-left corner and extent, in `f32` as the program
    /// keeps them.
    corner: [f32; 2],
    range: [f32; 2],
    /// Row by row from the bottom, `size[0]` cells a row.
    cells: Vec<Cell>,
    /// The light `k` leaves let through: the transmittance to the `k`.
    through: [f32; 256],
    remove_old_leaves: bool,
    z_is_up: bool,
}

impl Clover {
    pub fn new(c: &Canopy) -> Clover {
        let size = c.grid.map(|n| n.min(MAX_CELLS) as usize);
        Clover {
            size,
            corner: c.position.map(|v| v as f32),
            range: c.range.map(|v| v as f32),
            cells: initial_cells(size, c.image.as_ref()),
            through: transmittance_table(c.transmittance as f32),
            remove_old_leaves: c.remove_old_leaves,
            z_is_up: c.z_is_up,
        }
    }

    /// The cell under `at` (a point of the plane), unless it lies off the
    /// grid or is not a number.
    fn node(&self, at: [f32; 2]) -> Option<[i64; 2]> {
        let mut node = [0; 2];
        for c in 0..2 {
            let v = ((at[c] - self.corner[c]) / self.range[c] * self.size[c] as f32).floor();
            if v.is_nan() {
                return None;
            }
            // `as` saturates: a point too far away stays off the grid.
            node[c] = v as i64;
        }
        Some(node)
    }

    fn index(&self, [x, y]: [i64; 2]) -> Option<usize> {
        let inside = |v: i64, n: usize| v >= 0 && (v as u64) < n as u64;
        (inside(x, self.size[0]) && inside(y, self.size[1]))
            .then(|| y as usize * self.size[0] + x as usize)
    }

    /// What `q` asks, or `None` when the program would drop it (no
    /// parameter, or too few coordinates for its plane).
    fn read(&self, q: &Query) -> Option<Ask> {
        let p1 = *q.params.first()?;
        let at = match (self.z_is_up, &q.position[..]) {
            (true, [x, y, ..]) => [*x, *y],
            (false, [x, _, z, ..]) => [*x, *z],
            _ => return None,
        };
        if q.params.len() == 1 || p1 == 0.0 {
            return Some(Ask::Light { at });
        }
        Some(Ask::Leaf {
            at,
            add: p1 == 1.0,
            area: q.params[1],
        })
    }

    /// Lays (`add`) or lifts a leaf disc of `area` centred at `at`: the
    /// cells of an ellipse of half-extents `k`, counted in whole cells,
    /// with the program's bounds, which reach one cell further below and
    /// left of the centre than above and right.
    fn stamp(&mut self, at: [f32; 2], add: bool, area: f32) {
        // Leaves too small to count (and areas that are not numbers).
        if area.is_nan() || f64::from(area) < 0.000_000_1 {
            return;
        }
        let Some(node) = self.node(at) else { return };
        let radius = (f64::from(area) / std::f64::consts::PI).sqrt() as f32;
        let k: [i128; 2] = std::array::from_fn(|c| {
            (radius / self.range[c] * self.size[c] as f32 + 1.0) as i64 as i128
        });
        // Only the part of the disc on the grid is visited, so a leaf
        // larger than the grid costs no more than the grid.
        let span = |c: usize| {
            let (n, centre) = (self.size[c] as i128, i128::from(node[c]));
            (-k[c]).max(-centre)..k[c].min(n - centre)
        };
        for dy in span(1) {
            for dx in span(0) {
                if !in_ellipse(dx, dy, k) {
                    continue;
                }
                let cell = [node[0] + dx as i64, node[1] + dy as i64];
                let Some(i) = self.index(cell) else { continue };
                let leaves = &mut self.cells[i].leaves;
                *leaves = if add {
                    leaves.saturating_add(1)
                } else {
                    leaves.saturating_sub(1)
                };
            }
        }
    }

    /// The answer to a light query at `at` with `params` parameters: the
    /// light left under the leaves, and with two parameters or more the
    /// ratio too. Off the grid both are 0.
    fn light(&self, at: [f32; 2], params: usize) -> Answer {
        let cell = self.node(at).and_then(|n| self.index(n));
        let cell = cell.map(|i| self.cells[i]);
        // The program divides in double and stores the result as a float.
        let light = cell.map_or(0.0, |c| {
            (f64::from(c.light) / 255.0 * f64::from(self.through[usize::from(c.leaves)])) as f32
        });
        let mut answer = vec![Some(light)];
        if params >= 2 {
            answer.push(Some(cell.map_or(0.0, |c| f32::from(c.ratio) / 128.0)));
        }
        answer
    }
}

/// A query as the program tells them apart.
enum Ask {
    Light { at: [f32; 2] },
    Leaf { at: [f32; 2], add: bool, area: f32 },
}

impl Pass for Clover {
    fn answer(&mut self, queries: &[Query]) -> Vec<Answer> {
        if self.remove_old_leaves {
            self.cells.iter_mut().for_each(|c| c.leaves = 0);
        }
        // Leaves change the grid in the word's order; the light is read
        // once they all lie, so a query sees every leaf of its step.
        let mut asked = Vec::new();
        for (i, q) in queries.iter().enumerate() {
            match self.read(q) {
                Some(Ask::Light { at }) => asked.push((i, at)),
                Some(Ask::Leaf { at, add, area }) => self.stamp(at, add, area),
                None => {}
            }
        }
        let mut answers = vec![Vec::new(); queries.len()];
        for (i, at) in asked {
            answers[i] = self.light(at, queries[i].params.len());
        }
        answers
    }
}

/// The cells of a `size` grid before any leaf: each takes the pixel its
/// corner falls on when the image is stretched over the grid, corner to
/// corner; without an image, full light (and no ratio).
fn initial_cells(size: [usize; 2], image: Option<&Image>) -> Vec<Cell> {
    let Some(image) = image else {
        let lit = Cell {
            light: 255,
            ..Cell::default()
        };
        return vec![lit; size[0] * size[1]];
    };
    let (w, h) = (image.width(), image.height());
    // For a grid one cell wide the ratio is not a number (or infinite),
    // and `as` makes the pixel 0, the image's first column or row.
    let xr = (w - 1) as f32 / (size[0] as f32 - 1.0);
    let yr = (h - 1) as f32 / (size[1] as f32 - 1.0);
    let pixel = |i: usize, ratio: f32, n: u32| ((i as f32 * ratio) as u32).min(n - 1);
    let mut cells = Vec::with_capacity(size[0] * size[1]);
    for y in 0..size[1] {
        let py = pixel(y, yr, h);
        for x in 0..size[0] {
            let [red, green, ..] = image.texel(i64::from(pixel(x, xr, w)), i64::from(py));
            cells.push(Cell {
                leaves: 0,
                light: green,
                ratio: red,
            });
        }
    }
    cells
}

/// `t` to the powers 0..=255, each the one before times `t` in `f32`. A
/// leaf cannot stop all light: 0 is taken as 0.0001, as the program does.
fn transmittance_table(t: f32) -> [f32; 256] {
    let t = if t == 0.0 { 0.0001 } else { t };
    let mut table = [1.0f32; 256];
    for i in 1..256 {
        table[i] = t * table[i - 1];
    }
    table
}

/// Whether the offset (dx, dy) lies in the ellipse of half-extents `k`,
/// tested as the program does, in `f32`.
fn in_ellipse(dx: i128, dy: i128, k: [i128; 2]) -> bool {
    let term = |d: i128, k: i128| (d * d) as f32 / (k * k) as f32;
    term(dx, k[0]) + term(dy, k[1]) <= 1.0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 4 × 4 pixels: green 51·(1 + (x + y) mod 4), so light 0.2, 0.4,
    /// 0.6 or 0.8; red 64·x, so ratio 0, 0.5, 1 or 1.5.
    fn image() -> Image {
        let mut rgba = Vec::new();
        for y in 0..4u8 {
            for x in 0..4u8 {
                rgba.extend([64 * x, 51 * (1 + (x + y) % 4), 0, 255]);
            }
        }
        Image::new(4, 4, rgba).unwrap()
    }

    /// A 4 × 4 grid over the world's square (0,0)–(4,4): cell (x, y) is
    /// pixel (x, y) and covers x..x+1, y..y+1.
    fn canopy(t: f64) -> Canopy {
        Canopy {
            grid: [4, 4],
            position: [0.0, 0.0],
            range: [4.0, 4.0],
            transmittance: t,
            image_file: None,
            image: Some(image()),
            remove_old_leaves: false,
            z_is_up: true,
        }
    }

    fn q(params: &[f32], at: [f32; 3]) -> Query {
        Query {
            params: params.to_vec(),
            position: at.to_vec(),
        }
    }

    /// The light answered at the centre of cell (x, y).
    fn light(c: &mut Clover, x: f32, y: f32) -> f32 {
        c.answer(&[q(&[0.5], [x + 0.5, y + 0.5, 0.0])])[0][0].unwrap()
    }

    /// A leaf small enough to cover one cell's worth: half-extents of 1.
    const SMALL: f32 = 1.0;

    #[test]
    fn an_empty_canopy_answers_the_images_green() {
        let mut c = Clover::new(&canopy(0.5));
        // Pixel (2, 1): green 51·4.
        assert_eq!(light(&mut c, 2.0, 1.0), 0.8);
        assert_eq!(light(&mut c, 0.0, 0.0), 0.2);
        assert_eq!(light(&mut c, 3.0, 2.0), 0.4);
        // Off the grid: no light.
        assert_eq!(light(&mut c, 4.0, 0.0), 0.0);
        assert_eq!(light(&mut c, -1.0, 0.0), 0.0);
    }

    #[test]
    fn a_leaf_cuts_the_light_by_the_transmittance_until_it_is_lifted() {
        let mut c = Clover::new(&canopy(0.5));
        // The light query comes first in the word, yet sees the leaf.
        let got = c.answer(&[
            q(&[0.0, 7.0], [2.5, 1.5, 0.0]),
            q(&[1.0, SMALL], [2.5, 1.5, 0.0]),
        ]);
        assert_eq!(got, vec![vec![Some(0.4), Some(1.0)], vec![]]);
        // Half-extents 1: the cell, the one left and the one below; not
        // the one right or above (the stamp's bounds), nor the diagonal.
        assert_eq!(light(&mut c, 1.0, 1.0), 0.3);
        assert_eq!(light(&mut c, 2.0, 0.0), 0.3);
        assert_eq!(light(&mut c, 3.0, 1.0), 0.2, "right: unshaded");
        assert_eq!(light(&mut c, 2.0, 2.0), 0.2, "above: unshaded");
        assert_eq!(light(&mut c, 1.0, 0.0), 0.4, "diagonal: unshaded");
        // The leaf stays into later steps; a second one multiplies again.
        c.answer(&[q(&[1.0, SMALL], [2.5, 1.5, 0.0])]);
        assert_eq!(light(&mut c, 2.0, 1.0), 0.2);
        // Any first parameter but 0 and 1 lifts a leaf.
        c.answer(&[q(&[2.0, SMALL], [2.5, 1.5, 0.0])]);
        assert_eq!(light(&mut c, 2.0, 1.0), 0.4);
        c.answer(&[q(&[2.0, SMALL], [2.5, 1.5, 0.0])]);
        assert_eq!(light(&mut c, 2.0, 1.0), 0.8);
        // Lifting from bare ground leaves it bare.
        c.answer(&[q(&[2.0, SMALL], [2.5, 1.5, 0.0])]);
        assert_eq!(light(&mut c, 2.0, 1.0), 0.8);
    }

    #[test]
    fn two_parameters_get_the_ratio_of_the_images_red() {
        let mut c = Clover::new(&canopy(0.5));
        let got = c.answer(&[
            q(&[0.0, 9.0, 9.0], [1.5, 0.5, 0.0]),
            q(&[0.0, 9.0], [3.5, 0.5, 0.0]),
            q(&[0.0, 9.0], [9.5, 0.5, 0.0]),
        ]);
        // Pixel (1, 0): red 64, green 102; pixel (3, 0): red 192, green 204.
        assert_eq!(got[0], vec![Some(0.4), Some(0.5)]);
        assert_eq!(got[1], vec![Some(0.8), Some(1.5)]);
        assert_eq!(got[2], vec![Some(0.0), Some(0.0)], "off the grid");
    }

    #[test]
    fn the_image_stretches_corner_to_corner_over_a_finer_grid() {
        // 7 cells over 4 pixels: cell x takes pixel (int)(x · 0.5).
        let mut c = Clover::new(&Canopy {
            grid: [7, 7],
            range: [7.0, 7.0],
            ..canopy(0.5)
        });
        let row: Vec<f32> = (0..7).map(|x| light(&mut c, x as f32, 0.0)).collect();
        assert_eq!(row, [0.2, 0.2, 0.4, 0.4, 0.6, 0.6, 0.8]);
    }

    #[test]
    fn without_an_image_the_light_is_full_and_the_ratio_0() {
        let mut c = Clover::new(&Canopy {
            image: None,
            ..canopy(0.0)
        });
        let got = c.answer(&[q(&[0.0, 1.0], [0.5, 0.5, 0.0])]);
        assert_eq!(got[0], vec![Some(1.0), Some(0.0)]);
        // Transmittance 0 is taken as 0.0001.
        c.answer(&[q(&[1.0, SMALL], [0.5, 0.5, 0.0])]);
        assert_eq!(light(&mut c, 0.0, 0.0), (1.0f64 * 0.0001f32 as f64) as f32);
    }

    #[test]
    fn old_leaves_can_be_forgotten_and_the_plane_can_be_x_z() {
        let mut c = Clover::new(&Canopy {
            remove_old_leaves: true,
            z_is_up: false,
            ..canopy(0.5)
        });
        // In the x–z plane y does not count; a position without z is
        // dropped.
        let got = c.answer(&[
            q(&[1.0, SMALL], [2.5, 99.0, 1.5]),
            q(&[0.5], [2.5, -7.0, 1.5]),
            Query {
                params: vec![0.5],
                position: vec![2.5, 1.5],
            },
        ]);
        assert_eq!(got, vec![vec![], vec![Some(0.4)], vec![]]);
        let got = c.answer(&[q(&[0.5], [2.5, 0.0, 1.5])]);
        assert_eq!(got, vec![vec![Some(0.8)]], "the leaf is gone");
    }

    #[test]
    fn leaves_count_to_255_at_most() {
        let mut c = Clover::new(&canopy(0.5));
        let leaf = q(&[1.0, SMALL], [0.5, 0.5, 0.0]);
        c.answer(&vec![leaf; 300]);
        // 0.5 to the 255th is below the smallest f32: the table holds 0.
        assert_eq!(light(&mut c, 0.0, 0.0), 0.0);
        let lift = q(&[2.0, SMALL], [0.5, 0.5, 0.0]);
        c.answer(&vec![lift; 254]);
        assert_eq!(light(&mut c, 0.0, 0.0), 0.1);
    }

    #[test]
    fn odd_settings_and_queries_neither_panic_nor_hang() {
        let huge = Canopy {
            grid: [u32::MAX, 2],
            ..canopy(0.5)
        };
        let mut c = Clover::new(&huge);
        assert_eq!(c.size, [4096, 2]);
        let queries = [
            q(&[1.0, f32::MAX], [0.5, 0.5, 0.0]),
            q(&[1.0, f32::INFINITY], [f32::NAN, 0.5, 0.0]),
            q(&[1.0, f32::NAN], [0.5, 0.5, 0.0]),
            q(&[1.0, 1.0], [f32::INFINITY, -1e30, 0.0]),
            q(&[0.5], [f32::NAN, 0.5, 0.0]),
            q(&[], [0.5, 0.5, 0.0]),
        ];
        let got = c.answer(&queries);
        assert_eq!(got[4], vec![Some(0.0)], "not a number: off the grid");
        assert_eq!(got[5], vec![]);
        for grid in [[0, 0], [1, 1], [0, 5]] {
            let mut c = Clover::new(&Canopy {
                grid,
                ..canopy(0.5)
            });
            c.answer(&queries);
            let mut zero = Clover::new(&Canopy {
                range: [0.0, -1.0],
                grid,
                ..canopy(0.5)
            });
            zero.answer(&queries);
        }
        // A grid one cell wide takes the image's first pixel.
        let mut one = Clover::new(&Canopy {
            grid: [1, 1],
            ..canopy(0.5)
        });
        assert_eq!(light(&mut one, 0.0, 0.0), 0.2);
    }
}
