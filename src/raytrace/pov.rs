//! Scenes for POV-Ray 3.7: what graftal ray traces, written so that an
//! independent renderer draws it from the same camera under the same
//! lights. An instancing graph keeps its instancing: each symbol expanded
//! `k` more levels is one `#declare`d object made of the ones a level
//! below, down to the depth where every instance is under a pixel; what a
//! turtle drew is written primitive by primitive.
//!
//! POV-Ray's camera takes explicit `right`, `up` and `direction` vectors
//! here, so its left-handed habit plays no part: a pixel's ray is the one
//! graftal's tracer shoots.

use super::bounds::Volume;
use super::bvh::Item;
use super::graph::GraphScene;
use super::vec::{mul, V3};
use super::{lights_for, Options, RayCamera};
use crate::ir::graph::{Affine, Finish, Primitive, Shape};
use crate::number::exact;
use std::fmt::Write;

/// Levels of `#declare`s at most; deeper graphs are cut here.
const MAX_LEVELS: usize = 48;

fn v(p: V3) -> String {
    format!("<{}, {}, {}>", exact(p[0]), exact(p[1]), exact(p[2]))
}

/// POV-Ray's `matrix`: it takes row vectors, `p' = p M`, so graftal's
/// rows `[M | t]` are written column by column, then the translation.
fn matrix(a: &Affine) -> String {
    // POV-Ray refuses a singular matrix: thicken it as the tracer does.
    let a = a.inverse_thickened().inverse_thickened();
    let m = &a.0;
    let cols = (0..4).flat_map(|j| (0..3).map(move |i| exact(m[i][j])));
    format!("matrix <{}>", cols.collect::<Vec<_>>().join(", "))
}

fn texture(colour: [f64; 3], f: &Finish) -> String {
    format!(
        "pigment {{ srgb {} }} finish {{ ambient {} diffuse {} phong {} phong_size {} }}",
        v(colour),
        exact(f.ambient),
        exact(f.diffuse),
        exact(f.specular),
        exact(f.shininess)
    )
}

/// A primitive as POV-Ray writes it, without its texture; `None` for one
/// POV-Ray cannot hold (a cylinder of no length).
fn primitive(p: &Primitive) -> Option<String> {
    Some(match p {
        Primitive::Sphere { centre, radius } => {
            format!("sphere {{ {}, {} ", v(*centre), exact(*radius))
        }
        Primitive::Box { min, max } => format!("box {{ {}, {} ", v(*min), v(*max)),
        Primitive::Cylinder { base, top, radius } => {
            if base == top {
                return None;
            }
            format!("cylinder {{ {}, {}, {} ", v(*base), v(*top), exact(*radius))
        }
        Primitive::Cone {
            base,
            top,
            base_radius,
            top_radius,
        } => {
            if base == top {
                return None;
            }
            format!(
                "cone {{ {}, {}, {}, {} ",
                v(*base),
                exact(*base_radius),
                v(*top),
                exact(*top_radius)
            )
        }
        Primitive::Disc {
            centre,
            normal,
            radius,
        } => {
            format!(
                "disc {{ {}, {}, {} ",
                v(*centre),
                v(*normal),
                exact(*radius)
            )
        }
        Primitive::Triangle([a, b, c]) => format!("triangle {{ {}, {}, {} ", v(*a), v(*b), v(*c)),
        Primitive::Polygon(points) => {
            let first = *points.first()?;
            let fan: Vec<String> = points[1..]
                .windows(2)
                .map(|w| format!("triangle {{ {}, {}, {} }}", v(first), v(w[0]), v(w[1])))
                .collect();
            if fan.is_empty() {
                return None;
            }
            format!("union {{ {} ", fan.join(" "))
        }
    })
}

fn shape(s: &Shape) -> Option<String> {
    let body = primitive(&s.primitive)?;
    Some(format!(
        "{body}{} }}",
        texture(super::linear(s.colour), &s.finish)
    ))
}

/// The camera, the lights and the background graftal's tracer uses.
fn header(opts: &Options, world: (V3, V3)) -> String {
    let cam = RayCamera::new(opts.eye, opts, world);
    let (w, h) = (opts.width as f64, opts.height as f64);
    let mut out = String::from("// Written by graftal: a scene for POV-Ray 3.7.\n#version 3.7;\n");
    let lights = lights_for(opts, &cam);
    let ambient = lights.iter().fold([0.0; 3], |a, l| {
        [0, 1, 2].map(|k| a[k] + l.ambient[k] as f64)
    });
    let _ = writeln!(
        out,
        "global_settings {{ assumed_gamma 1.0 ambient_light rgb {} }}",
        v(ambient)
    );
    let _ = writeln!(
        out,
        "background {{ srgb {} }}",
        v(super::linear(opts.background))
    );
    let kind = if cam.perspective {
        "perspective"
    } else {
        "orthographic"
    };
    let _ = writeln!(
        out,
        "camera {{ {kind} location {} direction {} right {} up {} }}",
        v(cam.origin),
        v(cam.forward),
        v(mul(cam.right, w * cam.per_pixel)),
        v(mul(cam.up, h * cam.per_pixel))
    );
    for l in &lights {
        let colour = l.diffuse.map(|c| c as f64);
        if l.directional {
            // A parallel light far along its direction, aimed at the scene.
            let middle = mul(super::vec::add(world.0, world.1), 0.5);
            let far = super::vec::length(super::vec::sub(world.1, world.0)).max(1.0) * 1000.0;
            let from = super::vec::mad(middle, super::vec::normalize(l.vector), far);
            let _ = writeln!(
                out,
                "light_source {{ {} rgb {} parallel point_at {} }}",
                v(from),
                v(colour),
                v(middle)
            );
        } else {
            let _ = writeln!(out, "light_source {{ {} rgb {} }}", v(l.vector), v(colour));
        }
    }
    out
}

/// A scene of what a turtle drew (world primitives).
pub fn items_scene(items: &[Item], opts: &Options, world: (V3, V3)) -> String {
    let mut out = header(opts, world);
    for item in items {
        if let Some(body) = primitive(&item.primitive) {
            let placed = item
                .placed
                .map(|inv| matrix(&inv.inverse_thickened()))
                .unwrap_or_default();
            let _ = writeln!(
                out,
                "{body}{} {placed} }}",
                texture(item.colour, &item.finish)
            );
        }
    }
    out
}

/// A scene of an instancing graph, its instancing kept.
pub fn graph_scene(scene: &GraphScene, opts: &Options) -> String {
    let world = super::Scene::world_box(scene);
    let pixel = super::pixel_size(world, opts);
    let mut out = header(opts, world);
    out.push_str(&scene.declarations(pixel, MAX_LEVELS));
    out
}

impl GraphScene<'_> {
    /// The `#declare`s of the graph, `G_x_k` being symbol `x` expanded `k`
    /// levels more, and the axiom's objects.
    fn declarations(&self, pixel: f64, max_levels: usize) -> String {
        let (graph, bounds) = (self.graph(), self.bounds());
        let n = graph.symbols.len();
        let size = |x: usize| bounds.volumes[x].map_or(0.0, |v| v.size());
        // reach[k][x]: the largest size of x expanded k levels.
        let mut reach: Vec<Vec<f64>> = vec![(0..n).map(size).collect()];
        let axiom_reach = |r: &[f64]| {
            graph
                .axiom
                .iter()
                .map(|i| i.transform.contraction() * r[i.symbol])
                .fold(0.0, f64::max)
        };
        while reach.len() <= max_levels && axiom_reach(reach.last().expect("level 0")) > pixel {
            let below = reach.last().expect("a level");
            let next = (0..n)
                .map(|x| {
                    let edges = graph.successors(x).iter().enumerate();
                    edges
                        .map(|(k, e)| bounds.stretch[x][k] * below[e.symbol])
                        .fold(0.0, f64::max)
                })
                .collect();
            reach.push(next);
        }
        let levels = reach.len() - 1;
        let mut out = String::new();
        let mut declared = vec![vec![false; n]; levels + 1];
        for k in 0..=levels {
            for x in 0..n {
                if bounds.volumes[x].is_none() {
                    continue;
                }
                let sym = &graph.symbols[x];
                let mut parts: Vec<String> = Vec::new();
                let at_cut = k == 0 || sym.rule.is_none();
                if at_cut && self.is_pure() {
                    let volume = match bounds.volumes[x].expect("checked") {
                        Volume::Box { min, max } => Primitive::Box { min, max },
                        Volume::Sphere { centre, radius } => Primitive::Sphere { centre, radius },
                    };
                    let body = primitive(&volume).expect("a volume is never empty");
                    parts.push(format!(
                        "{body}{} }}",
                        texture(self.colour(), &Finish::default())
                    ));
                } else {
                    let alternative = sym
                        .alternative
                        .as_ref()
                        .filter(|a| reach[k][x] <= a.below_pixels * pixel);
                    let shapes = alternative.map_or(&sym.geometry, |a| &a.shapes);
                    parts.extend(shapes.iter().filter_map(shape));
                    if !at_cut && alternative.is_none() {
                        for e in graph.successors(x) {
                            if declared[k - 1][e.symbol] {
                                parts.push(format!(
                                    "object {{ G_{}_{} {} }}",
                                    e.symbol,
                                    k - 1,
                                    matrix(&e.transform)
                                ));
                            }
                        }
                    }
                }
                if parts.is_empty() {
                    continue;
                }
                declared[k][x] = true;
                let _ = writeln!(
                    out,
                    "#declare G_{x}_{k} = union {{\n  {}\n}}",
                    parts.join("\n  ")
                );
            }
        }
        for i in &graph.axiom {
            if declared[levels][i.symbol] {
                let _ = writeln!(
                    out,
                    "object {{ G_{}_{levels} {} }}",
                    i.symbol,
                    matrix(&i.transform)
                );
            }
        }
        out
    }
}
