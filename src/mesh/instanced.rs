//! Scenes of context-free deterministic systems from their shared
//! subtrees ([`Instanced::walk`]): the walk enters subtrees larger than a
//! chosen size and takes the others whole; each distinct whole subtree
//! becomes one mesh, and each occurrence a node placing it. Single steps
//! met on the way make one more mesh, placed where they are.
//!
//! The size is the square root of the whole word's segments (at least
//! [`MIN_SUBTREE`]), so that meshes and nodes grow alike: a word of 10⁶
//! segments is about a thousand meshes' segments and a thousand nodes.

use super::tube::{tube, Chainer};
use super::{Finish, Mesh, Node, Scene, Sizing, Transform};
use crate::ir::colours::DEFAULT_PALETTE;
use crate::ir::System;
use crate::turtle::instanced::{Instanced, Placement, Subtree, Summary, Walker};
use crate::turtle::Vec3;
use std::collections::HashMap;

/// Subtrees of at most this many segments are always taken whole.
pub const MIN_SUBTREE: u128 = 64;
/// Subtrees of more segments are always entered.
pub const MAX_SUBTREE: u128 = 1 << 16;
/// Words that would need more nodes than this (about 100 bytes each) are
/// not exported this way.
pub const MAX_NODES: u128 = 1 << 20;

/// The scene of the word of `inst` after `steps` steps; `None` when the
/// system changes colours or widths (every subtree would not draw alike)
/// or the word is too large even so ([`MAX_NODES`]).
pub fn scene(sys: &System, inst: &mut Instanced<'_>, steps: u64) -> Option<Scene> {
    if !inst.can_draw() {
        return None;
    }
    let whole = inst.word(steps);
    let [lo, hi] = [whole.lo, whole.hi];
    let bbox = whole
        .draws()
        .then_some([lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]]);
    let sizing = Sizing::new(bbox, sys.settings.world_widths);
    let palette = if sys.colours.is_empty() {
        DEFAULT_PALETTE.to_vec()
    } else {
        sys.colours.clone()
    };
    // The turtle starts at this colour index, and keeps it throughout.
    let start = sys.settings.colour.min(palette.len() - 1);
    let index = crate::turtle::index_of(start);
    let colour = Finish::new(palette[start], index, sys.look.lighting.as_ref());
    let width = sys.settings.width;
    let largest = ((whole.segments as f64).sqrt() as u128).clamp(MIN_SUBTREE, MAX_SUBTREE);
    if whole.segments / largest > MAX_NODES {
        return None;
    }
    let mut placer = Placer {
        largest,
        top: Chainer::new(width, colour),
        placed: Vec::new(),
    };
    inst.walk(steps, &mut placer);
    let mut scene = Scene::default();
    let mut mesh_of: HashMap<(Subtree, u64), usize> = HashMap::new();
    for (subtree, at) in placer.placed {
        let k = *mesh_of
            .entry((subtree, at.scale.to_bits()))
            .or_insert_with(|| {
                let mut lines = Chainer::new(width, colour);
                inst.walk_subtree(subtree, &mut Lines(&mut lines));
                // The mesh is drawn at unit step and placed scaled: its tubes
                // are as much thinner.
                let sizing = Sizing {
                    per_width: sizing.per_width / at.scale,
                };
                scene.meshes.push(tubes(&lines, &sizing));
                scene.meshes.len() - 1
            });
        scene.nodes.push(Node {
            mesh: k,
            place: placement(&at),
        });
    }
    if !placer.top.chains.is_empty() {
        scene.meshes.push(tubes(&placer.top, &sizing));
        scene.nodes.push(Node {
            mesh: scene.meshes.len() - 1,
            place: Transform::IDENTITY,
        });
    }
    Some(scene)
}

fn tubes(lines: &Chainer, sizing: &Sizing) -> Mesh {
    let mut mesh = Mesh::default();
    for c in &lines.chains {
        tube(&mut mesh, c, sizing);
    }
    mesh
}

/// The transform of a subtree placed at `at`: the start frame (H = +y,
/// L = −x, U = +z) turned to `at.frame`, so x goes to −L, y to H, z to U.
fn placement(at: &Placement) -> Transform {
    let [h, l, u] = at.frame;
    Transform {
        rotation: [l.map(|x| -x), h, u],
        translation: at.pos,
        scale: at.scale,
    }
}

/// Walks the word: enters subtrees larger than `largest`, places the
/// other subtrees, and chains single steps.
struct Placer {
    largest: u128,
    top: Chainer,
    placed: Vec<(Subtree, Placement)>,
}

impl Walker for Placer {
    fn enter(&mut self, x: &Summary, _: f64) -> bool {
        x.segments > self.largest
    }

    fn whole(&mut self, subtree: Subtree, at: &Placement, end: Vec3) {
        if subtree.depth == 0 {
            self.top.line(at.pos, end);
        } else {
            self.placed.push((subtree, *at));
            self.top.lift();
        }
    }

    fn lift(&mut self) {
        self.top.lift();
    }
}

/// Walks a subtree step by step into a [`Chainer`].
struct Lines<'c>(&'c mut Chainer);

impl Walker for Lines<'_> {
    fn enter(&mut self, _: &Summary, _: f64) -> bool {
        true
    }

    fn whole(&mut self, _: Subtree, at: &Placement, end: Vec3) {
        self.0.line(at.pos, end);
    }

    fn lift(&mut self) {
        self.0.lift();
    }
}
