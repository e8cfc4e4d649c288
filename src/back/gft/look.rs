//! Rotations, tropisms, the STL structure, the look, surfaces and
//! contours as `.gft` lines.

use super::expr::num;
use super::words::Spelling;
use crate::ir::look::{Contour, ContourRole, LineStyle, Look, Shading, Tropism, TropismKind};
use crate::ir::texture::{Filter, Texture, TextureMode};
use crate::ir::{Angle, BranchEntry, BranchTerm, Growth, Rgb, SeedItem, Shape, Structure, System};
use crate::number;
use std::fmt::Write;

/// `#rrggbb`.
pub fn hex(c: Rgb) -> String {
    format!("#{:02x}{:02x}{:02x}", c.0, c.1, c.2)
}

/// Angles in degrees when a decimal of degrees gives each one back
/// exactly, else in radians followed by ` rad`.
pub fn degrees_or_radians(radians: &[f64]) -> String {
    let degrees: Vec<String> = radians.iter().map(|&r| number::degrees(r)).collect();
    let exact = (degrees.iter().zip(radians)).all(|(d, r)| {
        d.parse::<f64>()
            .is_ok_and(|d| d.to_radians().to_bits() == r.to_bits())
    });
    if exact {
        degrees.join(" ")
    } else {
        let r: Vec<String> = radians.iter().map(|&r| num(r)).collect();
        format!("{} rad", r.join(" "))
    }
}

fn triple(v: [f64; 3]) -> String {
    format!("({}, {}, {})", num(v[0]), num(v[1]), num(v[2]))
}

/// An `f32` triple: the shortest decimal that reads back as the same `f32`.
fn triple32(v: [f32; 3]) -> String {
    format!("({}, {}, {})", v[0], v[1], v[2])
}

/// A rotation's angle: radians, `[lo hi]`, or a multiple of `delta`.
fn rotation_angle(a: Angle) -> String {
    match a {
        Angle::Radians(r) => num(r),
        Angle::Uniform { lo, hi } => format!("[{} {}]", num(lo), num(hi)),
        Angle::Delta(f) => format!("{}*delta", num(f)),
    }
}

/// `rotation NAME = (TORSION, CURVATURE)`, in the system's order.
pub fn rotations(out: &mut String, sys: &System) {
    for r in &sys.rotations {
        let name = if r.name.is_empty() {
            String::new()
        } else {
            format!(" {}", r.name)
        };
        let (t, c) = (rotation_angle(r.torsion), rotation_angle(r.curvature));
        let _ = writeln!(out, "rotation{name} = ({t}, {c})");
    }
}

/// `tropism (x, y, z) angle A intensity I elasticity E step S [kind]`.
pub fn tropism(out: &mut String, t: &Tropism) {
    let kind = match t.kind {
        TropismKind::Bend => "",
        TropismKind::Torque => " torque",
        TropismKind::BendAfterStep => " after-step",
    };
    let _ = writeln!(
        out,
        "tropism {} angle {} intensity {} elasticity {} step {}{kind}",
        triple(t.vector),
        num(t.angle),
        num(t.intensity),
        num(t.elasticity),
        num(t.step)
    );
}

/// `R{e1, , ~}`. Recursion is as deep as the term, which the STL front
/// end keeps within `ir::MAX_NESTING`.
fn term(st: &Structure, t: &BranchTerm) -> String {
    let name = st
        .rules
        .get(t.rule.0 as usize)
        .map_or("", |r| r.name.as_str());
    if t.grows {
        // A growth point of a planted seed: the rule's name alone.
        return name.to_string();
    }
    let entries: Vec<String> = (t.entries.iter())
        .map(|e| match e {
            BranchEntry::Empty => String::new(),
            BranchEntry::Failed => "~".into(),
            BranchEntry::Term(c) => term(st, c),
        })
        .collect();
    format!("{name}{{{}}}", entries.join(", "))
}

fn shape(s: &Shape) -> String {
    let xy = |x: f64, y: f64| format!("({}, {})", num(x), num(y));
    match s {
        Shape::Rectangle { colour, x, y, w, h } => {
            format!(
                "rectangle {} {} {} {}",
                xy(*x, *y),
                num(*w),
                num(*h),
                hex(*colour)
            )
        }
        Shape::RoundRect {
            colour,
            x,
            y,
            w,
            h,
            corner,
        } => format!(
            "round-rectangle {} {} {} {} {}",
            xy(*x, *y),
            num(*w),
            num(*h),
            num(*corner),
            hex(*colour)
        ),
        Shape::Ellipse { colour, x, y, w, h } => {
            format!(
                "ellipse {} {} {} {}",
                xy(*x, *y),
                num(*w),
                num(*h),
                hex(*colour)
            )
        }
        Shape::Polygon { colour, points } => {
            let ps: Vec<String> = points.iter().map(|&(x, y)| xy(x, y)).collect();
            format!("polygon {} {}", ps.join(" "), hex(*colour))
        }
    }
}

/// Rules, stems, seed, outline and growth (docs/gft.md §8).
pub fn structure(out: &mut String, sys: &System, sp: &Spelling, st: &Structure) {
    let no_names = super::Names {
        locals: &[],
        globals: &[],
        arrays: &[],
    };
    for r in &st.rules {
        let _ = write!(
            out,
            "rule {} = {}",
            r.name,
            sp.word(&r.body, &[], &no_names)
        );
        if let Some(n) = r.resemblance {
            let _ = write!(out, " resemblance {n}");
        }
        if let Some(u) = r.unit.and_then(|u| st.rules.get(u.0 as usize)) {
            let _ = write!(out, " unit {}", u.name);
        }
        out.push('\n');
    }
    let (b, l) = (st.stems.broadness, st.stems.length);
    let _ = writeln!(
        out,
        "stems broadness {} {} length {} {}",
        num(b.0),
        num(b.1),
        num(l.0),
        num(l.1)
    );
    // An outline's seed as planted: reading it grows it again.
    let seed = if st.planted.is_empty() {
        &st.seed
    } else {
        &st.planted
    };
    let items: Vec<String> = (seed.iter())
        .map(|item| match item {
            SeedItem::Word(w) => sp.word(w, &[], &no_names),
            SeedItem::Term(t) => term(st, t),
        })
        .collect();
    let _ = writeln!(out, "seed {}", items.join(" "));
    let c = &st.constraint;
    if !c.outline.is_empty() {
        out.push_str("outline {\n");
        for s in &c.outline {
            let _ = writeln!(out, "  {}", shape(s));
        }
        out.push_str("}\n");
    }
    let strategy = match c.strategy {
        Growth::BreadthFirst => "breadth-first",
        Growth::DepthFirst => "depth-first",
    };
    let _ = writeln!(out, "growth {strategy} levels {}", c.levels);
    let _ = sys;
}

/// Background, camera, lighting, lights and materials (docs/gft.md §9).
pub fn look(out: &mut String, look: &Look) {
    if let Some(b) = look.background {
        let _ = writeln!(out, "background {}", hex(b));
    }
    if let Some(c) = &look.camera {
        let _ = write!(
            out,
            "camera eye {} target {} up {}",
            triple(c.eye),
            triple(c.target),
            triple(c.up)
        );
        if let Some(p) = c.perspective {
            let _ = write!(out, " perspective {}", num(p));
        }
        out.push('\n');
    }
    let Some(l) = &look.lighting else {
        return;
    };
    let shading = match l.shading {
        Shading::Filled => "filled",
        Shading::Wireframe => "wireframe",
        Shading::Flat => "flat",
        Shading::Smooth => "smooth",
    };
    let style = match l.line_style {
        LineStyle::Pixel => "pixel",
        LineStyle::Polygon => "polygon",
        LineStyle::Cylinder => "cylinder",
    };
    let tapered = if l.tapered { " tapered" } else { "" };
    let shadows = if l.shadows { " shadows" } else { "" };
    let _ = writeln!(
        out,
        "lighting {shading} line-style {style}{tapered}{shadows} index-shift {} surface-ambient {} surface-diffuse {}",
        num(l.index_shift),
        num(l.surface_ambient),
        num(l.surface_diffuse)
    );
    for light in &l.lights {
        let kind = if light.directional {
            "directional"
        } else {
            "point"
        };
        let _ = writeln!(
            out,
            "light {} {kind} ambient {} diffuse {} specular {}",
            triple(light.vector),
            triple32(light.ambient),
            triple32(light.diffuse),
            triple32(light.specular)
        );
    }
    for (i, m) in l.materials.iter().enumerate() {
        let Some(m) = m else {
            // A last empty slot keeps the list's length: `material N` alone.
            if i + 1 == l.materials.len() {
                let _ = writeln!(out, "material {i}");
            }
            continue;
        };
        let _ = writeln!(
            out,
            "material {i} ambient {} diffuse {} specular {} emission {} shininess {} transparency {}",
            triple32(m.ambient),
            triple32(m.diffuse),
            triple32(m.specular),
            triple32(m.emission),
            m.shininess,
            m.transparency
        );
    }
    for t in &l.textures {
        texture(out, t);
    }
}

/// Whether `.gft` can name the image file `file`: in double quotes, so
/// without a double quote or a line break.
pub fn names_file(file: &str) -> bool {
    !file.contains(['"', '\r', '\n'])
}

/// `texture "FILE" filter F mode M ratio R [surface-wide]` (docs/gft.md
/// §9); a file name `.gft` cannot quote is not written (the translation
/// says so, W0615).
fn texture(out: &mut String, t: &Texture) {
    if !names_file(&t.file) {
        return;
    }
    let filter = match t.filter {
        Filter::Nearest => "nearest",
        Filter::Linear => "linear",
    };
    let mode = match t.mode {
        TextureMode::Modulate => "modulate",
        TextureMode::Decal => "decal",
        TextureMode::Blend => "blend",
    };
    let wide = if t.per_surface { " surface-wide" } else { "" };
    let _ = writeln!(
        out,
        "texture \"{}\" filter {filter} mode {mode} ratio {}{wide}",
        t.file,
        num(t.ratio)
    );
}

/// Surfaces, one triangle per line, then contours, four points a line.
/// The look's scene: one `backdrop` block a polygon.
fn scene(out: &mut String, look: &Look) {
    for p in &look.scene {
        let _ = writeln!(out, "backdrop {} {} {{", hex(p.colour), p.index);
        let points: Vec<String> = p.points.iter().map(|q| triple(*q)).collect();
        let _ = writeln!(out, "  {}", points.join(" "));
        out.push_str("}\n");
    }
}

pub fn surfaces(out: &mut String, sys: &System) {
    scene(out, &sys.look);
    for s in &sys.surfaces {
        // The texture counted from 1, as `set-texture` counts them.
        let texture = s
            .texture
            .map_or(String::new(), |t| format!(" texture {}", u32::from(t) + 1));
        let _ = writeln!(out, "surface {}{texture} {{", s.name);
        for (k, t) in s.triangles.iter().enumerate() {
            let _ = write!(out, "  {} {} {}", triple(t[0]), triple(t[1]), triple(t[2]));
            // Each corner's texture coordinates on its patch; those across
            // the whole surface are derived again on reading.
            if let Some(uv) = s.patch_uvs.get(k) {
                let pairs: Vec<String> = uv
                    .iter()
                    .map(|p| format!("({}, {})", num(p[0]), num(p[1])))
                    .collect();
                let _ = write!(out, " {}", pairs.join(" "));
            }
            out.push('\n');
        }
        out.push_str("}\n");
    }
    for c in &sys.contours {
        contour(out, c);
    }
}

fn contour(out: &mut String, c: &Contour) {
    let role = match c.role {
        ContourRole::CrossSection => "cross-section",
        ContourRole::Curve => "curve",
    };
    let closed = if c.closed { "closed" } else { "open" };
    let _ = writeln!(
        out,
        "contour {} {role} {closed} length {} {{",
        c.id,
        num(c.length)
    );
    for row in c.points.chunks(4) {
        let ps: Vec<String> = row.iter().map(|&p| triple(p)).collect();
        let _ = writeln!(out, "  {}", ps.join(" "));
    }
    out.push_str("}\n");
}
