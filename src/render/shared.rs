//! Pictures of context-free deterministic systems drawn from their shared
//! subtrees ([`Instanced::lines`]): nothing is derived or stored but the
//! picture's polylines, and a subtree within half a pixel is one line.

use super::{Fit, Picture, RenderOptions, Run};
use crate::ir::colours::DEFAULT_PALETTE;
use crate::ir::System;
use crate::turtle::instanced::{ldexp, Instanced, Lines};
use crate::turtle::Vec3;

/// The picture of the word of `inst` after `steps` steps, seen face on
/// (the default view), fitted as [`super::layout`] fits a geometry. It is
/// drawn in the unit [`Instanced::word_scaled`] chooses, so that a picture
/// whose size is beyond `f64` in turtle units is drawn all the same.
pub fn picture(
    sys: &System,
    inst: &mut Instanced<'_>,
    steps: u64,
    opts: &RenderOptions,
) -> Picture {
    let (whole, unit) = inst.word_scaled(steps);
    let corners = [[whole.lo[0], whole.lo[1]], [whole.hi[0], whole.hi[1]]];
    let settings = &sys.settings;
    // A width in turtle units is one in the picture's units too.
    let width = if settings.world_widths {
        ldexp(settings.width, -unit)
    } else {
        settings.width
    };
    let pad = super::margin_pad(width, opts, settings.world_widths);
    let fit = Fit::padded(corners.iter(), opts, pad);
    let mut pen = Pen {
        lines: Vec::new(),
        at: None,
        fit: &fit,
    };
    inst.lines(steps, fit.scale, unit, &mut pen);
    let palette = if sys.colours.is_empty() {
        DEFAULT_PALETTE.to_vec()
    } else {
        sys.colours.clone()
    };
    Picture {
        width: opts.width,
        height: opts.height,
        background: opts.background,
        background_alpha: opts.background_alpha,
        runs: vec![Run {
            colour: palette[settings.colour.min(palette.len() - 1)],
            width: fit.line_width(width, settings.world_widths),
            lines: pen.lines,
        }],
        polygons: Vec::new(),
        labels: Vec::new(),
        links: Default::default(),
    }
}

/// Polylines in pixels, joined where one line starts at the last's end,
/// with points closer than a tenth of a pixel to the previous one left out.
struct Pen<'f> {
    lines: Vec<Vec<[f64; 2]>>,
    at: Option<[f64; 2]>,
    fit: &'f Fit,
}

impl Lines for Pen<'_> {
    fn line(&mut self, a: Vec3, b: Vec3) {
        let (a, b) = (self.fit.to_px([a[0], a[1]]), self.fit.to_px([b[0], b[1]]));
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
