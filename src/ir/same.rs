//! Whether two systems say the same thing: [`System::same_as`].
//!
//! `PartialEq` on [`System`] compares symbol ids, so two readings of one
//! model that intern their symbols in another order differ, and it treats
//! `0.0 == -0.0`. A translation that must read back to the same system
//! (`.gft`, issue 19) needs the equality people mean: symbols by name,
//! symbols that occur nowhere ignored, every other field as it is, floats
//! bit for bit (`f64`'s `Debug` form is the shortest that reads back, so
//! two floats print alike exactly when their bits agree, NaN payloads
//! aside).

use super::{ContextFilter, Phase, Production, SeedItem, SymbolId, System, Word};
use std::collections::BTreeMap;
use std::fmt::Debug;

impl System {
    /// `Ok` when `self` and `other` are the same system spans aside:
    /// symbols compared by name (ids may differ), symbols that occur
    /// nowhere (not in the axiom, a production, a phase or the structure)
    /// ignored, even when given an operation, every other field compared field
    /// by field with floats bit-exact. `Err` names the first difference:
    /// the field's path and both values.
    pub fn same_as(&self, other: &System) -> Result<(), String> {
        let same = Same { a: self, b: other };
        same.symbols()?;
        same.word("axiom", &self.axiom, &other.axiom)?;
        debug("axiom_args", &self.axiom_args, &other.axiom_args)?;
        same.productions("productions", &self.productions, &other.productions)?;
        same.phase("decomposition", &self.decomposition, &other.decomposition)?;
        same.phase("homomorphism", &self.homomorphism, &other.homomorphism)?;
        debug("program", &self.program, &other.program)?;
        debug("ring", &self.ring, &other.ring)?;
        let cut = |s: &System| s.cut.map(|c| label(s, c));
        debug("cut", &cut(self), &cut(other))?;
        debug("policy", &self.policy, &other.policy)?;
        same.context("context", &self.context, &other.context)?;
        debug("label", &self.label, &other.label)?;
        same.sub_lsystems()?;
        debug("settings", &self.settings, &other.settings)?;
        debug("rotations", &self.rotations, &other.rotations)?;
        debug("colours", &self.colours, &other.colours)?;
        same.structure()?;
        debug("graph", &self.graph, &other.graph)?;
        debug("surfaces", &self.surfaces, &other.surfaces)?;
        debug("contours", &self.contours, &other.contours)?;
        same_environment(self, other)?;
        same_images(self, other)?;
        let (a, b) = (without_images(self), without_images(other));
        debug("look", &a.look, &b.look)
    }
}

/// The decoded images of the textures, where both systems have them: an
/// image is what its file held where the system was read (a `.gft` read
/// in another folder than its source's may find none, W0904), so the
/// texture's file name and settings say the system; but two decoded
/// images of one texture must be the same pixels.
fn same_images(a: &System, b: &System) -> Result<(), String> {
    let (ta, tb) = (a.look.textures(), b.look.textures());
    for (i, (x, y)) in ta.iter().zip(tb).enumerate() {
        if let (Some(p), Some(q)) = (&x.image, &y.image) {
            if p != q {
                return Err(format!(
                    "look.textures[{i}].image: {}×{} and {}×{} pixels differ",
                    p.width(),
                    p.height(),
                    q.width(),
                    q.height()
                ));
            }
        }
    }
    Ok(())
}

/// The environments alike: their settings, and the canopy's decoded image
/// where both have it (as for textures, a file's image is what its folder
/// held).
fn same_environment(a: &System, b: &System) -> Result<(), String> {
    use super::environment::Program;
    let image = |s: &System| match s.environment.as_ref().map(|e| &e.program) {
        Some(Program::Canopy(c)) => c.image.clone(),
        _ => None,
    };
    if let (Some(p), Some(q)) = (image(a), image(b)) {
        if p != q {
            return Err("environment image: the pixels differ".into());
        }
    }
    let bare = |s: &System| {
        let mut e = s.environment.clone();
        if let Some(Program::Canopy(c)) = e.as_mut().map(|e| &mut e.program) {
            c.image = None;
        }
        e
    };
    debug("environment", &bare(a), &bare(b))
}

/// The look of `sys` without its textures' decoded images.
fn without_images(sys: &System) -> System {
    let mut s = System {
        look: sys.look.clone(),
        ..System::new()
    };
    if let Some(l) = s.look.lighting.as_mut() {
        for t in &mut l.textures {
            t.image = None;
        }
    }
    s
}

struct Same<'a> {
    a: &'a System,
    b: &'a System,
}

/// How a symbol is known across systems: its name, or for a silent symbol
/// (empty name) the key it was interned under.
fn label(sys: &System, id: SymbolId) -> String {
    match sys.symbols.silent_key(id) {
        Some(key) => format!("`{key}` (silent)"),
        None => sys.symbols.name(id).to_string(),
    }
}

/// A word as names and bit-exact parameters, for messages.
fn word_text(sys: &System, w: &Word) -> String {
    let mut s = String::from("`");
    for (i, &id) in w.0.iter().enumerate() {
        if i > 0 {
            s.push(' ');
        }
        s.push_str(&label(sys, id));
        let args = w.args(i);
        if !args.is_empty() {
            s.push_str(&format!("{args:?}"));
        }
    }
    s.push('`');
    s
}

/// Compares two values by their pretty `Debug` form; the first line that
/// differs is reported under `path` and the fields that enclose it.
fn debug<T: Debug>(path: impl std::fmt::Display, a: &T, b: &T) -> Result<(), String> {
    // The compact forms first: cheaper, and equal when the pretty ones
    // are (`graftal fmt` compares ten thousand productions on a request).
    if format!("{a:?}") == format!("{b:?}") {
        return Ok(());
    }
    let (x, y) = (format!("{a:#?}"), format!("{b:#?}"));
    if x == y {
        return Ok(());
    }
    let (xs, ys): (Vec<&str>, Vec<&str>) = (x.lines().collect(), y.lines().collect());
    let k = (0..xs.len().max(ys.len()))
        .find(|&k| xs.get(k) != ys.get(k))
        .unwrap_or(0);
    let indent = |l: &str| l.len() - l.trim_start().len();
    let mut level = indent(xs.get(k).or(ys.get(k)).copied().unwrap_or(""));
    let mut inner = Vec::new();
    for l in xs[..k.min(xs.len())].iter().rev() {
        if indent(l) < level {
            level = indent(l);
            let name = l.trim().split(':').next().unwrap_or("");
            let name = name.trim_end_matches(['{', '(', '[', ' ']);
            if !name.is_empty() {
                inner.push(name);
            }
        }
    }
    let mut full = path.to_string();
    for name in inner.iter().rev().skip(1) {
        full.push('.');
        full.push_str(name);
    }
    // `name: value,` lines: the name joins the path, the values are shown.
    let ((name, x), (_, y)) = (named(xs.get(k).copied()), named(ys.get(k).copied()));
    if let Some(name) = name {
        full.push('.');
        full.push_str(name);
    }
    Err(format!("{full}: {x} vs {y}"))
}

/// A `name: value,` line of a `Debug` form as its name and value.
fn named(line: Option<&str>) -> (Option<&str>, &str) {
    let l = line.map_or("(nothing)", |l| l.trim().trim_end_matches(','));
    match l.split_once(": ") {
        Some((name, value)) if !name.contains(' ') => (Some(name), value),
        _ => (None, l),
    }
}

impl Same<'_> {
    /// `label(a, x) == label(b, y)`, without writing the labels of named
    /// symbols (most are).
    fn same_label(&self, x: SymbolId, y: SymbolId) -> bool {
        let (n, m) = (self.a.symbols.name(x), self.b.symbols.name(y));
        if !n.is_empty() || !m.is_empty() {
            return n == m;
        }
        label(self.a, x) == label(self.b, y)
    }

    /// The symbols that matter, by label: what each does to the turtle
    /// and, for a guarded one, its guard.
    fn symbols(&self) -> Result<(), String> {
        let by_label = |s: &System| -> BTreeMap<String, SymbolId> {
            s.mentioned()
                .into_iter()
                .map(|i| (label(s, i), i))
                .collect()
        };
        let (sa, sb) = (by_label(self.a), by_label(self.b));
        if let Some(l) = sa.keys().find(|l| !sb.contains_key(*l)) {
            return Err(format!("symbols: `{l}` only in the first system"));
        }
        if let Some(l) = sb.keys().find(|l| !sa.contains_key(*l)) {
            return Err(format!("symbols: `{l}` only in the second system"));
        }
        for (l, &ia) in &sa {
            let ib = sb[l];
            let op = |s: &System, i: SymbolId| s.interpretation.get(i.index()).copied().flatten();
            debug(
                format!("interpretation[`{l}`]"),
                &op(self.a, ia),
                &op(self.b, ib),
            )?;
            let guard = |s: &System, i: SymbolId| {
                (s.symbols.info(i).guard).map(|g| (g.probability, label(s, g.base)))
            };
            debug(
                format!("symbols[`{l}`].guard"),
                &guard(self.a, ia),
                &guard(self.b, ib),
            )?;
        }
        Ok(())
    }

    fn ids(
        &self,
        path: impl std::fmt::Display,
        a: &[SymbolId],
        b: &[SymbolId],
    ) -> Result<(), String> {
        if a.len() == b.len() && a.iter().zip(b).all(|(&x, &y)| self.same_label(x, y)) {
            return Ok(());
        }
        let la: Vec<String> = a.iter().map(|&s| label(self.a, s)).collect();
        let lb: Vec<String> = b.iter().map(|&s| label(self.b, s)).collect();
        Err(format!("{path}: {la:?} vs {lb:?}"))
    }

    fn word(&self, path: impl std::fmt::Display, a: &Word, b: &Word) -> Result<(), String> {
        let same_args = (0..a.len()).all(|i| {
            let (x, y) = (a.args(i), b.args(i));
            x.len() == y.len() && x.iter().zip(y).all(|(p, q)| p.to_bits() == q.to_bits())
        });
        let same_labels = (a.0.iter().zip(&b.0)).all(|(&x, &y)| self.same_label(x, y));
        if a.len() == b.len() && same_labels && same_args {
            return Ok(());
        }
        Err(format!(
            "{path}: {} vs {}",
            word_text(self.a, a),
            word_text(self.b, b)
        ))
    }

    fn productions(&self, path: &str, a: &[Production], b: &[Production]) -> Result<(), String> {
        debug(format!("{path}.len()"), &a.len(), &b.len())?;
        for (i, (p, q)) in a.iter().zip(b).enumerate() {
            // Paths are written only for a difference (`format_args!`).
            let at = format_args!("{path}[{i}]");
            self.ids(format_args!("{at}.left"), &p.left, &q.left)?;
            self.ids(
                format_args!("{at}.predecessor"),
                &p.predecessor,
                &q.predecessor,
            )?;
            self.ids(format_args!("{at}.right"), &p.right, &q.right)?;
            // The names are spelling, as spans are (`Formals::names`).
            let unnamed = |f: &super::Formals| super::Formals {
                names: Vec::new(),
                ..f.clone()
            };
            debug(
                format_args!("{at}.formals"),
                &unnamed(&p.formals),
                &unnamed(&q.formals),
            )?;
            debug(format_args!("{at}.before"), &p.before, &q.before)?;
            debug(format_args!("{at}.condition"), &p.condition, &q.condition)?;
            debug(format_args!("{at}.after"), &p.after, &q.after)?;
            debug(
                format_args!("{path}[{i}].alternatives.len()"),
                &p.alternatives.len(),
                &q.alternatives.len(),
            )?;
            for (k, (x, y)) in p.alternatives.iter().zip(&q.alternatives).enumerate() {
                let at = format_args!("{path}[{i}].alternatives[{k}]");
                debug(format_args!("{at}.weight"), &x.weight, &y.weight)?;
                debug(
                    format_args!("{at}.computed_weight"),
                    &x.computed_weight,
                    &y.computed_weight,
                )?;
                self.word(format_args!("{at}.successor"), &x.successor, &y.successor)?;
                debug(format_args!("{at}.args"), &x.args, &y.args)?;
            }
        }
        Ok(())
    }

    fn phase(&self, path: &str, a: &Phase, b: &Phase) -> Result<(), String> {
        self.productions(
            &format!("{path}.productions"),
            &a.productions,
            &b.productions,
        )?;
        debug(format!("{path}.depth"), &a.depth, &b.depth)?;
        debug(format!("{path}.seed"), &a.seed, &b.seed)
    }

    /// The filter's kind and its symbols as a set (the order of a list of
    /// ignored symbols means nothing).
    fn context(&self, path: &str, a: &ContextFilter, b: &ContextFilter) -> Result<(), String> {
        let set = |s: &System, f: &ContextFilter| {
            let (kind, ids) = match f {
                ContextFilter::Ignore(ids) => ("ignore", ids),
                ContextFilter::Consider(ids) => ("consider", ids),
            };
            let mut names: Vec<String> = ids.iter().map(|&i| label(s, i)).collect();
            names.sort();
            names.dedup();
            (kind, names)
        };
        debug(path, &set(self.a, a), &set(self.b, b))
    }

    /// Each sub-L-system, in order, as the main one is compared.
    fn sub_lsystems(&self) -> Result<(), String> {
        let (a, b) = (&self.a.sub_lsystems, &self.b.sub_lsystems);
        debug("sub_lsystems.len()", &a.len(), &b.len())?;
        for (i, (x, y)) in a.iter().zip(b).enumerate() {
            let at = format!("sub_lsystems[{i}]");
            debug(format!("{at}.label"), &x.label, &y.label)?;
            self.productions(&format!("{at}.productions"), &x.productions, &y.productions)?;
            self.phase(
                &format!("{at}.decomposition"),
                &x.decomposition,
                &y.decomposition,
            )?;
            self.phase(
                &format!("{at}.homomorphism"),
                &x.homomorphism,
                &y.homomorphism,
            )?;
            self.context(&format!("{at}.context"), &x.context, &y.context)?;
        }
        Ok(())
    }

    /// Seed items: words by their symbols' names, terms field by field.
    fn seed(&self, key: &str, a: &[SeedItem], b: &[SeedItem]) -> Result<(), String> {
        debug(format!("{key}.len()"), &a.len(), &b.len())?;
        for (i, (x, y)) in a.iter().zip(b).enumerate() {
            let at = format!("{key}[{i}]");
            match (x, y) {
                (SeedItem::Word(x), SeedItem::Word(y)) => self.word(&at, x, y)?,
                _ => debug(&at, x, y)?,
            }
        }
        Ok(())
    }

    fn structure(&self) -> Result<(), String> {
        let (a, b) = match (&self.a.structure, &self.b.structure) {
            (None, None) => return Ok(()),
            (Some(a), Some(b)) => (a, b),
            (a, b) => {
                let has = |x: bool| if x { "a structure" } else { "none" };
                return Err(format!(
                    "structure: {} vs {}",
                    has(a.is_some()),
                    has(b.is_some())
                ));
            }
        };
        debug("structure.rules.len()", &a.rules.len(), &b.rules.len())?;
        for (i, (x, y)) in a.rules.iter().zip(&b.rules).enumerate() {
            debug(format!("structure.rules[{i}].name"), &x.name, &y.name)?;
            self.word(format!("structure.rules[{i}].body"), &x.body, &y.body)?;
            debug(
                format!("structure.rules[{i}].resemblance"),
                &x.resemblance,
                &y.resemblance,
            )?;
            debug(format!("structure.rules[{i}].unit"), &x.unit, &y.unit)?;
        }
        self.seed("structure.seed", &a.seed, &b.seed)?;
        self.seed("structure.planted", &a.planted, &b.planted)?;
        debug("structure.constraint", &a.constraint, &b.constraint)?;
        debug("structure.stems", &a.stems, &b.stems)
    }
}

impl System {
    /// The symbols that matter to [`System::same_as`] and to a notation
    /// that writes everything: those that occur in the axiom, a
    /// production, a phase or the structure (and the bases of guarded
    /// ones); in id order, once each. A symbol that occurs nowhere cannot
    /// change a word or a picture, so what it would do to the turtle is
    /// not part of the system (a front end may give every symbol of its
    /// notation a meaning; `.gft`'s `turtle SET` does).
    pub fn mentioned(&self) -> Vec<SymbolId> {
        let mut seen = vec![false; self.symbols.len()];
        let mut add = |w: &[SymbolId]| {
            for &s in w {
                if let Some(slot) = seen.get_mut(s.index()) {
                    *slot = true;
                }
                if let Some(g) = self.symbols.info(s).guard {
                    seen[g.base.index()] = true;
                }
            }
        };
        add(&self.axiom.0);
        for p in self.every_production() {
            add(&p.left);
            add(&p.predecessor);
            add(&p.right);
            for a in &p.alternatives {
                add(&a.successor.0);
            }
        }
        if let Some(st) = &self.structure {
            for r in &st.rules {
                add(&r.body.0);
            }
            for item in st.seed.iter().chain(&st.planted) {
                if let SeedItem::Word(w) = item {
                    add(&w.0);
                }
            }
        }
        (0..seen.len())
            .filter(|&i| seen[i])
            .map(|i| SymbolId(i as u32))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::super::program::{Expr, Stmt};
    use super::super::*;

    /// `A -> A B` with `A` drawing and `B` turning, symbols interned in
    /// `order`.
    fn system(order: &[&str]) -> System {
        let mut s = System::new();
        for name in order {
            s.intern(name);
        }
        let (a, b) = (s.intern("A"), s.intern("B"));
        s.set_interpretation(a, TurtleOp::Forward { draw: true });
        s.set_interpretation(
            b,
            TurtleOp::Rotate {
                axis: Axis::Up,
                angle: Angle::Delta(1.0),
            },
        );
        s.axiom = Word::from(vec![a]);
        let alt = Alternative::new(1.0, Word::from(vec![a, b]));
        s.productions
            .push(Production::new(vec![], vec![a], vec![], vec![alt]));
        s
    }

    fn differs(change: impl Fn(&mut System), field: &str) {
        let a = system(&[]);
        let mut b = system(&[]);
        change(&mut b);
        let err = a.same_as(&b).expect_err(field);
        assert!(err.starts_with(field), "{field}: {err}");
    }

    #[test]
    fn symbol_order_and_unused_symbols_do_not_matter() {
        let a = system(&["A", "B"]);
        let mut b = system(&["Unused", "B", "A"]);
        b.intern("Other");
        assert_eq!(a.same_as(&b), Ok(()));
        assert_eq!(b.same_as(&a), Ok(()));
        assert_ne!(a, b);
    }

    #[test]
    fn what_an_unused_symbol_would_do_does_not_matter() {
        // `.gft`'s `turtle pfg` gives `&` a meaning that the pfg front
        // end gives too; neither matters where `&` occurs nowhere.
        let mut b = system(&[]);
        let c = b.intern("C");
        b.set_interpretation(c, TurtleOp::Push);
        assert_eq!(system(&[]).same_as(&b), Ok(()));
        b.axiom.push(c, &[]);
        let err = system(&[]).same_as(&b).unwrap_err();
        assert!(err.starts_with("symbols: `C` only in the second"), "{err}");
    }

    #[test]
    fn each_field_is_compared() {
        let op = |s: &mut System, name: &str, op| {
            let id = s.intern(name);
            s.set_interpretation(id, op);
        };
        differs(|s| op(s, "B", TurtleOp::Pop), "interpretation[`B`]");
        // `B` occurs in both (a symbol that occurs in one only is a
        // difference of the symbols).
        let b = |s: &mut System| s.intern("B");
        differs(
            |s| {
                let id = b(s);
                s.axiom.push(id, &[]);
            },
            "axiom",
        );
        differs(|s| s.axiom_args = vec![vec![Expr::Num(1.0)]], "axiom_args");
        differs(
            |s| s.productions.push(s.productions[0].clone()),
            "productions.len()",
        );
        differs(
            |s| s.productions[0].alternatives[0].weight = 2.0,
            "productions[0].alternatives[0].weight",
        );
        differs(
            |s| s.productions[0].condition = Some(Expr::Num(0.0)),
            "productions[0].condition",
        );
        differs(
            |s| s.productions[0].left = vec![b(s)],
            "productions[0].left",
        );
        differs(|s| s.decomposition.depth = 3, "decomposition.depth");
        differs(|s| s.homomorphism.seed = Some(1), "homomorphism.seed");
        differs(
            |s| s.program.start.push(Stmt::Eval(Expr::Num(1.0))),
            "program",
        );
        differs(|s| s.ring = true, "ring");
        differs(|s| s.cut = Some(SymbolId::OPEN), "cut");
        differs(|s| s.policy = RulePolicy::Weighted, "policy");
        differs(|s| s.context = ContextFilter::Consider(vec![]), "context");
        differs(|s| s.settings.step = 2.0, "settings");
        differs(
            |s| {
                s.rotations.push(Rotation {
                    name: "w".into(),
                    torsion: Angle::Radians(0.0),
                    curvature: Angle::Radians(1.0),
                })
            },
            "rotations",
        );
        differs(|s| s.colours.push(Rgb(1, 2, 3)), "colours");
        differs(|s| s.structure = Some(Structure::default()), "structure");
        differs(
            |s| {
                s.surfaces.push(SurfaceMesh {
                    name: "leaf".into(),
                    triangles: vec![],
                    ..Default::default()
                })
            },
            "surfaces",
        );
        differs(|s| s.look.background = Some(Rgb(0, 0, 0)), "look");
    }

    #[test]
    fn floats_are_compared_bit_for_bit() {
        let a = system(&[]);
        let mut b = system(&[]);
        b.settings.view = Some((0.0, -0.0));
        let mut c = a.clone();
        c.settings.view = Some((0.0, 0.0));
        let err = c.same_as(&b).unwrap_err();
        assert!(err.contains("-0.0"), "{err}");
    }

    #[test]
    fn the_first_difference_names_the_field_and_both_values() {
        let a = system(&[]);
        let mut b = system(&[]);
        b.settings.tropisms.push(look::Tropism {
            vector: [0.0, 1.0, 0.0],
            angle: 0.0,
            intensity: 1.0,
            elasticity: 0.5,
            step: 0.1,
            kind: look::TropismKind::Bend,
        });
        let mut c = b.clone();
        c.settings.tropisms[0].elasticity = 0.25;
        assert_eq!(
            b.same_as(&c).unwrap_err(),
            "settings.tropisms.Tropism.elasticity: 0.5 vs 0.25"
        );
        let mut d = a.clone();
        let x = d.intern("X");
        d.axiom.push(x, &[2.5]);
        let err = a.same_as(&d).unwrap_err();
        assert!(err.starts_with("symbols: `X`"), "{err}");
        d.set_interpretation(x, TurtleOp::Push);
        let mut e = a.clone();
        let x = e.intern("X");
        e.set_interpretation(x, TurtleOp::Push);
        e.axiom.push(x, &[]);
        assert_eq!(e.same_as(&d).unwrap_err(), "axiom: `A X` vs `A X[2.5]`");
    }
}
