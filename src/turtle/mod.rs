//! Turtle interpretation: a derived word -> [`Geometry`] (segments and
//! filled polygons in 3D turtle units).
//!
//! The turtle starts at the origin with step length 1, heading H = +y, left
//! L = −x and up U = H × L = +z, so a 2D system drawn in 3D lies in the
//! xy-plane and looks, from the default view (down −z), as in the papers.
//! Rotations are the book's matrices (see [`crate::ir::TurtleOp`]).
//!
//! `|` turns by exactly 180°. The Appendix A listing, which keeps the heading
//! as an integer multiple of δ, turns by `angle factor / 2` steps instead, so
//! for an odd angle factor its `|` falls short of a half turn; graftal
//! follows the book's definition (§2.3: `R_U(180°)`), which the listing
//! meets for every even angle factor.

mod cost;
mod gencyl;
pub mod instanced;
mod tropism;

use crate::ir::colours::DEFAULT_PALETTE;
use crate::ir::{
    Angle, Axis, ElasticityChange, QueryKind, Rgb, RotationId, SymbolId, System, TurtleOp, Word,
};
use crate::random::{Rng, Stream};
use serde::Serialize;

pub use cost::drawn_cost;

pub type Vec3 = [f64; 3];

/// A drawn line segment.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Segment {
    pub a: Vec3,
    pub b: Vec3,
    pub width: f64,
    pub colour: Rgb,
    /// The colour index it was drawn with: the material of a lit look
    /// ([`crate::ir::look::Lighting`]).
    pub index: u16,
    /// How many branches it is nested in (`[` deep), for a picture coloured
    /// by depth ([`crate::render::Palette::Depth`]).
    #[serde(skip)]
    pub depth: u16,
}

/// A filled polygon.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Polygon {
    pub points: Vec<Vec3>,
    pub colour: Rgb,
    /// The colour index it was drawn with: the material of a lit look
    /// ([`crate::ir::look::Lighting`]).
    pub index: u16,
    /// Part of a surface (`~`): cpfg's colour-map shading scales the index
    /// within its block of 64 for surfaces, and shifts it for polygons
    /// and the tubes of cylinders (manual §8.1.3).
    pub surface: bool,
}

/// The sequence of turtle positions along one branch (every move, drawn or
/// not), for spline rendering: the book draws kolams (§6.2) and Fig. 2.11
/// by using consecutive turtle positions as B-spline control points.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TurtlePath {
    pub points: Vec<Vec3>,
    pub width: f64,
    pub colour: Rgb,
    /// How many branches deep the path is (0 for the trunk), for colouring
    /// by depth ([`crate::render::Palette::Depth`]).
    pub depth: u16,
}

/// A filled disc facing the viewer (a cpfg sphere `@O` or circle `@o`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Disc {
    pub centre: Vec3,
    pub diameter: f64,
    /// Whether `diameter` is in pixels (a line width) rather than turtle
    /// units.
    pub pixels: bool,
    pub colour: Rgb,
    /// The colour index it was drawn with: the material of a lit look
    /// ([`crate::ir::look::Lighting`]).
    pub index: u16,
}

/// What the turtle drew.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Geometry {
    pub segments: Vec<Segment>,
    pub polygons: Vec<Polygon>,
    pub discs: Vec<Disc>,
    /// Whether segment widths are in turtle units rather than pixels
    /// ([`crate::ir::Settings::world_widths`]).
    pub world_widths: bool,
    /// Turtle paths, when asked for ([`TurtleOptions::paths`]).
    pub paths: Vec<TurtlePath>,
    /// The deepest branch nesting reached.
    pub max_depth: usize,
    /// Which module drew what, when asked for ([`TurtleOptions::origins`]).
    #[serde(skip)]
    pub origins: Origins,
    /// The order the turtle drew in, as runs of one kind, so that a stored
    /// drawing replays as it was drawn ([`Geometry::replay`]): a lit
    /// picture drawn from it and one drawn straight from the turtle agree.
    #[serde(skip)]
    pub order: Vec<(Drawn, u32)>,
}

/// Grows the box `b` (`[minx, miny, minz, maxx, maxy, maxz]`, `None` when
/// empty) to hold `p`.
pub fn grow_box(b: &mut Option<[f64; 6]>, p: Vec3) {
    let b = b.get_or_insert([p[0], p[1], p[2], p[0], p[1], p[2]]);
    for k in 0..3 {
        b[k] = b[k].min(p[k]);
        b[k + 3] = b[k + 3].max(p[k]);
    }
}

/// A kind of thing the turtle draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Drawn {
    Segment,
    Polygon,
    Disc,
}

/// Per segment, polygon and disc drawn, the index in the word of the
/// module that drew it: what lets a growth animation show the parts of a
/// word in the order they grew.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Origins {
    pub segments: Vec<usize>,
    pub polygons: Vec<usize>,
    pub discs: Vec<usize>,
}

/// What [`interpret_with`] records besides segments and polygons.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TurtleOptions {
    /// Record the turtle's positions per branch in [`Geometry::paths`].
    pub paths: bool,
    /// Record which module drew what in [`Geometry::origins`].
    pub origins: bool,
}

impl Geometry {
    /// `[minx, miny, minz, maxx, maxy, maxz]` of everything drawn, or `None`
    /// when nothing was drawn.
    pub fn bbox(&self) -> Option<[f64; 6]> {
        let pts = self
            .segments
            .iter()
            .flat_map(|s| [s.a, s.b])
            .chain(self.polygons.iter().flat_map(|p| p.points.iter().copied()))
            .chain(self.discs.iter().map(|d| d.centre));
        let mut b: Option<[f64; 6]> = None;
        for p in pts {
            grow_box(&mut b, p);
        }
        b
    }

    /// Nothing drawn: no segment, no polygon, and no path with a move.
    pub fn is_empty(&self) -> bool {
        self.segments.is_empty()
            && self.polygons.is_empty()
            && self.discs.is_empty()
            && self.paths.iter().all(|p| p.points.len() < 2)
    }
}

const NO_HISTORY: u32 = u32::MAX;

#[derive(Clone, Copy, Debug)]
struct State {
    pos: Vec3,
    h: Vec3,
    l: Vec3,
    u: Vec3,
    length: f64,
    width: f64,
    colour: usize,
    /// The colours `PreviousColour` goes back to: the head of a list kept
    /// in an arena shared by all states (so a push copies one index, not
    /// the history), `NO_HISTORY` when empty.
    history: u32,
    swapped: bool,
    /// A generalized cylinder being drawn: the last control point, the
    /// heading there, and the tangent factors of the next segment.
    cylinder: Option<Cylinder>,
    /// Fractint's real heading ([`TurtleOp::RotateReal`]): radians
    /// counter-clockwise from the initial H towards the initial L.
    real: f64,
    /// The cross-section of generalized cylinders: an index into
    /// [`System::contours`] plus one, 0 for the default circle.
    contour: u16,
    /// The tangent factors a control point set here gets (cpfg `@Gt`): for
    /// the piece of cylinder arriving at it, and the one leaving it.
    tangents: (f64, f64),
    /// The radius tangents a control point set here gets (cpfg `@Gr`):
    /// for the piece of cylinder arriving at it, and the one leaving it.
    radius_tangents: [[f64; 2]; 2],
    /// Whether the radius parts of the tangents are scaled by the distance
    /// between control points (cpfg `@Gr(s)`).
    scale_radius_tangents: bool,
}

#[derive(Clone, Copy, Debug)]
struct Cylinder {
    point: Vec3,
    heading: Vec3,
    /// The frame's up, the width and the cross-section there (what a mesh
    /// sweeps from).
    up: Vec3,
    width: f64,
    contour: u16,
    /// The tangent factors there (the leaving one starts the next piece).
    tangents: (f64, f64),
    /// The radius tangents there (the leaving one starts the next piece).
    radius_tangents: [[f64; 2]; 2],
}

/// cpfg's default tangent coefficients: the tangents at a Hermite
/// segment's ends are this many times the distance between its control
/// points.
const DEFAULT_TANGENTS: (f64, f64) = (1.2, 1.2);

impl Cylinder {
    /// A cylinder whose last control point is where the turtle is.
    fn at(st: &State) -> Self {
        Cylinder {
            point: st.pos,
            heading: st.h,
            up: st.u,
            width: st.width,
            contour: st.contour,
            tangents: st.tangents,
            radius_tangents: st.radius_tangents,
        }
    }
}

pub(crate) fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(crate) fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn add_scaled(a: Vec3, b: Vec3, k: f64) -> Vec3 {
    [a[0] + b[0] * k, a[1] + b[1] * k, a[2] + b[2] * k]
}

/// Points of the cubic Hermite curve from `p0` (tangent `t0`) to `p1`
/// (tangent `t1`), `n` pieces, without `p0`.
fn hermite(p0: Vec3, t0: Vec3, p1: Vec3, t1: Vec3, n: usize) -> Vec<Vec3> {
    (1..=n)
        .map(|k| {
            let t = k as f64 / n as f64;
            let (t2, t3) = (t * t, t * t * t);
            let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
            let h10 = t3 - 2.0 * t2 + t;
            let h01 = -2.0 * t3 + 3.0 * t2;
            let h11 = t3 - t2;
            std::array::from_fn(|i| h00 * p0[i] + h10 * t0[i] + h01 * p1[i] + h11 * t1[i])
        })
        .collect()
}

fn rotate(a: Vec3, b: Vec3, c: f64, s: f64) -> (Vec3, Vec3) {
    // (a', b') = (a cos − b sin, a sin + b cos)
    let a2 = [
        a[0] * c - b[0] * s,
        a[1] * c - b[1] * s,
        a[2] * c - b[2] * s,
    ];
    let b2 = [
        a[0] * s + b[0] * c,
        a[1] * s + b[1] * c,
        a[2] * s + b[2] * c,
    ];
    (a2, b2)
}

/// Rotations between two re-orthonormalisations of the frame: rounding in
/// each rotation moves the frame off orthonormal by about 1e-16, so millions
/// of rotations (a LinF random walk) would drift by 1e-10 and more.
const RENORMALISE_EVERY: u32 = 32;

/// A colour index as primitives keep it.
pub(crate) fn index_of(colour: usize) -> u16 {
    colour.min(u16::MAX as usize) as u16
}

fn normalised(v: Vec3) -> Vec3 {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / n, v[1] / n, v[2] / n]
}

impl State {
    /// Gram–Schmidt: H unit, L unit and orthogonal to H, U = H × L.
    fn renormalise(&mut self) {
        let h = normalised(self.h);
        let d = self.l[0] * h[0] + self.l[1] * h[1] + self.l[2] * h[2];
        let l = normalised([
            self.l[0] - d * h[0],
            self.l[1] - d * h[1],
            self.l[2] - d * h[2],
        ]);
        self.u = [
            h[1] * l[2] - h[2] * l[1],
            h[2] * l[0] - h[0] * l[2],
            h[0] * l[1] - h[1] * l[0],
        ];
        self.h = h;
        self.l = l;
    }

    fn turn(&mut self, axis: Axis, angle: f64) {
        let angle = if self.swapped { -angle } else { angle };
        let (s, c) = angle.sin_cos();
        match axis {
            // R_U(α): H' = H cos α − L sin α, L' = H sin α + L cos α
            Axis::Up => (self.h, self.l) = rotate(self.h, self.l, c, s),
            // R_L(α): H' = H cos α + U sin α, U' = −H sin α + U cos α
            Axis::Left => (self.u, self.h) = rotate(self.u, self.h, c, s),
            // R_H(α): L' = L cos α + U sin α, U' = −L sin α + U cos α
            Axis::Heading => (self.u, self.l) = rotate(self.u, self.l, c, s),
        }
    }

    /// A turn about U by `angle`, whether turns are swapped or not.
    fn turn_unswapped(&mut self, angle: f64) {
        let (s, c) = angle.sin_cos();
        (self.h, self.l) = rotate(self.h, self.l, c, s);
    }

    /// cpfg `@R`: heading along `heading` (unless it is zero), and cpfg's
    /// up (the turtle's −U) as near to `up` as it can be: L = H × up, as
    /// cpfg's left-handed frame has it.
    fn set_heading(&mut self, heading: Vec3, up: Vec3) {
        if dot(heading, heading) > 0.0 {
            let h = normalised(heading);
            let l = if dot(up, up) > 0.0 && dot(cross(up, h), cross(up, h)) > 1e-18 {
                normalised(cross(h, normalised(up)))
            } else {
                // Keep L as close as it can be: remove its part along the
                // new heading.
                let l = add_scaled(self.l, h, -dot(self.l, h));
                if dot(l, l) > 1e-18 {
                    normalised(l)
                } else {
                    normalised(cross(self.u, h))
                }
            };
            self.h = h;
            self.l = l;
            self.u = cross(h, l);
        }
    }

    /// cpfg `@v`: a roll about H bringing U as near to +y as it can be.
    fn roll_to_vertical(&mut self) {
        let l = cross([0.0, 1.0, 0.0], self.h);
        if dot(l, l) > 1e-18 {
            self.l = normalised(l);
            self.u = cross(self.h, self.l);
        }
    }

    /// The vector a query module asks for: cpfg's, whose up is the
    /// turtle's −U.
    fn vector(&self, kind: QueryKind) -> Vec3 {
        match kind {
            QueryKind::Position => self.pos,
            QueryKind::Heading => self.h,
            QueryKind::Left => self.l,
            // `0 − x`, not `−x`: no −0 in the word.
            QueryKind::Up => self.u.map(|x| 0.0 - x),
        }
    }
}

/// Interprets `word` as turtle commands of `sys`. `seed` drives interval
/// angles (a stream separate from the derivation's).
pub fn interpret(sys: &System, word: &Word, seed: u64) -> Geometry {
    interpret_with(sys, word, seed, TurtleOptions::default(), &mut |_, _, _| {})
}

/// Where the turtle's drawing goes: stored ([`Geometry`]), counted, or
/// drawn straight into a picture.
pub trait Sink {
    fn segment(&mut self, s: Segment);
    fn polygon(&mut self, p: Polygon);
    fn disc(&mut self, d: Disc);
}

impl Sink for Geometry {
    fn segment(&mut self, s: Segment) {
        self.note(Drawn::Segment);
        self.segments.push(s);
    }
    fn polygon(&mut self, p: Polygon) {
        self.note(Drawn::Polygon);
        self.polygons.push(p);
    }
    fn disc(&mut self, d: Disc) {
        self.note(Drawn::Disc);
        self.discs.push(d);
    }
}

impl Geometry {
    fn note(&mut self, kind: Drawn) {
        match self.order.last_mut() {
            Some((k, n)) if *k == kind && *n < u32::MAX => *n += 1,
            _ => self.order.push((kind, 1)),
        }
    }

    /// Gives everything drawn to `sink` in the order it was drawn; what
    /// was added without a note of its order (a layout, a geometry built by
    /// hand) follows: polygons, then segments, then discs.
    pub fn replay(&self, sink: &mut dyn Sink) {
        let mut next = [0usize; 3];
        let mut give = |kind: Drawn, n: usize, sink: &mut dyn Sink| {
            let k = kind as usize;
            let len = [self.segments.len(), self.polygons.len(), self.discs.len()][k];
            let end = next[k].saturating_add(n).min(len);
            for i in next[k]..end {
                match kind {
                    Drawn::Segment => sink.segment(self.segments[i].clone()),
                    Drawn::Polygon => sink.polygon(self.polygons[i].clone()),
                    Drawn::Disc => sink.disc(self.discs[i].clone()),
                }
            }
            next[k] = end;
        };
        for &(kind, n) in &self.order {
            give(kind, n as usize, sink);
        }
        for kind in [Drawn::Polygon, Drawn::Segment, Drawn::Disc] {
            give(kind, usize::MAX, sink);
        }
    }
}

/// [`interpret`], recording what `options` asks for. Modules' parameters
/// set lengths, angles, widths, colours and sizes; `query` receives, for
/// each query module (`?P`, `?H`, `?L`, `?U`), its index in `word` and the
/// vector it asks for.
pub fn interpret_with(
    sys: &System,
    word: &Word,
    seed: u64,
    options: TurtleOptions,
    query: &mut dyn FnMut(usize, QueryKind, Vec3),
) -> Geometry {
    let mut g = Geometry::default();
    let params = word.has_params().then_some(word);
    let info = run(
        sys,
        word.0.iter().copied(),
        params,
        seed,
        options,
        query,
        &mut g,
    );
    g.paths = info.paths;
    g.max_depth = info.max_depth;
    g.world_widths = info.world_widths;
    g.origins = info.origins;
    g
}

/// A sink that notes, for everything drawn, the module being interpreted
/// (`at`) before passing it on.
struct Noting<'s> {
    inner: &'s mut dyn Sink,
    at: &'s std::cell::Cell<usize>,
    origins: Origins,
}

impl Sink for Noting<'_> {
    fn segment(&mut self, s: Segment) {
        self.origins.segments.push(self.at.get());
        self.inner.segment(s);
    }
    fn polygon(&mut self, p: Polygon) {
        self.origins.polygons.push(self.at.get());
        self.inner.polygon(p);
    }
    fn disc(&mut self, d: Disc) {
        self.origins.discs.push(self.at.get());
        self.inner.disc(d);
    }
}

/// Interprets the symbols of `word` one by one, giving what is drawn to
/// `sink` (nothing is kept); returns the deepest branch nesting.
pub fn interpret_into(
    sys: &System,
    word: impl Iterator<Item = SymbolId>,
    seed: u64,
    sink: &mut dyn Sink,
) -> usize {
    run(
        sys,
        word,
        None,
        seed,
        TurtleOptions::default(),
        &mut |_, _, _| {},
        sink,
    )
    .max_depth
}

/// [`interpret_into`] for a whole word, its modules' parameters read:
/// what a picture drawn straight from the turtle replays, once per pass.
pub fn draw_into(sys: &System, word: &Word, seed: u64, sink: &mut dyn Sink) -> usize {
    let params = word.has_params().then_some(word);
    run(
        sys,
        word.0.iter().copied(),
        params,
        seed,
        TurtleOptions::default(),
        &mut |_, _, _| {},
        sink,
    )
    .max_depth
}

fn run(
    sys: &System,
    word: impl Iterator<Item = SymbolId>,
    params: Option<&Word>,
    seed: u64,
    options: TurtleOptions,
    query: &mut dyn FnMut(usize, QueryKind, Vec3),
    sink: &mut dyn Sink,
) -> Geometry {
    if !options.origins {
        return run_into(sys, word, params, seed, options, query, sink, None);
    }
    let at = std::cell::Cell::new(0);
    let mut noting = Noting {
        inner: sink,
        at: &at,
        origins: Origins::default(),
    };
    let mut info = run_into(
        sys,
        word,
        params,
        seed,
        options,
        query,
        &mut noting,
        Some(&at),
    );
    info.origins = noting.origins;
    info
}

/// [`run`], telling `at` which module is being interpreted.
#[allow(clippy::too_many_arguments)]
fn run_into(
    sys: &System,
    word: impl Iterator<Item = SymbolId>,
    params: Option<&Word>,
    seed: u64,
    options: TurtleOptions,
    query: &mut dyn FnMut(usize, QueryKind, Vec3),
    sink: &mut dyn Sink,
    at: Option<&std::cell::Cell<usize>>,
) -> Geometry {
    let ops: Vec<Option<TurtleOp>> = (0..sys.symbols.len())
        .map(|i| sys.op(SymbolId(i as u32)))
        .collect();
    let mut turtle = Turtle::new(sys, seed, options, sink, query);
    for (i, sym) in word.enumerate() {
        let Some(op) = ops.get(sym.index()).copied().flatten() else {
            continue;
        };
        let args = Args(match params {
            Some(w) => w.args(i),
            None => &[],
        });
        if let Some(at) = at {
            at.set(i);
        }
        turtle.apply(i, op, args);
    }
    turtle.finish()
}

/// The parameters of the module being interpreted.
#[derive(Clone, Copy)]
struct Args<'w>(&'w [f64]);

impl Args<'_> {
    /// Parameter `k`. A parameter that is not a number draws nothing odd:
    /// it is treated as absent.
    fn get(self, k: usize) -> Option<f64> {
        self.0.get(k).copied().filter(|v| v.is_finite())
    }

    /// How many parameters the module has.
    fn len(self) -> usize {
        self.0.len()
    }

    /// Parameters `k`, `k + 1` and `k + 2` as a vector, absent ones 0.
    fn vector(self, k: usize) -> Vec3 {
        [self.get(k), self.get(k + 1), self.get(k + 2)].map(|x| x.unwrap_or(0.0))
    }
}

/// How many pieces a cylinder module's parameter asks for.
fn pieces(n: f64) -> usize {
    n.clamp(1.0, 64.0) as usize
}

/// The turtle interpreting a word: its state and the enclosing branches'
/// states, and what it is building; what it draws goes to `sink`.
struct Turtle<'a> {
    sys: &'a System,
    palette: Vec<Rgb>,
    /// The stream interval angles are drawn from.
    rng: Rng,
    state: State,
    /// The states of the enclosing branches.
    stack: Vec<State>,
    /// Arena of the colour histories: (previous entry, colour).
    history: Vec<(u32, usize)>,
    /// The polygons being collected, innermost last: vertices and colour.
    open_polygons: Vec<(Vec<Vec3>, usize)>,
    /// The paths and the deepest nesting (segments, polygons and discs go
    /// to `sink`).
    geometry: Geometry,
    record_paths: bool,
    /// Index into `geometry.paths` of the current branch's path, and of
    /// the enclosing branches' paths.
    path: usize,
    path_stack: Vec<usize>,
    /// Rotations since the frame was last re-orthonormalised.
    rotations: u32,
    /// The system's tropisms and what bends with the turtle; `None` when
    /// it has none.
    tropisms: Option<tropism::Tropisms<'a>>,
    sink: &'a mut dyn Sink,
    query: &'a mut dyn FnMut(usize, QueryKind, Vec3),
}

impl<'a> Turtle<'a> {
    fn new(
        sys: &'a System,
        seed: u64,
        options: TurtleOptions,
        sink: &'a mut dyn Sink,
        query: &'a mut dyn FnMut(usize, QueryKind, Vec3),
    ) -> Self {
        let palette: Vec<Rgb> = if sys.colours.is_empty() {
            DEFAULT_PALETTE.to_vec()
        } else {
            sys.colours.clone()
        };
        let state = State {
            pos: [0.0; 3],
            h: [0.0, 1.0, 0.0],
            l: [-1.0, 0.0, 0.0],
            u: [0.0, 0.0, 1.0],
            length: sys.settings.step,
            width: sys.settings.width,
            colour: sys.settings.colour.min(palette.len() - 1),
            history: NO_HISTORY,
            swapped: false,
            cylinder: None,
            real: 0.0,
            contour: 0,
            tangents: DEFAULT_TANGENTS,
            radius_tangents: [[0.0; 2]; 2],
            scale_radius_tangents: false,
        };
        let mut turtle = Turtle {
            sys,
            palette,
            rng: Rng::new(seed, Stream::Turtle),
            state,
            stack: Vec::new(),
            history: Vec::new(),
            open_polygons: Vec::new(),
            geometry: Geometry::default(),
            record_paths: options.paths,
            path: usize::MAX,
            path_stack: Vec::new(),
            rotations: 0,
            tropisms: tropism::Tropisms::new(&sys.settings.tropisms, &state),
            sink,
            query,
        };
        if options.paths {
            turtle.path = turtle.start_path();
        }
        turtle
    }

    /// Interprets `op`, the module at index `i` of the word.
    // Inlined into `run`'s loop, as `forward` is: called as functions they
    // made interpretation (benches/throughput.rs, `interpret`) a fifth
    // slower.
    #[inline(always)]
    fn apply(&mut self, i: usize, op: TurtleOp, args: Args) {
        if self.rotations >= RENORMALISE_EVERY {
            self.state.renormalise();
            self.rotations = 0;
        }
        match op {
            TurtleOp::Forward { draw } if self.tropisms.is_some() => self.forward_bent(draw, args),
            TurtleOp::Forward { draw } => self.forward(self.state.h, draw, args),
            TurtleOp::ForwardReal { draw } => {
                // Along the real heading in the plane of the initial
                // H = +y and L = −x.
                let real = self.state.real;
                self.forward([-real.sin(), real.cos(), 0.0], draw, args);
            }
            TurtleOp::MoveTo => self.move_to(args),
            TurtleOp::Rotate { axis, angle } => self.rotate(axis, angle, args),
            TurtleOp::Frenet { rotation, negate } => self.frenet(rotation, negate),
            TurtleOp::TurnUnswapped(angle) => {
                let a = self.resolve(angle);
                self.state.turn_unswapped(a);
                self.rotations += 1;
            }
            TurtleOp::RotateReal(angle) => {
                let a = self.resolve(angle);
                // Positive turns right, as `Rotate` about U does.
                self.state.real -= if self.state.swapped { -a } else { a };
            }
            // Not affected by swapped turns: a half turn either way.
            TurtleOp::TurnAround => self.state.turn_unswapped(std::f64::consts::PI),
            TurtleOp::SwapTurns => self.state.swapped = !self.state.swapped,
            TurtleOp::SetHeading => self.state.set_heading(args.vector(0), args.vector(3)),
            TurtleOp::RollToVertical => self.state.roll_to_vertical(),
            TurtleOp::Push => self.push(),
            TurtleOp::Pop => self.pop(),
            // cpfg `{(n)`: a generalized cylinder, not a polygon.
            TurtleOp::PolygonBegin if args.get(0).is_some() => self.start_cylinder(),
            TurtleOp::PolygonBegin => self
                .open_polygons
                .push((vec![self.state.pos], self.state.colour)),
            TurtleOp::PolygonEnd if args.get(0).is_some() => self.cylinder_point(4, true),
            TurtleOp::PolygonEnd => self.end_polygon(),
            TurtleOp::PolygonVertex => self.polygon_vertex(args),
            TurtleOp::CylinderStart => self.start_cylinder(),
            TurtleOp::CylinderPoint { end } => {
                self.cylinder_point(pieces(args.get(0).unwrap_or(1.0)), end);
            }
            // cpfg `@Gt(a[,b])`: arriving a, leaving b (or a), for the
            // control points that follow; nothing without a parameter.
            TurtleOp::CylinderTangents => {
                if let Some(a) = args.get(0) {
                    self.state.tangents = (a, args.get(1).unwrap_or(a));
                }
            }
            TurtleOp::RadiusTangents => self.radius_tangents(args),
            TurtleOp::SetColour(n) => self.state.colour = n as usize % self.palette.len(),
            TurtleOp::ShiftColour { by, up } => self.shift_colour(by, up),
            TurtleOp::NextColour => self.next_colour(),
            TurtleOp::PreviousColour => self.previous_colour(),
            TurtleOp::ColourIndex { up } => self.colour_index(up, args),
            TurtleOp::DecrementWidth => self.state.width *= self.sys.settings.width_factor,
            TurtleOp::LineWidth { up } => self.line_width(up, args),
            TurtleOp::ScaleLength(f) => self.state.length *= f,
            TurtleOp::Stem { width, length } => {
                self.state.width = width;
                self.state.length = length;
            }
            TurtleOp::Sphere | TurtleOp::ScreenDisc => self.disc(args),
            TurtleOp::Circle => self.circle(args),
            TurtleOp::Surface(k) => self.surface(k, args),
            TurtleOp::Query(kind) => {
                let v = self.state.vector(kind);
                (self.query)(i, kind, v);
            }
            TurtleOp::Elasticity { tropism, change } => self.elasticity(tropism, change, args),
            TurtleOp::Untwist => {
                if let Some(t) = self.tropisms.as_mut() {
                    t.untwist(&mut self.state);
                }
            }
            TurtleOp::KeepTwist => {
                if let Some(t) = self.tropisms.as_mut() {
                    t.keep_twist(&self.state);
                }
            }
            TurtleOp::SetContour => self.set_contour(args),
        }
    }

    /// What the turtle leaves: the paths with a move, and the deepest
    /// nesting.
    fn finish(mut self) -> Geometry {
        self.geometry.paths.retain(|p| p.points.len() >= 2);
        self.geometry.world_widths = self.sys.settings.world_widths;
        self.geometry
    }

    /// The angle `a` stands for, drawing an interval angle from the
    /// turtle's stream.
    fn resolve(&mut self, a: Angle) -> f64 {
        match a {
            Angle::Delta(f) => f * self.sys.settings.delta,
            Angle::Radians(r) => r,
            Angle::Uniform { lo, hi } => lo + (hi - lo) * self.rng.next_f64(),
        }
    }

    /// The palette's colour `index`, the last one past its end.
    fn colour_of(&self, index: usize) -> Rgb {
        self.palette[index.min(self.palette.len() - 1)]
    }

    /// How many branches the turtle is in.
    fn depth(&self) -> u16 {
        u16::try_from(self.stack.len()).unwrap_or(u16::MAX)
    }

    /// The colour the turtle draws with.
    fn colour(&self) -> Rgb {
        self.colour_of(self.state.colour)
    }
}

/// Moves.
impl Turtle<'_> {
    /// A step along `direction`, drawn (when `draw`) as a segment, or a
    /// vertex of the polygon being collected.
    #[inline(always)]
    fn forward(&mut self, direction: Vec3, draw: bool, args: Args) {
        let a = self.state.pos;
        let b = add_scaled(a, direction, args.get(0).unwrap_or(self.state.length));
        self.state.pos = b;
        self.record_position();
        if let Some((points, _)) = self.open_polygons.last_mut() {
            points.push(b);
        } else if draw {
            let colour = self.colour();
            self.sink.segment(Segment {
                a,
                b,
                width: self.state.width,
                colour,
                index: index_of(self.state.colour),
                depth: self.depth(),
            });
        }
    }

    /// A step bent by the tropisms: the pulls act on the frame before the
    /// step, the older tropisms after it, and a drawn step is where the
    /// next untwisting starts from (cpfg's order).
    fn forward_bent(&mut self, draw: bool, args: Args) {
        if let Some(t) = self.tropisms.as_mut() {
            t.before_step(&mut self.state);
        }
        self.forward(self.state.h, draw, args);
        if let Some(t) = self.tropisms.as_mut() {
            t.after_step(&mut self.state);
            if draw {
                t.drawn_step(&self.state);
            }
        }
        self.rotations += 1;
    }

    /// `@Ts`, `@Ti`, `@Td`, `_`: an elasticity change; the tropism is the
    /// op's, or the one the first parameter names (1-based), and the value
    /// the parameter after it.
    fn elasticity(&mut self, tropism: Option<u16>, change: ElasticityChange, args: Args) {
        let Some(t) = self.tropisms.as_mut() else {
            return;
        };
        let (k, value) = match tropism {
            Some(k) => (Some(k as usize), args.get(0)),
            None => (
                args.get(0)
                    .filter(|id| *id >= 1.0 && *id <= tropism::MAX_TROPISMS as f64)
                    .map(|id| id as usize - 1),
                args.get(1),
            ),
        };
        if let Some(k) = k {
            t.change(k, change, value);
        }
    }

    /// cpfg `@M(x, y, z)`: a move to absolute coordinates, those given.
    fn move_to(&mut self, args: Args) {
        for k in 0..3 {
            if let Some(v) = args.get(k) {
                self.state.pos[k] = v;
            }
        }
        self.record_position();
    }

    fn record_position(&mut self) {
        if self.record_paths {
            self.geometry.paths[self.path].points.push(self.state.pos);
        }
    }

    /// Starts a path at the turtle; its index in `geometry.paths`.
    fn start_path(&mut self) -> usize {
        let colour = self.colour();
        self.geometry.paths.push(TurtlePath {
            points: vec![self.state.pos],
            width: self.state.width,
            colour,
            depth: self.depth(),
        });
        self.geometry.paths.len() - 1
    }
}

/// Rotations.
impl Turtle<'_> {
    /// A turn about `axis`; a module's parameter gives the angle in
    /// degrees, in the direction of the symbol's own.
    fn rotate(&mut self, axis: Axis, angle: Angle, args: Args) {
        let a = match (args.get(0), angle) {
            (Some(degrees), Angle::Delta(k)) => k.signum() * degrees.to_radians(),
            _ => self.resolve(angle),
        };
        self.state.turn(axis, a);
        self.rotations += 1;
    }

    /// A named LinF rotation: torsion about H, then curvature about U.
    fn frenet(&mut self, rotation: RotationId, negate: bool) {
        let Some(r) = self.sys.rotations.get(rotation.0 as usize) else {
            return;
        };
        let sign = if negate { -1.0 } else { 1.0 };
        let (t, k) = (self.resolve(r.torsion), self.resolve(r.curvature));
        self.state.turn(Axis::Heading, -sign * t);
        self.state.turn(Axis::Up, -sign * k);
        self.rotations += 1;
    }
}

/// Branches.
impl Turtle<'_> {
    fn push(&mut self) {
        self.stack.push(self.state);
        if let Some(t) = self.tropisms.as_mut() {
            t.push();
        }
        self.geometry.max_depth = self.geometry.max_depth.max(self.stack.len());
        if self.record_paths {
            self.path_stack.push(self.path);
            self.path = self.start_path();
        }
    }

    fn pop(&mut self) {
        if let Some(s) = self.stack.pop() {
            self.state = s;
            if let Some(t) = self.tropisms.as_mut() {
                t.pop();
            }
            if let Some(p) = self.path_stack.pop() {
                self.path = p;
            }
        }
    }
}

/// Polygons and generalized cylinders.
impl Turtle<'_> {
    fn end_polygon(&mut self) {
        if let Some((points, colour)) = self.open_polygons.pop() {
            if points.len() >= 3 {
                let index = index_of(colour);
                let colour = self.colour_of(colour);
                self.sink.polygon(Polygon {
                    points,
                    colour,
                    index,
                    surface: false,
                });
            }
        }
    }

    /// `.`: a vertex of the polygon being collected, or, with a parameter
    /// (cpfg `.(n)`), a control point of a generalized cylinder.
    fn polygon_vertex(&mut self, args: Args) {
        if let Some(n) = args.get(0) {
            self.cylinder_point(pieces(n), false);
        } else if let Some((points, _)) = self.open_polygons.last_mut() {
            points.push(self.state.pos);
        }
    }

    fn start_cylinder(&mut self) {
        self.state.cylinder = Some(Cylinder::at(&self.state));
    }

    /// A control point of the current generalized cylinder at the turtle:
    /// the axis from the previous control point is drawn as a Hermite curve
    /// of `pieces` segments (at least 4, so that curves look like curves),
    /// or, with a cross-section, swept in `pieces` rings as cpfg's `@Gc(n)`
    /// asks (a calyx of ten control points a step, as Lychnis's, would
    /// otherwise make four times the quadrilaterals cpfg draws).
    fn cylinder_point(&mut self, pieces: usize, end: bool) {
        let Some(c) = self.state.cylinder else {
            return;
        };
        if c.contour != 0 || self.state.contour != 0 {
            self.cylinder_mesh(&c, pieces);
        } else {
            self.cylinder_segments(&c, pieces.max(4));
        }
        self.state.cylinder = if end {
            None
        } else {
            Some(Cylinder::at(&self.state))
        };
    }

    /// cpfg `@Gr`: one parameter says whether radius tangents scale with
    /// the distance between control points; two or four set the arriving
    /// and leaving tangents from an angle (degrees) and a length each.
    fn radius_tangents(&mut self, args: Args) {
        let tangent = |k: usize| {
            let (a, l) = (args.get(k).unwrap_or(0.0).to_radians(), args.get(k + 1));
            let l = l.unwrap_or(0.0);
            [a.cos() * l, a.sin() * l]
        };
        match args.len() {
            0 => {}
            1 => self.state.scale_radius_tangents = args.get(0).is_some_and(|s| s != 0.0),
            n => {
                let arriving = tangent(0);
                let leaving = if n >= 4 { tangent(2) } else { arriving };
                self.state.radius_tangents = [arriving, leaving];
            }
        }
    }

    /// The tangent factors of the piece of cylinder from `c` to the turtle:
    /// the one leaving `c` and the one arriving here (cpfg's
    /// `interpolate_connection`).
    fn piece_tangents(&self, c: &Cylinder) -> (f64, f64) {
        (c.tangents.1, self.state.tangents.0)
    }

    /// The radius tangents of the piece of cylinder from `c` to the turtle:
    /// the one leaving `c`, the one arriving here, their radius parts
    /// scaled by the distance `d` when the turtle says so.
    fn piece_radius_tangents(&self, c: &Cylinder, d: f64) -> gencyl::RadiusTangents {
        let scale = if self.state.scale_radius_tangents {
            d
        } else {
            1.0
        };
        let scaled = |[t, r]: [f64; 2]| [t, r * scale];
        gencyl::RadiusTangents {
            start: scaled(c.radius_tangents[1]),
            end: scaled(self.state.radius_tangents[0]),
        }
    }

    /// A piece of generalized cylinder with a cross-section: the contour
    /// swept from `c` to the turtle as quadrilaterals.
    fn cylinder_mesh(&mut self, c: &Cylinder, pieces: usize) {
        let st = &self.state;
        let chord: Vec3 = std::array::from_fn(|i| st.pos[i] - c.point[i]);
        let radius_tangents = self.piece_radius_tangents(c, dot(chord, chord).sqrt());
        let from = gencyl::End {
            pos: c.point,
            h: c.heading,
            u: c.up,
            radius: c.width / 2.0,
        };
        let to = gencyl::End {
            pos: st.pos,
            h: st.h,
            u: st.u,
            radius: st.width / 2.0,
        };
        let section = |k: u16| match k.checked_sub(1) {
            Some(i) => self.sys.contours[usize::from(i)].points.clone(),
            None => gencyl::circle(),
        };
        let quads = gencyl::sweep(
            &from,
            &to,
            self.piece_tangents(c),
            radius_tangents,
            pieces,
            &section(c.contour),
            &section(st.contour),
        );
        let index = index_of(st.colour);
        let colour = self.colour();
        for q in quads {
            self.sink.polygon(Polygon {
                points: q.to_vec(),
                colour,
                index,
                surface: false,
            });
        }
    }

    /// A piece of generalized cylinder without a cross-section: its axis
    /// as a chain of segments as wide as the turtle's line.
    fn cylinder_segments(&mut self, c: &Cylinder, pieces: usize) {
        let st = &self.state;
        let d = {
            let v = [
                st.pos[0] - c.point[0],
                st.pos[1] - c.point[1],
                st.pos[2] - c.point[2],
            ];
            dot(v, v).sqrt()
        };
        let (f0, f1) = self.piece_tangents(c);
        let t0 = c.heading.map(|x| x * d * f0);
        let t1 = st.h.map(|x| x * d * f1);
        let colour = self.colour();
        let mut a = c.point;
        for b in hermite(c.point, t0, st.pos, t1, pieces) {
            self.sink.segment(Segment {
                a,
                b,
                width: st.width,
                colour,
                index: index_of(st.colour),
                depth: self.depth(),
            });
            a = b;
        }
    }
}

/// Colours, widths and lengths.
impl Turtle<'_> {
    /// cpfg `@#(id)`: the contour of that id becomes the cross-section of
    /// generalized cylinders; 0, no parameter or an id no contour has: the
    /// circle.
    fn set_contour(&mut self, args: Args) {
        let id = args.get(0).unwrap_or(0.0);
        self.state.contour = self
            .sys
            .contours
            .iter()
            .position(|c| {
                c.role == crate::ir::look::ContourRole::CrossSection
                    && f64::from(c.id) == id
                    && id >= 1.0
            })
            .map_or(0, |k| (k + 1).min(u16::MAX as usize) as u16);
    }

    /// Fractint's `<n` / `>n`: the colour `by` places up or down the
    /// palette, wrapping around and skipping colour 0.
    fn shift_colour(&mut self, by: u32, up: bool) {
        let len = self.palette.len() as i64;
        let by = i64::from(by) % len;
        let mut c = (self.state.colour as i64 + if up { by } else { -by }).rem_euclid(len);
        if c == 0 {
            c = if up { 1 } else { len - 1 };
        }
        self.state.colour = (c.min(len - 1)) as usize;
    }

    /// `'`: the next colour (wrapping around the default palette, staying
    /// at the last of a system's own), remembered for `PreviousColour`.
    fn next_colour(&mut self) {
        self.history.push((self.state.history, self.state.colour));
        self.state.history = (self.history.len() - 1) as u32;
        if self.sys.colours.is_empty() {
            self.state.colour = (self.state.colour + 1) % self.palette.len();
        } else {
            self.state.colour = (self.state.colour + 1).min(self.palette.len() - 1);
        }
    }

    fn previous_colour(&mut self) {
        if self.state.history != NO_HISTORY {
            let (previous, c) = self.history[self.state.history as usize];
            self.state.colour = c;
            self.state.history = previous;
        }
    }

    /// cpfg `;` / `,`: the colour index given, or one colour step up or
    /// down.
    fn colour_index(&mut self, up: bool, args: Args) {
        let step = self.sys.settings.colour_step;
        let c = match args.get(0) {
            Some(v) => v,
            None if up => self.state.colour as f64 + step,
            None => self.state.colour as f64 - step,
        };
        self.state.colour = c.round().clamp(0.0, (self.palette.len() - 1) as f64) as usize;
    }

    /// cpfg `#` / `!`: the line width given, or one width step up or down.
    fn line_width(&mut self, up: bool, args: Args) {
        let step = self.sys.settings.width_step;
        self.state.width = match args.get(0) {
            Some(v) => v.max(0.0),
            None if up => self.state.width + step,
            None => (self.state.width - step).max(0.0),
        };
    }
}

/// cpfg's shapes: discs, circles and surfaces.
impl Turtle<'_> {
    /// `@O` / `@o`: a disc at the turtle, of the diameter given (turtle
    /// units), else of the line width.
    fn disc(&mut self, args: Args) {
        let (diameter, pixels) = match args.get(0) {
            Some(d) => (d.abs(), false),
            None => (self.state.width, !self.sys.settings.world_widths),
        };
        let colour = self.colour();
        self.sink.disc(Disc {
            centre: self.state.pos,
            diameter,
            pixels,
            colour,
            index: index_of(self.state.colour),
        });
    }

    /// `@c`: a circle in the plane of H and L, as a 24-gon.
    fn circle(&mut self, args: Args) {
        let st = &self.state;
        let r = args.get(0).unwrap_or(st.width).abs() / 2.0;
        let points = (0..24)
            .map(|k| {
                let (s, c) = (k as f64 * std::f64::consts::TAU / 24.0).sin_cos();
                add_scaled(add_scaled(st.pos, st.h, r * c), st.l, r * s)
            })
            .collect();
        let colour = self.colour();
        self.sink.polygon(Polygon {
            points,
            colour,
            index: index_of(st.colour),
            surface: false,
        });
    }

    /// `~k`: surface `k`'s triangles placed in the turtle's frame, scaled
    /// by the parameters (one for all three axes, or one each).
    fn surface(&mut self, k: u16, args: Args) {
        let Some(mesh) = self.sys.surfaces.get(k as usize) else {
            return;
        };
        let scale: Vec3 = match (args.get(0), args.get(1), args.get(2)) {
            (Some(x), Some(y), Some(z)) => [x, y, z],
            (Some(s), _, _) => [s, s, s],
            _ => [1.0, 1.0, 1.0],
        };
        let colour = self.colour();
        let st = &self.state;
        for tri in &mesh.triangles {
            let points = tri
                .iter()
                .map(|p| {
                    let q = add_scaled(st.pos, st.l, p[0] * scale[0]);
                    let q = add_scaled(q, st.h, p[1] * scale[1]);
                    // z along cpfg's up, the turtle's −U.
                    add_scaled(q, st.u, -p[2] * scale[2])
                })
                .collect();
            self.sink.polygon(Polygon {
                points,
                colour,
                index: index_of(st.colour),
                surface: true,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::pfg::read_ok;
    use crate::ir::Word;

    fn draw(src: &str) -> Geometry {
        let sys = read_ok(src);
        interpret(&sys, &sys.axiom, 0)
    }

    fn close(a: Vec3, b: Vec3) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() < 1e-9)
    }

    /// Records the kinds given to it, in order.
    #[derive(Default)]
    struct Kinds(Vec<Drawn>);

    impl Sink for Kinds {
        fn segment(&mut self, _: Segment) {
            self.0.push(Drawn::Segment);
        }
        fn polygon(&mut self, _: Polygon) {
            self.0.push(Drawn::Polygon);
        }
        fn disc(&mut self, _: Disc) {
            self.0.push(Drawn::Disc);
        }
    }

    #[test]
    fn a_stored_drawing_replays_in_the_order_it_was_drawn() {
        let square = || Polygon {
            points: vec![[0.0; 3], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]],
            colour: Rgb(0, 0, 0),
            index: 0,
            surface: false,
        };
        let line = || Segment {
            a: [0.0; 3],
            b: [0.0, 1.0, 0.0],
            width: 1.0,
            colour: Rgb(0, 0, 0),
            index: 0,
            depth: 0,
        };
        let mut g = Geometry::default();
        g.segment(line());
        g.polygon(square());
        g.polygon(square());
        g.segment(line());
        // Added without a note of its order: after the rest.
        g.polygons.push(square());
        let mut kinds = Kinds::default();
        g.replay(&mut kinds);
        use Drawn::{Polygon as P, Segment as S};
        assert_eq!(kinds.0, [S, P, P, S, P]);
        assert_eq!(g.order, [(S, 1), (P, 2), (S, 1)]);
    }

    #[test]
    fn starts_at_origin_facing_up_and_plus_turns_right() {
        let g = draw("angle factor: 4\naxiom: F+F-F\n");
        assert!(close(g.segments[0].a, [0.0, 0.0, 0.0]));
        assert!(close(g.segments[0].b, [0.0, 1.0, 0.0]));
        assert!(
            close(g.segments[1].b, [1.0, 1.0, 0.0]),
            "{:?}",
            g.segments[1]
        );
        assert!(close(g.segments[2].b, [1.0, 2.0, 0.0]));
    }

    #[test]
    fn three_d_symbols_follow_the_book_matrices() {
        // & pitches: H' = H cos + U sin, so with δ=90° the heading becomes +z.
        let g = draw("angle factor: 4\naxiom: &F\n");
        assert!(close(g.segments[0].b, [0.0, 0.0, 1.0]));
        // \ rolls: then + (about the new U) turns right in the rolled plane.
        let g = draw("angle factor: 4\naxiom: \\+F\n");
        // Rolling by 90° makes L = +z, so a right turn heads to −L = −z.
        assert!(
            close(g.segments[0].b, [0.0, 0.0, -1.0]),
            "{:?}",
            g.segments[0]
        );
        // | turns around.
        let g = draw("angle factor: 4\naxiom: |F\n");
        assert!(close(g.segments[0].b, [0.0, -1.0, 0.0]));
    }

    #[test]
    fn branches_restore_state_and_count_depth() {
        let g = draw("angle factor: 4\naxiom: F[+F[-F]]F\n");
        assert_eq!(g.max_depth, 2);
        assert!(close(g.segments[3].a, [0.0, 1.0, 0.0]));
        assert!(close(g.segments[3].b, [0.0, 2.0, 0.0]));
    }

    #[test]
    fn polygons_collect_vertices_instead_of_lines() {
        let g = draw("angle factor: 4\naxiom: {f+f+f+f}F\n");
        assert_eq!(g.polygons.len(), 1);
        assert_eq!(g.polygons[0].points.len(), 5);
        assert_eq!(g.segments.len(), 1);
    }

    #[test]
    fn paths_follow_every_move_per_branch() {
        let sys = read_ok("angle factor: 4\naxiom: f+f[-fF]f\n");
        let g = interpret_with(
            &sys,
            &sys.axiom,
            0,
            TurtleOptions {
                paths: true,
                ..TurtleOptions::default()
            },
            &mut |_, _, _| {},
        );
        assert_eq!(g.paths.len(), 2);
        // The main axis: origin, two moves, then (after the branch) one more.
        assert_eq!(g.paths[0].points.len(), 4);
        assert!(close(g.paths[0].points[3], [2.0, 1.0, 0.0]));
        // The branch starts where it was pushed.
        assert!(close(g.paths[1].points[0], [1.0, 1.0, 0.0]));
        assert!(close(g.paths[1].points[2], [1.0, 3.0, 0.0]));
        // Without the option nothing is recorded.
        assert!(interpret(&sys, &sys.axiom, 0).paths.is_empty());
    }

    #[test]
    fn branching_does_not_copy_the_colour_history() {
        // 2^16 colour changes before 2^16 branches: a push must not copy them.
        let sys = read_ok("axiom: 'X\n' --> ''\nX --> X[F]X\n");
        let word = crate::eval::derive(&sys, &crate::eval::DeriveOptions::new(16)).unwrap();
        let t = std::time::Instant::now();
        let g = interpret(&sys, &word, 0);
        assert_eq!(g.segments.len(), (1 << 16) - 1);
        assert!(t.elapsed().as_secs_f64() < 1.0, "{:?}", t.elapsed());
    }

    #[test]
    fn previous_colour_goes_back_through_the_history_per_branch() {
        let mut sys = read_ok("axiom: F\n");
        let next = sys.intern("n");
        let prev = sys.intern("p");
        sys.set_interpretation(next, TurtleOp::NextColour);
        sys.set_interpretation(prev, TurtleOp::PreviousColour);
        sys.colours = vec![Rgb(1, 1, 1), Rgb(2, 2, 2), Rgb(3, 3, 3)];
        let word: Vec<SymbolId> = "FnFnF[pF]FpFpFpF"
            .chars()
            .map(|c| sys.symbols.get(&c.to_string()).unwrap())
            .collect();
        let g = interpret(&sys, &Word::from(word), 0);
        let colours: Vec<u8> = g.segments.iter().map(|s| s.colour.0).collect();
        assert_eq!(colours, [1, 2, 3, 2, 3, 2, 1, 1]);
    }

    /// The frame after `n` rotations by an irrational (torsion, curvature)
    /// pair, read off three unit segments drawn along t, n and −b.
    fn frame_after_rotations(n: usize) -> [Vec3; 3] {
        let mut sys = crate::front::linf::read_ok(
            "lines f\nangles w = (0.7311, 1.1234) q = (0, pi/2) p = (pi/2, pi/2)\nrules x = +w f+q+p",
        );
        let [f, w, q, p] = ["f", "+w", "+q", "+p"].map(|s| sys.symbols.get(s).unwrap());
        sys.axiom = Word::from([vec![w; n], vec![f, q, f, p, f]].concat());
        let g = interpret(&sys, &sys.axiom, 0);
        let d = |k: usize| {
            let s: &Segment = &g.segments[k];
            [s.b[0] - s.a[0], s.b[1] - s.a[1], s.b[2] - s.a[2]]
        };
        [d(0), d(1), d(2)]
    }

    #[test]
    fn frames_stay_orthonormal_over_millions_of_rotations() {
        let dot = |a: Vec3, b: Vec3| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let cross = |a: Vec3, b: Vec3| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let [t, n, minus_b] = frame_after_rotations(5_000_000);
        let mut worst: f64 = 0.0;
        for v in [t, n, minus_b] {
            worst = worst.max((dot(v, v) - 1.0).abs());
        }
        for (a, b) in [(t, n), (n, minus_b), (t, minus_b)] {
            worst = worst.max(dot(a, b).abs());
        }
        // b = t × n, and the third segment runs along −b.
        let b = cross(t, n);
        for k in 0..3 {
            worst = worst.max((b[k] + minus_b[k]).abs());
        }
        assert!(worst < 1e-13, "orthonormality error {worst:e}");
    }

    #[test]
    fn width_and_colour_change() {
        let g = draw("axiom: F!'F\n");
        assert!(g.segments[1].width < g.segments[0].width);
        assert_ne!(g.segments[1].colour, g.segments[0].colour);
    }
}
