//! `graftal stats`: a system derived and interpreted without drawing,
//! measured; from its shared tree where it has one.

use super::derive::written_symbols;
use super::derive::{derive_values, RunOptions};
use super::interpret::interpret;
use crate::diagnostics::Diagnostic;
use crate::eval::tree::{Tree, MAX_TREE_DEPTH};
use crate::eval::{self, Deriver};
use crate::ir::System;
use crate::turtle;
use crate::turtle::instanced::Instanced;
use serde::Serialize;
use std::time::{Duration, Instant};

/// What `graftal stats` reports.
#[derive(Clone, Debug, Serialize)]
pub struct Stats {
    pub steps: u64,
    pub symbols: u128,
    pub segments: u128,
    pub polygons: u128,
    /// `[minx, miny, minz, maxx, maxy, maxz]`, turtle units (zeros when
    /// nothing is drawn).
    pub bbox: [f64; 6],
    pub max_depth: usize,
    /// How the figures were found: `"shared subtrees"` (context-free
    /// systems, without deriving the word), `"streamed"` (the word's
    /// symbols interpreted one by one as they are derived, nothing kept) or
    /// `"derived"` (the word derived, then interpreted without keeping what
    /// is drawn).
    pub method: &'static str,
    /// How the word is derived ([`eval::Method::name`]): `"shared tree"`,
    /// `"table"`, `"general"` or `"modules"`, chosen from the system's
    /// properties.
    pub derivation: &'static str,
    /// Seconds per stage.
    pub time: StageTimes,
}

#[derive(Clone, Debug, Default, Serialize)]
pub struct StageTimes {
    /// Reading and checking the file (filled in by the caller that did it).
    pub parse: f64,
    pub derive: f64,
    pub interpret: f64,
}

/// A turtle sink that only counts and measures.
#[derive(Default)]
struct Counter {
    segments: u128,
    polygons: u128,
    bbox: Option<[f64; 6]>,
}

impl Counter {
    /// The figures counted, with what else `stats` reports: how the
    /// figures were found and how the word is derived.
    fn stats(
        self,
        steps: u64,
        symbols: u128,
        max_depth: usize,
        (method, derivation): (&'static str, &'static str),
        time: StageTimes,
    ) -> Stats {
        Stats {
            steps,
            symbols,
            segments: self.segments,
            polygons: self.polygons,
            bbox: self.bbox.unwrap_or([0.0; 6]),
            max_depth,
            method,
            derivation,
            time,
        }
    }

    fn point(&mut self, p: turtle::Vec3) {
        turtle::grow_box(&mut self.bbox, p);
    }
}

impl turtle::Sink for Counter {
    fn segment(&mut self, s: turtle::Segment) {
        self.segments += 1;
        self.point(s.a);
        self.point(s.b);
    }
    fn polygon(&mut self, p: turtle::Polygon) {
        self.polygons += 1;
        p.points.iter().for_each(|&q| self.point(q));
    }
    fn disc(&mut self, d: turtle::Disc) {
        self.point(d.centre);
    }
}

/// Derives and interprets without drawing, and measures; nothing drawn is
/// kept. A context-free deterministic system is measured on its shared
/// derivation tree ([`Instanced`]) without deriving its word, so its size
/// is not limited by `--max-symbols`; when its turtle commands cannot be
/// instanced, its word is streamed symbol by symbol through the turtle
/// (memory grows with the depth, not the word). Any other system is
/// derived (within the symbol limit), then interpreted.
pub fn stats(sys: &System, opts: &RunOptions) -> Result<Stats, Diagnostic> {
    let t0 = Instant::now();
    let dopts = opts.derive_options(sys);
    let steps = dopts.steps;
    let derivation = eval::plan(sys, steps).name();
    let secs = |d: Duration| d.as_secs_f64();
    let silent: Vec<u128> = sys
        .symbols
        .iter()
        .map(|(_, i)| u128::from(!i.name.is_empty()))
        .collect();
    let tree = (steps <= MAX_TREE_DEPTH).then(|| Tree::new(sys)).flatten();
    if let Some(t) = &tree {
        let symbols = t
            .weighed(steps, &silent, u128::MAX)
            .expect("no limit to pass");
        let measured = |c: Counter, max_depth: usize, method: &'static str| {
            let time = StageTimes {
                parse: 0.0,
                derive: 0.0,
                interpret: secs(t0.elapsed()),
            };
            c.stats(steps, symbols, max_depth, (method, derivation), time)
        };
        if let Some(mut inst) = Instanced::new(sys).filter(|i| i.fits(steps)) {
            let x = inst.word(steps);
            let c = Counter {
                segments: x.segments,
                polygons: 0,
                bbox: x
                    .draws()
                    .then(|| [x.lo[0], x.lo[1], x.lo[2], x.hi[0], x.hi[1], x.hi[2]]),
            };
            return Ok(measured(c, x.depth as usize, "shared subtrees"));
        }
        // Streaming costs time in proportion to the word: the limit says
        // so before it starts.
        Deriver::new(sys).tree_len(t, &dopts)?;
        let mut c = Counter::default();
        let run = turtle::Run::symbols(sys, t.symbols(steps), opts.seed);
        let max_depth = turtle::run(run, &mut c).max_depth;
        return Ok(measured(c, max_depth, "streamed"));
    }
    let (w, values) = derive_values(sys, opts, |_, _| {})?;
    let t1 = Instant::now();
    let (symbols, c, max_depth) = if sys.rewrites_modules() {
        // Drawn through the homomorphism, which may need the whole word.
        let g = interpret(sys, &w, &values, opts, false)?;
        let c = Counter {
            segments: g.segments.len() as u128,
            polygons: g.polygons.len() as u128,
            bbox: g.bbox(),
        };
        (w.len() as u128, c, g.max_depth)
    } else {
        let mut c = Counter::default();
        let run = turtle::Run::symbols(sys, w.0.iter().copied(), opts.seed);
        let depth = turtle::run(run, &mut c).max_depth;
        (written_symbols(sys, &w) as u128, c, depth)
    };
    let t2 = Instant::now();
    let time = StageTimes {
        parse: 0.0,
        derive: secs(t1 - t0),
        interpret: secs(t2 - t1),
    };
    Ok(c.stats(steps, symbols, max_depth, ("derived", derivation), time))
}
