//! Modules no production can ever rewrite because of their parameter
//! count. cpfg matches a module only with a predecessor of the same letter
//! *and* the same number of parameters: `A(1,2)` in the axiom with only
//! `A(l) --> …` is never rewritten, and the plant does not grow, without a
//! word. Such a module is reported where it is written.

use super::ast::{self, Item, Module, Section};
use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use std::collections::{BTreeSet, HashMap, HashSet};

/// The most modules reported: a mistake copied through a file is seen in
/// its first few.
const MAX_REPORTED: usize = 20;

/// Reports the modules of the axiom and the successors of `file` whose
/// letter has productions, none of them with the module's parameter count;
/// each (letter, count) once. What a homomorphism production writes is
/// only ever interpreted by the homomorphism, so only its productions count
/// there; the rest of the word meets every section.
pub fn check(file: &ast::File, diags: &mut Diagnostics) {
    let (every, homomorphism) = parameter_counts(file);
    let mut reported = HashSet::new();
    let mut section = None;
    for item in &file.items {
        let (written, taken) = match item {
            Item::Section(s, _) => {
                section = Some(*s);
                continue;
            }
            Item::Axiom(modules, _) => (modules.as_slice(), &every),
            Item::Production(p) if section == Some(Section::Homomorphism) => {
                (p.successor.as_slice(), &homomorphism)
            }
            Item::Production(p) => (p.successor.as_slice(), &every),
            _ => continue,
        };
        for m in written {
            if reported.len() == MAX_REPORTED {
                return;
            }
            if let Some(counts) = never_matched(m, taken) {
                if reported.insert((&m.name, m.args.len())) {
                    diags.push(never_rewritten(m, counts));
                }
            }
        }
    }
}

/// The parameter counts the productions of `m`'s letter take, when `m`'s
/// is not among them.
fn never_matched<'a>(m: &Module, taken: &'a Counts<'_>) -> Option<&'a BTreeSet<usize>> {
    // Turtle commands and queries are drawn or answered whatever their
    // parameters: a production for one count is often meant to leave the
    // others alone (`+(a) --> …` beside plain `+`).
    if super::lower::turtle_op(&m.name).is_some() || m.name.starts_with('?') {
        return None;
    }
    let counts = taken.get(m.name.as_str())?;
    (!counts.contains(&m.args.len())).then_some(counts)
}

/// The parameter counts the productions of each letter take.
type Counts<'a> = HashMap<&'a str, BTreeSet<usize>>;

/// For each letter with productions, the parameter counts its
/// predecessors take: in any section, and in the homomorphism.
fn parameter_counts(file: &ast::File) -> (Counts<'_>, Counts<'_>) {
    let (mut every, mut homomorphism) = (Counts::new(), Counts::new());
    let mut section = None;
    for item in &file.items {
        match item {
            Item::Section(s, _) => section = Some(*s),
            Item::Production(p) => {
                for m in &p.predecessor {
                    every.entry(&m.name).or_default().insert(m.args.len());
                    if section == Some(Section::Homomorphism) {
                        homomorphism
                            .entry(&m.name)
                            .or_default()
                            .insert(m.args.len());
                    }
                }
            }
            _ => {}
        }
    }
    (every, homomorphism)
}

fn never_rewritten(m: &Module, counts: &BTreeSet<usize>) -> Diagnostic {
    let said = |n: usize| match n {
        1 => "1 parameter".to_string(),
        n => format!("{n} parameters"),
    };
    let takes: Vec<String> = counts.iter().map(|&n| said(n)).collect();
    Diagnostic::at(
        codes::CPFG_PARAMETER_COUNT,
        m.span.clone(),
        format!(
            "`{}` has {} here, and no production of `{}` takes that many",
            m.name,
            said(m.args.len()),
            m.name
        ),
    )
    .with_label("never rewritten")
    .with_note(format!(
        "the productions of `{}` take {}; cpfg rewrites a module only with a \
         predecessor of as many parameters",
        m.name,
        takes.join(" or ")
    ))
    .with_help(format!(
        "give `{}` {} here, or write a production for this count",
        m.name,
        takes.join(" or ")
    ))
}
