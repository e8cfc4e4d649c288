//! The turtle's one entry point: [`run`] interprets the symbols of a
//! [`Run`] into a [`Sink`] and returns what the run learned ([`Learned`]).

use super::interpret::interpret;
use super::{Disc, Geometry, Origins, Polygon, Segment, Sink, TurtlePath, Vec3};
use crate::ir::{SymbolId, System, Word};
use std::cell::Cell;

/// What to interpret, and what to record on the way. Build one with
/// [`Run::word`] or [`Run::symbols`], and ask for more with struct update
/// syntax: `Run { paths: true, ..Run::word(sys, &word, seed) }`.
pub struct Run<'a, W> {
    pub system: &'a System,
    /// The symbols, in the order the turtle reads them.
    pub symbols: W,
    /// The word whose modules' parameters set lengths, angles, widths,
    /// colours and sizes (by index into `symbols`); `None` reads none.
    pub params: Option<&'a Word>,
    /// Drives interval angles (a stream separate from the derivation's).
    pub seed: u64,
    /// Record the turtle's positions per branch ([`Learned::paths`]).
    pub paths: bool,
    /// Record which module drew what ([`Learned::origins`]).
    pub origins: bool,
    /// Record what the query modules (`?P`, `?H`, `?L`, `?U`) find
    /// ([`Learned::answers`]).
    pub queries: bool,
}

/// The symbols of a stored word, as [`Run::word`] reads them.
pub type WordSymbols<'a> = std::iter::Copied<std::slice::Iter<'a, SymbolId>>;

impl<'a> Run<'a, WordSymbols<'a>> {
    /// A run over the whole of `word`, its modules' parameters read.
    pub fn word(system: &'a System, word: &'a Word, seed: u64) -> Self {
        Run {
            params: word.has_params().then_some(word),
            ..Run::symbols(system, word.0.iter().copied(), seed)
        }
    }

    /// [`run`] into a stored [`Geometry`], which keeps what the run
    /// learned (its paths, origins and deepest nesting) beside what it drew.
    // Not generic, so that the interpreter is compiled here, its calls
    // inlined, whichever crate asks (benches/throughput.rs `interpret`
    // was a sixth slower when it was instantiated there).
    pub fn geometry(self) -> Geometry {
        let world_widths = self.system.settings.world_widths;
        let mut g = Geometry::default();
        let learned = run(self, &mut g);
        g.paths = learned.paths;
        g.max_depth = learned.max_depth;
        g.origins = learned.origins;
        g.world_widths = world_widths;
        g
    }
}

impl<'a, W: Iterator<Item = SymbolId>> Run<'a, W> {
    /// A run over a stream of symbols (a word too large to store, say),
    /// without parameters; it records nothing but the deepest nesting.
    pub fn symbols(system: &'a System, symbols: W, seed: u64) -> Self {
        Run {
            system,
            symbols,
            params: None,
            seed,
            paths: false,
            origins: false,
            queries: false,
        }
    }
}

/// What a run learned besides what it drew: always the deepest nesting,
/// and what its [`Run`] asked to record.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Learned {
    /// The deepest branch nesting reached.
    pub max_depth: usize,
    /// The turtle's positions per branch, each path with a move
    /// ([`Run::paths`]).
    pub paths: Vec<TurtlePath>,
    /// Which module drew what ([`Run::origins`]).
    pub origins: Origins,
    /// Per query module, its index in the word and the vector it asks for
    /// ([`Run::queries`]).
    pub answers: Vec<(usize, Vec3)>,
}

/// What a [`Turtle`] records besides what it draws.
#[derive(Clone, Copy)]
pub(super) struct Record {
    pub(super) paths: bool,
    pub(super) queries: bool,
}

/// Interprets `run`'s symbols as turtle commands of its system, giving
/// what is drawn to `sink`; what the run learned.
pub fn run<W: Iterator<Item = SymbolId>>(run: Run<'_, W>, sink: &mut dyn Sink) -> Learned {
    if !run.origins {
        return interpret(run, sink, None);
    }
    let at = Cell::new(0);
    let mut noting = Noting {
        inner: sink,
        at: &at,
        origins: Origins::default(),
    };
    let mut learned = interpret(run, &mut noting, Some(&at));
    learned.origins = noting.origins;
    learned
}

/// A sink that notes, for everything drawn, the module being interpreted
/// (`at`) before passing it on.
struct Noting<'s> {
    inner: &'s mut dyn Sink,
    at: &'s Cell<usize>,
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
