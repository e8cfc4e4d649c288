//! `environment PROGRAM …`: what answers the `query environment` modules
//! of an open L-system (docs/gft.md §14), one line.

use super::items::{Fields, Val};
use super::Cx;
use crate::front::gft::ast::Keyword;
use crate::ir::environment::{
    Canopy, Circles, Density, Environment, Light, LightSource, Obstacles, Program,
};

/// The shape of each program's line, for the error that says what was
/// expected.
const SHAPES: &str = "environment density radius 0.5 [3d] | light grid 32 32 32 \
    transmittance 0.6 lower-to-upper 0.7 samples 20 radius 25 beam 0 [source (0, 1, 0) 1]… | \
    canopy grid 512 512 at (-1, -1) range (2, 2) transmittance 0.6 [image \"light.png\"] | \
    circles [3d] [vigor] | obstacles [segment (0, 0) (1, 0)]…, then [position \"%f %f %f\"] \
    [after-each-step] [cut-stops-queries]";

impl Cx<'_> {
    /// `environment PROGRAM SETTINGS [position "FORMAT"] [after-each-step]
    /// [cut-stops-queries]`.
    pub(super) fn environment(&mut self, k: &Keyword) {
        let mut f = Fields::new(k);
        let program = match f.word("", &["density", "light", "canopy", "circles", "obstacles"]) {
            Some(p) => match p.as_str() {
                "density" => density(&mut f),
                "light" => light(&mut f),
                "canopy" => self.canopy(&mut f),
                "circles" => Some(Program::Circles(Circles {
                    three_d: f.has("3d"),
                    vigor: f.has("vigor"),
                })),
                _ => Some(Program::Obstacles(Obstacles {
                    segments: pairs_after(&f, "segment"),
                })),
            },
            None => None,
        };
        let position = f
            .has("position")
            .then(|| quoted(&mut f, "position"))
            .flatten();
        if let (Some(program), None) = (program, &f.problem) {
            self.sys.environment = Some(Environment {
                program,
                position,
                after_each_step: f.has("after-each-step"),
                past_cut: !f.has("cut-stops-queries"),
            });
        }
        self.malformed(f, k, SHAPES);
    }

    fn canopy(&mut self, f: &mut Fields) -> Option<Program> {
        let grid = [f.number::<u32>("grid")?, f.second::<u32>("grid")?];
        let position = pair(f, "at")?;
        let range = pair(f, "range")?;
        let transmittance = f.number("transmittance")?;
        let image_file = f.has("image").then(|| quoted(f, "image")).flatten();
        let line = f.line().clone();
        let image = (image_file.as_deref())
            .and_then(|file| self.texture_image(file, &line))
            .map(|i| (*i).clone());
        Some(Program::Canopy(Canopy {
            grid: grid.map(|n| n.clamp(1, 4096)),
            position,
            range,
            transmittance,
            image_file,
            image,
            remove_old_leaves: f.has("remove-old-leaves"),
            z_is_up: !f.has("plane-xz"),
        }))
    }
}

fn density(f: &mut Fields) -> Option<Program> {
    Some(Program::Density(Density {
        radius: f.number("radius")?,
        three_d: f.has("3d"),
    }))
}

fn light(f: &mut Fields) -> Option<Program> {
    let grid = [
        f.number::<u32>("grid")?,
        f.second::<u32>("grid")?,
        f.third::<u32>("grid")?,
    ];
    let sources = sources(f);
    Some(Program::Light(Light {
        grid: grid.map(|n| n.clamp(1, 256)),
        transmittance: f.number("transmittance")?,
        lower_to_upper: f.number("lower-to-upper")?,
        samples: f.number::<u32>("samples")?.clamp(1, 100_000),
        radius: f.number("radius")?,
        beam_radius: f.number("beam")?,
        sources,
        estimate_area: f.has("estimate-area"),
        cie: f.has("cie"),
    }))
}

/// Every `source (x, y, z) w` of the line.
fn sources(f: &Fields) -> Vec<LightSource> {
    let vals = f.all();
    let mut out = Vec::new();
    for (k, v) in vals.iter().enumerate() {
        if !matches!(v, Val::Word(w, _) if w == "source") {
            continue;
        }
        if let (Some(Val::Tuple(parts, _)), Some(Val::Num(w, _))) =
            (vals.get(k + 1), vals.get(k + 2))
        {
            let xyz: Option<Vec<f64>> = parts.iter().map(|p| p.trim().parse().ok()).collect();
            if let (Some([x, y, z]), Ok(w)) = (xyz.as_deref(), w.parse()) {
                out.push(LightSource {
                    direction: [*x, *y, *z],
                    intensity: w,
                });
            }
        }
    }
    out.truncate(100);
    out
}

/// Every `segment (xa, ya) (xb, yb)` of the line.
fn pairs_after(f: &Fields, label: &str) -> Vec<[f64; 4]> {
    let vals = f.all();
    let two = |v: Option<&Val>| match v {
        Some(Val::Tuple(parts, _)) => match parts
            .iter()
            .map(|p| p.trim().parse().ok())
            .collect::<Option<Vec<f64>>>()
            .as_deref()
        {
            Some(&[x, y]) => Some([x, y]),
            _ => None,
        },
        _ => None,
    };
    let mut out = Vec::new();
    for (k, v) in vals.iter().enumerate() {
        if matches!(v, Val::Word(w, _) if w == label) {
            if let (Some(a), Some(b)) = (two(vals.get(k + 1)), two(vals.get(k + 2))) {
                out.push([a[0], a[1], b[0], b[1]]);
            }
        }
    }
    out.truncate(100);
    out
}

/// `(x, y)` after `label`.
fn pair(f: &mut Fields, label: &str) -> Option<[f64; 2]> {
    let [x, y, _] = f.pair_or_triple(label)?;
    Some([x, y])
}

/// The text in double quotes after `label`.
fn quoted(f: &mut Fields, label: &str) -> Option<String> {
    let w = f.word(label, &[])?;
    match w.strip_prefix('"').and_then(|w| w.strip_suffix('"')) {
        Some(inner) => Some(inner.to_string()),
        None => f.fail_at(label, "a format in double quotes"),
    }
}
