//! A picture drawn by the library's one call (`driver::picture::draw`):
//! its bytes, the files it needs beside it, its warnings, shown inline in a
//! notebook in its own format.

use crate::diagnostic::Diagnostics;
use graftal::diagnostics::Diagnostic as Found;
use graftal::driver::picture::{self, DrawError, Format, Quiet, Request, Target};
use graftal::driver::Compiled;
use graftal::mesh::MeshFormat;
use graftal::render::animate::Container;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use std::sync::Arc;

/// Why no picture was made, as the face raises it.
pub enum Refused {
    /// The diagnostics that stopped it (a limit, the model's program).
    Diagnostics(Vec<Found>),
    /// The file has errors, or a library's entry is not chosen.
    NotCompiled,
    /// A problem of the picture itself (its size, an animation's frames).
    Other(String),
}

/// Draws `c` as `req` asks.
pub fn draw(c: &Compiled, req: &Request) -> Result<picture::Picture, Refused> {
    picture::draw(c, req, &mut Quiet).map_err(|e| match e {
        DrawError::Stopped(d) => Refused::Diagnostics(vec![*d]),
        DrawError::NotCompiled => Refused::NotCompiled,
        other => Refused::Other(other.to_string()),
    })
}

/// A picture, a mesh or an animation: `data` (its bytes), `format`,
/// `warnings`, `side_files` (name -> bytes: an OBJ's materials), `method`
/// (how the library drew it); `save(path)` writes it with its side files.
#[pyclass(module = "graftal", frozen)]
pub struct Picture {
    #[pyo3(get)]
    data: Py<PyBytes>,
    /// Its format's name: png, svg, pov, obj, ply, glb, gif or apng.
    #[pyo3(get)]
    format: &'static str,
    /// Its media type (`image/png`, …).
    #[pyo3(get)]
    media_type: &'static str,
    #[pyo3(get)]
    method: &'static str,
    #[pyo3(get)]
    warnings: Py<Diagnostics>,
    side: Vec<(String, Vec<u8>)>,
}

impl Picture {
    pub fn new(
        py: Python<'_>,
        p: picture::Picture,
        target: Target,
        compiled: &Arc<Compiled>,
    ) -> PyResult<Picture> {
        let (format, media_type) = kind(target);
        Ok(Picture {
            data: PyBytes::new(py, &p.bytes).unbind(),
            format,
            media_type,
            method: p.method.name(),
            warnings: Py::new(py, Diagnostics::new(py, &p.warnings, compiled)?)?,
            side: (p.side_files.into_iter())
                .map(|s| (s.name, s.bytes))
                .collect(),
        })
    }

    /// Its bytes.
    pub fn bytes<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        self.data.bind(py).clone()
    }
}

/// A target's name and media type.
fn kind(target: Target) -> (&'static str, &'static str) {
    match target {
        Target::Still(Format::Png) => ("png", "image/png"),
        Target::Still(Format::Svg) => ("svg", "image/svg+xml"),
        Target::Still(Format::Pov) => ("pov", "text/plain"),
        Target::Mesh(MeshFormat::Obj) => ("obj", "model/obj"),
        Target::Mesh(MeshFormat::Ply) => ("ply", "application/octet-stream"),
        Target::Mesh(MeshFormat::Glb) => ("glb", "model/gltf-binary"),
        Target::Animation(Container::Gif) => ("gif", "image/gif"),
        // An animated PNG is a PNG to every viewer.
        Target::Animation(Container::Apng) => ("apng", "image/png"),
    }
}

#[pymethods]
impl Picture {
    /// The files to write beside it: name -> bytes.
    #[getter]
    fn side_files<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let files = PyDict::new(py);
        for (name, bytes) in &self.side {
            files.set_item(name, PyBytes::new(py, bytes))?;
        }
        Ok(files)
    }

    /// Writes it to `path`, and its side files into the same folder.
    fn save(&self, py: Python<'_>, path: std::path::PathBuf) -> PyResult<()> {
        let folder = path.parent().unwrap_or(std::path::Path::new(""));
        for (name, bytes) in &self.side {
            write(&folder.join(name), bytes)?;
        }
        write(&path, self.data.as_bytes(py))
    }

    fn __bytes__<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        self.bytes(py)
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        let n = self.data.as_bytes(py).len();
        format!("<graftal.Picture {} of {n} bytes>", self.format)
    }

    /// Shown in a notebook as what it is: an image (SVG, PNG, a GIF or an
    /// animated PNG); other formats have no picture to show.
    #[pyo3(signature = (include=None, exclude=None))]
    fn _repr_mimebundle_<'py>(
        &self,
        py: Python<'py>,
        include: Option<Bound<'py, PyAny>>,
        exclude: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let _ = (include, exclude);
        let bundle = PyDict::new(py);
        bundle.set_item("text/plain", self.__repr__(py))?;
        let bytes = self.data.as_bytes(py);
        match self.media_type {
            "image/svg+xml" => bundle.set_item(self.media_type, String::from_utf8_lossy(bytes))?,
            "image/png" | "image/gif" => {
                let encoded = py
                    .import("base64")?
                    .call_method1("b64encode", (self.data.bind(py),))?;
                bundle.set_item(self.media_type, encoded.call_method1("decode", ("ascii",))?)?
            }
            _ => {}
        }
        Ok(bundle)
    }
}

fn write(path: &std::path::Path, bytes: &[u8]) -> PyResult<()> {
    Ok(std::fs::write(path, bytes)?)
}
