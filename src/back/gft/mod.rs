//! The `.gft` emitter: a system written in graftal's own notation
//! (docs/gft.md), every field of the IR, never refused and never lossy.
//!
//! The file is written in a fixed order: settings that differ from the
//! default, rotations, colours, what each symbol does to the turtle
//! (the turtle set that needs the fewest `NAME = operation` lines, and
//! those lines), the rule policy, context filter, ring and cut, the program,
//! the axiom, the productions, the phases, the structure, the graph, the
//! look, surfaces and contours. Numbers are [`expr::num`]: bit-exact. Where
//! docs/gft.md is silent, docs/gft-emitter-notes.md says what is written.

mod environment;
pub mod expr;
mod graph;
mod look;
mod words;
pub use look::names_file;

use crate::ir::program::{Program, Stmt};
use crate::ir::{Phase, Production, Settings, System};
use expr::{num, Names};
use std::fmt::Write;
use words::Spelling;

/// The gft emitter in the registry.
pub struct Gft;

impl super::Back for Gft {
    fn name(&self) -> &'static str {
        "gft"
    }
    fn extension(&self) -> &'static str {
        "gft"
    }
    fn write(&self, e: &mut super::Emitter<'_>) -> String {
        write(e.sys, None)
    }
    fn write_everything(&self, sys: &System, steps: Option<u64>) -> Option<String> {
        Some(write(sys, steps))
    }
}

/// `sys` as a `.gft` file; `steps`, when given, replaces the system's
/// derivation length.
pub fn write(sys: &System, steps: Option<u64>) -> String {
    let sp = Spelling::new(sys);
    let mut out = String::new();
    settings(&mut out, &sys.settings, steps);
    look::rotations(&mut out, sys);
    if sys.colours == crate::common::palettes::fractint_palette() {
        out.push_str("colours fractint\n");
    } else if !sys.colours.is_empty() {
        let hex: Vec<String> = sys.colours.iter().map(|&c| look::hex(c)).collect();
        let _ = writeln!(out, "colours {}", hex.join(" "));
    }
    sp.turtle(&mut out, sys);
    rewriting(&mut out, sys, &sp);
    program(&mut out, &sys.program);
    let globals = global_names(&sys.program);
    let no_locals = Names {
        locals: &[],
        globals: &globals.0,
        arrays: &globals.1,
    };
    // An outline or a seed gives the axiom when read (docs/gft.md §8).
    if sys.structure.is_none() && !sys.axiom.is_empty() {
        let word = sp.word(&sys.axiom, &sys.axiom_args, &no_locals);
        let _ = writeln!(out, "axiom {word}");
    }
    for p in &sys.productions {
        production(&mut out, sys, &sp, p, "");
    }
    phase(&mut out, sys, &sp, "decomposition", &sys.decomposition);
    phase(&mut out, sys, &sp, "homomorphism", &sys.homomorphism);
    sub_lsystems(&mut out, sys, &sp);
    if let Some(st) = &sys.structure {
        look::structure(&mut out, sys, &sp, st);
    }
    if let Some(g) = &sys.graph {
        graph::graph(&mut out, g);
    }
    look::look(&mut out, &sys.look);
    look::surfaces(&mut out, sys);
    if let Some(env) = &sys.environment {
        environment::environment(&mut out, env);
    }
    out
}

/// One `key value` line per setting that differs from the default.
fn settings(out: &mut String, s: &Settings, steps: Option<u64>) {
    let d = Settings::default();
    let differs = |a: f64, b: f64| a.to_bits() != b.to_bits();
    if let Some(n) = steps.or(s.steps) {
        let _ = writeln!(out, "steps {n}");
    }
    if differs(s.delta, d.delta) {
        let _ = writeln!(out, "angle {}", look::degrees_or_radians(&[s.delta]));
    }
    let numbers = [
        ("length", s.step, d.step),
        ("scale", s.scale, d.scale),
        ("width", s.width, d.width),
        ("width-factor", s.width_factor, d.width_factor),
        ("width-step", s.width_step, d.width_step),
        ("colour-step", s.colour_step, d.colour_step),
    ];
    for (key, v, default) in numbers {
        if differs(v, default) {
            let _ = writeln!(out, "{key} {}", num(v));
        }
    }
    if s.world_widths {
        out.push_str("widths world\n");
    }
    if s.cpfg_polygons {
        out.push_str("cpfg-polygons\n");
    }
    if s.colour != d.colour {
        let _ = writeln!(out, "colour {}", s.colour);
    }
    if let Some((az, el)) = s.view {
        let _ = writeln!(out, "view {}", look::degrees_or_radians(&[az, el]));
    }
    if let Some(seed) = s.seed {
        let _ = writeln!(out, "seed {seed}");
    }
    if s.randomness == crate::ir::Randomness::Cpfg {
        out.push_str("random cpfg\n");
    }
    for t in &s.tropisms {
        look::tropism(out, t);
    }
}

/// Policy, context filter, ring and cut.
fn rewriting(out: &mut String, sys: &System, sp: &Spelling) {
    if sys.policy == crate::ir::RulePolicy::Weighted {
        out.push_str("choose weighted\n");
    }
    context(out, sp, &sys.context, "");
    if sys.ring {
        out.push_str("ring\n");
    }
    if let Some(c) = sys.cut {
        let _ = writeln!(out, "cut {}", sp.symbols(&[c]));
    }
}

/// The names of the globals and of the arrays.
fn global_names(p: &Program) -> (Vec<String>, Vec<String>) {
    let arrays = p.arrays.iter().map(|a| a.name.clone()).collect();
    (p.globals.clone(), arrays)
}

/// Globals, arrays, functions and the blocks around the derivation.
fn program(out: &mut String, p: &Program) {
    if !p.globals.is_empty() {
        let _ = writeln!(out, "globals {}", p.globals.join(", "));
    }
    for a in &p.arrays {
        let dims: String = a.dims.iter().map(|d| format!("[{d}]")).collect();
        let init: Vec<String> = a.init.iter().map(|&v| num(v)).collect();
        let _ = write!(out, "array {}{dims}", a.name);
        if !init.is_empty() {
            let _ = write!(out, " = {}", init.join(", "));
        }
        out.push('\n');
    }
    for f in &p.functions {
        let samples: Vec<String> = f.samples.iter().map(|&v| num(v)).collect();
        let _ = writeln!(out, "function {} = {}", f.name, samples.join(" "));
    }
    let (globals, arrays) = global_names(p);
    let names = Names {
        locals: &[],
        globals: &globals,
        arrays: &arrays,
    };
    let blocks: [(&str, &Vec<Stmt>); 4] = [
        ("start", &p.start),
        ("start-each", &p.start_each),
        ("end-each", &p.end_each),
        ("end", &p.end),
    ];
    for (key, ss) in blocks {
        if !ss.is_empty() {
            let _ = writeln!(out, "{key} {{");
            expr::stmts(out, ss, 2, &names);
            out.push_str("}\n");
        }
    }
}

/// The names of a production's local slots: the author's
/// (`Formals::names`) when each is a distinct identifier that no global or
/// array has, else `x0`, `x1`, … (with `_` added while a name is a
/// global's or an array's).
fn local_names(sys: &System, p: &Production) -> Vec<String> {
    let taken = |n: &str| {
        sys.program.globals.iter().any(|g| g == n) || sys.program.arrays.iter().any(|a| a.name == n)
    };
    let names = &p.formals.names;
    let identifier = |n: &str| {
        n.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
            && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            && !["if", "else", "while", "do"].contains(&n)
            && !crate::ir::program::BUILTINS.iter().any(|b| b.0 == n)
    };
    let distinct = (0..names.len()).all(|i| !names[..i].contains(&names[i]));
    let usable = names.len() == usize::from(p.formals.locals)
        && distinct
        && names.iter().all(|n| identifier(n) && !taken(n));
    if usable {
        return names.clone();
    }
    (0..p.formals.locals)
        .map(|k| {
            let mut name = format!("x{k}");
            while taken(&name) {
                name.push('_');
            }
            name
        })
        .collect()
}

/// `left < pred > right : {before} cond {after} -> succ : weight`, one
/// line per alternative after the first starting with `->`.
fn production(out: &mut String, sys: &System, sp: &Spelling, p: &Production, indent: &str) {
    let locals = local_names(sys, p);
    let (globals, arrays) = global_names(&sys.program);
    let names = Names {
        locals: &locals,
        globals: &globals,
        arrays: &arrays,
    };
    let mut head = String::from(indent);
    let f = &p.formals;
    if !p.left.is_empty() {
        let _ = write!(head, "{} < ", sp.pattern(&p.left, &f.left, &locals));
    }
    head.push_str(&sp.pattern(&p.predecessor, &f.predecessor, &locals));
    if !p.right.is_empty() {
        let _ = write!(head, " > {}", sp.pattern(&p.right, &f.right, &locals));
    }
    let guarded = p.condition.is_some() || !p.before.is_empty() || !p.after.is_empty();
    if guarded {
        head.push_str(" :");
        if !p.before.is_empty() {
            let _ = write!(head, " {}", expr::inline(&p.before, &names));
        }
        // cpfg's `*`: no condition, written only to place the statements.
        let cond = p
            .condition
            .as_ref()
            .map_or("*".into(), |c| expr::expr(c, &names));
        let _ = write!(head, " {cond}");
        if !p.after.is_empty() {
            let _ = write!(head, " {}", expr::inline(&p.after, &names));
        }
    }
    let width = head.len();
    let single = p.alternatives.len() == 1;
    for (k, a) in p.alternatives.iter().enumerate() {
        let lead = if k == 0 {
            head.clone()
        } else {
            " ".repeat(width)
        };
        let succ = sp.word(&a.successor, &a.args, &names);
        let line = format!("{lead} -> {succ}");
        out.push_str(line.trim_end());
        let weight = match &a.computed_weight {
            Some(w) => Some(expr::expr(w, &names)),
            None if !single || a.weight.to_bits() != 1f64.to_bits() => Some(num(a.weight)),
            None => None,
        };
        if let Some(w) = weight {
            let _ = write!(out, " : {w}");
        }
        out.push('\n');
    }
    if p.alternatives.is_empty() {
        // No alternative at all: the production is written without one.
        let _ = writeln!(out, "{head} ->");
    }
}

/// `decomposition depth N [seed S] { productions }`, when the phase has
/// anything.
fn phase(out: &mut String, sys: &System, sp: &Spelling, key: &str, ph: &Phase) {
    if *ph == Phase::default() {
        return;
    }
    let _ = write!(out, "{key} depth {}", ph.depth);
    phase_rest(out, sys, sp, ph);
}

/// A phase's seed and block, after its key and depth.
fn phase_rest(out: &mut String, sys: &System, sp: &Spelling, ph: &Phase) {
    if let Some(seed) = ph.seed {
        let _ = write!(out, " seed {seed}");
    }
    out.push_str(" {\n");
    for p in &ph.productions {
        production(out, sys, sp, p, "  ");
    }
    out.push_str("}\n");
}

/// An `ignore` or `consider` line, none for an empty `ignore`.
fn context(out: &mut String, sp: &Spelling, filter: &crate::ir::ContextFilter, indent: &str) {
    let (key, ids) = match filter {
        crate::ir::ContextFilter::Ignore(ids) => ("ignore", ids),
        crate::ir::ContextFilter::Consider(ids) => ("consider", ids),
    };
    if key == "consider" || !ids.is_empty() {
        let _ = writeln!(out, "{indent}{key} {}", sp.symbols(ids).trim_end());
    }
}

/// The main L-system's label (when not 1) and each sub-L-system: its
/// block, then its phases (docs/gft.md §5).
fn sub_lsystems(out: &mut String, sys: &System, sp: &Spelling) {
    if sys.label != 1 {
        let _ = writeln!(out, "label {}", sys.label);
    }
    for sub in &sys.sub_lsystems {
        let _ = writeln!(out, "sub-lsystem {} {{", sub.label);
        context(out, sp, &sub.context, "  ");
        for p in &sub.productions {
            production(out, sys, sp, p, "  ");
        }
        out.push_str("}\n");
        for (key, ph) in [
            ("decomposition", &sub.decomposition),
            ("homomorphism", &sub.homomorphism),
        ] {
            if *ph != Phase::default() {
                let _ = write!(out, "{key} lsystem {} depth {}", sub.label, ph.depth);
                phase_rest(out, sys, sp, ph);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::look::{Camera, Contour, ContourRole, Lighting, Tropism, TropismKind};
    use crate::ir::program::{ArrayDecl, Expr, Function, Var};
    use crate::ir::*;

    /// A system with every field away from its default.
    fn everything() -> System {
        let mut s = System::new();
        let (a, b, apex) = (s.intern("A"), s.intern("B"), s.intern("Apex"));
        let plus_t = s.intern("+t");
        let stem = s.intern_silent("stl-level-0");
        let guarded = s.symbols.intern_guarded(0.5, a);
        s.intern("0.5?A");
        s.set_interpretation(a, TurtleOp::Forward { draw: true });
        let turn = |angle| TurtleOp::Rotate {
            axis: Axis::Left,
            angle,
        };
        s.set_interpretation(b, turn(Angle::Radians(30f64.to_radians())));
        s.set_interpretation(
            plus_t,
            TurtleOp::Frenet {
                rotation: RotationId(0),
                negate: false,
            },
        );
        s.set_interpretation(
            stem,
            TurtleOp::Stem {
                width: 2.0,
                length: 3.0,
            },
        );
        s.rotations.push(Rotation {
            name: "t".into(),
            torsion: Angle::Radians(0.0),
            curvature: Angle::Uniform { lo: 0.0, hi: 1.5 },
        });
        s.axiom = Word::from(vec![a, guarded, stem]);
        s.axiom_args = vec![vec![Expr::Num(1.0)], vec![], vec![]];
        let mut p = Production::new(vec![b], vec![a], vec![apex], vec![]);
        p.formals = Formals {
            left: vec![vec![]],
            predecessor: vec![vec![0]],
            right: vec![vec![]],
            locals: 2,
            names: Vec::new(),
        };
        p.before = vec![Stmt::Assign(
            program::Place::Var(Var::Local(1)),
            Expr::Num(2.0),
        )];
        p.condition = Some(Expr::Binary(
            program::BinOp::Lt,
            Box::new(Expr::Var(Var::Local(0))),
            Box::new(Expr::Var(Var::Global(0))),
        ));
        let mut alt = Alternative::new(0.25, Word::from(vec![a, plus_t]));
        alt.args = vec![vec![Expr::Var(Var::Local(1))], vec![]];
        let mut computed = Alternative::new(1.0, Word::from(vec![b]));
        computed.computed_weight = Some(Expr::Num(0.75));
        p.alternatives = vec![alt, computed];
        s.productions.push(p.clone());
        s.decomposition = Phase {
            productions: vec![p.clone()],
            depth: 2,
            seed: None,
        };
        s.homomorphism = Phase {
            productions: vec![p],
            depth: 1,
            seed: Some(7),
        };
        s.program.globals = vec!["n".into()];
        s.program.arrays = vec![ArrayDecl {
            name: "v".into(),
            dims: vec![2],
            init: vec![1.0, 2.0],
        }];
        s.program.functions = vec![Function {
            name: "leaf".into(),
            samples: vec![0.0, 0.5],
        }];
        s.program.start = vec![Stmt::Assign(
            program::Place::Var(Var::Global(0)),
            Expr::Num(0.0),
        )];
        s.program.end_each = vec![Stmt::Eval(Expr::Var(Var::Global(0)))];
        s.ring = true;
        s.cut = Some(b);
        s.policy = RulePolicy::Weighted;
        s.context = ContextFilter::Consider(vec![a, b]);
        settings_and_look(&mut s);
        s
    }

    /// Settings, colours, surfaces, contours and the look.
    fn settings_and_look(s: &mut System) {
        s.settings.steps = Some(4);
        s.settings.delta = 0.1;
        s.settings.view = Some((30f64.to_radians(), 0.0));
        s.settings.seed = Some(3);
        s.settings.tropisms.push(Tropism {
            vector: [0.0, -1.0, 0.0],
            angle: 0.0,
            intensity: 1.0,
            elasticity: 0.25,
            step: 0.0,
            kind: TropismKind::Torque,
        });
        s.colours = vec![Rgb(255, 0, 16)];
        s.surfaces.push(SurfaceMesh {
            name: "leaf".into(),
            triangles: vec![[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]],
            ..Default::default()
        });
        s.contours.push(Contour {
            id: 1,
            role: ContourRole::CrossSection,
            points: vec![[1.0, 0.0, 0.0]],
            closed: true,
            length: 1.0,
        });
        s.look.background = Some(Rgb(0, 0, 0));
        s.look.camera = Some(Camera {
            eye: [0.0, 0.0, 10.0],
            target: [0.0; 3],
            up: [0.0, 1.0, 0.0],
            perspective: Some(45.0),
        });
        s.look.lighting = Some(Lighting::default());
    }

    #[test]
    fn every_field_is_written() {
        let text = write(&everything(), None);
        let lines = [
            "steps 4",
            "angle 0.1 rad",
            "view 30 0",
            "seed 3",
            "tropism (0, -1, 0) angle 0 intensity 1 elasticity 0.25 step 0 torque",
            "rotation t = (0, [0 1.5])",
            "colours #ff0010",
            "A = forward",
            "B = pitch 30deg",
            "+t = frenet t",
            "silent stl-level-0 = stem 2 3",
            "symbol Apex",
            "choose weighted",
            "consider A B",
            "ring",
            "cut B",
            "globals n",
            "array v[2] = 1, 2",
            "function leaf = 0 0.5",
            "start {\n  n = 0;\n}",
            "end-each {\n  n;\n}",
            "axiom A(1) 0.5?A `stl-level-0`",
            "B < A(x0) > Apex : { x1 = 2; } x0 < n -> A(x1) +t : 0.25",
            "\n                                      -> B : 0.75\n",
            "decomposition depth 2 {\n  B < A(x0)",
            "homomorphism depth 1 seed 7 {",
            "background #000000",
            "camera eye (0, 0, 10) target (0, 0, 0) up (0, 1, 0) perspective 45",
            "lighting filled line-style pixel tapered index-shift 10",
            "light (0, 0, 1) point ambient (1, 1, 1)",
            "surface leaf {\n  (0, 0, 0) (1, 0, 0) (0, 1, 0)\n}",
            "contour 1 cross-section closed length 1 {\n  (1, 0, 0)\n}",
        ];
        for line in lines {
            assert!(text.contains(line), "`{line}` missing from\n{text}");
        }
    }

    #[test]
    fn names_the_notation_cannot_read_bare_are_backquoted() {
        let mut s = System::new();
        let names = ["<", "{", "a b", "2x", "F"];
        let ids: Vec<SymbolId> = names.iter().map(|n| s.intern(n)).collect();
        s.axiom = Word::from(ids);
        let text = write(&s, None);
        assert!(text.contains("axiom `<` `{` `a b` `2x` F"), "{text}");
        assert!(text.contains("symbol `2x` `a b`"), "{text}");
        let ring = s.intern("ring");
        s.set_interpretation(ring, TurtleOp::Push);
        s.axiom.push(ring, &[]);
        let text = write(&s, None);
        assert!(text.contains("\n`ring` = push\n"), "{text}");
    }
}
