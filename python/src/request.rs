//! A picture's options, as Python passes them, into the library's request
//! (`graftal::driver::picture::Request`), checked as the command line
//! checks `graftal render`'s flags.

use graftal::driver::picture::{Format, Request, Target};
use graftal::mesh::MeshFormat;
use graftal::render::animate::Container;
use graftal::render::{Detail, Margin, Palette, View};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The largest picture side, as `graftal render --size` takes it: 8192²
/// pixels take 256 MB.
const MAX_SIDE: u32 = 8192;

/// The options `Model.picture` takes besides the format.
const OPTIONS: &[&str] = &[
    "size",
    "view",
    "steps",
    "seed",
    "max_symbols",
    "raytrace",
    "samples",
    "threads",
    "spline",
    "layout",
    "linked",
    "background",
    "stroke_width",
    "margin",
    "rotate",
    "palette",
    "detail",
    "fps",
    "material_library",
];

/// What `format` (a name: png, svg, pov, obj, ply, glb, gif, apng) makes.
pub fn target(format: &str) -> PyResult<Target> {
    let name = format.to_ascii_lowercase();
    if let Some(f) = Format::from_name(&name) {
        return Ok(Target::Still(f));
    }
    if let Some(m) = MeshFormat::ALL.into_iter().find(|m| m.extension() == name) {
        return Ok(Target::Mesh(m));
    }
    match (name.as_str(), Container::choose(None, Some(&name))) {
        ("gif" | "apng", Some(c)) => Ok(Target::Animation(c)),
        _ => Err(PyValueError::new_err(format!(
            "no format `{format}`: graftal makes {}",
            format_names().join(", ")
        ))),
    }
}

/// Every format's name, as `target` takes them.
fn format_names() -> Vec<String> {
    let named = |t: Target| match t {
        Target::Animation(Container::Apng) => "apng".to_string(),
        other => other.extension().to_string(),
    };
    Target::all().map(named).collect()
}

/// The animation `format` names: `gif`, or `apng` (also `png`).
pub fn animation_format(format: &str) -> PyResult<&'static str> {
    match format.to_ascii_lowercase().as_str() {
        "gif" => Ok("gif"),
        "apng" | "png" => Ok("apng"),
        _ => Err(PyValueError::new_err(format!(
            "`{format}`: an animation is a \"gif\" or an \"apng\" (an animated PNG)"
        ))),
    }
}

/// The request for a model's picture in a notebook: `format` (svg or png)
/// of `side` pixels, otherwise as `graftal render` draws it.
pub fn inline(format: &str, side: u32) -> Request {
    let format = Format::from_name(format).unwrap_or(Format::Svg);
    let mut req = Request::new(Target::Still(format));
    req.width = side.clamp(1, MAX_SIDE);
    req.height = req.width;
    req
}

/// The request for `format` with `options` (each `None` is as if not
/// given): `graftal render`'s defaults for the rest.
pub fn from_options(format: &str, options: Option<&Bound<'_, PyDict>>) -> PyResult<Request> {
    let mut req = Request::new(target(format)?);
    for (key, value) in options.into_iter().flat_map(|d| d.iter()) {
        let key: String = key.extract()?;
        if !value.is_none() {
            set(&mut req, &key, &value).map_err(|e| about(value.py(), &key, e))?;
        }
    }
    Ok(req)
}

/// An option's error, naming the option.
fn about(py: Python<'_>, key: &str, e: PyErr) -> PyErr {
    let why = e.value(py).to_string();
    match e.is_instance_of::<PyTypeError>(py) {
        true => PyTypeError::new_err(format!("{key}: {why}")),
        false => PyValueError::new_err(format!("{key}: {why}")),
    }
}

/// Sets the option `key` of `req` to `value`.
fn set(req: &mut Request, key: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
    match key {
        "size" => (req.width, req.height) = size(value)?,
        "view" => req.view = Some(view(value)?),
        "steps" => req.run.steps = Some(value.extract()?),
        "seed" => req.run.seed = value.extract()?,
        "max_symbols" => req.run.max_symbols = value.extract()?,
        "raytrace" => req.tracing.raytrace = Some(value.extract()?),
        "samples" => req.tracing.samples = within(value, &[1, 4, 9, 16])?,
        "threads" => req.tracing.threads = ranged(value, 1, 1024)? as usize,
        "spline" => req.spline = value.extract()?,
        "layout" => req.layout = value.extract()?,
        "linked" => req.linked = value.extract()?,
        "background" => req.style.background = Some(parsed(value, graftal::ir::colours::parse)?),
        "stroke_width" => req.style.stroke_width = Some(finite(value, 0.0, f64::from(MAX_SIDE))?),
        "margin" => req.style.margin = Some(margin(value)?),
        "rotate" => req.style.rotate = finite(value, f64::MIN, f64::MAX)?,
        "palette" => req.style.palette = Some(named(value, Palette::from_name, &Palette::NAMES)?),
        "detail" => req.detail = named(value, Detail::from_name, &Detail::NAMES)?,
        "fps" => req.fps = ranged(value, 1, 100)?,
        "material_library" => req.material_library = value.extract()?,
        _ => {
            return Err(PyTypeError::new_err(format!(
                "not an option; the options are {}",
                OPTIONS.join(", ")
            )))
        }
    }
    Ok(())
}

/// A size: N (square), (W, H), or "WxH"; each side 1..=8192.
fn size(value: &Bound<'_, PyAny>) -> PyResult<(u32, u32)> {
    let (w, h) = if let Ok(n) = value.extract::<u32>() {
        (n, n)
    } else if let Ok(text) = value.extract::<String>() {
        let (w, h) = text
            .split_once(['x', 'X'])
            .ok_or_else(|| PyValueError::new_err(format!("`{text}` is not WIDTHxHEIGHT")))?;
        let side = |s: &str| {
            s.trim()
                .parse::<u32>()
                .map_err(|_| PyValueError::new_err(format!("`{text}` is not WIDTHxHEIGHT")))
        };
        (side(w)?, side(h)?)
    } else {
        value.extract::<(u32, u32)>()?
    };
    if w == 0 || h == 0 || w > MAX_SIDE || h > MAX_SIDE {
        return Err(PyValueError::new_err(format!(
            "width and height must be 1..={MAX_SIDE}"
        )));
    }
    Ok((w, h))
}

/// A view: (azimuth, elevation) in degrees.
fn view(value: &Bound<'_, PyAny>) -> PyResult<View> {
    let (az, el): (f64, f64) = value.extract()?;
    if !az.is_finite() || !el.is_finite() {
        return Err(PyValueError::new_err("angles must be finite"));
    }
    Ok(View::degrees(az, el))
}

fn finite(value: &Bound<'_, PyAny>, low: f64, high: f64) -> PyResult<f64> {
    let x: f64 = value.extract()?;
    match x.is_finite() && (low..=high).contains(&x) {
        true => Ok(x),
        false => Err(PyValueError::new_err(format!(
            "{x} is not in {low}..={high}"
        ))),
    }
}

fn ranged(value: &Bound<'_, PyAny>, low: u32, high: u32) -> PyResult<u32> {
    let n: u32 = value.extract()?;
    match (low..=high).contains(&n) {
        true => Ok(n),
        false => Err(PyValueError::new_err(format!(
            "{n} is not in {low}..={high}"
        ))),
    }
}

fn within(value: &Bound<'_, PyAny>, allowed: &[u32]) -> PyResult<u32> {
    let n: u32 = value.extract()?;
    match allowed.contains(&n) {
        true => Ok(n),
        false => Err(PyValueError::new_err(format!(
            "{n} is not one of {allowed:?}"
        ))),
    }
}

/// A name the library looks up (`from_name`), one of `names`.
fn named<T>(
    value: &Bound<'_, PyAny>,
    from_name: impl Fn(&str) -> Option<T>,
    names: &[&str],
) -> PyResult<T> {
    let name: String = value.extract()?;
    from_name(&name).ok_or_else(|| {
        PyValueError::new_err(format!("`{name}` is not one of {}", names.join(", ")))
    })
}

/// A text the library parses (`parse`), its error raised as it words it.
fn parsed<T>(value: &Bound<'_, PyAny>, parse: impl Fn(&str) -> Result<T, String>) -> PyResult<T> {
    let text: String = value.extract()?;
    parse(&text).map_err(PyValueError::new_err)
}

/// A margin: pixels (a number), or a text as `--margin` takes it (`5%`,
/// `0.05`, `50`).
fn margin(value: &Bound<'_, PyAny>) -> PyResult<Margin> {
    match value.extract::<String>() {
        Ok(text) => Margin::parse(&text).map_err(PyValueError::new_err),
        Err(_) => {
            Margin::parse(&value.extract::<f64>()?.to_string()).map_err(PyValueError::new_err)
        }
    }
}
