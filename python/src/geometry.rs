//! What the turtle drew (`driver::geometry`) as NumPy arrays, for
//! analysis: the segments' ends, widths and colours; the polygons' points
//! laid end to end, with where each begins.

use graftal::diagnostics::Diagnostic;
use graftal::driver::{self, RunOptions};
use graftal::ir::System;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The arrays, filled without the GIL; made NumPy arrays with it.
pub struct Arrays {
    segments: Vec<f64>,
    widths: Vec<f64>,
    colours: Vec<u8>,
    polygon_points: Vec<f64>,
    polygon_offsets: Vec<i64>,
    polygon_colours: Vec<u8>,
}

impl Arrays {
    /// The segments and polygons the turtle draws for `sys` run as `opts`
    /// says (`driver::geometry`: derived, interpreted, with its look's
    /// scene).
    pub fn of(sys: &System, opts: &RunOptions) -> Result<Arrays, Diagnostic> {
        let (_, g) = driver::geometry(sys, opts)?;
        let mut a = Arrays {
            segments: Vec::with_capacity(g.segments.len() * 6),
            widths: Vec::with_capacity(g.segments.len()),
            colours: Vec::with_capacity(g.segments.len() * 3),
            polygon_points: Vec::new(),
            polygon_offsets: vec![0],
            polygon_colours: Vec::with_capacity(g.polygons.len() * 3),
        };
        for s in &g.segments {
            a.segments.extend(s.a.iter().chain(&s.b));
            a.widths.push(s.width);
            a.colours.extend([s.colour.0, s.colour.1, s.colour.2]);
        }
        for p in &g.polygons {
            a.polygon_points.extend(p.points.iter().flatten());
            let points = (a.polygon_points.len() / 3) as i64;
            a.polygon_offsets.push(points);
            a.polygon_colours
                .extend([p.colour.0, p.colour.1, p.colour.2]);
        }
        Ok(a)
    }

    pub fn into_dict(self, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let n = self.widths.len();
        let points = self.polygon_points.len() / 3;
        let polygons = self.polygon_colours.len() / 3;
        let d = PyDict::new(py);
        let segments = PyArray1::from_vec(py, self.segments).reshape([n, 2, 3])?;
        d.set_item("segments", segments)?;
        d.set_item("widths", PyArray1::from_vec(py, self.widths))?;
        d.set_item(
            "colours",
            PyArray1::from_vec(py, self.colours).reshape([n, 3])?,
        )?;
        let polygon_points = PyArray1::from_vec(py, self.polygon_points).reshape([points, 3])?;
        d.set_item("polygon_points", polygon_points)?;
        d.set_item(
            "polygon_offsets",
            PyArray1::from_vec(py, self.polygon_offsets),
        )?;
        let polygon_colours =
            PyArray1::from_vec(py, self.polygon_colours).reshape([polygons, 3])?;
        d.set_item("polygon_colours", polygon_colours)?;
        Ok(d)
    }
}
