//! Diagnostics as Python objects: each field the command line's JSON
//! record has (`graftal::diagnostics::to_json`), the fix, and the text the
//! command line prints (plain, or as HTML in a notebook); `GraftalError`
//! carries them.

use crate::html;
use graftal::diagnostics::{self, Diagnostic as Found};
use graftal::driver::Compiled;
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyIndexError};
use pyo3::prelude::*;
use pyo3::types::PyList;
use serde_json::Value;
use std::sync::Arc;

create_exception!(
    _graftal,
    GraftalError,
    PyException,
    "What graftal could not do: `diagnostics` holds the diagnostics that say why (empty when the \
     problem is not in a file, such as a file that cannot be read)."
);

/// One problem found in a file, with its place.
#[pyclass(module = "graftal", frozen)]
pub struct Diagnostic {
    found: Found,
    compiled: Arc<Compiled>,
    record: Value,
}

impl Diagnostic {
    pub fn new(found: Found, compiled: Arc<Compiled>) -> Diagnostic {
        let record = diagnostics::to_json(&found, &compiled.file);
        Diagnostic {
            found,
            compiled,
            record,
        }
    }

    fn field(&self, key: &str) -> Option<&Value> {
        self.record.get(key).filter(|v| !v.is_null())
    }

    fn number(&self, key: &str) -> Option<usize> {
        self.field(key)?.as_u64().map(|n| n as usize)
    }

    fn text(&self, key: &str) -> Option<String> {
        self.field(key)?.as_str().map(String::from)
    }
}

#[pymethods]
impl Diagnostic {
    /// The code, e.g. `E0004` (`graftal.explain(code)` explains it).
    #[getter]
    fn code(&self) -> String {
        self.found.code.0.to_string()
    }

    /// `"error"` or `"warning"`.
    #[getter]
    fn severity(&self) -> Option<String> {
        self.text("severity")
    }

    #[getter]
    fn message(&self) -> String {
        self.found.message.clone()
    }

    /// The file the place is in (a side file, such as a cpfg view file,
    /// when the problem is there).
    #[getter]
    fn file(&self) -> Option<String> {
        self.text("file")
    }

    /// The line of the place, from 1; `None` without a place.
    #[getter]
    fn line(&self) -> Option<usize> {
        self.number("line")
    }

    /// The column of the place, from 1; `None` without a place.
    #[getter]
    fn column(&self) -> Option<usize> {
        self.number("column")
    }

    /// The place as byte offsets `(start, end)` into the file's text.
    #[getter]
    fn span(&self) -> Option<(usize, usize)> {
        Some((self.number("start")?, self.number("end")?))
    }

    #[getter]
    fn help(&self) -> Option<String> {
        self.text("help")
    }

    #[getter]
    fn notes(&self) -> Vec<String> {
        let notes = self.field("notes").and_then(Value::as_array);
        let each = notes.into_iter().flatten().filter_map(Value::as_str);
        each.map(String::from).collect()
    }

    /// The edits that fix it: `(start, end, replacement)`, bytes of the
    /// file's text.
    #[getter]
    fn fixes(&self) -> Vec<(usize, usize, String)> {
        let fix = self.found.fix.as_ref();
        fix.map(|f| (f.span.start, f.span.end, f.replacement.clone()))
            .into_iter()
            .collect()
    }

    /// The diagnostic as the command line prints it (without colour).
    fn __str__(&self) -> String {
        self.render(false)
    }

    fn __repr__(&self) -> String {
        let place = match (self.line(), self.column()) {
            (Some(l), Some(c)) => format!(" at {}:{l}:{c}", self.file().unwrap_or_default()),
            _ => String::new(),
        };
        format!(
            "<Diagnostic {} {}{place}: {}>",
            self.code(),
            self.severity().unwrap_or_default(),
            self.found.message
        )
    }

    /// The command line's coloured text as HTML, the place marked.
    fn _repr_html_(&self) -> String {
        html::of_terminal(&self.render(true))
    }
}

impl Diagnostic {
    fn render(&self, colour: bool) -> String {
        diagnostics::render_human(&self.found, &self.compiled.file, colour)
    }
}

/// Diagnostics of one file: a sequence of `Diagnostic`, printed as the
/// command line prints them (the first 20, then what was not shown).
#[pyclass(module = "graftal", frozen, sequence)]
pub struct Diagnostics {
    items: Vec<Py<Diagnostic>>,
    compiled: Arc<Compiled>,
}

impl Diagnostics {
    pub fn new(py: Python<'_>, found: &[Found], compiled: &Arc<Compiled>) -> PyResult<Diagnostics> {
        let items = found
            .iter()
            .map(|d| Py::new(py, Diagnostic::new(d.clone(), compiled.clone())))
            .collect::<PyResult<_>>()?;
        Ok(Diagnostics {
            items,
            compiled: compiled.clone(),
        })
    }

    fn render(&self, colour: bool) -> String {
        let found: Vec<Found> = self.items.iter().map(|d| d.get().found.clone()).collect();
        diagnostics::render_all(&found, &self.compiled.file, colour)
    }

    /// The command line's coloured text as HTML, each place marked; `None`
    /// when there is nothing to show.
    pub fn html(&self) -> Option<String> {
        match self.items.is_empty() {
            true => None,
            false => Some(html::of_terminal(&self.render(true))),
        }
    }
}

#[pymethods]
impl Diagnostics {
    fn __len__(&self) -> usize {
        self.items.len()
    }

    fn __getitem__(&self, py: Python<'_>, index: isize) -> PyResult<Py<Diagnostic>> {
        let n = self.items.len() as isize;
        let at = if index < 0 { index + n } else { index };
        match usize::try_from(at).ok().and_then(|k| self.items.get(k)) {
            Some(d) => Ok(d.clone_ref(py)),
            None => Err(PyIndexError::new_err("diagnostic index out of range")),
        }
    }

    fn __iter__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let items = self.items.iter().map(|d| d.clone_ref(py));
        PyList::new(py, items)?.try_iter().map(Bound::into_any)
    }

    /// Whether any of them is an error.
    #[getter]
    fn has_errors(&self) -> bool {
        self.items.iter().any(|d| d.get().found.is_error())
    }

    fn __str__(&self) -> String {
        self.render(false)
    }

    fn __repr__(&self) -> String {
        let errors = self.items.iter().filter(|d| d.get().found.is_error());
        let errors = errors.count();
        let warnings = self.items.len() - errors;
        format!("<Diagnostics: {errors} error(s), {warnings} warning(s)>")
    }

    /// The command line's coloured text as HTML, each place marked.
    fn _repr_html_(&self) -> Option<String> {
        self.html()
    }
}

/// A `GraftalError` saying `message`, carrying `found` (diagnostics of
/// `compiled`'s file); its text is theirs as the command line prints them.
pub fn error(py: Python<'_>, found: &[Found], compiled: &Arc<Compiled>, message: &str) -> PyErr {
    let made = Diagnostics::new(py, found, compiled);
    let text = match found.is_empty() {
        true => message.to_string(),
        false => diagnostics::render_all(found, &compiled.file, false),
    };
    let err = GraftalError::new_err(text.trim_end().to_string());
    let attached = made
        .and_then(|d| Py::new(py, d))
        .and_then(|d| err.value(py).setattr("diagnostics", d));
    match attached {
        Ok(()) => err,
        Err(e) => e,
    }
}

/// A `GraftalError` with no diagnostics: a problem that is not in a file.
pub fn plain(py: Python<'_>, message: impl Into<String>) -> PyErr {
    let err = GraftalError::new_err(message.into());
    match err.value(py).setattr("diagnostics", PyList::empty(py)) {
        Ok(()) => err,
        Err(e) => e,
    }
}
