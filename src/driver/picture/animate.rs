//! Animations: the steps up to N, from the first that draws anything, as
//! the frames of a GIF or an animated PNG, each frame drawn as its still is
//! ([`super::still_counted`]) and framed as the last one; an outline's
//! growth replayed stem by stem.

use super::stored::{apply_look, render_bytes};
use super::{streamed, DrawError, Format, Method, Picture, Progress, Request, Stage, Subject};
use crate::diagnostics::codes;
use crate::driver::derive::{derive_values, RunOptions};
use crate::driver::interpret::{add_fixed, add_layout, check_moves_up_front, interpret};
use crate::ir::System;
use crate::render::animate::{Animation, Container, Frame};
use crate::render::{self, RenderOptions};
use crate::turtle::{self, Geometry};

/// An animation of a system's growth ([`render::animate`]): the still
/// pictures of steps F..=N (N from the request, F the first step that
/// draws anything) as frames, all fitted as the last one is. Every frame is
/// derived anew; the frames together move the turtle at most `max_moves`
/// times.
pub(super) fn draw(
    s: &Subject,
    req: &Request,
    container: Container,
    mut ropts: RenderOptions,
    progress: &mut dyn Progress,
) -> Result<Picture, DrawError> {
    let (sys, opts) = (s.sys, &req.run);
    let last = opts.derive_options(sys).steps;
    let mut anim = Animation {
        container,
        width: req.width,
        height: req.height,
        fps: req.fps,
        frames: last.saturating_add(1),
    };
    refuse(&anim)?;
    check_moves_up_front(sys, opts)?;
    let grown = (last == 0)
        .then(|| grown_geometry(sys, opts, req.layout))
        .flatten();
    if let Some(grown) = &grown {
        anim.frames = grown.frames;
        refuse(&anim)?;
    }
    let mut budget = opts.max_moves;
    let final_g = frame_geometry(sys, opts, last, budget, &ropts, req.layout)?;
    budget -= final_g.segments.len().min(budget);
    ropts.framing = Some(frame_framing(sys, &final_g, ropts));
    // When even the last step draws nothing, every frame is as blank as
    // step 0's: nothing is gained by looking for a first drawn step.
    let first = if grown.is_some() || final_g.is_empty() {
        0
    } else {
        first_drawn(sys, opts, last, budget, &ropts, req.layout)?
    };
    drop(final_g);
    if first > 0 {
        anim.frames = last - first + 1;
        refuse(&anim)?;
    }
    // A frame's error, kept while the encoder stops.
    let mut failed: Option<DrawError> = None;
    let mut frame = |k: u64| -> Result<Frame, String> {
        // Growth replayed: the stems grown before frame k's share of them.
        if let Some(grown) = grown.as_ref().filter(|g| k + 1 < g.frames) {
            let before = (u64::from(grown.stems) * (k + 1) / grown.frames) as u32;
            let part = render::animate::grown_part(&grown.geometry, &grown.appeared, before);
            let png = render_bytes(sys, &part, Format::Png, ropts).map_err(|e| e.to_string())?;
            return Frame::from_png(&png);
        }
        let step = if grown.is_some() { last } else { first + k };
        // The last step's moves were counted when it was framed.
        let at = RunOptions {
            steps: Some(step),
            max_moves: if step == last { opts.max_moves } else { budget },
            ..opts.clone()
        };
        let drawn = super::still_counted(
            s,
            &at,
            Format::Png,
            ropts,
            super::How::of(req),
            &mut super::Quiet,
        );
        match drawn {
            Ok((still, moves)) => {
                if step != last {
                    budget -= moves.min(budget);
                }
                Frame::from_png(&still.bytes)
            }
            Err(e) => {
                failed = Some(in_animation(e, opts.max_moves));
                Err("stopped".to_string())
            }
        }
    };
    let mut bytes = Vec::new();
    let mut frames = |done, total| progress.advanced(Stage::Frames, done, total);
    let done = render::animate::encode(&anim, &mut bytes, &mut frame, &mut frames);
    if let Some(e) = failed {
        return Err(e);
    }
    done.map_err(DrawError::Animation)?;
    Ok(Picture {
        bytes,
        side_files: Vec::new(),
        method: Method::Animation,
        warnings: Vec::new(),
        mesh: None,
    })
}

/// The animation's refusal before anything is drawn, if it has one.
fn refuse(anim: &Animation) -> Result<(), DrawError> {
    match anim.refusal() {
        Some(why) => Err(DrawError::Animation(why)),
        None => Ok(()),
    }
}

/// A frame's error, with a note that the limit on moves holds for all the
/// frames together.
fn in_animation(e: DrawError, max_moves: usize) -> DrawError {
    match e {
        DrawError::Stopped(d) if d.code == codes::TOO_MUCH_GEOMETRY => {
            DrawError::Stopped(Box::new(d.with_note(format!(
                "an animation moves the turtle at most {max_moves} times in all its frames"
            ))))
        }
        e => e,
    }
}

/// The first step before `last` whose picture draws anything, else `last`:
/// an axiom such as `X` draws nothing, and an animation that began there
/// would open on a blank frame. Only the steps before it are derived here,
/// and those are not framed, so no step but that one is derived twice.
fn first_drawn(
    sys: &System,
    opts: &RunOptions,
    last: u64,
    budget: usize,
    ropts: &RenderOptions,
    layout: bool,
) -> Result<u64, DrawError> {
    for step in 0..last {
        if !frame_geometry(sys, opts, step, budget, ropts, layout)?.is_empty() {
            return Ok(step);
        }
    }
    Ok(last)
}

/// The geometry of step `step`, as its stored still would draw it, within
/// `budget` moves.
fn frame_geometry(
    sys: &System,
    opts: &RunOptions,
    step: u64,
    budget: usize,
    ropts: &RenderOptions,
    layout: bool,
) -> Result<Geometry, DrawError> {
    let at = RunOptions {
        steps: Some(step),
        max_moves: budget,
        ..opts.clone()
    };
    let (word, values) = derive_values(sys, &at, |_, _| {})?;
    let mut g = interpret(sys, &word, &values, &at, ropts.spline)
        .map_err(|d| in_animation(d.into(), opts.max_moves))?;
    add_fixed(sys, &mut g, layout);
    Ok(g)
}

/// The framing of `g`'s still picture, from the renderer that draws it:
/// streamed ([`super::streamed`]), lit (which fits cylinders and spheres)
/// or flat ([`super::render_bytes`]).
fn frame_framing(sys: &System, g: &Geometry, mut ropts: RenderOptions) -> render::Framing {
    let streamed =
        streamed::streams(sys, Format::Png, &ropts) && g.polygons.is_empty() && g.discs.is_empty();
    apply_look(sys, &mut ropts);
    if streamed {
        let mut survey = render::coverage::Survey::new(&ropts);
        for s in &g.segments {
            turtle::Sink::segment(&mut survey, s.clone());
        }
        if survey.streams() {
            return survey.framing(&ropts, sys.settings.world_widths);
        }
    }
    match &sys.look.lighting {
        Some(lighting) => render::raster::framing(g, lighting, &ropts),
        None => render::framing(g, &ropts),
    }
}

/// A grown structure's picture with what drew each part, and when each
/// symbol of its word appeared in growth ([`crate::layout::seed::growth_order`]).
struct Grown {
    geometry: Geometry,
    appeared: Vec<u32>,
    stems: u32,
    frames: u64,
}

/// The frames of an outline's growth: one per stem, at most
/// [`render::animate::GROWTH_FRAMES`]. `None` unless the system's word is
/// its structure's grown seed and nothing rewrites it.
fn grown_geometry(sys: &System, opts: &RunOptions, layout: bool) -> Option<Grown> {
    let st = sys.structure.as_ref()?;
    let order = crate::layout::seed::growth_order(&mut sys.clone(), st).ok()??;
    if order.word != sys.axiom || sys.rewrites_modules() || order.stems == 0 {
        return None;
    }
    let mut geometry = turtle::Run {
        origins: true,
        ..turtle::Run::word(sys, &sys.axiom, opts.seed)
    }
    .geometry();
    if layout {
        let before = geometry.polygons.len();
        add_layout(sys, &mut geometry);
        // The layout's shapes come first and show in every frame.
        let added = geometry.polygons.len() - before;
        geometry
            .origins
            .polygons
            .splice(0..0, std::iter::repeat_n(usize::MAX, added));
    }
    Some(Grown {
        geometry,
        appeared: order.appeared,
        stems: order.stems,
        frames: u64::from(order.stems).min(render::animate::GROWTH_FRAMES),
    })
}
