//! `graftal stats`: a system derived and interpreted without drawing,
//! measured; from its shared tree where it has one.

use super::derive::written_symbols;
use super::derive::{derive_values, RunOptions};
use super::interpret::interpret;
use crate::diagnostics::{codes, Diagnostic};
use crate::eval::count::Count;
use crate::eval::tree::{Tree, COUNT_BUDGET, MAX_TREE_DEPTH};
use crate::eval::{self, Deriver};
use crate::ir::{SymbolId, System, TurtleOp};
use crate::turtle;
use crate::turtle::instanced::Instanced;
use serde::Serialize;
use std::time::{Duration, Instant};

/// What `graftal stats` reports.
#[derive(Clone, Debug, Serialize)]
pub struct Stats {
    pub steps: u64,
    /// Exact, however large (JSON numbers of as many digits as they take).
    pub symbols: Count,
    pub segments: Count,
    pub polygons: Count,
    /// `[minx, miny, minz, maxx, maxy, maxz]`, turtle units (zeros when
    /// nothing is drawn); `None` when it is beyond `f64`
    /// ([`codes::BOX_TOO_LARGE`], in [`Stats::warnings`]).
    pub bbox: Option<[f64; 6]>,
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
    /// An instancing graph's primitive instances expanded to the pixels of
    /// a 1024x1024 picture of it (its shapes placed, or, without shapes,
    /// the volumes at the pixel cut); `None` for an L-system.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub instances: Option<u128>,
    /// What could not be given, and why.
    #[serde(skip)]
    pub warnings: Vec<Diagnostic>,
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
    /// What was counted, with the word's symbols and deepest branching.
    fn measured(self, symbols: Count, max_depth: usize) -> Measured {
        Measured {
            symbols,
            segments: Count::from(self.segments),
            polygons: Count::from(self.polygons),
            bbox: finite_box(self.bbox),
            max_depth,
        }
    }

    fn point(&mut self, p: turtle::Vec3) {
        turtle::grow_box(&mut self.bbox, p);
    }

    /// Adds what `later` counted (a later piece of the word).
    fn add(&mut self, later: Counter) {
        self.segments += later.segments;
        self.polygons += later.polygons;
        turtle::join_boxes(&mut self.bbox, later.bbox);
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

/// The figures `stats` found, however it found them.
struct Measured {
    symbols: Count,
    segments: Count,
    polygons: Count,
    /// The box in turtle units (`None`: nothing drawn), or the warning
    /// that it cannot be given.
    bbox: Result<Option<[f64; 6]>, Diagnostic>,
    max_depth: usize,
}

impl Measured {
    /// The figures, with what else `stats` reports: how they were found
    /// and how the word is derived.
    fn stats(
        self,
        steps: u64,
        (method, derivation): (&'static str, &'static str),
        time: StageTimes,
    ) -> Stats {
        let (bbox, warnings) = match self.bbox {
            Ok(b) => (Some(b.unwrap_or([0.0; 6])), Vec::new()),
            Err(w) => (None, vec![w]),
        };
        Stats {
            steps,
            symbols: self.symbols,
            segments: self.segments,
            polygons: self.polygons,
            bbox,
            max_depth: self.max_depth,
            method,
            derivation,
            time,
            warnings,
            instances: None,
        }
    }
}

/// The side of the picture [`graph_stats`] counts instances for.
pub const GRAPH_STATS_PIXELS: u32 = 1024;

/// What `stats` says of an instancing graph: no word (0 steps, symbols,
/// segments), its box, and how many primitive instances a 1024x1024
/// picture of it expands to, counted without expanding them.
fn graph_stats(
    sys: &System,
    graph: &crate::ir::graph::InstancingGraph,
) -> Result<Stats, Diagnostic> {
    use crate::raytrace::{self, graph::GraphScene, Eye, Options, Scene};
    let t0 = Instant::now();
    let scene = GraphScene::new(graph, [0.5; 3]).map_err(|_| {
        Diagnostic::global(
            codes::GRAPH_UNBOUNDED,
            "the graph has no limit to count (see `graftal check`)",
        )
    })?;
    let (azimuth, elevation) = sys.settings.view.unwrap_or((0.0, 0.0));
    let opts = Options::new(
        GRAPH_STATS_PIXELS,
        GRAPH_STATS_PIXELS,
        Eye::View { azimuth, elevation },
    );
    let pixel = raytrace::pixel_size(&scene.fit_points(), &opts);
    let instances = raytrace::graph::count_instances(graph, scene.bounds(), pixel);
    let (lo, hi) = scene.world_box();
    Ok(Stats {
        steps: 0,
        symbols: Count::from(0u128),
        segments: Count::from(0u128),
        polygons: Count::from(0u128),
        bbox: Some([lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]]),
        max_depth: 0,
        method: "instancing graph",
        derivation: "none",
        time: StageTimes {
            parse: 0.0,
            derive: 0.0,
            interpret: t0.elapsed().as_secs_f64(),
        },
        warnings: Vec::new(),
        instances: Some(instances),
    })
}

/// `b`, or the warning that it is beyond `f64` when a bound is not finite.
fn finite_box(b: Option<[f64; 6]>) -> Result<Option<[f64; 6]>, Diagnostic> {
    match b {
        Some(b) if b.iter().any(|v| !v.is_finite()) => Err(box_too_large(None)),
        b => Ok(b),
    }
}

/// The warning that the box cannot be given: its extent, when known, is
/// `log10` of its width in turtle units.
fn box_too_large(log10: Option<f64>) -> Diagnostic {
    let across = match log10.filter(|l| l.is_finite()) {
        Some(l) => {
            let e = l.floor();
            format!("about {:.1}e{e} turtle units across", 10f64.powf(l - e))
        }
        None => "too large to measure".to_string(),
    };
    Diagnostic::global(
        codes::BOX_TOO_LARGE,
        format!(
            "the bounding box cannot be given: it is {across}, beyond the largest floating-point number ({:.1e})",
            f64::MAX
        ),
    )
    .with_note("the counts are exact whatever their size")
}

/// The error that exact counts would take too long to add up.
fn counts_too_long(steps: u64) -> Diagnostic {
    Diagnostic::global(
        codes::COUNTS_TOO_LONG,
        format!("the counts after {steps} steps would take too long to add up exactly"),
    )
    .with_note(format!(
        "adding them takes more than {COUNT_BUDGET} limb operations: numbers of thousands of digits, over many symbols"
    ))
    .with_help("count fewer steps with `-n`")
}

/// How many symbols the word after `steps` steps holds of those `which`
/// picks, exactly, from its shared tree.
fn tree_count(
    sys: &System,
    (t, steps): (&Tree, u64),
    which: impl Fn(SymbolId) -> bool,
) -> Result<Count, Diagnostic> {
    let weights: Vec<u128> = (0..sys.symbols.len() as u32)
        .map(|i| u128::from(which(SymbolId(i))))
        .collect();
    t.count(steps, &weights)
        .ok_or_else(|| counts_too_long(steps))
}

/// The figures of the system of `inst` after `steps` steps, from its
/// shared subtrees: the box in the unit that holds it, which says how far
/// beyond `f64` it is when that is not turtle units.
fn instanced(inst: &mut Instanced, steps: u64, symbols: Count, segments: Count) -> Measured {
    let (x, unit) = inst.word_scaled(steps);
    let b = [x.lo[0], x.lo[1], x.lo[2], x.hi[0], x.hi[1], x.hi[2]];
    let bbox = if !x.draws() {
        Ok(None)
    } else if unit == 0 {
        finite_box(Some(b))
    } else {
        let width = (0..3).map(|i| x.hi[i] - x.lo[i]).fold(0.0, f64::max);
        Err(box_too_large(Some(
            width.log10() + unit as f64 * std::f64::consts::LOG10_2,
        )))
    };
    Measured {
        symbols,
        segments,
        polygons: Count::zero(),
        bbox,
        max_depth: x.depth as usize,
    }
}

/// Derives and interprets without drawing, and measures; nothing drawn is
/// kept. A context-free deterministic system is measured on its shared
/// derivation tree ([`Instanced`]) without deriving its word, so its size
/// is not limited by `--max-symbols`, and its counts are exact however
/// large; when its turtle commands cannot be instanced, its word is
/// streamed symbol by symbol through the turtle (memory grows with the
/// depth, not the word). Any other system is derived (within the symbol
/// limit), then interpreted.
pub fn stats(sys: &System, opts: &RunOptions) -> Result<Stats, Diagnostic> {
    if let Some(graph) = &sys.graph {
        return graph_stats(sys, graph);
    }
    let t0 = Instant::now();
    let dopts = opts.derive_options(sys);
    let steps = dopts.steps;
    let derivation = eval::plan(sys, steps).name();
    let secs = |d: Duration| d.as_secs_f64();
    let tree = (steps <= MAX_TREE_DEPTH).then(|| Tree::new(sys)).flatten();
    if let Some(t) = &tree {
        let symbols = tree_count(sys, (t, steps), |s| !sys.symbols.info(s).name.is_empty())?;
        let done = |m: Measured, method: &'static str| {
            let time = StageTimes {
                parse: 0.0,
                derive: 0.0,
                interpret: secs(t0.elapsed()),
            };
            m.stats(steps, (method, derivation), time)
        };
        if let Some(mut inst) = Instanced::new(sys).filter(|i| i.fits(steps)) {
            // The drawing steps are what it draws, one segment each.
            let draws = |s| matches!(sys.op(s), Some(TurtleOp::Forward { draw: true }));
            let segments = tree_count(sys, (t, steps), draws)?;
            let m = instanced(&mut inst, steps, symbols, segments);
            return Ok(done(m, "shared subtrees"));
        }
        // Streaming costs time in proportion to the word: the limit says
        // so before it starts.
        Deriver::new(sys).tree_len(t, &dopts)?;
        let mut c = Counter::default();
        let run = turtle::Run::symbols(sys, t.symbols(steps), opts.seed);
        let max_depth = turtle::run(run, &mut c).max_depth;
        return Ok(done(c.measured(symbols, max_depth), "streamed"));
    }
    let (w, values) = derive_values(sys, opts, |_, _| {})?;
    let t1 = Instant::now();
    let m = if sys.rewrites_modules() {
        // Drawn through the homomorphism, which may need the whole word.
        let g = interpret(sys, &w, &values, opts, false)?;
        let c = Counter {
            segments: g.segments.len() as u128,
            polygons: g.polygons.len() as u128,
            bbox: g.bbox(),
        };
        c.measured(Count::from(w.len() as u64), g.max_depth)
    } else {
        let pieces = turtle::Pieces::plan(sys, &w.0[..], None, opts.seed, opts.threads);
        let (counts, depth) = turtle::pieces::each(&pieces, opts.threads, Counter::default);
        let mut c = Counter::default();
        for later in counts {
            c.add(later);
        }
        c.measured(Count::from(written_symbols(sys, &w) as u64), depth)
    };
    let t2 = Instant::now();
    let time = StageTimes {
        parse: 0.0,
        derive: secs(t1 - t0),
        interpret: secs(t2 - t1),
    };
    Ok(m.stats(steps, ("derived", derivation), time))
}
