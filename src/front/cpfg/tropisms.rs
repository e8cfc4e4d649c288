//! The view file's tropisms in the IR ([`crate::ir::look::Tropism`]):
//! `tropism:` and `torque:` lines (cpfg's movements, ids from 1 in file
//! order, changed by `@Ts`, `@Ti`, `@Td`), and the older `tropism
//! direction:` / `initial elasticity:` / `elasticity increment:`, changed
//! by the module `_`.

use super::view::{self, View};
use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::ir::look::{Tropism, TropismKind};
use crate::ir::{ElasticityChange, Lowered, TurtleOp};

/// cpfg's limit on `tropism:` and `torque:` lines (`MAXMOVEMENTS`).
const MAX_MOVEMENTS: usize = 10;

/// The modules that change elasticities, warned about when nothing bends.
const ELASTICITY_MODULES: &[&str] = &["@Ts", "@Ti", "@T", "@Td", "@Tp", "@Tf"];

/// Fills `settings.tropisms` from the view file, interprets `_`, and warns
/// about elasticity modules that change nothing.
pub(super) fn add_tropisms(lowered: &mut Lowered, view: &View, diags: &mut Diagnostics) {
    let sys = &mut lowered.system;
    if view.tropisms.len() > MAX_MOVEMENTS {
        diags.push(Diagnostic::global(
            codes::CPFG_NOT_DRAWN,
            format!(
                "the view file sets {} tropisms and torques; cpfg uses the first {MAX_MOVEMENTS}",
                view.tropisms.len()
            ),
        ));
    }
    sys.settings.tropisms = view
        .tropisms
        .iter()
        .take(MAX_MOVEMENTS)
        .map(movement)
        .collect();
    let underscore = sys.symbols.get("_");
    if view.initial_elasticity != 0.0 || underscore.is_some() {
        sys.settings.tropisms.push(older_tropism(view));
        if let Some(id) = underscore {
            let index = (sys.settings.tropisms.len() - 1) as u16;
            sys.set_interpretation(
                id,
                TurtleOp::Elasticity {
                    tropism: Some(index),
                    change: ElasticityChange::SetOrIncrease,
                },
            );
        }
    }
    if sys.settings.tropisms.is_empty() {
        warn_unbent(lowered, diags);
    }
}

/// A `tropism:` or `torque:` line. cpfg's pull is the vector times
/// `I / |T|` clamped to ±1 when `I:` is given, the unit vector otherwise.
fn movement(t: &view::Tropism) -> Tropism {
    let n = t.vector.iter().map(|x| x * x).sum::<f64>().sqrt();
    let intensity = match t.intensity {
        Some(i) if n > 0.0 => n * (i / n).clamp(-1.0, 1.0),
        _ => 1.0,
    };
    Tropism {
        vector: t.vector,
        angle: t.angle,
        intensity,
        elasticity: t.elasticity,
        step: t.step,
        kind: if t.torque {
            TropismKind::Torque
        } else {
            TropismKind::Bend
        },
    }
}

/// The older tropism: towards `tropism direction:` (default +y), of
/// elasticity `initial elasticity:`, stepped by `elasticity increment:`.
fn older_tropism(view: &View) -> Tropism {
    Tropism {
        vector: view.tropism_direction.unwrap_or([0.0, 1.0, 0.0]),
        angle: 0.0,
        intensity: 1.0,
        elasticity: view.initial_elasticity,
        step: view.elasticity_increment,
        kind: TropismKind::BendAfterStep,
    }
}

/// Elasticity modules in a system with no tropism change nothing: say so
/// at the first of each.
fn warn_unbent(lowered: &Lowered, diags: &mut Diagnostics) {
    for name in ELASTICITY_MODULES {
        let Some(id) = lowered.system.symbols.get(name) else {
            continue;
        };
        let span = lowered.spans.symbols.get(&id).cloned().unwrap_or(0..0);
        diags.push(
            Diagnostic::at(
                codes::CPFG_NOT_DRAWN,
                span,
                format!("`{name}` changes nothing: the view file sets no tropism"),
            )
            .with_label("no effect on the picture")
            .with_help("add `tropism: T: 0 -1 0 E: 0.1` to the view file"),
        );
    }
}
