//! What `check` derives to find the limits a derivation would reach.

use super::derive::{derive_values, RunOptions};
use super::load::{compile_as, Compiled};
use crate::diagnostics::{codes, Diagnostic};
use crate::eval::tree::{Tree, MAX_TREE_DEPTH};
use crate::eval::Deriver;
use crate::front::Front;
use crate::ir::System;

/// The most symbols `check` derives a system to (and 20 times as many
/// rewritten, [`crate::eval::DeriveOptions::max_symbols`]): a derivation beyond this
/// takes seconds, and `check` stays quick. A derivation counted on its
/// shared tree costs nothing to count, and is checked at `derive`'s own
/// limit.
pub const CHECK_MAX_SYMBOLS: usize = 1_000_000;

/// The most symbols `check` derives each entry of a library to, when no
/// entry is chosen and each is derived ([`derivation_diagnostics`]).
pub const CHECK_ENTRY_MAX_SYMBOLS: usize = 100_000;

/// The most entries of a library `check` lists, and derives one by one:
/// a library may hold 100,000, and one line each would flood the
/// terminal. The largest library known (Fractint's own `fractint.l`) has
/// 69, listed whole.
pub const LISTED_ENTRIES: usize = 100;

/// The most bytes of source `check` reads again to derive a library's
/// entries one by one: entries times the file's length (each entry is
/// compiled from the whole file). Beyond it entries are not derived.
const CHECK_LIBRARY_BYTES: usize = 16 << 20;

/// What `derive` would report besides the file's own diagnostics, found by
/// the derivation it runs (the file's steps, seed 0): a derivation past the
/// symbol or work limit (E0301, E0302). `check` reports these as warnings,
/// with a note that `derive` stops there; a derivation that is only too
/// long for `check`'s own limit ([`CHECK_MAX_SYMBOLS`]) says so. Of a
/// library without a chosen entry each listed entry is derived (to
/// [`CHECK_ENTRY_MAX_SYMBOLS`]), and its diagnostics name it.
pub fn derivation_diagnostics(c: &Compiled) -> Vec<Diagnostic> {
    if let Some(sys) = &c.system {
        return derivation_limits(c.front, sys, CHECK_MAX_SYMBOLS)
            .into_iter()
            .collect();
    }
    let Some(lib) = c.library.as_ref().filter(|l| l.needs_entry) else {
        return Vec::new();
    };
    let listed = lib.entries.len().min(LISTED_ENTRIES);
    if listed.saturating_mul(c.file.text.len()) > CHECK_LIBRARY_BYTES {
        return Vec::new();
    }
    let mut out = Vec::new();
    for e in &lib.entries[..listed] {
        let one = compile_as(c.file.clone(), Some(&e.name), Some(c.front));
        if one.system_or_recovered().is_some_and(|s| s.graph.is_some()) {
            // A library of instancing graphs (IFS codes): they have no
            // word to derive, and every entry is one.
            break;
        }
        let Some(sys) = &one.system else { continue };
        if let Some(mut d) = derivation_limits(one.front, sys, CHECK_ENTRY_MAX_SYMBOLS) {
            d.message = format!("entry `{}`: {}", e.name, d.message);
            out.push(d);
        }
    }
    out
}

/// The derivation `derive` runs of `sys`, checked against its limits: on
/// the shared tree when `derive` counts there (exact, at `derive`'s
/// limit), else derived up to `max` symbols. The limit's diagnostic, as a
/// warning, when one is reached.
fn derivation_limits(front: &dyn Front, sys: &System, max: usize) -> Option<Diagnostic> {
    let full = RunOptions::default();
    let dopts = full.derive_options(sys);
    let tree = (front.spells_words_by_name() && dopts.steps <= MAX_TREE_DEPTH)
        .then(|| Tree::new(sys))
        .flatten();
    let (result, capped) = match tree {
        Some(t) => (Deriver::new(sys).tree_len(&t, &dopts).map(|_| ()), false),
        None => {
            let opts = RunOptions {
                max_symbols: max.min(full.max_symbols),
                ..full
            };
            (derive_values(sys, &opts, |_, _| {}).map(|_| ()), true)
        }
    };
    let mut d = result.err()?;
    // The file is valid; the limit is `derive`'s: a warning, with a code
    // of its own (a warning never carries an error's code).
    d.code = match d.code {
        codes::TOO_MANY_SYMBOLS => codes::DERIVE_WOULD_EXCEED_SYMBOLS,
        codes::TOO_MUCH_WORK => codes::DERIVE_WOULD_TAKE_TOO_LONG,
        other => other,
    };
    d.severity = d.code.severity();
    Some(if capped {
        d.with_note(format!(
            "`check` derives up to {max} symbols and stops here; `graftal derive` allows {} \
             (`--max-symbols`), and stops with this error if the derivation goes past it",
            full.max_symbols
        ))
    } else {
        d.with_note("`graftal derive` stops here with this error")
    })
}
