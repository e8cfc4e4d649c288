//! The `.gft` emitter: a system written in graftal's own notation
//! (docs/gft.md), every field of the IR, never refused and never lossy.
//!
//! The file is written in a fixed order: settings that differ from the
//! default, rotations, colours, what each symbol does to the turtle
//! (`turtle none` and one `NAME = operation` line per symbol that does
//! something), the rule policy, context filter, ring and cut, the program,
//! the axiom, the productions, the phases, the structure, the look,
//! surfaces and contours. Numbers are [`expr::num`]: bit-exact. Where
//! docs/gft.md is silent, docs/gft-emitter-notes.md says what is written.

pub mod expr;
mod look;
mod words;

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
    if !sys.colours.is_empty() {
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
    if let Some(st) = &sys.structure {
        look::structure(&mut out, sys, &sp, st);
    }
    look::look(&mut out, &sys.look);
    look::surfaces(&mut out, sys);
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
    if s.colour != d.colour {
        let _ = writeln!(out, "colour {}", s.colour);
    }
    if let Some((az, el)) = s.view {
        let _ = writeln!(out, "view {}", look::degrees_or_radians(&[az, el]));
    }
    if let Some(seed) = s.seed {
        let _ = writeln!(out, "seed {seed}");
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
    let (key, ids) = match &sys.context {
        crate::ir::ContextFilter::Ignore(ids) => ("ignore", ids),
        crate::ir::ContextFilter::Consider(ids) => ("consider", ids),
    };
    if key == "consider" || !ids.is_empty() {
        let _ = writeln!(out, "{key} {}", sp.symbols(ids).trim_end());
    }
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

/// The names of a production's local slots: `x0`, `x1`, … (with `_`
/// added while a name is a global's or an array's).
fn local_names(sys: &System, p: &Production) -> Vec<String> {
    let taken = |n: &str| {
        sys.program.globals.iter().any(|g| g == n) || sys.program.arrays.iter().any(|a| a.name == n)
    };
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
    if let Some(seed) = ph.seed {
        let _ = write!(out, " seed {seed}");
    }
    out.push_str(" {\n");
    for p in &ph.productions {
        production(out, sys, sp, p, "  ");
    }
    out.push_str("}\n");
}
