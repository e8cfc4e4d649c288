//! `environment …`: an open L-system's environment as one `.gft` line
//! (docs/gft.md §14), as the front end reads it.

use super::expr::num;
use crate::ir::environment::{Environment, LightSource, Program};
use std::fmt::Write;

/// The environment's line.
pub(super) fn environment(out: &mut String, env: &Environment) {
    out.push_str("environment ");
    program(out, &env.program);
    if let Some(f) = env.position.as_deref().filter(|f| quotable(f)) {
        let _ = write!(out, " position \"{f}\"");
    }
    if env.after_each_step {
        out.push_str(" after-each-step");
    }
    if !env.past_cut {
        out.push_str(" cut-stops-queries");
    }
    out.push('\n');
}

/// Whether a text fits in a `.gft` string: no double quote, no line break.
fn quotable(s: &str) -> bool {
    !s.contains(['"', '\n', '\r'])
}

fn program(out: &mut String, p: &Program) {
    match p {
        Program::Density(d) => {
            let _ = write!(out, "density radius {}", num(d.radius));
            flag(out, d.three_d, "3d");
        }
        Program::Light(l) => {
            let [x, y, z] = l.grid;
            let _ = write!(
                out,
                "light grid {x} {y} {z} transmittance {} lower-to-upper {} samples {} radius {} beam {}",
                num(l.transmittance),
                num(l.lower_to_upper),
                l.samples,
                num(l.radius),
                num(l.beam_radius)
            );
            for s in &l.sources {
                source(out, s);
            }
            flag(out, l.estimate_area, "estimate-area");
            flag(out, l.cie, "cie");
        }
        Program::Canopy(c) => {
            let _ = write!(
                out,
                "canopy grid {} {} at ({}, {}) range ({}, {}) transmittance {}",
                c.grid[0],
                c.grid[1],
                num(c.position[0]),
                num(c.position[1]),
                num(c.range[0]),
                num(c.range[1]),
                num(c.transmittance)
            );
            if let Some(f) = c.image_file.as_deref().filter(|f| quotable(f)) {
                let _ = write!(out, " image \"{f}\"");
            }
            flag(out, c.remove_old_leaves, "remove-old-leaves");
            flag(out, !c.z_is_up, "plane-xz");
        }
        Program::Circles(c) => {
            out.push_str("circles");
            flag(out, c.three_d, "3d");
            flag(out, c.vigor, "vigor");
        }
        Program::Obstacles(o) => {
            out.push_str("obstacles");
            for [xa, ya, xb, yb] in &o.segments {
                let _ = write!(
                    out,
                    " segment ({}, {}) ({}, {})",
                    num(*xa),
                    num(*ya),
                    num(*xb),
                    num(*yb)
                );
            }
        }
    }
}

fn source(out: &mut String, s: &LightSource) {
    let [x, y, z] = s.direction;
    let _ = write!(
        out,
        " source ({}, {}, {}) {}",
        num(x),
        num(y),
        num(z),
        num(s.intensity)
    );
}

fn flag(out: &mut String, on: bool, word: &str) {
    if on {
        out.push(' ');
        out.push_str(word);
    }
}
