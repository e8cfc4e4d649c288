//! The cpfg dialect of `.l`: the L-system files of the Virtual Laboratory's
//! cpfg (Prusinkiewicz, Hanan, Mech and others; manual in
//! `../shared/reference/cpfg-manual.txt`).
//!
//! Reading a cpfg object: [`preprocess`] (the C preprocessor pass cpfg runs
//! over the `.l` file, with a map back to the original text) -> `lexer`
//! (logos, cpfg's two modes) -> `parser` (chumsky, one item per line,
//! recovering) -> `ast` -> `lower` (the IR, with its parametric part
//! [`crate::ir::parametric`]). The files beside the `.l` come in through
//! [`view`] (the `.v` view file: angle, widths, colours, surfaces,
//! functions), [`func`] (`.func`, `.fset`) and [`surface`] (`.s`).

pub mod ast;
pub mod func;
pub mod lexer;
pub mod lower;
pub mod parser;
pub mod preprocess;
pub mod surface;
pub mod view;

pub use crate::ir::Lowered;

use crate::diagnostics::Diagnostics;
use crate::front::{line_comments, strip_block_comments, Confidence, Front, Read};
use crate::ir::{Span, System};
use crate::source::SourceFile;

/// The cpfg dialect of `.l` in the registry.
pub struct Cpfg;

impl Front for Cpfg {
    fn name(&self) -> &'static str {
        "cpfg"
    }
    fn title(&self) -> &'static str {
        "cpfg"
    }
    fn extensions(&self) -> &'static [&'static str] {
        &["l"]
    }
    /// A line starting with `lsystem:`, `endlsystem` or a `#define`,
    /// `#include` or `#if` directive (outside `/* */` comments): marks of
    /// cpfg that neither pfg nor Fractint has.
    fn detect(&self, text: &str) -> Confidence {
        let text = strip_block_comments(text);
        let marked = text.lines().any(|l| {
            let l = l.trim_start().to_ascii_lowercase();
            let word = |w: &str| {
                l.strip_prefix(w)
                    .is_some_and(|r| r.trim_start().starts_with(':'))
            };
            word("lsystem")
                || l.starts_with("endlsystem")
                || ["define", "include", "if"].iter().any(|d| {
                    l.strip_prefix('#')
                        .is_some_and(|r| r.trim_start().starts_with(d))
                })
        });
        if marked {
            Confidence::Certain
        } else {
            Confidence::No
        }
    }
    fn read(&self, file: &SourceFile, _entry: Option<&str>, diags: &mut Diagnostics) -> Read {
        read_file(file, diags).into()
    }
    fn comments(&self, src: &str) -> Vec<(Span, String)> {
        line_comments(src, None)
    }
    fn describe(&self, sys: Option<&System>) -> Option<String> {
        Some(match sys {
            Some(p) => format!(
                "cpfg, {} productions, {} decomposition, {} homomorphism",
                p.productions.len(),
                p.decomposition.productions.len(),
                p.homomorphism.productions.len()
            ),
            None => "cpfg".to_string(),
        })
    }
}

/// Parses and lowers a preprocessed cpfg text.
pub fn read(src: &str, diags: &mut Diagnostics) -> Lowered {
    let ast = parser::parse(src, diags);
    lower::lower(&ast, diags)
}

/// How many samples of a user function the IR keeps (`func(id, x)` then
/// interpolates linearly between them; the curves are smooth, so the error
/// is far below what a picture shows).
pub const FUNCTION_SAMPLES: usize = 1025;

/// The most triangles one surface may have (its divisions are lowered to
/// fit).
const MAX_SURFACE_TRIANGLES: usize = 20_000;

/// A diagnostic about a file beside the `.l` (view, function, surface):
/// reported without a span in the `.l`, naming the file and line.
fn side_file(
    d: &crate::diagnostics::Diagnostic,
    name: &str,
    text: &str,
) -> crate::diagnostics::Diagnostic {
    let mut g = d.clone();
    if let Some(span) = d.span.clone() {
        let line = text[..span.start.min(text.len())].matches('\n').count() + 1;
        g.message = format!("{name}, line {line}: {}", d.message);
    } else {
        g.message = format!("{name}: {}", d.message);
    }
    g.span = None;
    g.labels.clear();
    g
}

/// Reads a cpfg `.l` file with what cpfg reads beside it: the preprocessor
/// runs first (with `#include`s from the file's folder and a macro for
/// each named user function), then the L-system is read, then the view
/// file (found as [`view::find_view`] says) sets the angle, widths, colours
/// and view, and brings in user functions and surfaces. Diagnostics point
/// into the original `.l` text; problems in the other files name the file.
pub fn read_file(file: &SourceFile, diags: &mut Diagnostics) -> Lowered {
    use std::path::Path;
    let path = Path::new(&file.name);
    let dir = path.parent().filter(|d| d.is_dir());
    let read_side = |name: &str| -> Option<String> {
        let d = dir?;
        std::fs::read(d.join(name))
            .ok()
            .map(|b| String::from_utf8_lossy(&b).into_owned())
    };
    // The view file and the user functions it names.
    let view_path = dir.and_then(|d| view::find_view(d, path.file_name()?.to_str()?));
    let view = match &view_path {
        Some(p) => {
            let text = std::fs::read(p)
                .map(|b| String::from_utf8_lossy(&b).into_owned())
                .unwrap_or_default();
            let name = p
                .file_name()
                .map_or(String::new(), |n| n.to_string_lossy().into_owned());
            let (v, d) = view::read_view(&text);
            for x in d.iter() {
                diags.push(side_file(x, &name, &text));
            }
            v
        }
        None => view::View::default(),
    };
    let mut functions: Vec<crate::ir::program::Function> = Vec::new();
    let mut defines: Vec<(String, String)> = Vec::new();
    let mut add_function =
        |name: Option<String>,
         f: &func::Function,
         functions: &mut Vec<crate::ir::program::Function>| {
            let samples = (0..FUNCTION_SAMPLES)
                .map(|k| f.eval(k as f64 / (FUNCTION_SAMPLES - 1) as f64))
                .collect();
            functions.push(crate::ir::program::Function {
                name: name.clone().unwrap_or_default(),
                samples,
            });
            // cpfg defines `FUNCNAME=id`, the name in capitals (manual §8.1.6).
            if let Some(n) = name {
                defines.push((n.to_uppercase(), functions.len().to_string()));
            }
        };
    for fname in &view.functions {
        match read_side(fname).map(|t| (func::read_func(&t), t)) {
            Some((Ok(f), _)) => add_function(f.name.clone(), &f, &mut functions),
            Some((Err(d), t)) => {
                for x in d.iter() {
                    diags.push(side_file(x, fname, &t));
                }
            }
            None => diags.push(missing_file(fname, "function")),
        }
    }
    for fname in &view.function_sets {
        match read_side(fname).map(|t| (func::read_fset(&t), t)) {
            Some((Ok(set), _)) => {
                for (name, f) in set {
                    add_function(Some(name), &f, &mut functions);
                }
            }
            Some((Err(d), t)) => {
                for x in d.iter() {
                    diags.push(side_file(x, fname, &t));
                }
            }
            None => diags.push(missing_file(fname, "function set")),
        }
    }
    // Preprocess, then read with spans mapped back.
    let pre =
        preprocess::preprocess_with_defines(&file.text, &defines, &mut |name| read_side(name));
    diags.extend(pre.diagnostics);
    let mut own = Diagnostics::default();
    let mut lowered = read(&pre.text, &mut own);
    let map = |s: &crate::ir::Span| pre.map.to_source(s.clone());
    for mut d in own.0 {
        d.span = d.span.as_ref().map(map);
        for l in &mut d.labels {
            l.span = map(&l.span);
        }
        diags.push(d);
    }
    let spans = &mut lowered.spans;
    for s in spans.productions.iter_mut().chain(spans.axiom.iter_mut()) {
        *s = map(s);
    }
    for s in spans.symbols.values_mut() {
        *s = map(s);
    }
    for alts in spans.successors.iter_mut() {
        for alt in alts.iter_mut() {
            for s in alt.iter_mut() {
                *s = map(s);
            }
        }
    }
    // Tropisms bend every segment in cpfg; graftal does not apply them yet,
    // so say so rather than draw a different plant silently.
    let bends = !view.tropisms.is_empty()
        || (view.tropism_direction.is_some() && view.initial_elasticity != 0.0);
    if bends {
        diags.push(
            crate::diagnostics::Diagnostic::global(
                crate::diagnostics::codes::CPFG_NOT_DRAWN,
                "the view file sets tropisms, which graftal does not apply: branches are drawn unbent",
            )
            .with_help("cpfg bends each segment towards the tropism vector by its elasticity"),
        );
    }
    // The view file's settings.
    let sys = &mut lowered.system;
    let st = &mut sys.settings;
    st.delta = view.angle.to_radians();
    st.width = view.initial_line_width;
    st.width_step = view.line_width_increment;
    st.world_widths = view.line_width_unit == view::WidthUnit::World;
    st.colour = view.initial_color as usize;
    st.colour_step = view.color_increment as f64;
    st.scale = (view.scale_factor * 100.0).clamp(1.0, 100.0);
    let d = [
        view.viewpoint[0] - view.view_reference_point[0],
        view.viewpoint[1] - view.view_reference_point[1],
        view.viewpoint[2] - view.view_reference_point[2],
    ];
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    if len > 0.0 && (d[0].abs() > 1e-12 || d[1].abs() > 1e-12) {
        st.view = Some((d[0].atan2(d[2]), (d[1] / len).asin()));
    }
    // cpfg draws on black, graftal on white: the colour map's white
    // (index 1, the usual foreground) is drawn black.
    sys.colours = view::default_colormap()
        .iter()
        .map(|&c| {
            if c == crate::ir::Rgb(255, 255, 255) {
                crate::ir::Rgb(0, 0, 0)
            } else {
                c
            }
        })
        .collect();
    sys.program.functions = functions;
    // Surfaces: `~id` draws surface `id` of the view file.
    for r in &view.surfaces {
        let Some(text) = read_side(&r.file) else {
            diags.push(missing_file(&r.file, "surface"));
            continue;
        };
        let surface = match surface::read_surface(&text) {
            Ok(s) => s,
            Err(d) => {
                for x in d.iter() {
                    diags.push(side_file(x, &r.file, &text));
                }
                continue;
            }
        };
        let mut div = r.s_divisions.max(r.t_divisions).clamp(1, 8);
        while div > 1 && surface.patches.len() * 2 * (div * div) as usize > MAX_SURFACE_TRIANGLES {
            div -= 1;
        }
        let triangles = surface
            .triangles(div)
            .into_iter()
            .map(|t| {
                t.map(|p| {
                    let [h, l, u] = surface.to_turtle(p);
                    [l * r.scale, h * r.scale, u * r.scale]
                })
            })
            .collect();
        let name = format!("~{}", r.id);
        sys.surfaces.push(crate::ir::SurfaceMesh {
            name: name.clone(),
            triangles,
        });
        let index = (sys.surfaces.len() - 1) as u16;
        if let Some(id) = sys.symbols.get(&name) {
            sys.set_interpretation(id, crate::ir::TurtleOp::Surface(index));
        }
    }
    // A `~` module whose surface the view file does not define.
    for (id, info) in sys.symbols.iter() {
        if info.name.starts_with('~') && info.name.len() > 1 && sys.op(id).is_none() {
            let span = lowered.spans.symbols.get(&id).cloned().unwrap_or(0..0);
            diags.push(
                crate::diagnostics::Diagnostic::at(
                    crate::diagnostics::codes::CPFG_UNSUPPORTED,
                    span,
                    format!("surface `{}` is not defined", &info.name[1..]),
                )
                .with_label("no `surface:` line of the view file names it")
                .with_help(format!(
                    "add `surface: {} file.s 1` to the view file",
                    &info.name[1..]
                )),
            );
        }
    }
    lowered
}

fn missing_file(name: &str, what: &str) -> crate::diagnostics::Diagnostic {
    crate::diagnostics::Diagnostic::global(
        crate::diagnostics::codes::CPFG_MISSING_INCLUDE,
        format!("the {what} file `{name}` named in the view file cannot be read"),
    )
    .with_help("put the file beside the `.l` file")
}

/// Reads a cpfg text that must be free of errors (for tests).
///
/// # Panics
/// When the text has errors; the message lists them.
pub fn read_ok(src: &str) -> crate::ir::System {
    let mut d = Diagnostics::default();
    let l = read(src, &mut d);
    assert!(!d.has_errors(), "{d:#?}");
    l.system
}
