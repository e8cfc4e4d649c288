//! Pictures of context-free deterministic systems drawn from their shared
//! subtrees ([`Instanced::lines`]): nothing is derived or stored but the
//! picture's polylines, and a subtree within half a pixel is one line.

use super::{Picture, RenderOptions, Run};
use crate::ir::System;
use crate::turtle::instanced::{Instanced, Lines};
use crate::turtle::{Vec3, DEFAULT_PALETTE};

/// The picture of the word of `inst` after `steps` steps, seen face on
/// (the default view), fitted as [`super::layout`] fits a geometry.
pub fn picture(
    sys: &System,
    inst: &mut Instanced<'_>,
    steps: u64,
    opts: &RenderOptions,
) -> Picture {
    let whole = inst.word(steps);
    let (w, h) = (opts.width as f64, opts.height as f64);
    let fill = 0.9 * opts.scale.clamp(1.0, 100.0) / 100.0;
    let (bw, bh) = (whole.hi[0] - whole.lo[0], whole.hi[1] - whole.lo[1]);
    let fit = |size: f64, extent: f64| {
        if extent > 0.0 {
            size * fill / extent
        } else {
            f64::INFINITY
        }
    };
    let mut s = fit(w, bw).min(fit(h, bh));
    if !s.is_finite() {
        s = 1.0;
    }
    let centre = (
        (whole.lo[0] + whole.hi[0]) / 2.0,
        (whole.lo[1] + whole.hi[1]) / 2.0,
    );
    let mut pen = Pen {
        lines: Vec::new(),
        at: None,
        size: (w, h),
        centre,
        pixels: s,
    };
    inst.lines(steps, s, &mut pen);
    let settings = &sys.settings;
    let palette = if sys.colours.is_empty() {
        DEFAULT_PALETTE.to_vec()
    } else {
        sys.colours.clone()
    };
    let base = (w.min(h) / 600.0).max(1.0);
    let colour = palette[settings.colour.min(palette.len() - 1)];
    let width = if settings.world_widths {
        (settings.width * s).max(0.5)
    } else {
        base * settings.width
    };
    Picture {
        width: opts.width,
        height: opts.height,
        runs: vec![Run {
            colour,
            width,
            lines: pen.lines,
        }],
        polygons: Vec::new(),
    }
}

/// Polylines in pixels, joined where one line starts at the last's end,
/// with points closer than a tenth of a pixel to the previous one left out.
struct Pen {
    lines: Vec<Vec<[f64; 2]>>,
    at: Option<[f64; 2]>,
    /// The picture's size, the centre of the figure (turtle units), and
    /// pixels per turtle unit.
    size: (f64, f64),
    centre: (f64, f64),
    pixels: f64,
}

impl Pen {
    fn to_px(&self, p: Vec3) -> [f64; 2] {
        let (w, h) = self.size;
        let (cx, cy) = self.centre;
        [
            w / 2.0 + (p[0] - cx) * self.pixels,
            h / 2.0 - (p[1] - cy) * self.pixels,
        ]
    }
}

impl Lines for Pen {
    fn line(&mut self, a: Vec3, b: Vec3) {
        let (a, b) = (self.to_px(a), self.to_px(b));
        match (self.at, self.lines.last_mut()) {
            (Some(p), Some(line)) if p == a => {
                let last = line[line.len() - 1];
                if (b[0] - last[0]).abs() >= 0.1 || (b[1] - last[1]).abs() >= 0.1 || line.len() < 2
                {
                    line.push(b);
                }
            }
            _ => self.lines.push(vec![a, b]),
        }
        self.at = Some(b);
    }

    fn lift(&mut self) {
        self.at = None;
    }
}
