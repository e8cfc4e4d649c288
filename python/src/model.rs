//! A compiled file and what can be asked of it: its diagnostics, its
//! word, its figures, its picture, its translation, its geometry. Each
//! method is one call of the library (`graftal::driver`), as the command
//! line makes it.

use crate::diagnostic::{self, Diagnostics};
use crate::picture::{self, Picture};
use crate::{call, geometry, request, word};
use graftal::back;
use graftal::diagnostics::Diagnostic as Found;
use graftal::driver::{self, Compiled, RunOptions};
use graftal::front::Front;
use graftal::source::SourceFile;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyString, PyTuple};
use std::sync::{Arc, Mutex};

/// The notation named `name` (`None`: as the file's extension and content
/// say).
pub fn front(name: Option<&str>) -> PyResult<Option<&'static dyn Front>> {
    let Some(name) = name else { return Ok(None) };
    match graftal::front::by_name(name) {
        Some(f) => Ok(Some(f)),
        None => Err(PyValueError::new_err(format!(
            "no notation named `{name}`: graftal reads {}",
            driver::notations()
        ))),
    }
}

/// `file` compiled (choosing `entry` of a library, in `notation` when
/// given), and the seconds it took (what `stats` reports as parsing).
pub fn compiled(
    file: SourceFile,
    entry: Option<&str>,
    notation: Option<&'static dyn Front>,
) -> (Compiled, f64) {
    let start = std::time::Instant::now();
    let c = driver::compile_as(file, entry, notation);
    (c, start.elapsed().as_secs_f64())
}

/// An L-system file, read and compiled: `graftal.load` and `graftal.parse`
/// make one, errors or not; `diagnostics` says what was found. A model
/// shows its picture in a notebook (`inline`: `"svg"` or `"png"`, of
/// `inline_size` pixels), or its diagnostics when it has none.
#[pyclass(module = "graftal")]
pub struct Model {
    compiled: Arc<Compiled>,
    parse_seconds: f64,
    inline: String,
    /// The side of the picture shown in a notebook, in pixels.
    #[pyo3(get, set)]
    inline_size: u32,
    /// The last picture shown inline, and what it was drawn as.
    shown: Mutex<Option<((String, u32), Shown)>>,
}

/// What a model shows inline: its picture's bytes, or the diagnostics that
/// say why there is none.
#[derive(Clone)]
enum Shown {
    Picture(Vec<u8>),
    Diagnostics(Vec<Found>),
}

impl Model {
    pub fn new(c: Compiled, parse_seconds: f64) -> Model {
        Model {
            compiled: Arc::new(c),
            parse_seconds,
            inline: "svg".into(),
            inline_size: 512,
            shown: Mutex::new(None),
        }
    }

    /// The compiled system, or the error that carries the file's
    /// diagnostics (and the one asking for a library's entry).
    fn system(&self, py: Python<'_>) -> PyResult<&graftal::ir::System> {
        let c = &self.compiled;
        match &c.system {
            Some(sys) => Ok(sys),
            None => Err(diagnostic::error(
                py,
                &self.compile_diagnostics(),
                c,
                "the file has errors",
            )),
        }
    }

    /// The file's diagnostics, with the error asking for an entry of a
    /// library whose entry was not chosen (as `derive` prints them).
    fn compile_diagnostics(&self) -> Vec<Found> {
        let c = &self.compiled;
        let mut found = c.diagnostics.0.clone();
        if c.needs_entry() {
            found.push(driver::choose_entry(c));
        }
        found
    }

    fn diagnostics_of(&self, py: Python<'_>, found: &[Found]) -> PyResult<Diagnostics> {
        Diagnostics::new(py, found, &self.compiled)
    }

    fn raise(&self, py: Python<'_>, found: Found) -> PyErr {
        let message = found.message.clone();
        diagnostic::error(py, &[found], &self.compiled, &message)
    }

    /// The inline picture as `inline` says, drawn once for each setting.
    fn shown(&self, py: Python<'_>) -> PyResult<Shown> {
        let key = (self.inline.clone(), self.inline_size);
        let mut kept = self.shown.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, s)) = kept.as_ref().filter(|(k, _)| *k == key) {
            return Ok(s.clone());
        }
        let req = request::inline(&self.inline, self.inline_size);
        let c = &self.compiled;
        let drawn = call(py, || picture::draw(c, &req))?;
        let s = match drawn {
            Ok(p) => Shown::Picture(p.bytes),
            Err(picture::Refused::Diagnostics(found)) => Shown::Diagnostics(found),
            Err(picture::Refused::NotCompiled) => Shown::Diagnostics(self.compile_diagnostics()),
            Err(picture::Refused::Other(why)) => return Err(diagnostic::plain(py, why)),
        };
        *kept = Some((key, s.clone()));
        Ok(s)
    }

    fn shown_as(&self, py: Python<'_>, format: &str) -> PyResult<Option<Vec<u8>>> {
        if self.inline != format {
            return Ok(None);
        }
        match self.shown(py)? {
            Shown::Picture(bytes) => Ok(Some(bytes)),
            Shown::Diagnostics(_) => Ok(None),
        }
    }
}

#[pymethods]
impl Model {
    /// The file's name (`std:NAME` for the standard library's).
    #[getter]
    fn file(&self) -> String {
        self.compiled.file.name.clone()
    }

    /// The notation the file was read as (`pfg`, `linf`, `stl`, …).
    #[getter]
    fn notation(&self) -> &'static str {
        self.compiled.front.name()
    }

    /// The file's text.
    #[getter]
    fn text(&self) -> String {
        self.compiled.file.text.clone()
    }

    /// Whether the file compiled to a system (no errors, and an entry
    /// chosen of a library).
    #[getter]
    fn ok(&self) -> bool {
        self.compiled.system.is_some()
    }

    /// A library's entries (`None` for a file of one system).
    #[getter]
    fn entries(&self) -> Option<Vec<String>> {
        let lib = self.compiled.library.as_ref()?;
        Some(lib.entries.iter().map(|e| e.name.clone()).collect())
    }

    /// What reading the file found.
    #[getter]
    fn diagnostics(&self, py: Python<'_>) -> PyResult<Diagnostics> {
        self.diagnostics_of(py, &self.compile_diagnostics())
    }

    /// The picture format shown in a notebook: `"svg"` or `"png"`.
    #[getter]
    fn inline(&self) -> &str {
        &self.inline
    }

    #[setter]
    fn set_inline(&mut self, format: &str) -> PyResult<()> {
        match format {
            "svg" | "png" => {
                self.inline = format.to_string();
                Ok(())
            }
            _ => Err(PyValueError::new_err(format!(
                "`{format}`: a model is shown inline as \"svg\" or \"png\""
            ))),
        }
    }

    /// What `graftal check` reports: the file's diagnostics and the limits
    /// its derivation reaches.
    fn check(&self, py: Python<'_>) -> PyResult<Diagnostics> {
        let c = &self.compiled;
        let mut found = c.diagnostics.0.clone();
        found.extend(call(py, || driver::derivation_diagnostics(c))?);
        self.diagnostics_of(py, &found)
    }

    /// The derived word after `steps` (the file's own by default), as
    /// `graftal derive` prints it (without its last newline). With
    /// `stream=True`, an iterator over the word's text in chunks, for
    /// words too big to hold as one string.
    #[pyo3(signature = (steps=None, seed=None, *, max_symbols=None, stream=false))]
    fn derive(
        &self,
        py: Python<'_>,
        steps: Option<u64>,
        seed: Option<u64>,
        max_symbols: Option<usize>,
        stream: bool,
    ) -> PyResult<Py<PyAny>> {
        let sys = self.system(py)?;
        let opts = run_options(steps, seed, max_symbols);
        if stream {
            let chunks = word::WordChunks::start(self.compiled.clone(), opts)?;
            return Ok(Py::new(py, chunks)?.into_any());
        }
        let c = &self.compiled;
        let written = call(py, || {
            let mut out = Vec::new();
            driver::write_derived(c.front, sys, &opts, &mut out, |_, _| {}).map(|()| out)
        })?;
        let mut bytes = written.map_err(|d| self.raise(py, d))?;
        if bytes.last() == Some(&b'\n') {
            bytes.pop();
        }
        // Decoded once, by Python: the word is UTF-8 as the library writes it.
        Ok(PyString::from_bytes(py, &bytes)?.into_any().unbind())
    }

    /// What `graftal stats --format json` reports, as a dict; `warnings`
    /// holds what could not be measured.
    #[pyo3(signature = (steps=None, seed=None, *, max_symbols=None))]
    fn stats<'py>(
        &self,
        py: Python<'py>,
        steps: Option<u64>,
        seed: Option<u64>,
        max_symbols: Option<usize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let sys = self.system(py)?;
        let opts = run_options(steps, seed, max_symbols);
        let measured = call(py, || driver::stats(sys, &opts))?;
        let mut s = measured.map_err(|d| self.raise(py, d))?;
        s.time.parse = self.parse_seconds;
        let json = serde_json::to_string(&s).map_err(|e| diagnostic::plain(py, e.to_string()))?;
        let figures = py.import("json")?.call_method1("loads", (json,))?;
        figures.set_item("warnings", self.diagnostics_of(py, &s.warnings)?)?;
        Ok(figures)
    }

    /// The picture (PNG, SVG, POV-Ray scene), mesh (OBJ, PLY, GLB) or
    /// animation (GIF, APNG) `format` names, as bytes, drawn as
    /// `graftal render` draws it. Options: size (pixels: N, (W, H) or
    /// "WxH"), view ((azimuth, elevation) in degrees), steps, seed,
    /// max_symbols, raytrace, samples, threads, spline, layout, linked,
    /// background, stroke_width, margin, rotate, palette, detail, fps.
    #[pyo3(signature = (format="png", **options))]
    fn render<'py>(
        &self,
        py: Python<'py>,
        format: &str,
        options: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyBytes>> {
        Ok(self.picture(py, format, options)?.bytes(py))
    }

    /// `render`'s picture as an object: its bytes (`data`), its format, its
    /// warnings, the files it needs beside it (an OBJ's materials), shown
    /// inline in a notebook; `save(path)` writes them all.
    #[pyo3(signature = (format="png", **options))]
    fn picture(
        &self,
        py: Python<'_>,
        format: &str,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Picture> {
        let req = request::from_options(format, options)?;
        self.system(py)?;
        let c = &self.compiled;
        let drawn = call(py, || picture::draw(c, &req))?;
        let found = match drawn {
            Ok(p) => return Picture::new(py, p, req.target, c),
            Err(picture::Refused::Other(why)) => return Err(diagnostic::plain(py, why)),
            Err(picture::Refused::Diagnostics(found)) => found,
            Err(picture::Refused::NotCompiled) => self.compile_diagnostics(),
        };
        let message = found.first().map(|d| d.message.clone()).unwrap_or_default();
        Err(diagnostic::error(py, &found, c, &message))
    }

    /// The steps from 0 as the frames of an animation (`"gif"`, or
    /// `"apng"` for an animated PNG), from the first that draws anything,
    /// framed as the last; shown inline in a notebook. Takes `picture`'s
    /// options.
    #[pyo3(signature = (format="gif", **options))]
    fn animate(
        &self,
        py: Python<'_>,
        format: &str,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Picture> {
        let name = request::animation_format(format)?;
        self.picture(py, name, options)
    }

    /// The system written in the notation `to` (`graftal.targets()`):
    /// `(text, diagnostics)`. What the target cannot express raises
    /// `GraftalError`, or with `lossy=True` is approximated with a warning.
    #[pyo3(signature = (to, *, lossy=false, steps=None))]
    fn translate<'py>(
        &self,
        py: Python<'py>,
        to: &str,
        lossy: bool,
        steps: Option<u64>,
    ) -> PyResult<Bound<'py, PyTuple>> {
        let target = back::by_name(to).ok_or_else(|| {
            let names: Vec<&str> = back::BACKS.iter().map(|b| b.name()).collect();
            PyValueError::new_err(format!(
                "no notation `{to}` to translate to: graftal writes {}",
                names.join(", ")
            ))
        })?;
        let sys = self.system(py)?;
        let req = back::Request {
            target,
            lossy,
            steps,
        };
        let c = &self.compiled;
        let t = call(py, || driver::translate(c, sys, &req))?;
        let Some(text) = t.text else {
            let message = format!("cannot translate to {to}");
            return Err(diagnostic::error(py, &t.diagnostics.0, c, &message));
        };
        let found = self.diagnostics_of(py, &t.diagnostics.0)?;
        (text, found).into_pyobject(py)
    }

    /// What the turtle draws, as NumPy arrays (turtle units): a dict of
    /// `segments` (N x 2 x 3: each segment's ends), `widths` (N),
    /// `colours` (N x 3, 0..255), `polygon_points` (M x 3),
    /// `polygon_offsets` (P + 1: polygon k is points[offsets[k]:offsets[k+1]])
    /// and `polygon_colours` (P x 3).
    #[pyo3(signature = (steps=None, seed=None, *, max_symbols=None))]
    fn geometry<'py>(
        &self,
        py: Python<'py>,
        steps: Option<u64>,
        seed: Option<u64>,
        max_symbols: Option<usize>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let sys = self.system(py)?;
        let opts = run_options(steps, seed, max_symbols);
        let drawn = call(py, || geometry::Arrays::of(sys, &opts))?;
        drawn.map_err(|d| self.raise(py, d))?.into_dict(py)
    }

    fn __repr__(&self) -> String {
        let c = &self.compiled;
        let errors = c.diagnostics.iter().filter(|d| d.is_error()).count();
        let state = match (&c.system, errors) {
            (Some(_), _) => String::new(),
            (None, 0) => ", no entry chosen".into(),
            (None, n) => format!(", {n} error(s)"),
        };
        format!(
            "<graftal.Model {} ({}){state}>",
            c.file.name,
            c.front.name()
        )
    }

    fn _repr_svg_(&self, py: Python<'_>) -> PyResult<Option<String>> {
        let svg = self.shown_as(py, "svg")?;
        Ok(svg.map(|b| String::from_utf8_lossy(&b).into_owned()))
    }

    fn _repr_png_<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyBytes>>> {
        let png = self.shown_as(py, "png")?;
        Ok(png.map(|b| PyBytes::new(py, &b)))
    }

    /// The diagnostics, when the model has no picture to show.
    fn _repr_html_(&self, py: Python<'_>) -> PyResult<Option<String>> {
        match self.shown(py)? {
            Shown::Picture(_) => Ok(None),
            Shown::Diagnostics(found) => Ok(self.diagnostics_of(py, &found)?.html()),
        }
    }
}

/// The run `derive`, `stats` and `geometry` make: the file's steps unless
/// `steps`, seed 0 unless `seed`, the command line's limits.
pub fn run_options(
    steps: Option<u64>,
    seed: Option<u64>,
    max_symbols: Option<usize>,
) -> RunOptions {
    RunOptions {
        steps,
        seed: seed.unwrap_or(0),
        max_symbols: max_symbols.unwrap_or(driver::DEFAULT_MAX_SYMBOLS),
        ..RunOptions::default()
    }
}
