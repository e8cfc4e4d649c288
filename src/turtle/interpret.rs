//! What each symbol does: the turtle walking a word, one module at a time,
//! turning, moving, branching, drawing and colouring as the book, cpfg,
//! LinF and Fractint define their symbols.

use super::geometry::index_of;
use super::run::{Learned, Record, Run};
use super::state::{
    add_scaled, dot, hermite, Cylinder, State, DEFAULT_TANGENTS, NO_HISTORY, RENORMALISE_EVERY,
};
use super::{gencyl, tropism, Disc, Polygon, Segment, Sink, Textured, TurtlePath, Vec3};
use crate::ir::colours::DEFAULT_PALETTE;
use crate::ir::{Angle, Axis, ElasticityChange, Rgb, RotationId, SymbolId, System, TurtleOp, Word};
use crate::random::{keyed, Stream};
use std::cell::Cell;

/// [`run`](super::run), telling `at` which module is being interpreted.
// Here, beside the turtle, so that its calls are compiled (and inlined)
// with the loop: `interpret` in benches/throughput.rs was 5% slower with
// the loop in another module.
pub(super) fn interpret<W: Iterator<Item = SymbolId>>(
    run: Run<'_, W>,
    sink: &mut dyn Sink,
    at: Option<&Cell<usize>>,
) -> Learned {
    let sys = run.system;
    let ops = ops_of(sys);
    let record = Record {
        paths: run.paths,
        queries: run.queries,
    };
    let mut turtle = Turtle::new(sys, run.seed, record, sink);
    turtle.walk(run.symbols, 0, run.params, &ops, at);
    turtle.finish()
}

/// Each symbol's turtle command, by symbol index.
pub(super) fn ops_of(sys: &System) -> Vec<Option<TurtleOp>> {
    (0..sys.symbols.len())
        .map(|i| sys.op(SymbolId(i as u32)))
        .collect()
}

/// The parameters of the module being interpreted.
#[derive(Clone, Copy)]
pub(super) struct Args<'w>(&'w [f64]);

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

/// The first parameter of module `i` of a word with `params`, as the
/// turtle reads it (absent when it is not a number).
pub(super) fn first_arg(params: Option<&Word>, i: usize) -> Option<f64> {
    params.and_then(|w| Args(w.args(i)).get(0))
}

/// How many pieces a cylinder module's parameter asks for.
pub(super) fn pieces(n: f64) -> usize {
    n.clamp(1.0, 64.0) as usize
}

/// The turtle interpreting a word: its state and the enclosing branches'
/// states, and what it is building; what it draws goes to `sink`.
pub(super) struct Turtle<'a> {
    sys: &'a System,
    palette: Vec<Rgb>,
    /// What interval angles are drawn from: the seed, the index of the
    /// module being interpreted and how many it has drawn so far, so that
    /// a draw depends on where it is in the word, not on what was drawn
    /// before it (a piece of the word drawn on its own draws the same).
    seed: u64,
    at: usize,
    draws: u64,
    state: State,
    /// The states of the enclosing branches.
    stack: Vec<State>,
    /// The scale in force inside each sub-L-system call the turtle is in,
    /// innermost last (cpfg's sub-L-system stack, apart from the turtle's:
    /// `]` does not leave a call).
    sub_scales: Vec<f64>,
    /// The system's string literals, found at the first label.
    strings: Option<Vec<&'a str>>,
    /// Arena of the colour histories: (previous entry, colour).
    history: Vec<(u32, usize)>,
    /// The polygons being collected, innermost last.
    open_polygons: Vec<OpenPolygon>,
    /// What the run learns: the paths, the deepest nesting and the
    /// queries' answers (segments, polygons and discs go to `sink`).
    learned: Learned,
    record_paths: bool,
    record_queries: bool,
    /// Index into `geometry.paths` of the current branch's path, and of
    /// the enclosing branches' paths.
    path: usize,
    path_stack: Vec<usize>,
    /// The system's tropisms and what bends with the turtle; `None` when
    /// it has none.
    tropisms: Option<tropism::Tropisms<'a>>,
    sink: &'a mut dyn Sink,
}

/// What [`Turtle::snapshot`] keeps.
#[derive(Clone)]
pub(super) struct Snapshot<'a> {
    state: State,
    stack: Vec<State>,
    history: Vec<(u32, usize)>,
    tropisms: Option<tropism::Tropisms<'a>>,
}

/// A polygon being collected (`{` … `}`).
struct OpenPolygon {
    points: Vec<Vec3>,
    colour: usize,
    /// The turtle at the first point, once there is one.
    first: Option<FirstVertex>,
}

/// What cpfg keeps of a polygon's first vertex to lay a texture on it.
#[derive(Clone, Copy)]
struct FirstVertex {
    h: Vec3,
    l: Vec3,
    texture: Option<u16>,
}

/// Texture coordinates for a polygon, as cpfg's `SetPolygonTextureParams`
/// lays them: s across the first vertex's −L, t along its H, each
/// stretched so that the polygon's extent spans the image once (a polygon
/// with no extent along an axis takes 0 there).
fn polygon_uvs(points: &[Vec3], h: Vec3, l: Vec3) -> Vec<[f64; 2]> {
    let s_axis = [-l[0], -l[1], -l[2]];
    let span = |axis: Vec3| {
        let (lo, hi) = points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                let d = dot(*p, axis);
                (lo.min(d), hi.max(d))
            });
        let scale = if hi > lo { 1.0 / (hi - lo) } else { 0.0 };
        move |p: Vec3| (dot(p, axis) - lo) * scale
    };
    let (s, t) = (span(s_axis), span(h));
    points.iter().map(|&p| [s(p), t(p)]).collect()
}

impl<'a> Turtle<'a> {
    /// A turtle at the start of a word of `sys`, recording what `record`
    /// asks for.
    pub(super) fn new(sys: &'a System, seed: u64, record: Record, sink: &'a mut dyn Sink) -> Self {
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
            texture: None,
            tangents: DEFAULT_TANGENTS,
            radius_tangents: [[0.0; 2]; 2],
            scale_radius_tangents: false,
            scale: 1.0,
            rotations: 0,
        };
        let mut turtle = Turtle {
            sys,
            palette,
            seed,
            at: 0,
            draws: 0,
            state,
            stack: Vec::new(),
            sub_scales: Vec::new(),
            strings: None,
            history: Vec::new(),
            open_polygons: Vec::new(),
            learned: Learned::default(),
            record_paths: record.paths,
            record_queries: record.queries,
            path: usize::MAX,
            path_stack: Vec::new(),
            tropisms: tropism::Tropisms::new(&sys.settings.tropisms, &state),
            sink,
        };
        if record.paths {
            turtle.path = turtle.start_path();
        }
        turtle
    }

    /// Interprets `symbols`, the first of them at index `first` of the
    /// word whose parameters are `params`, telling `at` which module is
    /// being interpreted.
    #[inline(always)]
    pub(super) fn walk<W: Iterator<Item = SymbolId>>(
        &mut self,
        symbols: W,
        first: usize,
        params: Option<&Word>,
        ops: &[Option<TurtleOp>],
        at: Option<&Cell<usize>>,
    ) {
        for (k, sym) in symbols.enumerate() {
            let Some(op) = ops.get(sym.index()).copied().flatten() else {
                continue;
            };
            let i = first + k;
            let args = Args(match params {
                Some(w) => w.args(i),
                None => &[],
            });
            if let Some(at) = at {
                at.set(i);
            }
            self.apply(i, op, args);
        }
    }

    /// Where the turtle is, to start another from ([`Turtle::resumed`]):
    /// everything a branch keeps, and the colour histories.
    pub(super) fn snapshot(&self) -> Snapshot<'a> {
        Snapshot {
            state: self.state,
            stack: self.stack.clone(),
            history: self.history.clone(),
            tropisms: self.tropisms.clone(),
        }
    }

    /// A turtle at `snapshot`, drawing into `sink` and recording nothing
    /// (no polygon is open there: the caller starts it where none is).
    pub(super) fn resumed(
        sys: &'a System,
        seed: u64,
        snapshot: &Snapshot<'a>,
        sink: &'a mut dyn Sink,
    ) -> Self {
        let record = Record {
            paths: false,
            queries: false,
        };
        let mut turtle = Turtle::new(sys, seed, record, sink);
        turtle.state = snapshot.state;
        turtle.stack.clone_from(&snapshot.stack);
        turtle.history.clone_from(&snapshot.history);
        turtle.tropisms.clone_from(&snapshot.tropisms);
        turtle
    }

    /// Interprets `op`, the module at index `i` of the word.
    // Inlined into `run::interpret`'s loop, as `forward` is: called as functions they
    // made interpretation (benches/throughput.rs, `interpret`) a fifth
    // slower.
    #[inline(always)]
    pub(super) fn apply(&mut self, i: usize, op: TurtleOp, args: Args<'_>) {
        if self.state.rotations >= RENORMALISE_EVERY {
            self.state.renormalise();
            self.state.rotations = 0;
        }
        self.at = i;
        self.draws = 0;
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
                self.state.rotations += 1;
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
            TurtleOp::PolygonBegin => {
                self.open_polygons.push(OpenPolygon {
                    points: Vec::new(),
                    colour: self.state.colour,
                    first: None,
                });
                if !self.sys.settings.cpfg_polygons {
                    self.polygon_point(self.state.pos);
                }
            }
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
                if self.record_queries {
                    let v = self.state.vector(kind);
                    self.learned.answers.push((i, v));
                }
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
            TurtleOp::SetTexture => self.set_texture(args),
            TurtleOp::SubLsystemCall => self.enter_sub_lsystem(args),
            TurtleOp::SubLsystemReturn => self.leave_sub_lsystem(),
            TurtleOp::Label => self.label(args),
        }
    }

    /// What the turtle learned: the paths with a move, the deepest
    /// nesting and the queries' answers.
    pub(super) fn finish(mut self) -> Learned {
        self.learned.paths.retain(|p| p.points.len() >= 2);
        self.learned
    }

    /// The angle `a` stands for, drawing an interval angle from the
    /// turtle's stream.
    fn resolve(&mut self, a: Angle) -> f64 {
        match a {
            Angle::Delta(f) => f * self.sys.settings.delta,
            Angle::Radians(r) => r,
            Angle::Uniform { lo, hi } => {
                let u = keyed(self.seed, Stream::Turtle, self.at as u64, self.draws);
                self.draws += 1;
                lo + (hi - lo) * u
            }
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
        let step = args.get(0).unwrap_or(self.state.length) * self.state.scale;
        let b = add_scaled(a, direction, step);
        self.state.pos = b;
        self.record_position();
        let in_polygon = self.polygon_point(b);
        if draw && (!in_polygon || self.sys.settings.cpfg_polygons) {
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
        self.state.rotations += 1;
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
            self.learned.paths[self.path].points.push(self.state.pos);
        }
    }

    /// Starts a path at the turtle; its index in `geometry.paths`.
    fn start_path(&mut self) -> usize {
        let colour = self.colour();
        self.learned.paths.push(TurtlePath {
            points: vec![self.state.pos],
            width: self.state.width,
            colour,
            depth: self.depth(),
        });
        self.learned.paths.len() - 1
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
        self.state.rotations += 1;
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
        self.state.rotations += 1;
    }
}

/// Branches.
impl Turtle<'_> {
    fn push(&mut self) {
        self.stack.push(self.state);
        if let Some(t) = self.tropisms.as_mut() {
            t.push();
        }
        self.learned.max_depth = self.learned.max_depth.max(self.stack.len());
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
        let Some(open) = self.open_polygons.pop() else {
            return;
        };
        if open.points.len() < 3 {
            return;
        }
        let texture = open.first.and_then(|first| {
            let t = first.texture?;
            self.sys.look.textures().get(usize::from(t))?;
            Some(Textured {
                texture: t,
                uvs: polygon_uvs(&open.points, first.h, first.l),
            })
        });
        self.sink.polygon(Polygon {
            colour: self.colour_of(open.colour),
            index: index_of(open.colour),
            points: open.points,
            surface: false,
            texture,
        });
    }

    /// Adds `p` to the polygon being collected, if there is one (the
    /// first point keeps the turtle's frame and texture, from which cpfg
    /// lays a texture on the polygon); whether there was.
    fn polygon_point(&mut self, p: Vec3) -> bool {
        let Some(open) = self.open_polygons.last_mut() else {
            return false;
        };
        if open.points.is_empty() {
            open.first = Some(FirstVertex {
                h: self.state.h,
                l: self.state.l,
                texture: self.state.texture,
            });
        }
        open.points.push(p);
        true
    }

    /// `.`: a vertex of the polygon being collected, or, with a parameter
    /// (cpfg `.(n)`), a control point of a generalized cylinder.
    fn polygon_vertex(&mut self, args: Args) {
        if let Some(n) = args.get(0) {
            self.cylinder_point(pieces(n), false);
        } else {
            self.polygon_point(self.state.pos);
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
        // A textured cylinder is a mesh, its cross-section the default
        // circle when it has none: the image lies on its quadrilaterals.
        let mut texture_v = c.texture_v;
        if c.contour != 0 || self.state.contour != 0 || self.cylinder_texture().is_some() {
            texture_v = self.cylinder_mesh(&c, pieces);
        } else {
            self.cylinder_segments(&c, pieces.max(4));
        }
        self.state.cylinder = if end {
            None
        } else {
            Some(Cylinder {
                texture_v,
                ..Cylinder::at(&self.state)
            })
        };
    }

    /// The texture the turtle lays on cylinders. Its image need not have
    /// been read: what is drawn has one shape whether or not the image
    /// is found (a picture without it draws the mesh untextured).
    fn cylinder_texture(&self) -> Option<(u16, &crate::ir::texture::Texture)> {
        let t = self.state.texture?;
        let texture = self.sys.look.textures().get(usize::from(t))?;
        Some((t, texture))
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
    /// swept from `c` to the turtle as quadrilaterals; the texture's v it
    /// ends at. A texture goes once around the cross-section (u from 0 to
    /// 1 along its points) and up the cylinder as [`Texture::v_along`]
    /// says for the piece's mean width and length, the image keeping its
    /// proportions (stretched by the texture's ratio).
    ///
    /// [`Texture::v_along`]: crate::ir::texture::Texture::v_along
    fn cylinder_mesh(&mut self, c: &Cylinder, pieces: usize) -> f64 {
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
        let length = dot(chord, chord).sqrt();
        let textured = self
            .cylinder_texture()
            .map(|(t, texture)| (t, texture.v_along((c.width + st.width) / 2.0, length)));
        let v_end = c.texture_v + textured.map_or(0.0, |(_, dv)| dv);
        let around = (quads.len() / pieces.max(1)).max(1);
        for (k, q) in quads.into_iter().enumerate() {
            let texture = textured.map(|(texture, dv)| {
                // Quadrilateral k: ring k / around to the next, between
                // cross-section points k % around and the next.
                let (ring, i) = ((k / around) as f64, (k % around) as f64);
                let v = |r: f64| c.texture_v + dv * r / pieces as f64;
                let u = |i: f64| i / around as f64;
                Textured {
                    texture,
                    uvs: vec![
                        [u(i), v(ring)],
                        [u(i + 1.0), v(ring)],
                        [u(i + 1.0), v(ring + 1.0)],
                        [u(i), v(ring + 1.0)],
                    ],
                }
            });
            self.sink.polygon(Polygon {
                points: q.to_vec(),
                colour,
                index,
                surface: false,
                texture,
            });
        }
        v_end
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
    /// cpfg `@L("format", p1, …)`: the format is the string literal the
    /// first parameter stands for ([`System::strings`]), printf'd with the
    /// rest; a label without a format writes nothing.
    fn label(&mut self, args: Args) {
        let Some(k) = args.get(0) else { return };
        let sys = self.sys;
        let strings = self.strings.get_or_insert_with(|| sys.strings());
        let Some(format) = strings.get(k as usize).filter(|_| k >= 0.0) else {
            return;
        };
        let values: Vec<f64> = (1..).map_while(|i| args.get(i)).collect();
        let text = super::label::printf(format, &values);
        let colour = self.colour();
        self.sink.label(super::Label {
            at: self.state.pos,
            text,
            colour,
            index: index_of(self.state.colour),
        });
    }

    /// cpfg `?(n, s)`: the scale becomes the enclosing call's times `s`,
    /// and the line width follows it (`interpret.c`,
    /// `UpdateCurrentLsystem`). Without parameters it is not a call.
    fn enter_sub_lsystem(&mut self, args: Args) {
        if args.get(0).is_none() {
            return;
        }
        let outer = self.sub_scales.last().copied().unwrap_or(1.0);
        let inner = outer * args.get(1).unwrap_or(1.0);
        self.sub_scales.push(inner);
        self.rescale(outer, inner);
    }

    /// cpfg `$`: back to the enclosing call's scale; an unmatched `$` is
    /// ignored, as cpfg ignores it.
    fn leave_sub_lsystem(&mut self) {
        let Some(inner) = self.sub_scales.pop() else {
            return;
        };
        let outer = self.sub_scales.last().copied().unwrap_or(1.0);
        self.rescale(inner, outer);
    }

    /// The turtle's scale goes from `from` to `to`, and its line width by
    /// the same ratio (a zero scale leaves the width as it is rather than
    /// dividing by it).
    fn rescale(&mut self, from: f64, to: f64) {
        self.state.scale = to;
        if from != 0.0 && (to / from).is_finite() {
            self.state.width *= to / from;
        }
    }

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

    /// `@Tx(n)`: texture `n` (from 1) of the look; 0, no parameter or a
    /// number the look has no texture for: none.
    fn set_texture(&mut self, args: Args) {
        let n = args.get(0).unwrap_or(0.0);
        let count = self.sys.look.textures().len() as f64;
        self.state.texture = (n >= 1.0 && n <= count).then(|| (n as u16).saturating_sub(1));
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
    /// cpfg `;` / `,`: the colour index given (truncated, as cpfg casts
    /// it to an int), or one colour step up or down; an index past either
    /// end of cpfg's 256 colours wraps once to the other end (`interpret.c`),
    /// then stays within the palette.
    fn colour_index(&mut self, up: bool, args: Args) {
        let step = self.sys.settings.colour_step;
        let c = match args.get(0) {
            Some(v) => v.trunc(),
            None if up => self.state.colour as f64 + step,
            None => self.state.colour as f64 - step,
        };
        let wrapped = if c < 0.0 {
            c + 256.0
        } else if c > 255.0 {
            c - 256.0
        } else {
            c
        };
        let last = (self.palette.len() - 1) as f64;
        self.state.colour = wrapped.round().clamp(0.0, last) as usize;
    }

    /// cpfg `#` / `!`: the line width given, or one width step up or down,
    /// each times the turtle's scale (cpfg multiplies by `scale_factor`).
    fn line_width(&mut self, up: bool, args: Args) {
        let step = self.sys.settings.width_step * self.state.scale;
        self.state.width = match args.get(0) {
            Some(v) => (v * self.state.scale).max(0.0),
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
            Some(d) => (d.abs() * self.state.scale, false),
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
        let r = args.get(0).map_or(st.width, |d| d * st.scale).abs() / 2.0;
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
            texture: None,
        });
    }

    /// `~k`: surface `k`'s triangles placed in the turtle's frame, scaled
    /// by the parameters (one for all three axes, or one each).
    fn surface(&mut self, k: u16, args: Args) {
        let Some(mesh) = self.sys.surfaces.get(k as usize) else {
            return;
        };
        let k = self.state.scale;
        let scale: Vec3 = match (args.get(0), args.get(1), args.get(2)) {
            (Some(x), Some(y), Some(z)) => [x * k, y * k, z * k],
            (Some(s), _, _) => [s * k; 3],
            _ => [k; 3],
        };
        let colour = self.colour();
        let st = &self.state;
        let texture = mesh.texture.or(st.texture);
        let per_surface = texture
            .and_then(|t| self.sys.look.textures().get(usize::from(t)))
            .is_some_and(|t| t.per_surface);
        let uvs = if per_surface {
            &mesh.surface_uvs
        } else {
            &mesh.patch_uvs
        };
        for (k, tri) in mesh.triangles.iter().enumerate() {
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
                texture: texture.zip(uvs.get(k)).map(|(texture, uv)| Textured {
                    texture,
                    uvs: uv.to_vec(),
                }),
            });
        }
    }
}
