//! The ray tracer (`graftal::raytrace`), held by what must hold whatever a
//! picture looks like: an instancing graph traced without expanding it
//! draws what its expansion draws, pixel for pixel; a Sierpinski
//! tetrahedron seen along the line through the midpoints of two opposite
//! edges covers a square at every depth; the bytes do not depend on the
//! thread count; shadows fall where the light is blocked; and the library's
//! one call for a picture chooses the tracer by the request or the model.

use graftal::driver::picture::{self, Format, Method, Quiet, Request, Target, Tracing};
use graftal::driver::{compile, load};
use graftal::ir::graph::{
    Affine, Alternative, Finish, GraphSymbol, Instance, InstancingGraph, Primitive, Shape,
};
use graftal::ir::{Rgb, System};
use graftal::raytrace::{bvh::Bvh, graph::GraphScene, trace, Eye, Options};

fn symbol(name: &str, geometry: Vec<Shape>, rule: Option<Vec<Instance>>) -> GraphSymbol {
    GraphSymbol {
        name: name.into(),
        geometry,
        alternative: None,
        rule,
    }
}

fn at(transform: Affine, symbol: usize) -> Instance {
    Instance { transform, symbol }
}

fn shape(primitive: Primitive, colour: Rgb) -> Shape {
    Shape {
        primitive,
        colour,
        finish: Finish {
            specular: 0.3,
            ..Finish::default()
        },
    }
}

/// Sierpinski's tetrahedron: 4 maps of scale 1/2 towards the corners of
/// the tetrahedron inscribed in [-1, 1]^3, no geometry.
fn tetrahedron() -> InstancingGraph {
    let corners = [
        [1.0, 1.0, 1.0],
        [1.0, -1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
    ];
    let rule = corners
        .iter()
        .map(|c| {
            let half = c.map(|x| x / 2.0);
            at(
                Affine::translate(half).then_after(&Affine::scale([0.5; 3])),
                0,
            )
        })
        .collect();
    InstancingGraph {
        symbols: vec![symbol("A", vec![], Some(rule))],
        axiom: vec![at(Affine::IDENTITY, 0)],
    }
}

/// A small tree with no cycle: a trunk (a cylinder) carrying three turned,
/// shrunk copies of a branch, each carrying two leaves (spheres) and a
/// box; rotations, non-uniform scales and a shear among the transforms.
fn small_tree() -> InstancingGraph {
    let brown = Rgb(120, 80, 40);
    let green = Rgb(40, 160, 60);
    let trunk = shape(
        Primitive::Cylinder {
            base: [0.0, 0.0, 0.0],
            top: [0.0, 1.0, 0.0],
            radius: 0.08,
        },
        brown,
    );
    let leaf = shape(
        Primitive::Sphere {
            centre: [0.0, 0.0, 0.0],
            radius: 0.15,
        },
        green,
    );
    let cube = shape(
        Primitive::Box {
            min: [-0.1, -0.1, -0.1],
            max: [0.1, 0.1, 0.1],
        },
        Rgb(200, 60, 60),
    );
    let branch_at = |turn: f64| {
        Affine::translate([0.0, 1.0, 0.0])
            .then_after(&Affine::rotate([0.0, 1.0, 0.0], turn).unwrap())
            .then_after(&Affine::rotate([0.0, 0.0, 1.0], 0.6).unwrap())
            .then_after(&Affine::scale([0.6, 0.7, 0.6]))
    };
    let leaves = vec![
        at(Affine::translate([0.0, 1.0, 0.2]), 2),
        at(
            Affine::translate([0.1, 0.8, -0.2]).then_after(&Affine::shear(0, 1, 0.3)),
            2,
        ),
        at(Affine::translate([0.0, 0.5, 0.0]), 3),
    ];
    InstancingGraph {
        symbols: vec![
            symbol(
                "T",
                vec![trunk.clone()],
                Some(vec![
                    at(branch_at(0.0), 1),
                    at(branch_at(2.1), 1),
                    at(branch_at(4.2), 1),
                ]),
            ),
            symbol("B", vec![trunk], Some(leaves)),
            symbol("L", vec![leaf], None),
            symbol("C", vec![cube], None),
        ],
        axiom: vec![at(Affine::IDENTITY, 0)],
    }
}

fn options(size: u32, eye: Eye) -> Options {
    let mut o = Options::new(size, size, eye);
    o.threads = 1;
    o
}

fn view(az: f64, el: f64) -> Eye {
    Eye::View {
        azimuth: az.to_radians(),
        elevation: el.to_radians(),
    }
}

fn background_pixels(rgba: &[u8], bg: [u8; 3]) -> Vec<bool> {
    rgba.chunks(4).map(|p| p[..3] == bg).collect()
}

#[test]
fn an_instanced_graph_draws_what_its_expansion_draws_pixel_for_pixel() {
    let g = small_tree();
    let scene = GraphScene::new(&g, [0.5; 3]).unwrap();
    // Nothing in the tree is near a pixel at this size: neither cuts.
    let items = scene.expand(1e-9, 1000).unwrap();
    assert_eq!(
        items.len(),
        1 + 3 * (1 + 3),
        "a trunk, and per branch itself, 2 leaves, a box"
    );
    let flat = Bvh::new(items);
    // A camera of its own: both pictures seen through the same lens (a
    // parallel view is fitted to each scene's own hull).
    let camera = |eye: [f64; 3]| {
        Eye::Camera(graftal::ir::look::Camera {
            eye,
            target: [0.0, 1.2, 0.0],
            up: [0.0, 1.0, 0.0],
            perspective: Some(40.0),
        })
    };
    for eye in [camera([1.8, 1.9, 2.4]), camera([-2.4, 2.4, -1.2])] {
        let opts = options(96, eye);
        let instanced = trace(&scene, &opts);
        let expanded = trace(&flat, &opts);
        let drawn = background_pixels(&instanced, [255; 3])
            .iter()
            .filter(|b| !**b)
            .count();
        assert!(
            drawn > 500,
            "the tree covers part of the picture: {drawn} pixels"
        );
        let differ = instanced
            .chunks(4)
            .zip(expanded.chunks(4))
            .filter(|(a, b)| a != b)
            .count();
        assert_eq!(
            differ, 0,
            "{differ} pixels differ between the instanced and the flat tracing"
        );
    }
}

#[test]
fn the_sierpinski_tetrahedron_seen_along_its_edge_midpoints_covers_a_square() {
    // The midpoints of the opposite edges (1,1,1)–(-1,-1,1) and
    // (1,-1,-1)–(-1,1,-1) are (0,0,1) and (0,0,-1): seen along z, every
    // level of the tetrahedron projects onto the square [-1,1]^2. The
    // pixel cut comes at another depth at each size.
    let g = tetrahedron();
    let scene = GraphScene::new(&g, [0.6; 3]).unwrap();
    for size in [20u32, 41, 64, 130, 256] {
        let mut opts = options(size, view(0.0, 0.0));
        opts.samples = 1;
        let rgba = trace(&scene, &opts);
        let bg = background_pixels(&rgba, [255; 3]);
        // The square fills 90% of the picture, centred.
        let (lo, hi) = (size as f64 * 0.05, size as f64 * 0.95);
        for y in 0..size as usize {
            for x in 0..size as usize {
                let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
                let inside = cx > lo + 1.0 && cx < hi - 1.0 && cy > lo + 1.0 && cy < hi - 1.0;
                let outside = cx < lo - 1.0 || cx > hi + 1.0 || cy < lo - 1.0 || cy > hi + 1.0;
                let covered = !bg[y * size as usize + x];
                assert!(
                    !inside || covered,
                    "size {size}: ({x}, {y}) inside the square is not covered"
                );
                assert!(
                    !outside || !covered,
                    "size {size}: ({x}, {y}) outside the square is covered"
                );
            }
        }
    }
}

#[test]
fn the_bytes_are_the_same_for_every_thread_count() {
    let g = small_tree();
    let scene = GraphScene::new(&g, [0.5; 3]).unwrap();
    let tet = tetrahedron();
    let tet_scene = GraphScene::new(&tet, [0.5; 3]).unwrap();
    for scene in [&scene as &dyn graftal::raytrace::Scene, &tet_scene] {
        let mut opts = options(70, view(25.0, 30.0));
        let one = trace(scene, &opts);
        for threads in [2, 3, 5] {
            opts.threads = threads;
            assert!(
                trace(scene, &opts) == one,
                "{threads} threads draw other bytes"
            );
        }
    }
}

#[test]
fn a_shadow_falls_where_the_light_is_blocked() {
    // A ball over a slab, lit from straight above: the slab's middle is in
    // the ball's shadow, its corner is not.
    let slab = shape(
        Primitive::Box {
            min: [-2.0, -0.1, -2.0],
            max: [2.0, 0.0, 2.0],
        },
        Rgb(200, 200, 200),
    );
    let ball = shape(
        Primitive::Sphere {
            centre: [0.0, 1.0, 0.0],
            radius: 0.5,
        },
        Rgb(200, 50, 50),
    );
    let g = InstancingGraph {
        symbols: vec![symbol("S", vec![slab, ball], None)],
        axiom: vec![at(Affine::IDENTITY, 0)],
    };
    let scene = GraphScene::new(&g, [0.5; 3]).unwrap();
    let mut opts = options(64, view(0.0, 90.0));
    opts.lights = vec![graftal::ir::look::Light {
        vector: [0.0, 1.0, 0.0],
        directional: true,
        ambient: [0.2; 3],
        diffuse: [0.8; 3],
        specular: [0.0; 3],
    }];
    let lit = |rgba: &[u8], x: usize, y: usize| rgba[(y * 64 + x) * 4] as u32;
    // Seen from straight above, a light from straight above hides the
    // shadow under the ball; a light from +x casts it towards −x.
    opts.lights[0].vector = [1.0, 1.0, 0.0];
    let slanted = trace(&scene, &opts);
    opts.shadows = false;
    let slanted_without = trace(&scene, &opts);
    // The shadow falls towards −x: left of the ball in the picture.
    let (x, y) = (14, 32);
    assert!(
        lit(&slanted, x, y) < lit(&slanted_without, x, y),
        "the slab left of the ball is darker with shadows: {} vs {}",
        lit(&slanted, x, y),
        lit(&slanted_without, x, y)
    );
    assert_eq!(lit(&slanted, 60, 32), lit(&slanted_without, 60, 32));
}

#[test]
fn an_alternative_geometry_replaces_a_symbol_under_its_size() {
    // A box whose alternative (a red sphere) is drawn once the box is
    // under 30 pixels: at 16 pixels the sphere shows, at 256 the box.
    let grey = Rgb(128, 128, 128);
    let red = Rgb(255, 0, 0);
    let mut s = symbol(
        "B",
        vec![shape(
            Primitive::Box {
                min: [-1.0; 3],
                max: [1.0; 3],
            },
            grey,
        )],
        None,
    );
    s.alternative = Some(Alternative {
        shapes: vec![shape(
            Primitive::Sphere {
                centre: [0.0; 3],
                radius: 1.0,
            },
            red,
        )],
        below_pixels: 30.0,
    });
    let g = InstancingGraph {
        symbols: vec![s],
        axiom: vec![at(Affine::IDENTITY, 0)],
    };
    let scene = GraphScene::new(&g, [0.5; 3]).unwrap();
    let reddish = |rgba: &[u8]| {
        rgba.chunks(4)
            .any(|p| p[0] as u32 > 2 * p[1].max(1) as u32 && p[0] > 60)
    };
    let mut small = options(16, view(0.0, 0.0));
    small.scale = 100.0;
    assert!(
        reddish(&trace(&scene, &small)),
        "the alternative is drawn small"
    );
    let large = options(256, view(0.0, 0.0));
    assert!(!reddish(&trace(&scene, &large)), "the box is drawn large");
}

fn png_pixels(bytes: &[u8]) -> Vec<u8> {
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    buf
}

#[test]
fn the_one_call_for_a_picture_traces_a_graph_and_a_shadowed_look() {
    let mut sys = System::new();
    sys.graph = Some(tetrahedron());
    sys.settings.view = Some((0.5, 0.4));
    let mut req = Request::new(Target::Still(Format::Png));
    (req.width, req.height) = (48, 48);
    let p = picture::draw_system(&sys, &req, &mut Quiet).unwrap();
    assert_eq!(p.method, Method::RayTraced);
    let px = png_pixels(&p.bytes);
    assert!(px.chunks(4).any(|c| c[..3] != [255, 255, 255]));
    // An SVG of it carries the PNG.
    req.target = Target::Still(Format::Svg);
    let svg = picture::draw_system(&sys, &req, &mut Quiet).unwrap();
    assert!(String::from_utf8(svg.bytes)
        .unwrap()
        .contains("data:image/png;base64,"));

    // cpfg's `render mode: shadows` is traced; the same object asked not
    // to be (a plain look) is not.
    let lilac = format!(
        "{}/tests/corpus/cpfg/11-CPFG-Lilac/plant.l",
        env!("CARGO_MANIFEST_DIR")
    );
    let c = compile(load(&lilac).unwrap());
    let mut req = Request::new(Target::Still(Format::Png));
    (req.width, req.height) = (64, 64);
    req.run.steps = Some(3);
    let p = picture::draw(&c, &req, &mut Quiet).unwrap();
    assert_eq!(p.method, Method::RayTraced);
    req.tracing = Tracing {
        raytrace: Some(false),
        ..Tracing::default()
    };
    assert_ne!(
        picture::draw(&c, &req, &mut Quiet).unwrap().method,
        Method::RayTraced
    );
}

#[test]
fn render_raytrace_draws_a_lit_linf_tree_the_same_with_any_threads() {
    let out = |threads: &str| {
        let path = crate::common::temp(&format!("rt-{threads}.png"));
        let p = path.to_str().unwrap();
        let args = [
            "render",
            "std:linf/fig08-tree-3d",
            "--raytrace",
            "--size",
            "120x120",
            "--threads",
            threads,
            "-o",
            p,
        ];
        let o = crate::common::graftal(&args);
        assert_eq!(o.status, 0, "{}", o.stderr);
        std::fs::read(&path).unwrap()
    };
    let one = out("1");
    assert_eq!(out("2"), one);
    assert_eq!(out("3"), one);
    let px = png_pixels(&one);
    // Lit: the tree's greens come in many shades, not the one or two of
    // flat lines.
    let shades: std::collections::BTreeSet<&[u8]> = px
        .chunks(4)
        .filter(|p| p[1] > p[0] && p[1] > p[2])
        .collect();
    assert!(shades.len() > 20, "{} shades of green", shades.len());
}

/// The pixels of a PNG as RGB, whatever its colour type and depth.
fn rgb_pixels(bytes: &[u8]) -> (u32, u32, Vec<[u8; 3]>) {
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::normalize_to_color8());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let channels = info.color_type.samples();
    let px = buf[..info.buffer_size()]
        .chunks(channels)
        .map(|c| match channels {
            1 | 2 => [c[0]; 3],
            _ => [c[0], c[1], c[2]],
        })
        .collect();
    (info.width, info.height, px)
}

/// Intersection over union of two pictures' silhouettes (what is not the
/// white background).
fn silhouette_iou(a: &[[u8; 3]], b: &[[u8; 3]]) -> f64 {
    let ink = |p: &[u8; 3]| p.iter().any(|c| *c < 235);
    let (mut both, mut either) = (0usize, 0usize);
    for (p, q) in a.iter().zip(b) {
        both += (ink(p) && ink(q)) as usize;
        either += (ink(p) || ink(q)) as usize;
    }
    both as f64 / either.max(1) as f64
}

/// POV-Ray renders `scene` (a `.pov` text) at `size`: its PNG, or `None`
/// when POV-Ray is not installed (an error where `.ci/run` installs it).
fn povray(scene: &[u8], size: u32, name: &str) -> Option<Vec<u8>> {
    let dir = crate::common::temp(name);
    std::fs::create_dir_all(&dir).unwrap();
    let (input, output) = (dir.join("scene.pov"), dir.join("scene.png"));
    std::fs::write(&input, scene).unwrap();
    let run = std::process::Command::new("povray")
        .arg(format!("+I{}", input.display()))
        .arg(format!("+O{}", output.display()))
        .args([
            &format!("+W{size}"),
            &format!("+H{size}"),
            "-D",
            "-V",
            "+FN",
            "-A",
            "+WT1",
        ])
        .output();
    match run {
        Ok(out) => {
            assert!(
                out.status.success(),
                "povray: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            Some(std::fs::read(&output).unwrap())
        }
        Err(_) => {
            assert!(
                std::env::var("GRAFTAL_NEED_POVRAY").as_deref() != Ok("1"),
                "povray is missing and GRAFTAL_NEED_POVRAY=1: `.ci/run` installs it"
            );
            eprintln!("povray is missing: the POV-Ray scene was not rendered");
            None
        }
    }
}

#[test]
fn pov_ray_draws_the_scene_graftal_writes_with_graftals_silhouette() {
    // An independent renderer: POV-Ray 3.7 renders the `.pov` graftal
    // writes, and its silhouette is graftal's own ray-traced picture's.
    const SIZE: u32 = 96;
    let mut sys = System::new();
    sys.graph = Some(small_tree());
    sys.settings.view = Some((0.6, 0.3));
    let mut tree = Request::new(Target::Still(Format::Png));
    (tree.width, tree.height) = (SIZE, SIZE);
    tree.tracing.samples = 1;
    let ours = picture::draw_system(&sys, &tree, &mut Quiet).unwrap().bytes;
    tree.target = Target::Still(Format::Pov);
    let scene = picture::draw_system(&sys, &tree, &mut Quiet).unwrap().bytes;
    let text = String::from_utf8(scene.clone()).unwrap();
    assert!(
        text.contains("#declare G_0_1 = union"),
        "instancing kept: {text}"
    );
    let Some(theirs) = povray(&scene, SIZE, "pov-tree") else {
        return;
    };
    let (w, h, theirs) = rgb_pixels(&theirs);
    assert_eq!((w, h), (SIZE, SIZE));
    let iou = silhouette_iou(&rgb_pixels(&ours).2, &theirs);
    assert!(
        iou >= 0.95,
        "the instanced tree: silhouettes overlap by {iou:.3}"
    );

    // A turtle's plant, flattened to primitives.
    let plant = crate::common::temp("pov-plant.pov");
    let png = crate::common::temp("pov-plant.png");
    for (out, extra) in [(&plant, None), (&png, Some("--raytrace"))] {
        let mut args = vec![
            "render",
            "std:gft/signal-plant-3d",
            "--size",
            "96x96",
            "--samples",
            "1",
            "-o",
        ];
        args.push(out.to_str().unwrap());
        args.extend(extra);
        let o = crate::common::graftal(&args);
        assert_eq!(o.status, 0, "{}", o.stderr);
    }
    let Some(theirs) = povray(&std::fs::read(&plant).unwrap(), SIZE, "pov-plant") else {
        return;
    };
    // Its branches are a pixel or two wide, so the two renderers' edges
    // (each its own arithmetic) make most of the difference: every inked
    // pixel of either lies within a pixel of the other's ink.
    let (ours, theirs) = (
        rgb_pixels(&std::fs::read(&png).unwrap()).2,
        rgb_pixels(&theirs).2,
    );
    for (a, b, which) in [(&ours, &theirs, "graftal's"), (&theirs, &ours, "POV-Ray's")] {
        let near = within_a_pixel(a, b, SIZE as usize);
        assert!(
            near >= 0.995,
            "the signal plant: {near:.4} of {which} ink is within a pixel of the other's"
        );
    }
}

/// The share of `a`'s inked pixels with an inked pixel of `b` at most one
/// pixel away.
fn within_a_pixel(a: &[[u8; 3]], b: &[[u8; 3]], size: usize) -> f64 {
    let ink = |p: &[u8; 3]| p.iter().any(|c| *c < 235);
    let (mut inked, mut near) = (0usize, 0usize);
    for y in 0..size {
        for x in 0..size {
            if !ink(&a[y * size + x]) {
                continue;
            }
            inked += 1;
            let ys = y.saturating_sub(1)..=(y + 1).min(size - 1);
            near += ys
                .flat_map(|yy| {
                    (x.saturating_sub(1)..=(x + 1).min(size - 1)).map(move |xx| (xx, yy))
                })
                .any(|(xx, yy)| ink(&b[yy * size + xx])) as usize;
        }
    }
    near as f64 / inked.max(1) as f64
}

#[test]
fn a_context_free_plant_is_traced_from_its_shared_subtrees_as_its_geometry_is() {
    // The derivation tree of plant (e) is an instancing graph of a few
    // dozen subtrees; traced without deriving the word, it draws what the
    // word's interpreted geometry draws through the flat hierarchy,
    // within a pixel.
    use graftal::raytrace::{bvh, subtrees};
    use graftal::turtle::instanced::Instanced;
    let c = compile(load("std:plant-e").unwrap());
    let sys = c.system.as_ref().unwrap();
    let steps = 5;
    let mut inst = Instanced::new(sys).unwrap();
    let colour = Rgb(0, 0, 0);
    let size = 128;
    let eye = view(0.0, 0.0);
    let bare = subtrees::graph(&mut inst, steps, 0.0, colour).unwrap();
    let opts = options(size, eye);
    let points = graftal::raytrace::Scene::fit_points(&GraphScene::new(&bare, [0.0; 3]).unwrap());
    let pixel = graftal::raytrace::pixel_size(&points, &opts);
    let g = subtrees::graph(&mut inst, steps, pixel / sys.settings.step, colour).unwrap();
    let segments = 2usize * 4usize.pow(steps as u32);
    assert!(
        g.symbols.len() < 40,
        "{} graph symbols for a word of about {segments} segments",
        g.symbols.len()
    );
    let instanced = trace(&GraphScene::new(&g, [0.0; 3]).unwrap(), &opts);

    let run = graftal::driver::RunOptions {
        steps: Some(steps),
        ..Default::default()
    };
    let (_, geometry) = graftal::driver::geometry(sys, &run).unwrap();
    let mut geometry = geometry;
    // Lines of 2 pixels, as the graph's (radius: a pixel).
    for s in &mut geometry.segments {
        s.width = 2.0;
    }
    let flat = trace(
        &Bvh::new(bvh::from_geometry(&geometry, pixel, Finish::default(), &[])),
        &opts,
    );
    let rgb = |px: &[u8]| {
        px.chunks(4)
            .map(|p| [p[0], p[1], p[2]])
            .collect::<Vec<[u8; 3]>>()
    };
    let (a, b) = (rgb(&instanced), rgb(&flat));
    assert!(
        a.iter().filter(|p| p[0] < 235).count() > 500,
        "the plant is drawn"
    );
    for (x, y, which) in [(&a, &b, "instanced"), (&b, &a, "flat")] {
        let near = within_a_pixel(x, y, size as usize);
        assert!(
            near >= 0.99,
            "{near:.4} of the {which} picture's ink is within a pixel of the other's"
        );
    }
}

/// A unit square wearing a 2 × 2 image (bottom row red, green; top row
/// blue, transparent), its corners at the image's corners, traced face on.
fn textured_square(textured: bool) -> Vec<[u8; 3]> {
    use graftal::ir::texture::{Image, Texture};
    use graftal::turtle::{Geometry, Polygon, Textured};
    let rgba = vec![
        255, 0, 0, 255, 0, 255, 0, 255, // bottom: red, green
        0, 0, 255, 255, 0, 0, 0, 0, // top: blue, transparent
    ];
    let image = Image::new(2, 2, rgba).unwrap();
    let texture = Texture::new("quad.png", Some(std::sync::Arc::new(image)));
    let g = Geometry {
        polygons: vec![Polygon {
            points: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ],
            colour: Rgb(255, 255, 255),
            index: 1,
            surface: true,
            texture: textured.then(|| Textured {
                texture: 0,
                uvs: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            }),
        }],
        ..Geometry::default()
    };
    let mut opts = options(64, view(0.0, 0.0));
    opts.samples = 1;
    opts.background = Rgb(0, 0, 0);
    let items = graftal::raytrace::bvh::from_geometry(&g, 0.01, Finish::default(), &[texture]);
    trace(&Bvh::new(items), &opts)
        .chunks(4)
        .map(|p| [p[0], p[1], p[2]])
        .collect()
}

#[test]
fn a_textured_square_shows_its_image_and_lets_rays_through_where_it_is_transparent() {
    let count = |px: &[[u8; 3]], f: &dyn Fn([i32; 3]) -> bool| {
        px.iter().filter(|p| f(p.map(i32::from))).count()
    };
    let plain = textured_square(false);
    let lit = count(&plain, &|p| p != [0, 0, 0]);
    assert!(lit > 64 * 64 / 2, "{lit} pixels of the square");
    // Untextured, the white square is grey to white: no colour dominates.
    assert_eq!(count(&plain, &|p| (p[0] - p[1]).abs() > 30), 0);
    let px = textured_square(true);
    let red = count(&px, &|p| p[0] > p[1] + 50 && p[0] > p[2] + 50);
    let green = count(&px, &|p| p[1] > p[0] + 50 && p[1] > p[2] + 50);
    let blue = count(&px, &|p| p[2] > p[0] + 50 && p[2] > p[1] + 50);
    let quarter = lit / 4;
    for (name, n) in [("red", red), ("green", green), ("blue", blue)] {
        assert!(
            n * 10 > quarter * 8 && n * 10 < quarter * 12,
            "{name}: {n} pixels, a quarter of the square is {quarter}"
        );
    }
    // The transparent quarter is cut out: the background shows there.
    let through = count(&px, &|p| p == [0, 0, 0]) - count(&plain, &|p| p == [0, 0, 0]);
    assert!(
        through * 10 > quarter * 8 && through * 10 < quarter * 12,
        "{through} pixels cut out of {quarter}"
    );
    // Red beside green, blue above (or below) red: the image's layout.
    let at = |x: usize, y: usize| px[y * 64 + x];
    let red_at = |p: [u8; 3]| p[0] > p[1] + 50;
    let (xs, ys): (Vec<usize>, Vec<usize>) = (0..64 * 64)
        .filter(|&i| red_at(px[i]))
        .map(|i| (i % 64, i / 64))
        .unzip();
    let (cx, cy) = (
        xs.iter().sum::<usize>() / xs.len(),
        ys.iter().sum::<usize>() / ys.len(),
    );
    let mirrored_x = 63 - cx;
    let mirrored_y = 63 - cy;
    assert!(at(mirrored_x, cy)[1] > 100, "green across from red");
    assert!(at(cx, mirrored_y)[2] > 100, "blue across from red");
}
