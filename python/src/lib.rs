//! graftal for Python: a thin face over the library the command line and
//! the page use. Each function parses its arguments, calls the library
//! (`graftal::driver` and what it returns) with the GIL released, and
//! converts what comes back; how a file is read, derived, drawn or
//! translated is decided in the library alone.
//!
//! The rooms: `model.rs` (a compiled file and what can be asked of it),
//! `request.rs` (a picture's options into the library's request),
//! `picture.rs` (a picture's bytes, shown inline), `word.rs` (a derived
//! word streamed in chunks), `geometry.rs` (segments and polygons as NumPy
//! arrays), `diagnostic.rs` (diagnostics and `GraftalError`) and `html.rs`
//! (the command line's coloured diagnostics as HTML).

// The library's diagnostics are returned by value on cold error paths, as
// the library itself returns them; boxing them buys nothing.
#![allow(clippy::result_large_err)]

mod diagnostic;
mod geometry;
mod html;
mod model;
mod picture;
mod request;
mod word;

use diagnostic::GraftalError;
use graftal::driver;
use pyo3::prelude::*;

/// The stack of the thread each library call runs on: the command line's
/// (`src/main.rs`), so that every input the command line reads is read here
/// too.
const STACK_BYTES: usize = 64 << 20;

/// Runs `work` with the GIL released, on a thread with the command line's
/// stack; a panic in the library is raised as `GraftalError`, never an
/// abort of the interpreter.
pub(crate) fn call<T: Send>(py: Python<'_>, work: impl FnOnce() -> T + Send) -> PyResult<T> {
    let joined = py.detach(|| {
        std::thread::scope(|scope| {
            let thread = std::thread::Builder::new()
                .name("graftal".into())
                .stack_size(STACK_BYTES)
                .spawn_scoped(scope, work);
            match thread {
                Ok(t) => t.join().map_err(|panic| panic_message(&*panic)),
                Err(e) => Err(format!("cannot start a thread: {e}")),
            }
        })
    });
    joined.map_err(|why| diagnostic::plain(py, format!("graftal stopped: {why}")))
}

/// What a panic says.
fn panic_message(panic: &(dyn std::any::Any + Send)) -> String {
    match (panic.downcast_ref::<&str>(), panic.downcast_ref::<String>()) {
        (Some(s), _) => s.to_string(),
        (_, Some(s)) => s.clone(),
        _ => "a panic".into(),
    }
}

/// Reads a file (a path, `std:NAME`, or `FILE:NAME` for a library's entry)
/// and compiles it: a `Model`, with its diagnostics, errors or not. Raises
/// `GraftalError` only when the file cannot be read.
#[pyfunction]
#[pyo3(signature = (path_or_std, entry=None, notation=None))]
fn load(
    py: Python<'_>,
    path_or_std: &str,
    entry: Option<&str>,
    notation: Option<&str>,
) -> PyResult<model::Model> {
    let front = model::front(notation)?;
    let (path, named) = driver::split_entry(path_or_std);
    let loaded = call(py, || {
        let file = driver::load(&path)?;
        Ok(model::compiled(file, entry.or(named.as_deref()), front))
    })?;
    let (c, seconds) =
        loaded.map_err(|e: driver::LoadError| diagnostic::plain(py, e.to_string()))?;
    Ok(model::Model::new(c, seconds))
}

/// Compiles `text` in `notation` (else as a file called `name` would be
/// read: by its extension, and for `.l` by its content).
#[pyfunction]
#[pyo3(signature = (text, notation=None, name=None))]
fn parse(
    py: Python<'_>,
    text: &str,
    notation: Option<&str>,
    name: Option<&str>,
) -> PyResult<model::Model> {
    let front = model::front(notation)?;
    let name = match (name, front) {
        (Some(n), _) => n.to_string(),
        (None, Some(f)) => format!("<text>.{}", f.extensions().first().unwrap_or(&"l")),
        (None, None) => "<text>.l".to_string(),
    };
    let file = graftal::source::SourceFile::new(name, text);
    let (c, seconds) = call(py, || model::compiled(file, None, front))?;
    Ok(model::Model::new(c, seconds))
}

/// A diagnostic code's title and explanation, as `graftal explain CODE`
/// prints them.
#[pyfunction]
fn explain(py: Python<'_>, code: &str) -> PyResult<String> {
    let info = graftal::diagnostics::codes::lookup(code).ok_or_else(|| {
        diagnostic::plain(
            py,
            format!("no diagnostic code `{code}` (codes look like E0004 or W0001)"),
        )
    })?;
    Ok(graftal::diagnostics::codes::explain_text(info))
}

/// The notations graftal reads (what `notation=` takes).
#[pyfunction]
fn notations() -> Vec<&'static str> {
    graftal::front::FRONTS.iter().map(|f| f.name()).collect()
}

/// The notations graftal writes (what `Model.translate` takes).
#[pyfunction]
fn targets() -> Vec<&'static str> {
    graftal::back::BACKS.iter().map(|b| b.name()).collect()
}

/// The standard library's entries, as `load` takes them (`std:NAME`).
#[pyfunction]
fn stdlib() -> Vec<String> {
    graftal::stdlib::names()
        .map(|n| format!("std:{n}"))
        .collect()
}

#[pymodule]
fn _graftal(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("GraftalError", m.py().get_type::<GraftalError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<model::Model>()?;
    m.add_class::<diagnostic::Diagnostic>()?;
    m.add_class::<diagnostic::Diagnostics>()?;
    m.add_class::<picture::Picture>()?;
    m.add_class::<word::WordChunks>()?;
    for f in [
        wrap_pyfunction!(load, m)?,
        wrap_pyfunction!(parse, m)?,
        wrap_pyfunction!(explain, m)?,
        wrap_pyfunction!(notations, m)?,
        wrap_pyfunction!(targets, m)?,
        wrap_pyfunction!(stdlib, m)?,
    ] {
        m.add_function(f)?;
    }
    Ok(())
}
