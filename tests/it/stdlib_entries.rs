//! Every stdlib entry either draws at its defaults or is a schema that says
//! so: a new user who renders `std:NAME` never gets a silent blank picture.
//! Drawn means more than one segment or a filled polygon (for the kolams
//! drawn as splines, more than one turtle position), spread over two
//! dimensions.

use graftal::driver::picture::{self, Format, Method, Quiet, Request, Target};
use graftal::driver::{compile, derive_values, interpret, load, why_nothing_drawn, RunOptions};
use graftal::stdlib::{Kind, ENTRIES};
use graftal::turtle::{Geometry, Vec3};

/// The points the picture of `g` is made of; for a spline, the turtle's
/// positions it passes through.
fn points(g: &Geometry, spline: bool) -> Vec<Vec3> {
    if spline {
        return g.paths.iter().flat_map(|p| p.points.clone()).collect();
    }
    let polygons = g.polygons.iter().flat_map(|p| p.points.clone());
    g.segments
        .iter()
        .flat_map(|s| [s.a, s.b])
        .chain(polygons)
        .collect()
}

/// How many axes the points spread along (relative to their largest extent).
fn spread_axes(points: &[Vec3]) -> usize {
    let extent = |k: usize| {
        let (lo, hi) = points.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
            (lo.min(p[k]), hi.max(p[k]))
        });
        (hi - lo).max(0.0)
    };
    let e = [extent(0), extent(1), extent(2)];
    let largest = e.iter().cloned().fold(0.0, f64::max);
    e.iter()
        .filter(|&&x| largest > 0.0 && x > 1e-6 * largest)
        .count()
}

#[test]
fn every_entry_draws_at_its_defaults_or_is_a_schema() {
    let opts = RunOptions::default();
    let mut schemata = Vec::new();
    for e in ENTRIES {
        let c = compile(load(&format!("std:{}", e.name)).unwrap());
        let sys = c
            .system
            .as_ref()
            .unwrap_or_else(|| panic!("{} compiles", e.name));
        if sys.graph.is_some() {
            // An instancing graph is drawn, never derived: a small picture
            // shows it.
            let mut req = Request::new(Target::Still(Format::Png));
            (req.width, req.height) = (24, 24);
            req.tracing.samples = 1;
            let p = picture::draw_system(sys, &req, &mut Quiet).unwrap();
            assert_eq!(p.method, Method::RayTraced, "{}", e.name);
            assert!(inked(&p.bytes) > 20, "{} draws", e.name);
            continue;
        }
        let (word, values) = derive_values(sys, &opts, |_, _| {}).unwrap();
        let spline = e.kind() == Kind::Spline;
        let g = interpret(sys, &word, &values, &opts, spline).unwrap();
        let pts = points(&g, spline);
        let drawn = if spline { pts.len() } else { g.segments.len() };
        let draws = (drawn > 1 || !g.polygons.is_empty()) && spread_axes(&pts) >= 2;
        match e.kind() {
            Kind::Schema => {
                assert!(!draws, "{} draws: it is no schema", e.name);
                assert!(e.schema_reason().is_some_and(|r| !r.is_empty()));
                let why = why_nothing_drawn(sys, &word, e.file, opts.steps.unwrap_or(1));
                assert!(why.unwrap().contains("is a schema"), "{}", e.name);
                schemata.push(e.name);
            }
            _ => assert!(draws, "{} draws {drawn} ({:?})", e.name, e.kind()),
        }
    }
    // The string examples and schemata of the book's chapters 1 and 3.
    assert_eq!(schemata.len(), 10, "{schemata:?}");
}

#[test]
fn the_kolams_draw_as_splines_and_say_why_without() {
    let opts = RunOptions::default();
    let mut blank = 0;
    for e in ENTRIES.iter().filter(|e| e.kind() == Kind::Spline) {
        assert!(e.name.starts_with("kolam-"), "{}", e.name);
        let c = compile(load(&format!("std:{}", e.name)).unwrap());
        let sys = c.system.unwrap();
        let (word, values) = derive_values(&sys, &opts, |_, _| {}).unwrap();
        let g = interpret(&sys, &word, &values, &opts, false).unwrap();
        if !g.segments.is_empty() {
            continue;
        }
        blank += 1;
        let why = why_nothing_drawn(&sys, &word, "kolam.l", 4).unwrap();
        assert!(why.contains("--spline"), "{why}");
    }
    // Mango leaves draws its `F`s without the spline; the other three
    // move only with `f`.
    assert_eq!(blank, 3);
}

#[test]
fn entries_name_their_figure() {
    for e in ENTRIES {
        let fig = e.figure().to_lowercase();
        let data = e.name.starts_with("hogeweg-hesper");
        assert!(
            fig.contains("fig")
                || fig.contains("section")
                || fig.contains('§')
                // Smith's paper names its pictures plates and its tables.
                || fig.contains("plate")
                || fig.contains("table")
                // The .gft library's own models, printed in no book.
                || (e.name.starts_with("gft/") && fig.starts_with("new: "))
                || data,
            "{}: `{fig}`",
            e.name
        );
    }
}

#[test]
fn unknown_names_suggest_the_nearest_entries() {
    let m = graftal::stdlib::unknown("fig08-tree-3d");
    assert!(m.contains("did you mean `std:linf/fig08-tree-3d`?"), "{m}");
    assert!(m.contains("`graftal list`"), "{m}");
    let m = graftal::stdlib::unknown("koch");
    assert!(m.contains("`std:koch-"), "{m}");
    let m = graftal::stdlib::unknown("algea");
    assert!(m.contains("`std:algae`"), "{m}");
    let m = graftal::stdlib::unknown("");
    assert!(!m.contains("did you mean"), "{m}");
    // A huge name is shown shortened, and not compared.
    let m = graftal::stdlib::unknown(&"koch".repeat(100_000));
    assert!(m.len() < 200 && !m.contains("did you mean"), "{m}");
}

/// Pixels of a PNG unlike its first (the background).
fn inked(png_bytes: &[u8]) -> usize {
    let decoder = png::Decoder::new(std::io::Cursor::new(png_bytes));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let px: Vec<&[u8]> = buf[..info.buffer_size()].chunks(4).collect();
    px.iter().filter(|p| **p != px[0]).count()
}
