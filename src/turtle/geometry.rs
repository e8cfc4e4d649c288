//! What the turtle draws (segments, polygons, discs, paths) and where it
//! goes: a [`Sink`], which stores it ([`Geometry`]), counts it or draws it
//! straight into a picture.

use super::pieces::Pieced;
use super::Vec3;
use crate::ir::Rgb;
use serde::Serialize;

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
    /// The texture it wears, with its corners' texture coordinates.
    pub texture: Option<Textured>,
}

/// A texture on a [`Polygon`]: an index of
/// [`crate::ir::look::Look::textures`] and, point by point, the texture
/// coordinates (u, v) of the polygon's points.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Textured {
    pub texture: u16,
    pub uvs: Vec<[f64; 2]>,
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

/// Text written at a point, facing the viewer (a cpfg label `@L`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Label {
    pub at: Vec3,
    pub text: String,
    pub colour: Rgb,
    pub index: u16,
}

/// What the turtle drew.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Geometry {
    pub segments: Vec<Segment>,
    pub polygons: Vec<Polygon>,
    pub discs: Vec<Disc>,
    /// Labels, drawn over everything else as cpfg writes them.
    pub labels: Vec<Label>,
    /// Whether segment widths are in turtle units rather than pixels
    /// ([`crate::ir::Settings::world_widths`]).
    pub world_widths: bool,
    /// Turtle paths, when asked for ([`Run::paths`](super::Run::paths)).
    pub paths: Vec<TurtlePath>,
    /// The deepest branch nesting reached.
    pub max_depth: usize,
    /// Which module drew what, when asked for ([`Run::origins`](super::Run::origins)).
    #[serde(skip)]
    pub origins: Origins,
    /// The order the turtle drew in, as runs of one kind, so that a stored
    /// drawing replays as it was drawn ([`Geometry::replay`]): a lit
    /// picture drawn from it and one drawn straight from the turtle agree.
    #[serde(skip)]
    pub order: Vec<(Drawn, u32)>,
    /// Where each piece of the word after the first starts, as a count of
    /// things drawn before it ([`crate::turtle::Pieces`]): a lit picture
    /// drawn from this cuts its parts there, as the picture drawn straight
    /// from the turtle does, so that the two agree.
    #[serde(skip)]
    pub cuts: Vec<usize>,
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

/// `b` grown to hold box `other` too (a box of a later piece).
pub fn join_boxes(b: &mut Option<[f64; 6]>, other: Option<[f64; 6]>) {
    if let Some(o) = other {
        grow_box(b, [o[0], o[1], o[2]]);
        grow_box(b, [o[3], o[4], o[5]]);
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

/// A colour index as primitives keep it.
pub(crate) fn index_of(colour: usize) -> u16 {
    colour.min(u16::MAX as usize) as u16
}

/// Where the turtle's drawing goes: stored ([`Geometry`]), counted, or
/// drawn straight into a picture.
pub trait Sink {
    fn segment(&mut self, s: Segment);
    fn polygon(&mut self, p: Polygon);
    fn disc(&mut self, d: Disc);
    /// A label; only the pictures that write text keep it.
    fn label(&mut self, _l: Label) {}
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
    fn label(&mut self, l: Label) {
        self.labels.push(l);
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
        for run in self.runs() {
            self.give(run, sink);
        }
    }

    /// What is drawn as runs of one kind, `(kind, first, end)` indices into
    /// its list, in the order [`Geometry::replay`] gives them.
    fn runs(&self) -> Vec<(Drawn, usize, usize)> {
        let lens = [self.segments.len(), self.polygons.len(), self.discs.len()];
        let mut next = [0usize; 3];
        let mut runs = Vec::with_capacity(self.order.len() + 3);
        let mut take = |kind: Drawn, n: usize| {
            let k = kind as usize;
            let end = next[k].saturating_add(n).min(lens[k]);
            if end > next[k] {
                runs.push((kind, next[k], end));
            }
            next[k] = end;
        };
        for &(kind, n) in &self.order {
            take(kind, n as usize);
        }
        for kind in [Drawn::Polygon, Drawn::Segment, Drawn::Disc] {
            take(kind, usize::MAX);
        }
        runs
    }

    fn give(&self, (kind, first, end): (Drawn, usize, usize), sink: &mut dyn Sink) {
        for i in first..end {
            match kind {
                Drawn::Segment => sink.segment(self.segments[i].clone()),
                Drawn::Polygon => sink.polygon(self.polygons[i].clone()),
                Drawn::Disc => sink.disc(self.discs[i].clone()),
            }
        }
    }

    /// Adds `later` (drawn after this, by the same turtle: its order notes
    /// complete) after what this holds.
    pub fn append(&mut self, later: Geometry) {
        let before = self.segments.len() + self.polygons.len() + self.discs.len();
        self.cuts.push(before);
        self.cuts.extend(later.cuts.iter().map(|c| before + c));
        self.segments.extend(later.segments);
        self.polygons.extend(later.polygons);
        self.discs.extend(later.discs);
        self.labels.extend(later.labels);
        self.max_depth = self.max_depth.max(later.max_depth);
        for (kind, n) in later.order {
            match self.order.last_mut() {
                Some((k, m)) if *k == kind && m.checked_add(n).is_some() => *m += n,
                _ => self.order.push((kind, n)),
            }
        }
    }

    /// The drawing in parts, in order, to be drawn on several threads
    /// ([`Pieced`]): cut where the pieces of its word started, if it was
    /// drawn in pieces ([`Geometry::cuts`]), else every `most` things.
    pub fn in_parts(&self, most: usize) -> Parts<'_> {
        let most = most.max(1);
        let mut cuts = self.cuts.iter().copied().filter(|&c| c > 0);
        let mut parts = vec![Vec::new()];
        // Things until the next cut, and things given so far.
        let next_cut =
            |cuts: &mut dyn Iterator<Item = usize>, done: usize| match self.cuts.is_empty() {
                true => most,
                false => cuts.next().map_or(usize::MAX, |c| c - done),
            };
        let mut done = 0;
        let mut room = next_cut(&mut cuts, done);
        for (kind, mut first, end) in self.runs() {
            while first < end {
                if room == 0 {
                    parts.push(Vec::new());
                    room = next_cut(&mut cuts, done);
                    continue;
                }
                let take = room.min(end - first);
                parts
                    .last_mut()
                    .expect("a part")
                    .push((kind, first, first + take));
                first += take;
                room -= take;
                done += take;
            }
        }
        Parts { g: self, parts }
    }
}

/// A stored drawing cut into parts ([`Geometry::in_parts`]).
pub struct Parts<'g> {
    g: &'g Geometry,
    parts: Vec<Vec<(Drawn, usize, usize)>>,
}

impl Pieced for Parts<'_> {
    fn count(&self) -> usize {
        self.parts.len()
    }

    fn run(&self, k: usize, sink: &mut dyn Sink) -> usize {
        for &run in &self.parts[k] {
            self.g.give(run, sink);
        }
        self.g.max_depth
    }
}
