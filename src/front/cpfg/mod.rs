//! The cpfg dialect of `.l`: the L-system files of the Virtual Laboratory's
//! cpfg (Prusinkiewicz, Hanan, Mech and others; manual in
//! `../shared/reference/cpfg-manual.txt`).
//!
//! Reading a cpfg object: [`preprocess`] (the C preprocessor pass cpfg runs
//! over the `.l` file, with a map back to the original text) -> `lexer`
//! (logos, cpfg's two modes) -> `parser` (chumsky, one item per line,
//! recovering) -> `ast` -> `lower` (the IR: modules with parameters,
//! [`crate::ir::program`]). The files beside the `.l` come in through
//! [`view`] (the `.v` view file: angle, widths, colours, surfaces,
//! functions), [`func`] (`.func`, `.fset`) and [`surface`] (`.s`).

mod arity;
pub mod ast;
pub mod calls;
pub mod contour;
pub mod declared;
pub mod environment;
mod folder;
pub mod func;
pub mod lexer;
pub mod look;
pub mod lower;
pub mod parser;
pub mod preprocess;
pub mod scene;
pub mod surface;
mod textures;
mod tropisms;
pub mod view;

pub use crate::ir::Lowered;

use crate::diagnostics::{Diagnostic, Diagnostics, SideFile};
use crate::front::{
    line_comments, strip_block_comments, Confidence, Declaration, Front, FunctionSite, Read,
};
use crate::ir::{Span, System};
use crate::source::SourceFile;
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

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
    fn keywords(&self) -> Vec<&'static str> {
        (lexer::Keyword::ALL.iter()).map(|k| k.text()).collect()
    }
    fn comment_spans(&self, src: &str) -> Vec<Span> {
        lexer::comment_spans(src)
    }
    fn declarations(&self, src: &str) -> Vec<Declaration> {
        declared::macros(src)
    }
    fn user_functions(&self, path: &Path) -> Vec<FunctionSite> {
        function_sites(path)
    }
    fn user_function_called_at<'t>(&self, src: &'t str, at: usize) -> Option<&'t str> {
        declared::user_function_called_at(src, at)
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

/// Reads a cpfg `.l` file with what cpfg reads beside it: the preprocessor
/// runs first (with `#include`s from the file's folder and a macro for
/// each named user function), then the L-system is read, then the view
/// file (found as [`view::find_view`] says) sets the angle, widths, colours
/// and view, and brings in user functions and surfaces. Diagnostics point
/// into the original `.l` text; problems in the other files name the file.
pub fn read_file(file: &SourceFile, diags: &mut Diagnostics) -> Lowered {
    let path = Path::new(&file.name);
    let beside = Beside::new(path);
    let view = beside.view(path, diags);
    let functions = beside.user_functions(&view, diags);
    let contours = beside.contours(&view, diags);
    let curves: Vec<u32> = contours
        .iter()
        .filter(|c| c.role == crate::ir::look::ContourRole::Curve)
        .map(|c| c.id)
        .collect();
    let mut lowered = beside.read_mapped(&file.text, &functions, &curves, diags);
    tropisms::add_tropisms(&mut lowered, &view, diags);
    apply_view(&mut lowered.system, &view);
    beside.add_look(&mut lowered.system, path, &view, diags);
    beside.add_scenes(&mut lowered.system, &view, diags);
    beside.add_textures(&mut lowered.system, &view, diags);
    lowered.system.program.functions = functions.functions;
    lowered.system.contours = contours;
    beside.add_surfaces(&mut lowered.system, &view, diags);
    if lowered.system.look.textures().is_empty() {
        // Texture coordinates serve only textures: a look without any
        // keeps its surfaces bare (and their `.gft` short).
        for m in &mut lowered.system.surfaces {
            (m.patch_uvs, m.surface_uvs) = (Vec::new(), Vec::new());
        }
    }
    report_undefined_surfaces(&lowered, &view, diags);
    let when = (view.environment_after_step, view.interpret_past_cut);
    lowered.system.environment = environment::read(&beside, path, when, diags);
    beside.report_other_case(diags);
    lowered
}

/// The user functions of the cpfg object whose `.l` file is at `path`, as
/// [`read_file`] numbers them: the view file's `function:` files, then its
/// `function set:` files; those that do not read are left out, as there.
pub fn function_sites(path: &Path) -> Vec<FunctionSite> {
    let beside = Beside::new(path);
    if beside.dir.is_none() {
        return Vec::new();
    }
    let view = beside.view(path, &mut Diagnostics::default());
    let mut out: Vec<FunctionSite> = Vec::new();
    let files = (view.functions.iter().map(|f| (f, false)))
        .chain(view.function_sets.iter().map(|f| (f, true)));
    for (fname, is_set) in files {
        let (Some(path), Some(text)) = (beside.path(fname), beside.read(fname)) else {
            continue;
        };
        let functions = if is_set {
            func::read_fset(&text).map(|set| set.into_iter().map(|(_, f)| f).collect())
        } else {
            func::read_func(&text).map(|f| vec![f])
        };
        let names = func::name_spans(&text);
        for (k, function) in functions.unwrap_or_default().into_iter().enumerate() {
            // `NAME` in capitals, as the macro cpfg defines for it.
            out.push(FunctionSite {
                number: out.len() + 1,
                name: function.name.as_ref().map(|n| n.to_uppercase()),
                path: path.clone(),
                text: text.clone(),
                span: names.get(k).cloned().unwrap_or(0..0),
                points: function.points,
                samples: function.samples,
            });
        }
    }
    out
}

/// The folder of the `.l` file at `path`: its parent, or the current
/// folder for a bare name (`plant.l` given from its own folder has the
/// empty parent, which is no folder) when the file is there on disk; none
/// for a text with no file behind it.
fn folder_of(path: &Path) -> Option<&Path> {
    match path.parent() {
        Some(d) if d.as_os_str().is_empty() => path.is_file().then_some(Path::new(".")),
        Some(d) => Some(d).filter(|d| d.is_dir()),
        None => None,
    }
}

/// The folder of the `.l` file, where cpfg finds the files it reads beside
/// it (none when the `.l` has no folder on disk).
struct Beside<'a> {
    dir: Option<&'a Path>,
    /// Side files read under another case than the name written: (the name
    /// written, the name on disk), each once.
    other_case: std::cell::RefCell<Vec<(String, String)>>,
}

impl<'a> Beside<'a> {
    /// The folder of the `.l` file at `path`.
    fn new(path: &'a Path) -> Self {
        Beside {
            dir: folder_of(path),
            other_case: Default::default(),
        }
    }

    /// The text of the file `name` of the folder, if it can be read and
    /// lies inside the folder ([`inside`]).
    fn read(&self, name: &str) -> Option<String> {
        read_lossy(&self.path(name)?)
    }

    /// The path of the file `name` of the folder ([`inside`]), noting a
    /// name found in another case than written.
    fn path(&self, name: &str) -> Option<std::path::PathBuf> {
        let dir = self.dir?;
        let path = inside(dir, name)?;
        let on_disk = folder::name_in(dir, &path);
        if on_disk != name.trim_start_matches("./") && path.exists() {
            let mut seen = self.other_case.borrow_mut();
            let pair = (name.to_string(), on_disk);
            if !seen.contains(&pair) {
                seen.push(pair);
            }
        }
        Some(path)
    }

    /// A warning for each side file read under another case than written.
    fn report_other_case(&self, diags: &mut Diagnostics) {
        for (written, on_disk) in self.other_case.borrow().iter() {
            diags.push(
                Diagnostic::global(
                    crate::diagnostics::codes::CPFG_NAME_CASE,
                    format!(
                        "`{written}` is not in the object's folder; `{on_disk}` is read instead"
                    ),
                )
                .with_help(format!(
                    "write `{on_disk}` where `{written}` is named, so that the object reads \
                     the same on a file system that tells cases apart"
                )),
            );
        }
    }

    /// The file `name` of the folder (a `what` file named by the view file)
    /// read by `read`; a file that is missing or wrong is reported.
    fn read_with<T>(
        &self,
        name: &str,
        what: &str,
        read: impl FnOnce(&str) -> Result<T, Diagnostics>,
        diags: &mut Diagnostics,
    ) -> Option<T> {
        let Some(text) = self.read(name) else {
            diags.push(self.unreadable(name, what, "the view file"));
            return None;
        };
        match read(&text) {
            Ok(x) => Some(x),
            Err(d) => {
                let path = self
                    .dir
                    .map_or(Path::new(name).to_path_buf(), |d| d.join(name));
                push_side_file(diags, &d, &path, &text);
                None
            }
        }
    }

    /// Why the `what` file `name`, named in `named_in`, was not read:
    /// outside the folder, or missing.
    fn unreadable(&self, name: &str, what: &str, named_in: &str) -> crate::diagnostics::Diagnostic {
        if self.dir.is_some_and(|d| inside(d, name).is_none()) {
            outside_folder(name, what, named_in)
        } else {
            missing_file(name, what, named_in)
        }
    }

    /// The view file of the `.l` at `path`; the defaults when there is none.
    fn view(&self, path: &Path, diags: &mut Diagnostics) -> view::View {
        let (Some(dir), Some(l_name)) = (self.dir, path.file_name()) else {
            return view::View::default();
        };
        let l_name = l_name.to_string_lossy();
        let p = match view::find_view(dir, &l_name) {
            Ok(p) => p,
            Err(why) => {
                diags.push(no_view(&l_name, why));
                return view::View::default();
            }
        };
        let text = read_lossy(&p).unwrap_or_default();
        let (mut v, d) = view::read_view(&text);
        push_side_file(diags, &d, &p, &text);
        v.source = Some((p, text));
        v
    }

    /// The user functions of the view's `function:` files, then of its
    /// `function set:` files.
    fn user_functions(&self, view: &view::View, diags: &mut Diagnostics) -> UserFunctions {
        let mut user = UserFunctions::default();
        for fname in &view.functions {
            if let Some(f) = self.read_with(fname, "function", func::read_func, diags) {
                user.add(f.name.clone(), &f);
            }
        }
        for fname in &view.function_sets {
            if let Some(set) = self.read_with(fname, "function set", func::read_fset, diags) {
                for (name, f) in set {
                    user.add(Some(name), &f);
                }
            }
        }
        user
    }

    /// Preprocesses the `.l` text (its `#include`s come from the folder)
    /// and reads it, with the spans of the diagnostics and of the IR mapped
    /// back to the original text.
    fn read_mapped(
        &self,
        text: &str,
        functions: &UserFunctions,
        curves: &[u32],
        diags: &mut Diagnostics,
    ) -> Lowered {
        let defines = &functions.defines;
        let pre = preprocess::preprocess_with_defines(text, defines, &mut |name| self.read(name));
        let mut named = SidePaths::new(self.dir);
        for d in pre.diagnostics.0 {
            diags.push(match &d.side {
                Some(side) => {
                    let side = named.path_of(side);
                    d.in_side_file(side)
                }
                None => d,
            });
        }
        let mut own = Diagnostics::default();
        let ast = parser::parse(&pre.text, &mut own);
        let mut lowered = lower::lower_with_curves(&ast, curves, &mut own);
        let (arrays, given) = (&lowered.system.program.arrays, functions.functions.len());
        calls::check(&ast, arrays, given, &mut own);
        arity::check(&ast, &mut own);
        let map = |s: &Span| pre.map.to_source(s.clone());
        for d in own.0 {
            // Where expansion stopped too deep the text is left as written:
            // the parser meets the same nesting again.
            if pre.stopped_too_deep && d.code == crate::diagnostics::codes::NESTED_TOO_DEEPLY {
                continue;
            }
            diags.push(named.located(d, &pre.map));
        }
        map_spans(&mut lowered.spans, map);
        lowered
    }

    /// The view file's contours (`contour:`, cross-sections) and curves
    /// (`curve:`), sampled; a file that is missing or wrong is reported and
    /// left out.
    fn contours(
        &self,
        view: &view::View,
        diags: &mut Diagnostics,
    ) -> Vec<crate::ir::look::Contour> {
        use crate::ir::look::{Contour, ContourRole, CONTOUR_SAMPLES};
        let refs = (view.contours.iter().map(|r| (r, ContourRole::CrossSection)))
            .chain(view.curves.iter().map(|r| (r, ContourRole::Curve)));
        let mut out = Vec::new();
        for (r, role) in refs {
            let Some(file) = self.read_with(&r.file, "contour", contour::read_contour, diags)
            else {
                continue;
            };
            // A cross-section has the points its file asks for (cpfg's
            // sampling), never more than a curve's.
            let samples = match role {
                ContourRole::CrossSection => file.samples.unwrap_or(CONTOUR_SAMPLES),
                ContourRole::Curve => CONTOUR_SAMPLES,
            };
            let (mut points, length) = file.sample(samples.clamp(2, CONTOUR_SAMPLES));
            if role == ContourRole::CrossSection && file.closed {
                start_on_x_axis(&mut points);
            }
            out.push(Contour {
                id: r.id,
                role,
                points,
                closed: file.closed,
                length,
            });
        }
        out
    }

    /// The bytes of the file `name` of the folder (at most a `.l`'s size
    /// cap), if it lies inside the folder.
    fn read_bytes(&self, name: &str) -> Option<Vec<u8>> {
        use std::io::Read;
        let file = std::fs::File::open(self.path(name)?).ok()?;
        let mut bytes = Vec::new();
        let cap = crate::source::MAX_SOURCE_BYTES as u64;
        file.take(cap + 1).read_to_end(&mut bytes).ok()?;
        (bytes.len() as u64 <= cap).then_some(bytes)
    }

    /// The colours and look of the picture: the colour maps or materials
    /// the object's `specifications` names for the `.l` at `path` (cpfg's
    /// default colour map when it names none), and the view's camera and
    /// lights.
    fn add_look(&self, sys: &mut System, path: &Path, view: &view::View, diags: &mut Diagnostics) {
        let l_name = path.file_name().map(|n| n.to_string_lossy().into_owned());
        let files = match self.read("specifications") {
            Some(spec) => look::colour_files(&spec, l_name.as_deref().unwrap_or("")),
            None => self.colour_files_of_folder(path, diags),
        };
        let mut palette = view::default_colormap().to_vec();
        for (block, name) in &files.maps {
            if let Some(map) = self.read_binary(name, "colour map", look::read_map, diags) {
                let at = block * map.len();
                if palette.len() < at + map.len() {
                    palette.resize(at + map.len(), crate::ir::Rgb(0, 0, 0));
                }
                palette[at..at + map.len()].copy_from_slice(&map);
            }
        }
        let materials = files
            .materials
            .as_deref()
            .and_then(|name| self.read_binary(name, "material", look::read_materials, diags))
            .unwrap_or_default();
        for (slot, m) in palette.iter_mut().zip(&materials) {
            *slot = look::flat_colour(m.as_ref().unwrap_or(&look::DEFAULT_MATERIAL));
        }
        sys.look = look::look(view, &palette, &materials);
        sys.colours = palette;
    }

    /// The view's background scenes, drawn with the model. A scene's
    /// materials (or, with a colour map, their diffuse colours) take the
    /// colour indices after the ones the object's files use, so that they
    /// never stand in for the plant's.
    fn add_scenes(&self, sys: &mut System, view: &view::View, diags: &mut Diagnostics) {
        for (name, _) in &view.scenes {
            let Some(text) = self.read(name) else {
                diags.push(self.unreadable(name, "background scene", "the view file"));
                continue;
            };
            let pre = preprocess::preprocess(&text, &mut |n| self.read(n));
            let lighting = sys.look.lighting.as_ref();
            let materials = lighting.map_or(0, |l| l.materials.len());
            let first = sys.colours.len().max(materials).max(256);
            let Ok(first) = u16::try_from(first) else {
                continue;
            };
            let tapered = lighting.is_none_or(|l| l.tapered);
            let mut found = Diagnostics::default();
            let scene = scene::read_scene(&pre.text, first, tapered, &mut found);
            let located = found.iter().map(|d| {
                let mut d = d.clone();
                d.span = d.span.map(|s| pre.map.locate(s).0);
                d
            });
            let located = Diagnostics(located.collect());
            let path = self
                .dir
                .map_or(Path::new(name).to_path_buf(), |d| d.join(name));
            push_side_file(diags, &located, &path, &text);
            let colours = scene.materials.iter().map(look::flat_colour);
            sys.colours
                .resize(usize::from(first), crate::ir::Rgb(0, 0, 0));
            sys.colours.extend(colours);
            if let Some(l) = sys
                .look
                .lighting
                .as_mut()
                .filter(|l| !l.materials.is_empty())
            {
                l.materials.resize(usize::from(first), None);
                l.materials.extend(scene.materials.into_iter().map(Some));
            }
            sys.look.scene.extend(scene.polygons);
        }
    }

    /// The colour files of a folder with no `specifications` (L-studio's
    /// layout): the `.map` and the `.mat` named like the `.l`, else the
    /// folder's only one of each; a warning says which were taken.
    fn colour_files_of_folder(&self, path: &Path, diags: &mut Diagnostics) -> look::ColourFiles {
        let (Some(dir), Some(stem)) = (self.dir, path.file_stem()) else {
            return look::ColourFiles::default();
        };
        let stem = stem.to_string_lossy();
        let map = folder::named_like_or_only(dir, &stem, "map");
        let materials = folder::named_like_or_only(dir, &stem, "mat");
        let taken: Vec<String> = map
            .iter()
            .chain(&materials)
            .map(|n| format!("`{n}`"))
            .collect();
        if !taken.is_empty() {
            let l_name = path.file_name().unwrap_or_default().to_string_lossy();
            let flags = (map.iter().map(|m| format!(" -m {m}")))
                .chain(materials.iter().map(|m| format!(" -M {m}")))
                .collect::<String>();
            diags.push(
                Diagnostic::global(
                    crate::diagnostics::codes::CPFG_FOLDER_COLOURS,
                    format!(
                        "no `specifications` in the object's folder: the colours of {} are used, \
                         as L-studio does",
                        taken.join(" and ")
                    ),
                )
                .with_help(format!(
                    "to choose the files, write a `specifications` file with the line \
                     `cpfg {l_name}{flags}`"
                )),
            );
        }
        look::ColourFiles {
            maps: map.map(|m| (0, m)).into_iter().collect(),
            materials,
        }
    }

    /// A binary side file named on the object's `cpfg` command line, read
    /// by `read`; a missing or malformed one is reported.
    fn read_binary<T>(
        &self,
        name: &str,
        what: &str,
        read: impl FnOnce(&[u8]) -> Result<T, String>,
        diags: &mut Diagnostics,
    ) -> Option<T> {
        let Some(bytes) = self.read_bytes(name) else {
            let d = self.unreadable(name, what, "`specifications`");
            diags.push(
                if d.code == crate::diagnostics::codes::CPFG_OUTSIDE_FOLDER {
                    d
                } else {
                    crate::diagnostics::Diagnostic::global(
                        crate::diagnostics::codes::CPFG_COLOUR_FILE,
                        format!("{}; cpfg's default colours are used", d.message),
                    )
                    .with_help("put the file in the object's folder")
                },
            );
            return None;
        };
        read(&bytes)
            .map_err(|e| {
                diags.push(
                    crate::diagnostics::Diagnostic::global(
                        crate::diagnostics::codes::CPFG_COLOUR_FILE,
                        format!("{name}: {e}; cpfg's default colours are used"),
                    )
                    .with_help("save the file again with vlab's palette or medit editor"),
                );
            })
            .ok()
    }

    /// Surfaces: `~id` draws surface `id` of the view file.
    fn add_surfaces(&self, sys: &mut System, view: &view::View, diags: &mut Diagnostics) {
        let mut missing = Diagnostics::default();
        for r in &view.surfaces {
            if self.is_missing(&r.file) {
                missing.push(missing_surface(r));
                continue;
            }
            let Some(surface) = self.read_with(&r.file, "surface", surface::read_surface, diags)
            else {
                continue;
            };
            let name = format!("~{}", r.id);
            let texture = self.surface_texture(sys, r, &mut missing);
            sys.surfaces.push(crate::ir::SurfaceMesh {
                name: name.clone(),
                texture,
                ..surface_mesh(r, &surface)
            });
            let index = (sys.surfaces.len() - 1) as u16;
            if let Some(id) = sys.symbols.get(&name) {
                sys.set_interpretation(id, crate::ir::TurtleOp::Surface(index));
            }
        }
        if let Some((path, text)) = &view.source {
            push_side_file(diags, &missing, path, text);
        }
    }

    /// Whether the side file `name` would lie in the object's folder but
    /// is not there (cpfg checks a surface's file exists before reading it).
    fn is_missing(&self, name: &str) -> bool {
        self.dir
            .and_then(|d| inside(d, name))
            .is_some_and(|p| !p.exists())
    }
}

/// The path of the side file `name` when it lies inside `dir`: a
/// relative name without `..` whose file, links followed, is in the folder
/// (checked when the file exists; a missing file is reported as missing).
/// A name in another case than on disk finds the file, as on the
/// case-insensitive systems cpfg objects were written on.
fn inside(dir: &Path, name: &str) -> Option<std::path::PathBuf> {
    use std::path::Component;
    let relative = Path::new(name);
    if !relative
        .components()
        .all(|c| matches!(c, Component::Normal(_) | Component::CurDir))
    {
        return None;
    }
    let path = folder::find_any_case(dir, name).unwrap_or_else(|| dir.join(relative));
    match (path.canonicalize(), dir.canonicalize()) {
        (Ok(file), Ok(folder)) if !file.starts_with(&folder) => None,
        _ => Some(path),
    }
}

fn outside_folder(name: &str, what: &str, named_in: &str) -> crate::diagnostics::Diagnostic {
    crate::diagnostics::Diagnostic::global(
        crate::diagnostics::codes::CPFG_OUTSIDE_FOLDER,
        format!("the {what} file `{name}` named in {named_in} is outside the object's folder"),
    )
    .with_help("copy the file into the object's folder and name it there")
}

/// A side file's text, read no further than the size cap (a link to a
/// device or a pipe cannot make graftal read without end); `None` when it
/// cannot be read or is too large.
fn read_lossy(path: &Path) -> Option<String> {
    let file = crate::source::SourceFile::read(path).ok()?;
    file.oversize().is_none().then_some(file.text)
}

/// How diagnostics name a file of the object's folder.
fn shown_name(path: &Path) -> String {
    path.strip_prefix(".").unwrap_or(path).display().to_string()
}

/// Reports the diagnostics of a file beside the `.l` (view, function,
/// surface) as that file's: their spans point into `text`, shown as `path`.
fn push_side_file(diags: &mut Diagnostics, d: &Diagnostics, path: &Path, text: &str) {
    if d.is_empty() {
        return;
    }
    let side = std::sync::Arc::new(crate::diagnostics::SideFile {
        name: shown_name(path),
        text: text.to_string(),
    });
    for x in d.iter() {
        diags.push(x.clone().in_side_file(side.clone()));
    }
}

/// The files `#include`d in the `.l`, named by their path in the object's
/// folder (the preprocessor knows them by the name written), each once.
struct SidePaths<'a> {
    dir: Option<&'a Path>,
    named: HashMap<String, Arc<SideFile>>,
}

impl<'a> SidePaths<'a> {
    fn new(dir: Option<&'a Path>) -> Self {
        SidePaths {
            dir,
            named: HashMap::new(),
        }
    }

    /// `side`, named by its path.
    fn path_of(&mut self, side: &Arc<SideFile>) -> Arc<SideFile> {
        let dir = self.dir;
        let named = self.named.entry(side.name.clone()).or_insert_with(|| {
            let path = dir.map_or(Path::new(&side.name).to_path_buf(), |d| d.join(&side.name));
            Arc::new(SideFile {
                name: shown_name(&path),
                text: side.text.clone(),
            })
        });
        named.clone()
    }

    /// `d`, found in the preprocessed text, placed where its text was
    /// written: in the `.l`, or in the file `#include`d there (with notes
    /// naming the includes). A label in another file than the primary
    /// span becomes a note.
    fn located(&mut self, mut d: Diagnostic, map: &preprocess::SourceMap) -> Diagnostic {
        let Some(span) = d.span.clone() else {
            return d;
        };
        let (span, from) = map.locate(span);
        d.span = Some(span);
        let file = from.as_ref().map(|(f, _)| f.clone());
        let same = |other: &Option<preprocess::IncludedFrom>| match (other, &file) {
            (None, None) => true,
            (Some((a, _)), Some(b)) => Arc::ptr_eq(a, b),
            _ => false,
        };
        for label in std::mem::take(&mut d.labels) {
            let (span, there) = map.locate(label.span);
            if same(&there) {
                d.labels.push(crate::diagnostics::Label { span, ..label });
            } else {
                d.notes.push(label.message);
            }
        }
        if let Some(fix) = d.fix.take() {
            let (span, there) = map.locate(fix.span);
            d.fix = same(&there).then_some(crate::diagnostics::Fix { span, ..fix });
        }
        match from {
            Some((file, notes)) => {
                d.notes.extend(notes);
                d.in_side_file(self.path_of(&file))
            }
            None => d,
        }
    }
}

/// The user functions in the IR's order, sampled, and the macro cpfg
/// defines for each named one.
#[derive(Default)]
struct UserFunctions {
    functions: Vec<crate::ir::program::Function>,
    defines: Vec<(String, String)>,
}

impl UserFunctions {
    fn add(&mut self, name: Option<String>, f: &func::Function) {
        let samples = (0..FUNCTION_SAMPLES)
            .map(|k| f.eval(k as f64 / (FUNCTION_SAMPLES - 1) as f64))
            .collect();
        self.functions.push(crate::ir::program::Function {
            name: name.clone().unwrap_or_default(),
            samples,
        });
        // cpfg defines `FUNCNAME=id`, the name in capitals (manual §8.1.6).
        if let Some(n) = name {
            self.defines
                .push((n.to_uppercase(), self.functions.len().to_string()));
        }
    }
}

/// cpfg turns a closed cross-section about its origin so that it starts
/// on the +x axis (the up side of the cylinder).
fn start_on_x_axis(points: &mut [[f64; 3]]) {
    let Some(&[x0, y0, _]) = points.first() else {
        return;
    };
    let n = (x0 * x0 + y0 * y0).sqrt();
    if n < 1e-9 {
        return;
    }
    let (c, s) = (x0 / n, y0 / n);
    for p in points.iter_mut() {
        *p = [p[0] * c + p[1] * s, p[1] * c - p[0] * s, p[2]];
    }
}

/// Sends every span of the IR through `map`.
fn map_spans(spans: &mut crate::ir::SpanTable, map: impl Fn(&Span) -> Span) {
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
}

/// The view file's settings: angle, widths, colours, scale and view
/// direction.
fn apply_view(sys: &mut System, view: &view::View) {
    let st = &mut sys.settings;
    st.delta = view.angle.to_radians();
    st.width = view.initial_line_width;
    st.width_step = view.line_width_increment;
    st.world_widths = view.line_width_unit == view::WidthUnit::World;
    st.cpfg_polygons = true;
    st.randomness = crate::ir::Randomness::Cpfg;
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
}

/// The triangles of a surface placed as `r` says, in turtle coordinates,
/// with no more than [`MAX_SURFACE_TRIANGLES`], and their texture
/// coordinates: per patch its parameters, across the surface its x and y
/// (cpfg's, along the turtle's L and H) over their extent, as cpfg's
/// `set_texture_coordinates` lays a texture in the plane z = 0.
fn surface_mesh(r: &view::SurfaceRef, surface: &surface::Surface) -> crate::ir::SurfaceMesh {
    let mut div = r.s_divisions.max(r.t_divisions).clamp(1, 8);
    while div > 1 && surface.patches.len() * 2 * (div * div) as usize > MAX_SURFACE_TRIANGLES {
        div -= 1;
    }
    // cpfg normalises a surface by its `SIZE:`, so that the view file's
    // scale (and a `~` module's parameter) is the drawn size in turtle
    // units, whatever units the surface editor used.
    let scale = if surface.size > 0.0 {
        r.scale / surface.size
    } else {
        r.scale
    };
    let (triangles, patch_uvs): (Vec<_>, Vec<_>) = surface
        .triangles_with_parameters(div)
        .into_iter()
        .map(|(t, uv)| {
            let placed = t.map(|p| {
                let [h, l, u] = surface.to_turtle(p);
                [l * scale, h * scale, u * scale]
            });
            (placed, uv)
        })
        .unzip();
    let surface_uvs = crate::ir::SurfaceMesh::extent_uvs(&triangles);
    crate::ir::SurfaceMesh {
        triangles,
        patch_uvs,
        surface_uvs,
        ..Default::default()
    }
}

/// A `~` module whose surface the view file does not define: the rest of
/// the plant is drawn without it (some vlab objects, insect-realistic and
/// two-trees, name surfaces their folder lacks). A surface the view file
/// names but whose file is missing was reported with the file.
fn report_undefined_surfaces(lowered: &Lowered, view: &view::View, diags: &mut Diagnostics) {
    let sys = &lowered.system;
    for (id, info) in sys.symbols.iter() {
        let Some(name) = info.name.strip_prefix('~').filter(|n| !n.is_empty()) else {
            continue;
        };
        if sys.op(id).is_none() && !view.surfaces.iter().any(|r| r.id.to_string() == name) {
            let span = lowered.spans.symbols.get(&id).cloned().unwrap_or(0..0);
            diags.push(
                crate::diagnostics::Diagnostic::at(
                    crate::diagnostics::codes::CPFG_NOT_DRAWN,
                    span,
                    format!("surface `{name}` is not defined: `~{name}` draws nothing"),
                )
                .with_label("no `surface:` line of the view file names it")
                .with_help(format!(
                    "add `surface: {} file.s 1` to the view file",
                    &info.name[1..]
                )),
            );
        }
    }
}

/// The warning for an object drawn without a view file: which defaults
/// cpfg's picture then has.
fn no_view(l_name: &str, why: view::NoView) -> Diagnostic {
    let (message, help) = match why {
        view::NoView::Named(v) => (
            format!("the view file `{v}` named in `specifications` is not in the object's folder"),
            format!("put `{v}` beside `{l_name}`"),
        ),
        view::NoView::Absent => (
            format!("no view file for `{l_name}`"),
            format!(
                "cpfg reads one named on its command line: put a `.v` file named like \
                 `{l_name}` beside it"
            ),
        ),
    };
    Diagnostic::global(crate::diagnostics::codes::CPFG_NO_VIEW, message)
        .with_note(format!(
            "drawn with cpfg's defaults: {}",
            view::defaults_said()
        ))
        .with_help(help)
}

/// The warning for a `surface:` line whose file is not in the folder.
fn missing_surface(r: &view::SurfaceRef) -> Diagnostic {
    Diagnostic::at(
        crate::diagnostics::codes::CPFG_MISSING_SURFACE,
        r.line.clone(),
        format!(
            "the surface file `{}` is not in the object's folder: `~{}` draws nothing",
            r.file, r.id
        ),
    )
    .with_label("named here")
    .with_note("cpfg skips a surface whose file is missing, draws the rest, and leaves the turtle where it is at the module")
    .with_help(format!(
        "put `{}` in the object's folder, or take this line out",
        r.file
    ))
}

fn missing_file(name: &str, what: &str, named_in: &str) -> crate::diagnostics::Diagnostic {
    crate::diagnostics::Diagnostic::global(
        crate::diagnostics::codes::CPFG_MISSING_INCLUDE,
        format!("the {what} file `{name}` named in {named_in} cannot be read"),
    )
    .with_help("put the file beside the `.l` file")
}

/// Reads a cpfg text that must be free of errors (for tests).
///
/// # Panics
/// When the text has errors; the message lists them.
pub fn read_ok(src: &str) -> crate::ir::System {
    crate::front::read_clean(|d| read(src, d))
}
