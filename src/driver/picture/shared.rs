//! Pictures drawn from a context-free system's shared derivation tree.

use super::stored::{apply_look, encode};
use super::{DrawError, Format};
use crate::driver::derive::RunOptions;
use crate::driver::empty::NEARLY_NOTHING;
use crate::eval::tree::MAX_TREE_DEPTH;
use crate::ir::System;
use crate::render::{self, RenderOptions};
use crate::turtle::instanced::Instanced;

/// Draws a context-free deterministic system from its shared derivation
/// tree ([`render::shared::picture`]): nothing is derived or stored but the
/// picture's polylines, and a subtree within one pixel is drawn as one
/// line. `Ok(None)` when the system or the view is not one this covers (a 2D
/// system in one colour and width, seen face on, without splines); the
/// caller then derives and interprets.
pub(super) fn draw(
    sys: &System,
    opts: &RunOptions,
    format: Format,
    mut ropts: RenderOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Option<Vec<u8>>, DrawError> {
    let steps = opts.derive_options(sys).steps;
    // A lit look or a camera draws through the full geometry.
    let look = &sys.look;
    // So do a rotation (the fit needs every point, not the box) and a
    // palette (it colours each segment).
    if ropts.spline
        || ropts.style.rotate != 0.0
        || ropts.style.palette.is_some()
        || ropts.view != render::View::default()
        || steps > MAX_TREE_DEPTH
        || look.lighting.is_some()
        || look.camera.is_some()
    {
        return Ok(None);
    }
    let inst = Instanced::new(sys).filter(|i| i.can_draw() && i.fits(steps));
    let Some(mut inst) = inst else {
        return Ok(None);
    };
    // In the unit that holds it, however deep: the picture converges.
    let (whole, _) = inst.word_scaled(steps);
    let flat = whole.lo[2] == whole.hi[2];
    let finite = whole.lo.iter().chain(&whole.hi).all(|v| v.is_finite());
    if !whole.draws() || !flat || !finite {
        return Ok(None);
    }
    apply_look(sys, &mut ropts);
    let pic = render::shared::picture(sys, &mut inst, steps, &ropts);
    // A picture that is nearly a line is drawn the long way, which says so
    // ([`crate::driver::nearly_nothing_drawn`]).
    if render::picture_spread(&pic).width < NEARLY_NOTHING {
        return Ok(None);
    }
    encode(&pic, format, &ropts, progress).map(Some)
}
