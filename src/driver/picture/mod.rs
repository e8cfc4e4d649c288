//! One call for a picture, as resvg has one `render`: a [`Request`] says
//! what to draw (the steps, seed and limits of the run) and how (a
//! [`Target`]: PNG, SVG, a mesh or an animation; size, view, style,
//! detail, splines, layout), and [`draw`] returns a [`Picture`]: its
//! bytes, its side files (an OBJ's material library), the warnings it
//! raised and the [`Method`] it chose. [`make`] also reads and compiles
//! the source. The command line, the gallery, an animation's frames and
//! every face to come draw through these calls.
//!
//! The method is chosen here from the system and the request, as
//! [`crate::eval::plan`] chooses a derivation, and the methods are private:
//! a still picture is drawn from shared subtrees where the system and the
//! view allow (`shared.rs`), else streamed segment by segment (`streamed.rs`),
//! else lit straight from the turtle (`lit.rs`), else from stored geometry
//! (`stored.rs`); meshes in `mesh.rs`, animations in `animate.rs`. A
//! system that is an instancing graph (an IFS) is drawn by its attractor
//! at pixel resolution (`attractor.rs`).

mod animate;
mod attractor;
mod linked;
mod lit;
mod mesh;
mod shared;
mod stored;
mod streamed;
mod traced;

use super::derive::{derive_symbols, derive_values, RunOptions};
use super::empty::{nearly_nothing_drawn, nothing_drawn};
use super::interpret::{add_fixed, check_moves_up_front, interpret};
use super::load::{compile_as, load, split_entry, Compiled, LoadError};
use crate::diagnostics::{Diagnostic, Diagnostics};
use crate::front::Front;
use crate::ir::{SpanTable, System};
use crate::mesh::{MeshFormat, MeshStats};
use crate::render::animate::Container;
use crate::render::{Detail, RenderOptions, Style, View};
use crate::source::SourceFile;
use std::path::Path;

pub(in crate::driver) use stored::apply_look;
pub use stored::render_bytes;
pub use traced::Tracing;

/// The formats of a still picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Png,
    Svg,
    /// A scene for POV-Ray 3.7: what graftal ray traces, for another
    /// renderer.
    Pov,
}

impl Format {
    /// Every still format. A name is looked up here, so the help that
    /// lists them ([`Target::all`]) names every one that can be written.
    pub const ALL: [Format; 3] = [Format::Png, Format::Svg, Format::Pov];

    /// The formats' names, as `render --to` takes them and as extensions.
    pub const NAMES: &'static [&'static str] = &["png", "svg", "pov"];

    /// The format named `name` (`png`, `svg`; any case).
    pub fn from_name(name: &str) -> Option<Format> {
        Format::ALL
            .into_iter()
            .find(|f| f.name().eq_ignore_ascii_case(name))
    }

    /// The format for an output path, by its extension.
    pub fn from_path(path: &str) -> Option<Format> {
        Format::from_name(Path::new(path).extension()?.to_str()?)
    }

    pub fn name(self) -> &'static str {
        match self {
            Format::Png => "png",
            Format::Svg => "svg",
            Format::Pov => "pov",
        }
    }
}

/// What a picture is made into.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// A still picture.
    Still(Format),
    /// A mesh: OBJ (with its material library as a side file), PLY, glTF.
    Mesh(MeshFormat),
    /// The steps up to N, from the first that draws anything, as the
    /// frames of a GIF or an animated PNG.
    Animation(Container),
}

impl Target {
    /// Every target graftal makes: each still format, mesh format and
    /// animation container, from the lists their names are looked up in,
    /// so that what the help and the errors list is what can be written.
    pub fn all() -> impl Iterator<Item = Target> {
        let stills = Format::ALL.into_iter().map(Target::Still);
        let meshes = MeshFormat::ALL.into_iter().map(Target::Mesh);
        stills
            .chain(meshes)
            .chain(Container::ALL.into_iter().map(Target::Animation))
    }

    /// The format's name, in capitals: PNG, SVG, OBJ, PLY, GLB, GIF, APNG.
    pub fn name(self) -> &'static str {
        match self {
            Target::Still(Format::Png) => "PNG",
            Target::Still(Format::Svg) => "SVG",
            Target::Still(Format::Pov) => "POV-Ray scene",
            Target::Mesh(MeshFormat::Obj) => "OBJ",
            Target::Mesh(MeshFormat::Ply) => "PLY",
            Target::Mesh(MeshFormat::Glb) => "GLB",
            Target::Animation(Container::Gif) => "GIF",
            Target::Animation(Container::Apng) => "APNG",
        }
    }

    /// The extension of a file of it.
    pub fn extension(self) -> &'static str {
        match self {
            Target::Still(f) => f.name(),
            Target::Mesh(f) => f.extension(),
            Target::Animation(c) => c.extension(),
        }
    }
}

/// Frames per second of an animation unless the request says otherwise.
pub const DEFAULT_FPS: u32 = 10;

/// The request for a picture: the run (steps, seed, limits) and how it is
/// drawn. [`Request::new`] gives `graftal render`'s defaults.
#[derive(Clone, Debug)]
pub struct Request {
    pub run: RunOptions,
    pub target: Target,
    pub width: u32,
    pub height: u32,
    /// The view asked for; `None` takes the file's own (or its camera),
    /// else face on.
    pub view: Option<View>,
    pub style: Style,
    /// What an SVG keeps of detail finer than its pixels.
    pub detail: Detail,
    /// Branches drawn as B-splines through the turtle's positions. The
    /// stdlib's kolams are drawn so whatever this says.
    pub spline: bool,
    /// An STL file's layout shapes drawn under the tree.
    pub layout: bool,
    /// Frames per second of an animation.
    pub fps: u32,
    /// The file name an OBJ's `mtllib` line gives its material library,
    /// returned as a side file of that name.
    pub material_library: String,
    /// Whether the picture is ray traced, with how many samples and
    /// threads.
    pub tracing: Tracing,
    /// An SVG whose drawn parts name the source that drew them
    /// (`data-src="FROM-TO"`, bytes of the source): what the live page
    /// links picture and text by. Only a flat picture of plain symbols is
    /// linked; the rest is drawn as without it.
    pub linked: bool,
}

impl Request {
    /// A request for `target` with `graftal render`'s defaults: the file's
    /// steps, seed 0, 1024x1024, the file's view, a layout, 10 frames a
    /// second.
    pub fn new(target: Target) -> Request {
        Request {
            run: RunOptions::default(),
            target,
            width: 1024,
            height: 1024,
            view: None,
            style: Style::default(),
            detail: Detail::default(),
            spline: false,
            layout: true,
            fps: DEFAULT_FPS,
            material_library: "graftal.mtl".into(),
            tracing: Tracing::default(),
            linked: false,
        }
    }
}

/// How a picture was made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// From the shared derivation tree, without deriving the word.
    SharedSubtrees,
    /// The word's segments drawn into the picture as the turtle makes
    /// them; none stored.
    Streamed,
    /// A lit look drawn straight from the turtle, band by band.
    Lit,
    /// The word interpreted into stored geometry, then drawn.
    Stored,
    /// A glTF with one mesh per repeated subtree.
    InstancedMesh,
    /// A mesh of the interpreted geometry.
    Mesh,
    /// The frames of an animation, each drawn as its still is.
    Animation,
    /// Ray traced: an instancing graph without expanding it, or the
    /// turtle's geometry through a bounding volume hierarchy.
    RayTraced,
    /// The attractor of a planar instancing graph (a 2D IFS), pixel by
    /// pixel.
    Attractor,
}

impl Method {
    pub fn name(self) -> &'static str {
        match self {
            Method::SharedSubtrees => "shared subtrees",
            Method::Streamed => "streamed",
            Method::Lit => "lit",
            Method::Stored => "stored",
            Method::InstancedMesh => "instanced mesh",
            Method::Mesh => "mesh",
            Method::Animation => "animation",
            Method::RayTraced => "ray traced",
            Method::Attractor => "attractor",
        }
    }
}

/// A file written beside the picture.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SideFile {
    /// Its file name, without folder.
    pub name: String,
    pub bytes: Vec<u8>,
}

/// What [`draw`] made.
#[derive(Clone, Debug)]
pub struct Picture {
    pub bytes: Vec<u8>,
    pub side_files: Vec<SideFile>,
    pub method: Method,
    /// What the picture shows badly or not at all (W0008, W0009).
    pub warnings: Vec<Diagnostic>,
    /// What a mesh holds.
    pub mesh: Option<MeshStats>,
}

/// Why no picture was made.
#[derive(Debug)]
pub enum DrawError {
    /// The source could not be read ([`make`]).
    NotRead(LoadError),
    /// The source has errors, or is a library whose entry was not chosen:
    /// the compiled file's diagnostics say which.
    NotCompiled,
    /// The derivation or the interpretation stopped: a limit, or an error
    /// in the model's program.
    Stopped(Box<Diagnostic>),
    /// The picture cannot be encoded at this size.
    Encode { width: u32, height: u32 },
    /// The animation is refused: why (too many frames or pixels).
    Animation(String),
    /// A POV-Ray scene was asked of a picture drawn flat.
    NoScene,
    /// The system is not drawn as asked: why (a 3D instancing graph,
    /// which is ray traced).
    NotDrawable(String),
}

impl std::fmt::Display for DrawError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DrawError::NotRead(e) => write!(f, "{e}"),
            DrawError::NotCompiled => f.write_str("the file has errors"),
            DrawError::Stopped(d) => f.write_str(&d.message),
            DrawError::Encode { width, height } => {
                write!(f, "cannot make a {width}x{height} PNG")
            }
            DrawError::Animation(why) | DrawError::NotDrawable(why) => f.write_str(why),
            DrawError::NoScene => {
                f.write_str("a POV-Ray scene is written from 3D geometry, not from a flat picture")
            }
        }
    }
}

impl From<Diagnostic> for DrawError {
    fn from(d: Diagnostic) -> DrawError {
        DrawError::Stopped(Box::new(d))
    }
}

/// What the drawing reports while it works: the CLI shows it as progress
/// bars. Every method has a default that does nothing ([`Quiet`]).
pub trait Progress {
    /// After each derivation step: `step` of `steps`, the word `symbols`
    /// long.
    fn derived(&mut self, _step: u64, _steps: u64, _symbols: usize) {}
    /// `done` of `total` units of `stage`.
    fn advanced(&mut self, _stage: Stage, _done: u64, _total: u64) {}
}

/// The stages [`Progress::advanced`] reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Segments drawn.
    Drawing,
    /// Primitives meshed.
    Meshing,
    /// Frames of an animation.
    Frames,
}

/// Progress nobody watches.
pub struct Quiet;

impl Progress for Quiet {}

/// Where a source comes from, for [`make`].
#[derive(Clone, Debug)]
pub enum Source {
    /// A path, `std:NAME`, or `FILE:NAME` for a library's entry.
    Spec(String),
    /// Text, named as a file would be (its extension chooses the notation).
    Text { name: String, text: String },
}

/// What [`make`] read and made: the compiled file (for its diagnostics)
/// when the source could be read, and the picture or why there is none.
pub struct Made {
    pub compiled: Option<Compiled>,
    pub picture: Result<Picture, DrawError>,
}

/// Reads `source` (choosing `entry` of a library, reading it as
/// `notation` when given), compiles it and draws it as `req` asks.
pub fn make(
    source: &Source,
    entry: Option<&str>,
    notation: Option<&'static dyn Front>,
    req: &Request,
    progress: &mut dyn Progress,
) -> Made {
    let (file, named) = match source {
        Source::Spec(spec) => {
            let (path, named) = split_entry(spec);
            match load(&path) {
                Ok(file) => (file, named),
                Err(e) => {
                    return Made {
                        compiled: None,
                        picture: Err(DrawError::NotRead(e)),
                    }
                }
            }
        }
        Source::Text { name, text } => (SourceFile::new(name.as_str(), text.as_str()), None),
    };
    let c = compile_as(file, entry.or(named.as_deref()), notation);
    let picture = draw(&c, req, progress);
    Made {
        compiled: Some(c),
        picture,
    }
}

/// Draws the compiled file `c` as `req` asks, choosing the method.
pub fn draw(
    c: &Compiled,
    req: &Request,
    progress: &mut dyn Progress,
) -> Result<Picture, DrawError> {
    let sys = c.system.as_ref().ok_or(DrawError::NotCompiled)?;
    let subject = Subject {
        sys,
        file: &c.file.name,
        diagnostics: &c.diagnostics,
        spans: Some(&c.spans),
    };
    draw_subject(&subject, req, progress)
}

/// [`draw`] of a system and what is known of its file.
fn draw_subject(
    s: &Subject,
    req: &Request,
    progress: &mut dyn Progress,
) -> Result<Picture, DrawError> {
    let ropts = render_options(req, s.sys, s.file);
    if let Some(graph) = &s.sys.graph {
        // A plane IFS is drawn flat, pixel by pixel, unless a ray-traced
        // picture (or a scene for one) is asked for; every other graph is
        // ray traced (`still_counted`).
        if let Target::Still(format) = req.target {
            let traced = format == Format::Pov
                || traced::wanted(s.sys, &req.tracing)
                || !attractor::draws(graph);
            if traced {
                let how = How::of(req);
                return still_counted(s, &req.run, format, ropts, how, progress).map(|(p, _)| p);
            }
        }
        let bytes = attractor::draw(s.sys, graph, req.target, ropts)?;
        return Ok(Picture {
            bytes,
            side_files: Vec::new(),
            method: Method::Attractor,
            warnings: Vec::new(),
            mesh: None,
        });
    }
    match req.target {
        Target::Still(format) => {
            let how = How::of(req);
            still_counted(s, &req.run, format, ropts, how, progress).map(|(p, _)| p)
        }
        Target::Mesh(format) => mesh::draw(s.sys, format, req, progress),
        Target::Animation(container) => animate::draw(s, req, container, ropts, progress),
    }
}

/// [`draw`] for a system that comes from no file (built by hand, or
/// changed after compiling): nothing is known of its file.
pub fn draw_system(
    sys: &System,
    req: &Request,
    progress: &mut dyn Progress,
) -> Result<Picture, DrawError> {
    let diagnostics = Diagnostics::default();
    let subject = Subject {
        sys,
        file: "",
        diagnostics: &diagnostics,
        spans: None,
    };
    draw_subject(&subject, req, progress)
}

/// The system drawn, with what a warning about its picture names: its
/// file and the diagnostics it was compiled with.
struct Subject<'a> {
    sys: &'a System,
    file: &'a str,
    diagnostics: &'a Diagnostics,
    /// Where the file writes its symbols, for a linked picture.
    spans: Option<&'a SpanTable>,
}

/// The picture `req` asks for, in the renderer's terms: the view asked
/// for, else the file's own; the stdlib's kolams drawn as splines.
fn render_options(req: &Request, sys: &System, file: &str) -> RenderOptions {
    // The file's view is in radians, as `View` holds it.
    let view = req
        .view
        .or(sys.settings.view.map(|(az, el)| View {
            azimuth: az,
            elevation: el,
        }))
        .unwrap_or_default();
    RenderOptions {
        width: req.width,
        height: req.height,
        view,
        spline: req.spline || crate::stdlib::draws_as_spline(file),
        view_given: req.view.is_some(),
        style: req.style,
        detail: req.detail,
        threads: req.tracing.threads,
        ..RenderOptions::default()
    }
}

/// What a still picture is made with besides its run and options.
#[derive(Clone, Copy, Debug)]
struct How {
    /// An STL file's layout drawn under the tree.
    layout: bool,
    tracing: Tracing,
    /// An SVG linked to its source ([`Request::linked`]).
    linked: bool,
}

impl How {
    fn of(req: &Request) -> How {
        How {
            layout: req.layout,
            tracing: req.tracing,
            linked: req.linked,
        }
    }
}

/// A still picture by the first method that serves: ray traced where the
/// request or the model asks, else shared subtrees, streamed, lit, stored,
/// with the segments it kept in memory (the stored way's; an animation's
/// frames share one limit on them). Only the stored way explains an empty
/// picture, so the others hand over to it when they draw nearly nothing.
fn still_counted(
    s: &Subject,
    run: &RunOptions,
    format: Format,
    ropts: RenderOptions,
    how: How,
    progress: &mut dyn Progress,
) -> Result<(Picture, usize), DrawError> {
    let sys = s.sys;
    let layout = how.layout;
    let picture = |bytes, method| Picture {
        bytes,
        side_files: Vec::new(),
        method,
        warnings: Vec::new(),
        mesh: None,
    };
    if let Some(g) = &sys.graph {
        let bytes = traced::graph(sys, g, format, &ropts, &how.tracing)?;
        return Ok((picture(bytes, Method::RayTraced), 0));
    }
    // A POV-Ray scene is what the tracer would draw.
    let ray_traced = format == Format::Pov || traced::wanted(sys, &how.tracing);
    let mut drawing = |done: u64, total: u64| progress.advanced(Stage::Drawing, done, total);
    if let (true, Format::Svg, Some(spans)) = (how.linked, format, s.spans) {
        if let Some(bytes) = linked::draw(sys, spans, run, ropts, layout)? {
            return Ok((picture(bytes, Method::Stored), 0));
        }
    }
    if ray_traced {
        // A context-free system is traced from its shared subtrees; the
        // rest needs the geometry (streaming and lit bands draw lines).
        if let Some(bytes) = traced::shared(sys, run, format, &ropts, &how.tracing)? {
            return Ok((picture(bytes, Method::RayTraced), 0));
        }
    } else if let Some(bytes) = shared::draw(sys, run, format, ropts, &mut drawing)? {
        return Ok((picture(bytes, Method::SharedSubtrees), 0));
    }
    check_moves_up_front(sys, run)?;
    let steps = run.derive_options(sys).steps;
    let (word, values) = if !ray_traced && streamed::streams(sys, format, &ropts) {
        let w = derive_symbols(sys, run, |k, n| progress.derived(k, steps, n))?;
        let mut drawing = |done: u64, total: u64| progress.advanced(Stage::Drawing, done, total);
        match streamed::draw(sys, run, w, ropts, &mut drawing)? {
            streamed::Streamed::Picture(bytes) => return Ok((picture(bytes, Method::Streamed), 0)),
            streamed::Streamed::Word(w, values) => (w, values),
        }
    } else {
        derive_values(sys, run, |k, n| progress.derived(k, steps, n))?
    };
    let mut drawing = |done: u64, total: u64| progress.advanced(Stage::Drawing, done, total);
    if !ray_traced && lit::streams_lit(sys, format, &ropts, layout) {
        if let Some(bytes) = lit::draw(sys, &word, &values, run, ropts, &mut drawing)? {
            return Ok((picture(bytes, Method::Lit), 0));
        }
    }
    let mut g = interpret(sys, &word, &values, run, ropts.spline)?;
    add_fixed(sys, &mut g, layout);
    let warning = if g.is_empty() {
        Some(nothing_drawn(sys, &word, s.file, run, s.diagnostics))
    } else {
        nearly_nothing_drawn(sys, &g, &ropts)
    };
    let (bytes, method) = if ray_traced && !g.is_empty() {
        let bytes = traced::geometry(sys, &g, format, &ropts, &how.tracing)?;
        (bytes, Method::RayTraced)
    } else {
        let bytes = stored::render_bytes_with(sys, &g, format, ropts, &mut drawing)?;
        (bytes, Method::Stored)
    };
    let mut p = picture(bytes, method);
    p.warnings.extend(warning);
    Ok((p, g.segments.len()))
}
