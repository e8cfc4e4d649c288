//! The cpfg view file (`.v`, manual §8.1 and §9): drawing parameters (angle,
//! line width, colours, elasticity), the view (viewpoint, projection, scale),
//! rendering switches and the names of the surface, contour and function
//! files. Values not given keep the manual's defaults ([`View::default`]).
//!
//! Lines are `command: value`; C comments (`/* */`, and `//` as some corpus
//! files use) are ignored, later commands win. Unknown commands are warned
//! about and skipped, as cpfg skips them; commands graftal reads but does not
//! use (lights, textures, fonts, …) are listed in [`View::unused`].

use crate::diagnostics::{codes, nearest, Diagnostic, Diagnostics};
use crate::ir::texture::{Filter, TextureMode};
use crate::ir::{Rgb, Span};
use std::path::{Path, PathBuf};

/// Units of the line width.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WidthUnit {
    /// Flat lines, width in pixels (`pixels`, `p`; the default).
    Pixels,
    /// Polygons or cylinders, width in world units (`shaded`, `s`, or a
    /// `line style:` other than `pixel`).
    World,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineStyle {
    Pixel,
    Polygon,
    Cylinder,
    /// Not in the manual, but seven vlab view files write `line style:
    /// wireframe`; lines are then drawn like `pixel` lines.
    Wireframe,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Projection {
    Parallel,
    Perspective,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RenderMode {
    Filled,
    Fast,
    Wireframe,
    Interpolated,
    Flat,
    Shaded,
    Shadows,
}

/// A `surface:` (or `line:`) command: `surface: id file.s scale [i j] [texture]`.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceRef {
    /// The character after `~` that draws it.
    pub id: char,
    pub file: String,
    pub scale: f64,
    /// Polygons along the rows and columns of a patch (0 = cpfg's default).
    pub s_divisions: u32,
    pub t_divisions: u32,
    pub texture: Option<String>,
    /// The view file's line that names it.
    pub line: Span,
}

/// A `contour:` (`contour: id file.con`, a cross-section of generalized
/// cylinders) or a `curve:` (`curve: file`, read by `curveX(id, t)`: its id
/// is its place among the `curve:` lines, from 1).
/// A `texture:` command (manual §8.1.7): `F: file`, `H:`/`L:` filters,
/// `E:` mode, `S:` (per surface), `R: ratio`. Numbered from 1 in the order
/// of the view file, as `@Tx(n)` names them.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureRef {
    pub file: String,
    pub filter: Filter,
    pub mode: TextureMode,
    pub per_surface: bool,
    pub ratio: f64,
    pub line: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct ContourRef {
    pub id: u32,
    pub file: String,
}

/// A `tropism:` or `torque:` command (manual §8.1.8). Both share one list
/// and one numbering (cpfg's movements), in the order of the file.
#[derive(Clone, Debug, PartialEq)]
pub struct Tropism {
    /// `T:` the tropism vector.
    pub vector: [f64; 3],
    /// `A:` the angle (degrees) to the vector segments try to reach.
    pub angle: f64,
    /// `I:` intensity, when given.
    pub intensity: Option<f64>,
    /// `E:` initial elasticity.
    pub elasticity: f64,
    /// `S:` elasticity step.
    pub step: f64,
    /// A `torque:` (twists about H) rather than a `tropism:`.
    pub torque: bool,
}

impl Default for Tropism {
    fn default() -> Self {
        Tropism {
            vector: [0.0, 1.0, 0.0],
            angle: 0.0,
            intensity: None,
            elasticity: 0.0,
            step: 0.0,
            torque: false,
        }
    }
}

/// Everything a view file sets. [`Default`] gives the manual's defaults.
#[derive(Clone, Debug, PartialEq)]
pub struct View {
    /// The angle of `+ - & ^ \ / |`, in degrees: `angle increment: a` or
    /// 360/n from `angle factor: n`; 45° by default.
    pub angle: f64,
    pub initial_line_width: f64,
    pub line_width_unit: WidthUnit,
    pub line_width_increment: f64,
    pub initial_color: u32,
    /// The optional second index of `initial color:` (back of surfaces).
    pub initial_back_color: Option<u32>,
    pub color_increment: u32,
    /// `initial elasticity:` (deprecated; the tropism's `E:` in new files).
    pub initial_elasticity: f64,
    pub elasticity_increment: f64,
    /// `initial scale:` of the turtle.
    pub initial_scale: f64,
    /// Size of the image on the screen (1 = full size).
    pub scale_factor: f64,
    pub viewpoint: [f64; 3],
    pub view_reference_point: [f64; 3],
    /// Rotation of the image on the screen, in tenths of a degree.
    pub twist: f64,
    pub projection: Projection,
    /// Viewing angle of the perspective projection, degrees.
    pub viewing_angle: f64,
    pub front_distance: f64,
    pub back_distance: f64,
    /// `box:` x, y and z ranges, when given.
    pub bounding_box: Option<[[f64; 2]; 3]>,
    /// `tropism direction:` (deprecated form of a tropism's `T:`).
    pub tropism_direction: Option<[f64; 3]>,
    /// `tropism:` and `torque:` commands, in order (ids from 1).
    pub tropisms: Vec<Tropism>,
    /// `function:` files in order: `func(k, x)` is `functions[k-1]`.
    pub functions: Vec<String>,
    /// The precomputed sample count of each `function:` (`None`: exact).
    pub function_samples: Vec<Option<u32>>,
    pub function_sets: Vec<String>,
    pub surfaces: Vec<SurfaceRef>,
    /// `texture:` commands, numbered from 1 in this order.
    pub textures: Vec<TextureRef>,
    /// `line:` commands (lines drawn with a surface).
    pub lines: Vec<SurfaceRef>,
    pub contours: Vec<ContourRef>,
    /// `curve:` files, ids in order from 1.
    pub curves: Vec<ContourRef>,
    pub contour_sides: u32,
    pub tapered_lines: bool,
    pub line_style: LineStyle,
    pub render_mode: RenderMode,
    pub z_buffer: bool,
    /// `interpretation past %:`.
    pub interpret_past_cut: bool,
    /// `environment display:`: the environment is asked after each step
    /// (and of the axiom) rather than before each.
    pub environment_after_step: bool,
    pub twist_of_cylinders: bool,
    /// `light:` commands (material mode), in order.
    pub lights: Vec<crate::ir::look::Light>,
    /// `light direction:` (colour-map mode).
    pub light_direction: [f64; 3],
    /// `diffuse reflection:`, `surface ambient:`, `surface diffuse:`
    /// (colour-map shading, manual §8.1.3).
    pub diffuse_reflection: f64,
    pub surface_ambient: f64,
    pub surface_diffuse: f64,
    /// Commands read but not used by graftal (lights, textures, fonts, …),
    /// with the span of each line.
    pub unused: Vec<(String, Span)>,
    /// The view file read, and its text, for what is found wrong with the
    /// files it names after it was read.
    pub source: Option<(PathBuf, String)>,
    /// `background scene:` files, each with its line.
    pub scenes: Vec<(String, Span)>,
}

impl Default for View {
    fn default() -> Self {
        View {
            angle: 45.0,
            initial_line_width: 1.0,
            line_width_unit: WidthUnit::Pixels,
            line_width_increment: 0.0,
            initial_color: 128,
            initial_back_color: None,
            color_increment: 1,
            initial_elasticity: 0.0,
            elasticity_increment: 0.0,
            initial_scale: 1.0,
            scale_factor: 1.0,
            viewpoint: [0.0, 0.0, 1.0],
            view_reference_point: [0.0, 0.0, 0.0],
            twist: 0.0,
            projection: Projection::Parallel,
            viewing_angle: 45.0,
            front_distance: -100000.0,
            back_distance: 100000.0,
            bounding_box: None,
            tropism_direction: None,
            tropisms: Vec::new(),
            functions: Vec::new(),
            function_samples: Vec::new(),
            function_sets: Vec::new(),
            surfaces: Vec::new(),
            textures: Vec::new(),
            lines: Vec::new(),
            contours: Vec::new(),
            curves: Vec::new(),
            contour_sides: 3,
            tapered_lines: true,
            line_style: LineStyle::Pixel,
            render_mode: RenderMode::Filled,
            z_buffer: true,
            interpret_past_cut: true,
            environment_after_step: false,
            twist_of_cylinders: false,
            lights: Vec::new(),
            light_direction: [1.0, 0.0, 0.0],
            diffuse_reflection: 10.0,
            surface_ambient: 0.15,
            surface_diffuse: 0.75,
            unused: Vec::new(),
            source: None,
            scenes: Vec::new(),
        }
    }
}

/// Commands that change cpfg's picture and that graftal does not draw:
/// each is a warning at its line.
const NOT_DRAWN: &[(&str, &str)] = &[("tsurface", "the rayshade surfaces are not drawn")];

/// Commands cpfg knows that graftal reads and needs not use: interactive
/// settings, fonts, deprecated commands cpfg itself ignores, and the
/// shadow map a ray tracer does without.
const UNUSED: &[&str] = &[
    "antialiasing",
    "concave polygons",
    "font",
    "min zoom",
    "max zoom",
    "generate on view change",
    "scale multiplier",
    "polygonization level",
    "ambient light",
    "background color",
    "cue range",
    "interpretation step",
    // Shadows (`render mode: shadows`) are ray traced: exact, no map.
    "shadow map",
];

const KNOWN: &[&str] = &[
    "angle increment",
    "angle factor",
    "initial color",
    "color increment",
    "initial line width",
    "line width increment",
    "initial scale",
    "interpretation past %",
    "environment display",
    "viewpoint",
    "view reference point",
    "twist",
    "projection",
    "viewing angle",
    "front distance",
    "back distance",
    "scale factor",
    "box",
    "line style",
    "tapered lines",
    "line",
    "contour",
    "curve",
    "contour sides",
    "twist of cylinders",
    "surface",
    "function",
    "function set",
    "tropism",
    "torque",
    "tropism direction",
    "initial elasticity",
    "elasticity increment",
    "render mode",
    "shade mode",
    "z buffer",
    "background scene",
    "texture",
    "tsurface",
    "shadow map",
    "light",
    "light direction",
    "diffuse reflection",
    "surface ambient",
    "surface diffuse",
];

/// Reads a view file. Never fails: problems are diagnostics, and the
/// commands they concern keep their defaults.
pub fn read_view(text: &str) -> (View, Diagnostics) {
    let mut v = View::default();
    let mut d = Diagnostics::default();
    let clean = blank_comments(text);
    let mut at = 0;
    for line in clean.split_inclusive('\n') {
        let start = at;
        at += line.len();
        if let Some(c) = command_at(line, start, &mut d) {
            apply(&mut v, &c, &mut d);
        }
    }
    (v, d)
}

/// One `command: value` line of a view file.
struct Command<'a> {
    /// The command's name in lower case, its words joined by single spaces.
    name: String,
    value: &'a str,
    /// The whole line, without its surrounding blanks.
    span: Span,
    name_span: Span,
    value_span: Span,
}

impl Command<'_> {
    /// Reports a value that is not the `what` the command expects.
    fn bad(&self, d: &mut Diagnostics, what: &str) {
        // The vlab exercises (snowflake-exercise) leave `?` where the
        // student writes a value: say so, not only that `?` is no number.
        if self.value.trim() == "?" {
            return d.push(
                Diagnostic::at(
                    codes::CPFG_VIEW_BLANK,
                    self.value_span.clone(),
                    format!(
                        "`{}:` is left as `?`: the object is an exercise with blanks to fill in",
                        self.name
                    ),
                )
                .with_label(format!("write {what} here"))
                .with_help("fill in every field marked `?`, in the view file and the `.l` file"),
            );
        }
        d.push(
            Diagnostic::at(
                codes::CPFG_VIEW_VALUE,
                self.value_span.clone(),
                format!("`{}:` expects {what}; the line is ignored", self.name),
            )
            .with_label(format!("not {what}")),
        );
    }
}

/// The command on a line starting at byte `start` of the text: `None` for a
/// blank line, and for a line without a colon, which is reported.
fn command_at<'a>(line: &'a str, start: usize, d: &mut Diagnostics) -> Option<Command<'a>> {
    let body = line.trim_end();
    let lead = body.len() - body.trim_start().len();
    let body = body.trim_start();
    if body.is_empty() {
        return None;
    }
    let span = start + lead..start + lead + body.len();
    let Some(colon) = body.find(':') else {
        d.push(
            Diagnostic::at(
                codes::CPFG_UNKNOWN_VIEW_COMMAND,
                span,
                "line without `command:` is ignored",
            )
            .with_label("not a view command"),
        );
        return None;
    };
    let raw_name = &body[..colon];
    let name = raw_name
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .to_ascii_lowercase();
    let after = &body[colon + 1..];
    let value = after.trim();
    let value_start = span.start + colon + 1 + (after.len() - after.trim_start().len());
    Some(Command {
        name,
        value,
        name_span: span.start..span.start + raw_name.trim_end().len(),
        value_span: value_start..value_start + value.len(),
        span,
    })
}

/// Applies one command to the view: each group of commands below returns
/// whether it knew the command.
fn apply(v: &mut View, c: &Command, d: &mut Diagnostics) {
    let known = set_drawing(v, c, d)
        || set_forces(v, c, d)
        || set_camera(v, c, d)
        || set_rendering(v, c, d)
        || set_lights(v, c, d)
        || add_file(v, c, d);
    if !known {
        note_other(v, c, d);
    }
}

/// The turtle's angle, colours, widths and scale.
fn set_drawing(v: &mut View, c: &Command, d: &mut Diagnostics) -> bool {
    match c.name.as_str() {
        "angle increment" => match num(c.value) {
            Some(a) => v.angle = a,
            None => c.bad(d, "a number of degrees"),
        },
        "angle factor" => match num(c.value) {
            Some(n) if n != 0.0 => v.angle = 360.0 / n,
            _ => c.bad(d, "a non-zero number"),
        },
        "initial color" => {
            let ns = nums(c.value);
            match ns.first() {
                Some(&col) if col >= 0.0 => {
                    v.initial_color = col as u32;
                    v.initial_back_color = ns.get(1).map(|&b| b.max(0.0) as u32);
                }
                _ => c.bad(d, "a colour index"),
            }
        }
        "color increment" => match num(c.value) {
            Some(inc) => v.color_increment = inc.max(0.0) as u32,
            None => c.bad(d, "a number"),
        },
        "initial line width" => set_line_width(v, c, d),
        "line width increment" => set_num(&mut v.line_width_increment, c, d),
        "initial scale" => set_num(&mut v.initial_scale, c, d),
        _ => return false,
    }
    true
}

/// `initial line width: w [style]`: as cpfg's `ReadViewData` reads it, the
/// style is a polygon in world units unless the word after the width
/// starts with `p` (pixels) or `s` (shaded cylinders, world units).
fn set_line_width(v: &mut View, c: &Command, d: &mut Diagnostics) {
    let Some(w) = num(c.value) else {
        c.bad(d, "a number");
        return;
    };
    v.initial_line_width = w;
    let unit = c
        .value
        .split_whitespace()
        .nth(1)
        .unwrap_or("")
        .to_ascii_lowercase();
    let (unit, style) = match unit.chars().next() {
        Some('p') => (WidthUnit::Pixels, LineStyle::Pixel),
        Some('s') => (WidthUnit::World, LineStyle::Cylinder),
        None => (WidthUnit::World, LineStyle::Polygon),
        Some(_) => {
            c.bad(d, "a width and `pixels` or `shaded`");
            (WidthUnit::World, LineStyle::Polygon)
        }
    };
    v.line_width_unit = unit;
    v.line_style = style;
}

/// Tropisms, torques and elasticity (manual §8.1.8).
fn set_forces(v: &mut View, c: &Command, d: &mut Diagnostics) -> bool {
    match c.name.as_str() {
        "initial elasticity" => set_num(&mut v.initial_elasticity, c, d),
        "elasticity increment" => set_num(&mut v.elasticity_increment, c, d),
        "tropism direction" => {
            let mut t = [0.0; 3];
            if set_vec(&mut t, c, d) {
                v.tropism_direction = Some(t);
            }
        }
        "tropism" | "torque" => match tropism(c.value) {
            Some(t) => v.tropisms.push(Tropism {
                torque: c.name == "torque",
                ..t
            }),
            None => c.bad(d, "subcommands with a non-zero `T: x y z`"),
        },
        _ => return false,
    }
    true
}

/// Where the view looks from and how it projects.
fn set_camera(v: &mut View, c: &Command, d: &mut Diagnostics) -> bool {
    match c.name.as_str() {
        "scale factor" => set_num(&mut v.scale_factor, c, d),
        "viewing angle" => set_num(&mut v.viewing_angle, c, d),
        "front distance" => set_num(&mut v.front_distance, c, d),
        "back distance" => set_num(&mut v.back_distance, c, d),
        "twist" => set_num(&mut v.twist, c, d),
        "viewpoint" => {
            set_vec(&mut v.viewpoint, c, d);
        }
        "view reference point" => {
            set_vec(&mut v.view_reference_point, c, d);
        }
        "projection" => match c.value.to_ascii_lowercase().as_str() {
            "parallel" => v.projection = Projection::Parallel,
            "perspective" => v.projection = Projection::Perspective,
            _ => c.bad(d, "`parallel` or `perspective`"),
        },
        "box" => set_box(v, c, d),
        _ => return false,
    }
    true
}

/// `box: x: min,max y: min,max z: min,max`; an axis not given keeps 0..1.
fn set_box(v: &mut View, c: &Command, d: &mut Diagnostics) {
    let subs = subcommands(c.value);
    let mut b = [[0.0, 1.0]; 3];
    let mut ok = true;
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        match subs.iter().find(|(n, _)| n.eq_ignore_ascii_case(axis)) {
            Some((_, vals)) if vals.len() >= 2 => b[k] = [vals[0], vals[1]],
            Some(_) => ok = false,
            None => {}
        }
    }
    if ok {
        v.bounding_box = Some(b);
    } else {
        c.bad(d, "`x: min,max y: min,max z: min,max`");
    }
}

/// How lines and surfaces are drawn.
fn set_rendering(v: &mut View, c: &Command, d: &mut Diagnostics) -> bool {
    match c.name.as_str() {
        "line style" => set_line_style(v, c, d),
        "render mode" => set_render_mode(v, c, d),
        "shade mode" => set_shade_mode(v, c, d),
        "z buffer" => set_flag(&mut v.z_buffer, c, d),
        "tapered lines" => set_flag(&mut v.tapered_lines, c, d),
        "tappered lines" => {
            d.push(
                Diagnostic::at(
                    codes::CPFG_DEPRECATED_VIEW_SPELLING,
                    c.name_span.clone(),
                    "`tappered lines` read as `tapered lines`",
                )
                .with_label("misspelt")
                .with_note("old cpfg versions accepted this spelling")
                .with_help("write `tapered lines:`"),
            );
            set_flag(&mut v.tapered_lines, c, d);
        }
        "twist of cylinders" => set_flag(&mut v.twist_of_cylinders, c, d),
        "interpretation past %" => set_flag(&mut v.interpret_past_cut, c, d),
        "environment display" => set_flag(&mut v.environment_after_step, c, d),
        "contour sides" => match num(c.value) {
            Some(n) if n >= 1.0 => v.contour_sides = n as u32,
            _ => c.bad(d, "a positive number"),
        },
        _ => return false,
    }
    true
}

/// Lights: `light:` in material mode, the rest in colour-map mode.
fn set_lights(v: &mut View, c: &Command, d: &mut Diagnostics) -> bool {
    match c.name.as_str() {
        "light" => match light(c.value) {
            Some(l) => v.lights.push(l),
            None => c.bad(d, "subcommands such as `V: x y z` or `O: x y z`"),
        },
        "light direction" => {
            set_vec(&mut v.light_direction, c, d);
        }
        "diffuse reflection" => set_num(&mut v.diffuse_reflection, c, d),
        "surface ambient" => set_num(&mut v.surface_ambient, c, d),
        "surface diffuse" => set_num(&mut v.surface_diffuse, c, d),
        "texture" => match texture_ref(c.value, c.span.clone()) {
            Some(t) => v.textures.push(t),
            None => c.bad(d, "`F: file` and subcommands `H:`, `L:`, `E:`, `S:`, `R:`"),
        },
        _ => return false,
    }
    true
}

/// A `light:` command's subcommands (manual §8.1.3): `O:` a point light's
/// position, `V:` a directional light's vector, `A:`, `D:`, `S:` its
/// colours; `P:` (spotlight) and `T:` (attenuation) are accepted and not
/// used.
fn light(value: &str) -> Option<crate::ir::look::Light> {
    let mut l = crate::ir::look::Light::default();
    let rgb = |v: &[f64]| [v[0] as f32, v[1] as f32, v[2] as f32];
    for (k, vals) in subcommands(value) {
        match (k.to_ascii_uppercase().as_str(), vals.as_slice()) {
            ("O", [x, y, z, ..]) => (l.vector, l.directional) = ([*x, *y, *z], false),
            ("V", [x, y, z, ..]) => (l.vector, l.directional) = ([*x, *y, *z], true),
            ("A", v @ [_, _, _, ..]) => l.ambient = rgb(v),
            ("D", v @ [_, _, _, ..]) => l.diffuse = rgb(v),
            ("S", v @ [_, _, _, ..]) => l.specular = rgb(v),
            ("P" | "T", _) => {}
            _ => return None,
        }
    }
    Some(l)
}

/// `line style:` sets the unit of the line width with the style.
fn set_line_style(v: &mut View, c: &Command, d: &mut Diagnostics) {
    let (style, unit) = match c.value.to_ascii_lowercase().as_str() {
        "pixel" | "pixels" => (LineStyle::Pixel, WidthUnit::Pixels),
        "polygon" | "polygons" => (LineStyle::Polygon, WidthUnit::World),
        "cylinder" | "cylinders" => (LineStyle::Cylinder, WidthUnit::World),
        "wireframe" => (LineStyle::Wireframe, WidthUnit::Pixels),
        _ => return c.bad(d, "`pixel`, `polygon` or `cylinder`"),
    };
    v.line_style = style;
    v.line_width_unit = unit;
}

fn set_render_mode(v: &mut View, c: &Command, d: &mut Diagnostics) {
    let m = match c.value.to_ascii_lowercase().as_str() {
        "filled" => RenderMode::Filled,
        "fast" => RenderMode::Fast,
        "wireframe" => RenderMode::Wireframe,
        "interpolated" => RenderMode::Interpolated,
        "flat" => RenderMode::Flat,
        "shaded" => RenderMode::Shaded,
        "shadows" => RenderMode::Shadows,
        _ => return c.bad(d, "a render mode (filled, wireframe, shaded, …)"),
    };
    v.render_mode = m;
}

/// The deprecated `shade mode: i` (manual §8.1.10), read as the render
/// mode it stands for: 1 simple fill, 2 interpolated, 3 Gouraud, 4 and 5
/// B-spline (filled), 6 two-sided (shaded), 7 wireframe.
fn set_shade_mode(v: &mut View, c: &Command, d: &mut Diagnostics) {
    v.render_mode = match num(c.value).map(|x| x as i64) {
        Some(1 | 4 | 5) => RenderMode::Filled,
        Some(2) => RenderMode::Interpolated,
        Some(3 | 6) => RenderMode::Shaded,
        Some(7) => RenderMode::Wireframe,
        _ => return c.bad(d, "a shade mode from 1 to 7"),
    };
}

/// The function, surface and contour files the view names.
fn add_file(v: &mut View, c: &Command, d: &mut Diagnostics) -> bool {
    match c.name.as_str() {
        "function" => {
            let mut w = c.value.split_whitespace();
            match w.next() {
                Some(f) => {
                    v.functions.push(f.to_string());
                    v.function_samples
                        .push(w.next().and_then(num).map(|n| n.max(0.0) as u32));
                }
                None => c.bad(d, "a file name"),
            }
        }
        "function set" => match c.value.split_whitespace().next() {
            Some(f) => v.function_sets.push(f.to_string()),
            None => c.bad(d, "a file name"),
        },
        "surface" | "line" => match surface_ref(c.value, c.span.clone()) {
            Some(s) if c.name == "surface" => v.surfaces.push(s),
            Some(s) => v.lines.push(s),
            None => c.bad(d, "`id file.s scale`"),
        },
        "contour" => {
            let mut w = c.value.split_whitespace();
            match (w.next().and_then(num), w.next()) {
                (Some(id), Some(f)) => v.contours.push(ContourRef {
                    id: id.max(0.0) as u32,
                    file: f.to_string(),
                }),
                _ => c.bad(d, "`id file.con`"),
            }
        }
        "background scene" => {
            let names = c
                .value
                .split([' ', '\t', ',', ';'])
                .filter(|n| !n.is_empty());
            let before = v.scenes.len();
            v.scenes
                .extend(names.map(|n| (n.to_string(), c.span.clone())));
            if v.scenes.len() == before {
                c.bad(d, "a file name");
            }
        }
        "curve" => match c.value.split_whitespace().next() {
            Some(f) => {
                let id = v.curves.len() as u32 + 1;
                v.curves.push(ContourRef {
                    id,
                    file: f.to_string(),
                })
            }
            None => c.bad(d, "a file name"),
        },
        _ => return false,
    }
    true
}

/// A command graftal does not use is listed; one cpfg does not know is
/// reported, with the nearest known name.
fn note_other(v: &mut View, c: &Command, d: &mut Diagnostics) {
    let name = c.name.as_str();
    if let Some((_, what)) = NOT_DRAWN.iter().find(|(n, _)| *n == name) {
        d.push(
            Diagnostic::at(
                codes::CPFG_VIEW_NOT_DRAWN,
                c.span.clone(),
                format!("`{name}:` is not drawn by graftal: {what}"),
            )
            .with_label("read, not drawn"),
        );
        return;
    }
    if UNUSED.contains(&name) {
        v.unused.push((name.to_string(), c.span.clone()));
        return;
    }
    let mut all: Vec<&str> = KNOWN.to_vec();
    all.extend_from_slice(UNUSED);
    let mut diag = Diagnostic::at(
        codes::CPFG_UNKNOWN_VIEW_COMMAND,
        c.name_span.clone(),
        format!("unknown view command `{name}` is ignored"),
    )
    .with_label("not a view command");
    if let Some(s) = nearest(name, &all).first() {
        let help = format!("did you mean `{s}:`?");
        diag = diag.with_fix(c.name_span.clone(), s.to_string(), help);
    }
    d.push(diag);
}

fn set_num(slot: &mut f64, c: &Command, d: &mut Diagnostics) {
    match num(c.value) {
        Some(x) => *slot = x,
        None => c.bad(d, "a number"),
    }
}

fn set_vec(slot: &mut [f64; 3], c: &Command, d: &mut Diagnostics) -> bool {
    let ns = nums(c.value);
    if ns.len() >= 3 {
        *slot = [ns[0], ns[1], ns[2]];
        true
    } else {
        c.bad(d, "three numbers `x,y,z`");
        false
    }
}

fn set_flag(slot: &mut bool, c: &Command, d: &mut Diagnostics) {
    match c
        .value
        .split_whitespace()
        .next()
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        Some("on" | "yes" | "1") => *slot = true,
        Some("off" | "no" | "0") => *slot = false,
        _ => c.bad(d, "`on` or `off`"),
    }
}

/// The leading number of a value (`2 pixels` → 2), as C's `atof` reads it
/// but requiring at least one digit.
fn num(s: &str) -> Option<f64> {
    let s = s.trim_start();
    let b = s.as_bytes();
    let mut i = 0;
    if matches!(b.first(), Some(b'+' | b'-')) {
        i += 1;
    }
    let digits_start = i;
    while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'.') {
        i += 1;
    }
    if !b[digits_start..i].iter().any(u8::is_ascii_digit) {
        return None;
    }
    if i < b.len() && matches!(b[i], b'e' | b'E') {
        let mut j = i + 1;
        if matches!(b.get(j), Some(b'+' | b'-')) {
            j += 1;
        }
        if b.get(j).is_some_and(u8::is_ascii_digit) {
            i = j;
            while i < b.len() && b[i].is_ascii_digit() {
                i += 1;
            }
        }
    }
    s[..i].parse().ok().filter(|x: &f64| x.is_finite())
}

/// All numbers of a value separated by commas or spaces.
fn nums(s: &str) -> Vec<f64> {
    s.split([',', ' ', '\t'])
        .filter(|w| !w.is_empty())
        .map_while(num)
        .collect()
}

/// `X: a b c Y: d …` → [("X", [a, b, c]), ("Y", [d])]; `A:90` works too.
fn subcommands(s: &str) -> Vec<(String, Vec<f64>)> {
    let mut out: Vec<(String, Vec<f64>)> = Vec::new();
    for w in s.split([' ', '\t', ',']).filter(|w| !w.is_empty()) {
        let (key, rest) = match w.find(':') {
            Some(k) => (Some(&w[..k]), &w[k + 1..]),
            None => (None, w),
        };
        if let Some(k) = key {
            out.push((k.to_string(), Vec::new()));
        }
        if !rest.is_empty() {
            if let (Some(x), Some(last)) = (num(rest), out.last_mut()) {
                last.1.push(x);
            }
        }
    }
    out
}

fn tropism(value: &str) -> Option<Tropism> {
    let mut t = Tropism::default();
    let mut has_t = false;
    for (k, vals) in subcommands(value) {
        match (k.to_ascii_uppercase().as_str(), vals.as_slice()) {
            ("T", [x, y, z, ..]) => {
                t.vector = [*x, *y, *z];
                has_t = true;
            }
            ("A", [a, ..]) => t.angle = *a,
            ("I", [i, ..]) => t.intensity = Some(*i),
            ("E", [e, ..]) => t.elasticity = *e,
            ("S", [s, ..]) => t.step = *s,
            _ => return None,
        }
    }
    // cpfg ignores a tropism without direction or intensity.
    let pulls = t.vector != [0.0; 3] && t.intensity != Some(0.0);
    (has_t && pulls).then_some(t)
}

/// A `texture:` command's subcommands, as cpfg's `read_texture` reads
/// them: a letter, then (but for `S:`) a word. `L:` (the filter for
/// texels smaller than pixels, mipmaps included) is read and not used: the
/// pictures read textures through `H:`'s filter. The file is mandatory; an
/// unknown subcommand makes cpfg drop the line, as here.
fn texture_ref(value: &str, line: Span) -> Option<TextureRef> {
    let mut words = value.split([' ', '\t', ':', ',']).filter(|w| !w.is_empty());
    let mut t = TextureRef {
        file: String::new(),
        filter: Filter::Nearest,
        mode: TextureMode::Modulate,
        per_surface: false,
        ratio: 1.0,
        line,
    };
    while let Some(key) = words.next() {
        match key.chars().next()? {
            'F' => t.file = words.next()?.to_string(),
            'H' => {
                if let Some(f) = words.next()?.chars().next() {
                    t.filter = if f == 'l' { Filter::Linear } else { t.filter };
                }
            }
            'L' => {
                words.next()?;
            }
            'E' => {
                t.mode = match words.next()?.chars().next() {
                    Some('d') => TextureMode::Decal,
                    Some('b') => TextureMode::Blend,
                    Some('m') => TextureMode::Modulate,
                    _ => t.mode,
                }
            }
            'S' => t.per_surface = true,
            'R' => t.ratio = words.next().and_then(num).unwrap_or(t.ratio),
            _ => return None,
        }
    }
    (!t.file.is_empty()).then_some(t)
}

fn surface_ref(value: &str, line: Span) -> Option<SurfaceRef> {
    let w: Vec<&str> = value.split_whitespace().collect();
    let mut id_chars = w.first()?.chars();
    let id = id_chars.next()?;
    if id_chars.next().is_some() {
        return None;
    }
    let file = w.get(1)?.to_string();
    let scale = num(w.get(2)?)?;
    let s = w.get(3).and_then(|x| num(x));
    let t = w.get(4).and_then(|x| num(x));
    let texture_at = 3 + usize::from(s.is_some()) + usize::from(t.is_some());
    Some(SurfaceRef {
        id,
        file,
        scale,
        s_divisions: s.map_or(0, |x| x.max(0.0) as u32),
        t_divisions: t.map_or(0, |x| x.max(0.0) as u32),
        texture: w.get(texture_at).map(|x| x.to_string()),
        line,
    })
}

/// The text with `/* */` and `//` comments replaced by spaces, byte for
/// byte (line breaks kept).
fn blank_comments(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = b.to_vec();
    let mut i = 0;
    while i < b.len() {
        let end = if b[i..].starts_with(b"/*") {
            text[i + 2..].find("*/").map_or(b.len(), |k| i + 2 + k + 2)
        } else if b[i..].starts_with(b"//") {
            text[i..].find('\n').map_or(b.len(), |k| i + k)
        } else {
            i += 1;
            continue;
        };
        for c in &mut out[i..end] {
            if *c != b'\n' {
                *c = b' ';
            }
        }
        i = end;
    }
    String::from_utf8(out).unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned())
}

/// Whether a `.v` file is a vlab control panel (`panel name:` …, `type:
/// SLIDER`) rather than a view file.
pub fn is_panel(text: &str) -> bool {
    let first = text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty())
        .unwrap_or("");
    first.starts_with("panel name:")
        || text.lines().any(|l| {
            matches!(
                l.trim(),
                "type: SLIDER" | "type: BUTTON" | "type: MENU" | "type: LABEL"
            )
        })
}

/// Why an object has no view file to read.
#[derive(Clone, Debug, PartialEq)]
pub enum NoView {
    /// The `cpfg` line of `specifications` names this view file, and it is
    /// not in the folder.
    Named(String),
    /// Nothing names one, and the folder holds none (or several, none
    /// named like the `.l`).
    Absent,
}

/// The view file of the L-system `l_file` in `dir`: the `.v` with the same
/// stem; else the `.v` named after `l_file` on the `cpfg …` line of the
/// folder's `specifications` file; else the folder's only view file. Panel
/// files named `*.v` are never taken; names match in any case (L-studio's
/// objects were written on Windows).
pub fn find_view(dir: &Path, l_file: &str) -> Result<PathBuf, NoView> {
    let is_view = |p: &Path| {
        std::fs::read(p)
            .ok()
            .is_some_and(|b| !is_panel(&String::from_utf8_lossy(&b)))
    };
    let stem = Path::new(l_file)
        .file_stem()
        .map_or(String::new(), |s| s.to_string_lossy().into_owned());
    if let Some(same) = super::folder::find_any_case(dir, &format!("{stem}.v")) {
        if is_view(&same) {
            return Ok(same);
        }
    }
    let named = named_in_specifications(dir, l_file);
    if let Some(v) = &named {
        match super::folder::find_any_case(dir, v) {
            Some(p) if is_view(&p) => return Ok(p),
            _ => {}
        }
    }
    let mut views: Vec<PathBuf> = (super::folder::with_extension(dir, "v").unwrap_or_default())
        .into_iter()
        .map(|n| dir.join(n))
        .filter(|p| is_view(p))
        .collect();
    match (views.len(), named) {
        (1, _) => Ok(views.remove(0)),
        (_, Some(v)) => Err(NoView::Named(v)),
        (_, None) => Err(NoView::Absent),
    }
}

/// The `.v` file the `cpfg` line of `dir`'s `specifications` names after
/// `l_file`.
fn named_in_specifications(dir: &Path, l_file: &str) -> Option<String> {
    let spec = std::fs::read(dir.join("specifications")).ok()?;
    let spec = String::from_utf8_lossy(&spec);
    let l_name = Path::new(l_file)
        .file_name()?
        .to_string_lossy()
        .into_owned();
    spec.lines().find_map(|line| {
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.first() != Some(&"cpfg") {
            return None;
        }
        let k = words.iter().position(|w| *w == l_name)?;
        let v = words[k + 1..].iter().find(|w| w.ends_with(".v"))?;
        Some(v.to_string())
    })
}

/// What cpfg draws with when it reads no view file, as a warning says it.
pub fn defaults_said() -> String {
    let v = View::default();
    format!(
        "angle {}°, line width {} pixel, colour {}, viewpoint on the z axis, parallel projection",
        v.angle, v.initial_line_width, v.initial_color
    )
}

/// The colour map used when an object has no `.map` file.
///
/// cpfg draws colour indices through a 256-entry colour map (`-m file.map`).
/// vlab's default palette could not be found, so this is a documented
/// substitute built on what cpfg itself assumes about colour maps:
///
/// - index 0 is the background (manual §8.1.10: "background color … use
///   instead: color index 0"): black, as cpfg's window is;
/// - indices 1–15 are distinct, clearly visible colours (white, then red,
///   green, blue, yellow, cyan, magenta, orange, …), since simple models
///   draw with `initial color: 1` and step through low indices with `;`;
/// - indices 16–255 are ramps of 64 entries from dark to light (cpfg's
///   surface shading works in blocks of 64: intensity = col/64 − ⌊col/64⌋,
///   manual §8.1.3): 16–63 greens, 64–127 browns (wood), 128–191 leaf
///   greens, 192–255 reds to pinks (flowers). The ramp starts at 25 % so no
///   shaded colour disappears into the background.
pub fn default_colormap() -> [Rgb; 256] {
    const LOW: [(u8, u8, u8); 16] = [
        (0, 0, 0),
        (255, 255, 255),
        (230, 25, 25),
        (40, 180, 60),
        (50, 90, 230),
        (240, 220, 40),
        (40, 210, 220),
        (210, 60, 210),
        (245, 140, 30),
        (150, 230, 90),
        (140, 90, 50),
        (250, 170, 190),
        (130, 130, 130),
        (120, 60, 180),
        (0, 130, 130),
        (200, 200, 120),
    ];
    const RAMPS: [(f64, f64, f64); 4] = [
        (0.35, 0.85, 0.35), // 0..63 (16..63 used)
        (0.65, 0.45, 0.25), // 64..127
        (0.30, 0.75, 0.20), // 128..191
        (0.95, 0.35, 0.45), // 192..255
    ];
    let mut map = [Rgb(0, 0, 0); 256];
    for (i, slot) in map.iter_mut().enumerate() {
        *slot = if i < 16 {
            let (r, g, b) = LOW[i];
            Rgb(r, g, b)
        } else {
            let (r, g, b) = RAMPS[i / 64];
            let t = 0.25 + 0.75 * (i % 64) as f64 / 63.0;
            let c = |x: f64| (255.0 * (x * t).min(1.0)).round() as u8;
            Rgb(c(r), c(g), c(b))
        };
    }
    map
}

#[cfg(test)]
mod tests {
    use super::*;

    fn codes_of(d: &Diagnostics) -> Vec<&'static str> {
        d.iter().map(|x| x.code.0).collect()
    }

    #[test]
    fn defaults_follow_the_manual() {
        let (v, d) = read_view("");
        assert!(d.is_empty());
        assert_eq!(v, View::default());
        assert_eq!(v.angle, 45.0);
        assert_eq!(v.initial_color, 128);
        assert_eq!(v.line_width_unit, WidthUnit::Pixels);
        assert!(v.z_buffer && v.tapered_lines);
    }

    #[test]
    fn angle_and_widths() {
        let (v, d) = read_view("angle factor: 16 /* 22.5 */\ninitial line width: 2.0 pixels\nline width increment: 0.5\n");
        assert!(d.is_empty(), "{d:?}");
        assert_eq!(v.angle, 22.5);
        assert_eq!(v.initial_line_width, 2.0);
        assert_eq!(v.line_width_increment, 0.5);
        // The later of angle factor / angle increment wins.
        let (v, _) = read_view("angle factor: 16\nangle increment: 30\n");
        assert_eq!(v.angle, 30.0);
        let (v, _) = read_view("angle increment: 30\nangle factor: 8\n");
        assert_eq!(v.angle, 45.0);
        // cpfg's `ReadViewData`: a polygon in world units unless the word
        // after the width starts with `p` (pixels) or `s` (cylinders).
        for (line, unit, style) in [
            ("0.1 s", WidthUnit::World, LineStyle::Cylinder),
            ("0.1 shaded", WidthUnit::World, LineStyle::Cylinder),
            (".1", WidthUnit::World, LineStyle::Polygon),
            ("3 pixels", WidthUnit::Pixels, LineStyle::Pixel),
            ("3 p", WidthUnit::Pixels, LineStyle::Pixel),
        ] {
            let (v, d) = read_view(&format!("initial line width: {line}\n"));
            assert!(d.is_empty(), "{line}: {d:?}");
            assert_eq!((v.line_width_unit, v.line_style), (unit, style), "{line}");
        }
    }

    #[test]
    fn view_vectors_and_modes() {
        let src = "viewpoint: 0,10,30\nview reference point: 0, 5.5 ,0\ntwist: 900\nprojection: perspective\n\
                   render mode: shaded\nz buffer: off\nline style: polygon\nbox: x: -4,4 y: -2,7 z:-4,4\n\
                   initial color: 16 32\ncolor increment: 2\n";
        let (v, d) = read_view(src);
        assert!(d.is_empty(), "{d:?}");
        assert_eq!(v.viewpoint, [0.0, 10.0, 30.0]);
        assert_eq!(v.view_reference_point, [0.0, 5.5, 0.0]);
        assert_eq!(v.twist, 900.0);
        assert_eq!(v.projection, Projection::Perspective);
        assert_eq!(v.render_mode, RenderMode::Shaded);
        assert!(!v.z_buffer);
        assert_eq!(v.line_style, LineStyle::Polygon);
        assert_eq!(
            v.bounding_box,
            Some([[-4.0, 4.0], [-2.0, 7.0], [-4.0, 4.0]])
        );
        assert_eq!(
            (v.initial_color, v.initial_back_color, v.color_increment),
            (16, Some(32), 2)
        );
    }

    #[test]
    fn files_and_tropisms() {
        let src = "function: internode.func 100\nfunction: leaf.func\nfunction set: functions.fset\n\
                   surface: l leaf.s 1 8 4\nsurface: p petal.s 2.75\nline: L line.s .01\ncontour: 1 leaf.con\n\
                   curve: profile.con\ntropism: T: 0.0  1.0 0.0  A:90\ntorque: T: 0,1,0 E: 0.2\n\
                   tropism direction: 0.2,1.0,0.0\ninitial elasticity: 0.15\nelasticity increment: -0.06\n";
        let (v, d) = read_view(src);
        assert!(d.is_empty(), "{d:?}");
        let leaf = src.find("surface: l").unwrap();
        assert_eq!(
            v.surfaces[0].line,
            leaf..leaf + "surface: l leaf.s 1 8 4".len()
        );
        assert_eq!(v.functions, ["internode.func", "leaf.func"]);
        assert_eq!(v.function_samples, [Some(100), None]);
        assert_eq!(v.function_sets, ["functions.fset"]);
        assert_eq!(
            v.surfaces[0],
            SurfaceRef {
                id: 'l',
                file: "leaf.s".into(),
                scale: 1.0,
                s_divisions: 8,
                t_divisions: 4,
                texture: None,
                line: leaf..leaf + 23,
            }
        );
        assert_eq!((v.surfaces[1].scale, v.surfaces[1].s_divisions), (2.75, 0));
        assert_eq!((v.lines[0].id, v.lines[0].scale), ('L', 0.01));
        assert_eq!(
            (&v.contours[..], &v.curves[..]),
            (
                &[ContourRef {
                    id: 1,
                    file: "leaf.con".into()
                }][..],
                &[ContourRef {
                    id: 1,
                    file: "profile.con".into()
                }][..]
            )
        );
        assert_eq!(
            (v.tropisms[0].vector, v.tropisms[0].angle),
            ([0.0, 1.0, 0.0], 90.0)
        );
        assert_eq!(
            (v.tropisms[1].elasticity, v.tropisms[1].torque),
            (0.2, true)
        );
        assert!(!v.tropisms[0].torque);
        assert_eq!(v.tropism_direction, Some([0.2, 1.0, 0.0]));
        assert_eq!(
            (v.initial_elasticity, v.elasticity_increment),
            (0.15, -0.06)
        );
    }

    #[test]
    fn unknown_misspelt_and_unused() {
        let src = "angel factor: 16\ntappered lines: off\nfont: V: 0 1 0\n// scale factor: 3\nangle factor: x\n";
        let (v, d) = read_view(src);
        assert_eq!(codes_of(&d), ["W0804", "W0805", "W0808"]);
        assert_eq!(&src[d.0[0].span.clone().unwrap()], "angel factor");
        assert_eq!(
            d.0[0].help.as_deref(),
            Some("did you mean `angle factor:`?")
        );
        assert_eq!(&src[d.0[1].span.clone().unwrap()], "tappered lines");
        assert_eq!(&src[d.0[2].span.clone().unwrap()], "x");
        assert!(!v.tapered_lines);
        assert_eq!(v.scale_factor, 1.0);
        assert_eq!(v.angle, 45.0);
        assert_eq!(v.unused, [("font".to_string(), 37..51)]);
    }

    #[test]
    fn shade_modes_and_what_is_not_drawn() {
        let (v, d) = read_view("shade mode: 3\n");
        assert!(d.is_empty());
        assert_eq!(v.render_mode, RenderMode::Shaded);
        let (v, _) = read_view("render mode: shaded\nshade mode: 7\n");
        assert_eq!(v.render_mode, RenderMode::Wireframe);
        let (_, d) = read_view("shade mode: 9\n");
        assert_eq!(codes_of(&d), ["W0808"]);
        let src = "font: x\ntsurface: t bark.ray 1\n";
        let (_, d) = read_view(src);
        assert_eq!(codes_of(&d), ["W0807"]);
        assert_eq!(&src[d.0[0].span.clone().unwrap()], "tsurface: t bark.ray 1");
        // Scenes are read: several files on one line.
        let src = "background scene: a.dat, b.dat;c.dat\n";
        let (v, d) = read_view(src);
        assert!(d.is_empty(), "{d:?}");
        let names: Vec<&str> = v.scenes.iter().map(|s| s.0.as_str()).collect();
        assert_eq!(names, ["a.dat", "b.dat", "c.dat"]);
    }

    #[test]
    fn textures_are_read_as_cpfg_reads_them() {
        let src = "texture: F: maple.png H:n L:n E:m S: /* whole */\n\
                   texture: F: squares.png E: d R: 0.5 H: l L: mll\n\
                   texture: T: bark.png\ntexture: H: l\n";
        let (v, d) = read_view(src);
        assert_eq!(codes_of(&d), ["W0808", "W0808"]);
        assert_eq!(v.textures.len(), 2);
        let (a, b) = (&v.textures[0], &v.textures[1]);
        assert_eq!(
            (a.file.as_str(), a.filter, a.mode),
            ("maple.png", Filter::Nearest, TextureMode::Modulate)
        );
        assert!(a.per_surface && a.ratio == 1.0);
        assert_eq!(
            &src[a.line.clone()],
            "texture: F: maple.png H:n L:n E:m S: /* whole */".trim_end_matches(" /* whole */")
        );
        assert_eq!(
            (b.file.as_str(), b.filter, b.mode),
            ("squares.png", Filter::Linear, TextureMode::Decal)
        );
        assert!(!b.per_surface && b.ratio == 0.5);
    }

    #[test]
    fn lights_and_colour_map_shading() {
        let src = "light: V: 0 1 0 D: 0.5 0.5 0.5\nlight: O: 1 2 3\nlight direction: 0,0,1\n\
                   diffuse reflection: 4\nsurface ambient: 0.3\nsurface diffuse: 0.6\n";
        let (v, d) = read_view(src);
        assert!(d.is_empty(), "{d:?}");
        assert_eq!(v.lights.len(), 2);
        assert!(v.lights[0].directional);
        assert_eq!(v.lights[0].vector, [0.0, 1.0, 0.0]);
        assert_eq!(v.lights[0].diffuse, [0.5; 3]);
        assert!(!v.lights[1].directional);
        assert_eq!(v.lights[1].vector, [1.0, 2.0, 3.0]);
        assert_eq!(v.light_direction, [0.0, 0.0, 1.0]);
        assert_eq!(
            (v.diffuse_reflection, v.surface_ambient, v.surface_diffuse),
            (4.0, 0.3, 0.6)
        );
        let (_, d) = read_view("light: Q: 1\n");
        assert_eq!(codes_of(&d), ["W0808"]);
    }

    /// The vlab exercises leave `?` for the student: one error says so.
    #[test]
    fn a_value_left_as_a_question_mark_is_an_exercise_blank() {
        let src = "angle increment: ?\ninitial line width: 1 pixels\n";
        let (_, d) = read_view(src);
        assert_eq!(codes_of(&d), ["E0812"]);
        assert_eq!(&src[d.0[0].span.clone().unwrap()], "?");
        assert!(d.0[0].message.contains("exercise"), "{}", d.0[0].message);
    }

    #[test]
    fn panels_are_recognised() {
        assert!(is_panel(
            "panel name: Water\nbackground: 0\n\ntype: SLIDER\n"
        ));
        assert!(!is_panel("angle factor: 8\n"));
    }

    #[test]
    fn colormap_background_and_distinct_low_indices() {
        let m = default_colormap();
        assert_eq!(m[0], Rgb(0, 0, 0));
        for i in 1..16 {
            assert_ne!(m[i], m[0]);
            for j in 1..i {
                assert_ne!(m[i], m[j], "{i} {j}");
            }
        }
        // Ramps get lighter within a block of 64 and never reach black.
        for block in [64, 128, 192] {
            let lum = |c: Rgb| c.0 as u32 + c.1 as u32 + c.2 as u32;
            assert!(lum(m[block]) < lum(m[block + 63]));
            assert!(lum(m[block]) > 0);
        }
    }
}
