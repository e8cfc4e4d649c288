//! Context-free turtle systems as instancing graphs: the shared subtrees
//! graftal already draws them by ([`Instanced`]) are the nodes of
//! Bekaert & Willems' graph. A subtree `(symbol, depth, turns swapped)`
//! is one graph symbol, wherever it occurs; its rule places the subtrees
//! of its successor where the turtle leaves them, seen from its own start
//! (heading along +y, left along −x, up along +z, a unit step); a single
//! drawn step is a terminal whose geometry is a round-jointed cylinder.
//! The word is never derived: the tracer expands only what a ray meets.
//!
//! A subtree smaller than a pixel is drawn as the line from its start to
//! its end (its alternative geometry), the criterion the flat pictures of
//! shared subtrees use, so a curve stays connected however deep it is.

use crate::ir::graph::{
    Affine, Alternative, Finish, GraphSymbol, Instance, InstancingGraph, Primitive, Shape,
};
use crate::ir::Rgb;
use crate::turtle::instanced::{Instanced, Placement, Subtree, Summary, Walker};
use crate::turtle::Vec3;
use std::collections::HashMap;

/// Graph symbols at most: past this the flat hierarchy draws the word.
const MAX_SYMBOLS: usize = 1 << 16;

/// The transform that places a subtree: its start frame (H = +y,
/// L = −x, U = +z, unit step) turned to `at`'s frame, scaled and moved.
fn placement(at: &Placement) -> Affine {
    let [h, l, u] = at.frame;
    let s = at.scale;
    let mut m = [[0.0; 4]; 3];
    for i in 0..3 {
        m[i] = [-l[i] * s, h[i] * s, u[i] * s, at.pos[i]];
    }
    Affine(m)
}

/// The symbol a single drawn step is: a cylinder along +y of unit length.
const STEP: usize = 0;

/// Collects the instances one walk places.
struct Collect {
    /// Whether the next `enter` is the subtree's own root (walked into).
    root: bool,
    placed: Vec<(Subtree, Placement, Vec3)>,
}

impl Walker for Collect {
    fn enter(&mut self, _: &Summary, _: f64) -> bool {
        std::mem::replace(&mut self.root, false)
    }

    fn whole(&mut self, subtree: Subtree, at: &Placement, end: Vec3) {
        self.placed.push((subtree, *at, end));
    }

    fn lift(&mut self) {}
}

/// The graph as it is built: subtrees met and not yet expanded.
struct Builder {
    g: InstancingGraph,
    index: HashMap<Subtree, usize>,
    todo: Vec<Subtree>,
    radius: f64,
    colour: Rgb,
}

impl Builder {
    fn shape(&self, primitive: Primitive) -> Shape {
        Shape {
            primitive,
            colour: self.colour,
            finish: Finish {
                specular: 0.2,
                ..Finish::default()
            },
        }
    }

    /// The instance of a subtree placed at `at` and ending at `end`,
    /// adding its symbol when it is new.
    fn instance(&mut self, (sub, at, end): (Subtree, Placement, Vec3)) -> Instance {
        let transform = placement(&at);
        if sub.depth == 0 {
            return Instance {
                transform,
                symbol: STEP,
            };
        }
        if let Some(&symbol) = self.index.get(&sub) {
            return Instance { transform, symbol };
        }
        // The line from its start to its end, seen from its start.
        let local_end = transform.inverse().map_or([0.0; 3], |inv| inv.apply(end));
        let radius = self.radius;
        let chord = if local_end.iter().any(|x| x.abs() > 1e-9) {
            Primitive::Cylinder {
                base: [0.0; 3],
                top: local_end,
                radius,
            }
        } else {
            Primitive::Sphere {
                centre: [0.0; 3],
                radius,
            }
        };
        let alternative = Alternative {
            shapes: vec![self.shape(chord)],
            below_pixels: 1.0,
        };
        let swapped = if sub.swapped { "'" } else { "" };
        self.g.symbols.push(GraphSymbol {
            name: format!("{}:{}{swapped}", sub.symbol.index(), sub.depth),
            geometry: Vec::new(),
            alternative: Some(alternative),
            rule: None,
        });
        let symbol = self.g.symbols.len() - 1;
        self.index.insert(sub, symbol);
        self.todo.push(sub);
        Instance { transform, symbol }
    }
}

/// The graph of the word after `steps` steps, its lines `radius` thick
/// (in the units of a step) and `colour`; `None` when the system cannot be
/// drawn from shared subtrees in one colour and width, or the graph would
/// be too large.
pub fn graph(
    inst: &mut Instanced<'_>,
    steps: u64,
    radius: f64,
    colour: Rgb,
) -> Option<InstancingGraph> {
    if !inst.can_draw() || !inst.fits(steps) {
        return None;
    }
    let mut b = Builder {
        g: InstancingGraph::default(),
        index: HashMap::new(),
        todo: Vec::new(),
        radius,
        colour,
    };
    let step = GraphSymbol {
        name: "step".into(),
        geometry: vec![
            b.shape(Primitive::Cylinder {
                base: [0.0; 3],
                top: [0.0, 1.0, 0.0],
                radius,
            }),
            b.shape(Primitive::Sphere {
                centre: [0.0, 1.0, 0.0],
                radius,
            }),
        ],
        alternative: None,
        rule: None,
    };
    b.g.symbols.push(step);
    let mut top = Collect {
        root: false,
        placed: Vec::new(),
    };
    inst.walk(steps, &mut top);
    b.g.axiom = top.placed.into_iter().map(|p| b.instance(p)).collect();
    while let Some(sub) = b.todo.pop() {
        if b.g.symbols.len() > MAX_SYMBOLS {
            return None;
        }
        let mut walk = Collect {
            root: true,
            placed: Vec::new(),
        };
        inst.walk_subtree(sub, &mut walk);
        let rule: Vec<Instance> = walk.placed.into_iter().map(|p| b.instance(p)).collect();
        let at = b.index[&sub];
        b.g.symbols[at].rule = Some(rule);
    }
    Some(b.g)
}
