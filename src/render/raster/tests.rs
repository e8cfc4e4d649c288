use super::tessellate::ear_clip;
use super::*;
use crate::ir::look::{Camera, Light, LineStyle, Material};
use crate::turtle::{Disc, Polygon, Segment, Sink};

const BLACK: Rgb = Rgb(0, 0, 0);

fn lighting(shading: Shading, line_style: LineStyle) -> Lighting {
    Lighting {
        shading,
        line_style,
        ..Lighting::default()
    }
}

fn draw(g: &Geometry, l: &Lighting, opts: &RenderOptions) -> tiny_skia::Pixmap {
    let palette: Vec<Rgb> = (0..=255).map(|i| Rgb(i as u8, i as u8, i as u8)).collect();
    let bytes = png(g, l, &palette, opts, &mut |_, _| {}).expect("a picture");
    tiny_skia::Pixmap::decode_png(&bytes).expect("a PNG")
}

fn small(size: u32) -> RenderOptions {
    RenderOptions {
        width: size,
        height: size,
        background: BLACK,
        ..RenderOptions::default()
    }
}

fn rgb(pm: &tiny_skia::Pixmap, x: u32, y: u32) -> [u8; 3] {
    let p = pm.pixel(x, y).unwrap().demultiply();
    [p.red(), p.green(), p.blue()]
}

fn square(z: f64, half: f64, grey: u8) -> Polygon {
    Polygon {
        points: vec![
            [-half, -half, z],
            [half, -half, z],
            [half, half, z],
            [-half, half, z],
        ],
        colour: Rgb(grey, grey, grey),
        index: grey as u16,
        surface: false,
        texture: None,
    }
}

#[test]
fn the_nearer_triangle_wins_whatever_the_order() {
    let filled = lighting(Shading::Filled, LineStyle::Pixel);
    let (near, far) = (square(1.0, 1.0, 200), square(-1.0, 2.0, 100));
    for polygons in [vec![near.clone(), far.clone()], vec![far, near]] {
        let g = Geometry {
            polygons,
            ..Geometry::default()
        };
        let pm = draw(&g, &filled, &small(60));
        assert_eq!(rgb(&pm, 30, 30), [200; 3]);
        assert_eq!(rgb(&pm, 5, 5), [100; 3]);
    }
}

#[test]
fn a_concave_polygon_covers_its_area() {
    // An L of area 3 in a 2×2 box, and a point so the fit is known.
    let l_shape = Polygon {
        points: vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
        ],
        colour: Rgb(255, 255, 255),
        index: 255,
        surface: false,
        texture: None,
    };
    let g = Geometry {
        polygons: vec![l_shape],
        ..Geometry::default()
    };
    let size = 100;
    let pm = draw(
        &g,
        &lighting(Shading::Filled, LineStyle::Pixel),
        &small(size),
    );
    let covered: f64 = pm.pixels().iter().map(|p| f64::from(p.red()) / 255.0).sum();
    // The 2×2 box fills 90% of the picture each way.
    let unit = (0.9 * f64::from(size) / 2.0).powi(2);
    let area = covered / unit;
    assert!((area - 3.0).abs() < 0.09, "area {area}");
}

#[test]
fn a_lit_sphere_is_brighter_towards_the_light() {
    let mut l = lighting(Shading::Smooth, LineStyle::Cylinder);
    l.lights = vec![Light {
        vector: [1.0, 0.0, 0.0],
        directional: true,
        ambient: [0.0; 3],
        ..Light::default()
    }];
    l.materials = vec![Some(Material::CPFG_DEFAULT)];
    let g = Geometry {
        discs: vec![Disc {
            centre: [0.0; 3],
            diameter: 2.0,
            pixels: false,
            colour: Rgb(255, 255, 255),
            index: 0,
        }],
        ..Geometry::default()
    };
    let pm = draw(&g, &l, &small(60));
    let (right, left) = (rgb(&pm, 45, 30)[0], rgb(&pm, 15, 30)[0]);
    assert!(right > 100 && left < 20, "right {right}, left {left}");
}

#[test]
fn colour_map_cylinders_move_the_index_around_the_axis() {
    let mut l = lighting(Shading::Smooth, LineStyle::Cylinder);
    l.lights = vec![Light {
        vector: [1.0, 0.0, 0.0],
        directional: true,
        ..Light::default()
    }];
    l.index_shift = 50.0;
    let g = Geometry {
        segments: vec![Segment {
            a: [0.0, -2.0, 0.0],
            b: [0.0, 2.0, 0.0],
            width: 2.0,
            colour: Rgb(100, 100, 100),
            index: 100,
            depth: 0,
        }],
        ..Geometry::default()
    };
    let pm = draw(&g, &l, &small(60));
    // Seen face on, the cylinder spans x = 30 ± 9 pixels: lit towards
    // +x (index up to 150), darker towards −x (down to 50); 5 pixels
    // off the axis N·L is ±0.6.
    let (right, middle, left) = (
        rgb(&pm, 35, 30)[0],
        rgb(&pm, 30, 30)[0],
        rgb(&pm, 25, 30)[0],
    );
    assert!(right > 120 && left < 80, "{left} {middle} {right}");
    assert!((95..=105).contains(&middle), "{middle}");
}

#[test]
fn the_background_fills_what_nothing_covers() {
    let g = Geometry {
        polygons: vec![square(0.0, 1.0, 255)],
        discs: vec![Disc {
            centre: [5.0, 5.0, 0.0],
            diameter: 0.0,
            pixels: true,
            colour: Rgb(255, 255, 255),
            index: 255,
        }],
        ..Geometry::default()
    };
    let opts = RenderOptions {
        background: Rgb(10, 20, 30),
        ..small(40)
    };
    let pm = draw(&g, &lighting(Shading::Filled, LineStyle::Pixel), &opts);
    let bg = pm
        .pixels()
        .iter()
        .filter(|p| [p.red(), p.green(), p.blue()] == [10, 20, 30]);
    // The fit holds −1..5 each way in 36 pixels: the square covers
    // 12 × 12 pixels.
    let n = bg.count();
    assert!((40 * 40 - 170..=40 * 40 - 120).contains(&n), "{n}");
    let empty = draw(
        &Geometry::default(),
        &lighting(Shading::Flat, LineStyle::Cylinder),
        &opts,
    );
    assert!(empty
        .pixels()
        .iter()
        .all(|p| [p.red(), p.green(), p.blue()] == [10, 20, 30]));
}

#[test]
fn a_transparent_background_stays_transparent_around_what_is_drawn() {
    let g = Geometry {
        polygons: vec![square(0.0, 1.0, 255)],
        ..Geometry::default()
    };
    let opts = RenderOptions {
        background: Rgb(10, 20, 30),
        background_alpha: 0,
        ..small(40)
    };
    let pm = draw(&g, &lighting(Shading::Filled, LineStyle::Pixel), &opts);
    let alphas: Vec<u8> = pm.pixels().iter().map(|p| p.alpha()).collect();
    assert_eq!(alphas[0], 0);
    assert!(alphas.contains(&255));
    // An edge pixel half covered is the square's colour, half opaque:
    // no tint of the transparent background's colour.
    let inside = pm.pixel(20, 20).unwrap();
    assert_eq!(inside.alpha(), 255);
    let near = |a: u8, b: u8| a.abs_diff(b) <= 3;
    for p in pm.pixels().iter().filter(|p| (1..255).contains(&p.alpha())) {
        let c = p.demultiply();
        assert!(
            near(c.red(), inside.red()) && near(c.blue(), inside.blue()),
            "{c:?} {inside:?}"
        );
    }
}

#[test]
fn a_camera_puts_its_target_at_the_centre() {
    // A small square at the target and a bigger one off to the side.
    let target = [3.0, 1.0, 0.0];
    let mut off = square(0.0, 0.5, 100);
    for p in &mut off.points {
        p[0] += 3.0 + 4.0;
        p[1] += 1.0 + 1.0;
    }
    let mut mark = square(0.0, 0.2, 255);
    for p in &mut mark.points {
        p[0] += target[0];
        p[1] += target[1];
    }
    let g = Geometry {
        polygons: vec![mark, off],
        ..Geometry::default()
    };
    let opts = RenderOptions {
        camera: Some(Camera {
            eye: [3.0, 1.0, 20.0],
            target,
            up: [0.0, 1.0, 0.0],
            perspective: Some(30.0),
        }),
        ..small(81)
    };
    let pm = draw(&g, &lighting(Shading::Filled, LineStyle::Pixel), &opts);
    assert_eq!(rgb(&pm, 40, 40), [255; 3]);
    // The mark is 0.4 wide against an extent of ±4.5: ~3.6 pixels.
    assert_eq!(rgb(&pm, 40, 34), [0; 3]);
    assert_eq!(rgb(&pm, 46, 40), [0; 3]);
}

#[test]
fn the_same_input_gives_the_same_bytes() {
    let g = Geometry {
        segments: (0..50)
            .map(|i| {
                let t = f64::from(i) * 0.3;
                Segment {
                    a: [t.cos(), t, t.sin()],
                    b: [(t + 0.3).cos(), t + 0.3, (t + 0.3).sin()],
                    width: 0.2,
                    colour: Rgb(90, 90, 90),
                    index: 90,
                    depth: 0,
                }
            })
            .collect(),
        polygons: vec![square(0.5, 1.0, 50)],
        ..Geometry::default()
    };
    let l = lighting(Shading::Smooth, LineStyle::Cylinder);
    let palette = [Rgb(1, 2, 3), Rgb(200, 100, 50)];
    let once = png(&g, &l, &palette, &small(70), &mut |_, _| {});
    let twice = png(&g, &l, &palette, &small(70), &mut |_, _| {});
    assert!(once.is_some());
    assert_eq!(once, twice);
}

/// A helix of tapered cylinders through a smooth surface of quads and
/// spheres, drawn in any number of bands on any number of threads:
/// the same bytes, since a sample's colour does not depend on its band.
#[test]
fn bands_and_threads_do_not_change_the_picture() {
    let mut g = Geometry::default();
    for i in 0..40 {
        let t = f64::from(i) * 0.3;
        g.segment(Segment {
            a: [t.cos(), t / 3.0, t.sin()],
            b: [(t + 0.3).cos(), (t + 0.3) / 3.0, (t + 0.3).sin()],
            width: 0.3 - f64::from(i) * 0.005,
            colour: Rgb(90, 90, 90),
            index: 90,
            depth: 0,
        });
        if i % 10 == 0 {
            for k in 0..6 {
                let (a, b) = (f64::from(k) * 0.2, f64::from(k + 1) * 0.2);
                g.polygon(Polygon {
                    points: vec![
                        [a, t / 3.0, a * a],
                        [b, t / 3.0, b * b],
                        [b, t / 3.0 + 0.4, b * b],
                        [a, t / 3.0 + 0.4, a * a],
                    ],
                    colour: Rgb(40, 160, 40),
                    index: 40,
                    surface: true,
                    texture: None,
                });
            }
            g.disc(Disc {
                centre: [0.0, t / 3.0, 0.0],
                diameter: 0.5,
                colour: Rgb(200, 30, 30),
                pixels: false,
                index: 200,
            });
        }
    }
    let l = Lighting {
        tapered: true,
        ..lighting(Shading::Smooth, LineStyle::Cylinder)
    };
    let palette = [Rgb(1, 2, 3), Rgb(200, 100, 50)];
    let opts = RenderOptions {
        width: 60,
        height: 301,
        ..small(60)
    };
    let drawing = Drawing::stored(&g);
    let survey = survey(&drawing, &l, &opts);
    let scene = Scene::new(&survey, false, &l, &palette, &opts);
    let draw = |threads| {
        png_in_bands(
            &drawing,
            &scene,
            survey.drawn,
            &opts,
            threads,
            &mut |_, _| {},
        )
        .expect("a picture")
    };
    let one = draw(1);
    for threads in [2, 3, 7] {
        assert!(
            draw(threads) == one,
            "{threads} threads draw another picture"
        );
    }
    // And the picture is not blank: a band drawn twice or not at all
    // would show.
    let pm = tiny_skia::Pixmap::decode_png(&one).unwrap();
    let lit = (0..301)
        .filter(|&y| (0..60).any(|x| rgb(&pm, x, y) != [0, 0, 0]))
        .count();
    assert!(lit > 60, "{lit} rows drawn");
}

#[test]
fn empty_and_degenerate_geometry_draws_without_panicking() {
    let seg = |a: Vec3, b: Vec3, width: f64| Segment {
        a,
        b,
        width,
        colour: BLACK,
        index: 0,
        depth: 0,
    };
    let g = Geometry {
        segments: vec![
            seg([0.0; 3], [0.0; 3], 1.0),
            seg([0.0; 3], [0.0, 1.0, 0.0], f64::NAN),
            seg([0.0; 3], [0.0, 0.0, 5.0], 1.0),
            seg([f64::NAN; 3], [0.0; 3], 1.0),
            seg([0.0; 3], [1e300, 0.0, 0.0], 1e300),
        ],
        polygons: vec![
            Polygon {
                points: vec![[0.0; 3], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0], [3.0, 3.0, 3.0]],
                colour: BLACK,
                index: 0,
                surface: false,
                texture: None,
            },
            Polygon {
                points: vec![[0.0; 3], [1.0, 0.0, 0.0]],
                colour: BLACK,
                index: 0,
                surface: false,
                texture: None,
            },
            // A bow tie: crosses itself.
            Polygon {
                points: vec![[0.0; 3], [1.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
                colour: BLACK,
                index: 7,
                surface: false,
                texture: None,
            },
        ],
        discs: vec![Disc {
            centre: [0.0; 3],
            diameter: f64::INFINITY,
            pixels: false,
            colour: BLACK,
            index: 300,
        }],
        ..Geometry::default()
    };
    for shading in [
        Shading::Filled,
        Shading::Wireframe,
        Shading::Flat,
        Shading::Smooth,
    ] {
        for style in [LineStyle::Pixel, LineStyle::Polygon, LineStyle::Cylinder] {
            let l = lighting(shading, style);
            for size in [1, 7] {
                draw(&g, &l, &small(size));
                draw(&Geometry::default(), &l, &small(size));
            }
            let zero = RenderOptions {
                width: 0,
                ..small(5)
            };
            assert!(png(&g, &l, &[BLACK], &zero, &mut |_, _| {}).is_none());
        }
    }
}

#[test]
fn ear_clipping_covers_a_concave_polygon_once() {
    let pts = [
        [0.0, 0.0, 0.0],
        [4.0, 0.0, 0.0],
        [4.0, 4.0, 0.0],
        [2.0, 1.0, 0.0],
        [0.0, 4.0, 0.0],
    ];
    let tris = ear_clip(&pts, [0.0, 0.0, 1.0]);
    assert_eq!(tris.len(), 3);
    let area: f64 = tris
        .iter()
        .map(|&[a, b, c]| {
            let (p, q, r) = (pts[a], pts[b], pts[c]);
            ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])).abs() / 2.0
        })
        .sum();
    assert!((area - 10.0).abs() < 1e-9, "{area}");
}

/// A translucent material is blended over what lies behind it, after
/// everything opaque and whatever the order (cpfg's second pass, depth
/// kept); what lies in front of it still covers it; with the same material
/// opaque the front square is all there is.
#[test]
fn translucent_materials_blend_over_what_is_behind() {
    let emissive = |c: [f32; 3], transparency: f32| Material {
        ambient: [0.0; 3],
        diffuse: [0.0; 3],
        specular: [0.0; 3],
        emission: c,
        shininess: 0.0,
        transparency,
    };
    let mut l = lighting(Shading::Flat, LineStyle::Cylinder);
    let glass = |t| {
        let mut p = square(0.0, 1.0, 1);
        p.index = 1;
        (p, t)
    };
    let mut behind = square(-1.0, 2.0, 2);
    behind.index = 2;
    let mut front = square(1.0, 0.25, 3);
    front.index = 3;
    for (transparency, expected) in [(0.5f32, [128, 0, 127]), (0.0, [255, 0, 0])] {
        l.materials = vec![
            None,
            Some(emissive([1.0, 0.0, 0.0], glass(transparency).1)),
            Some(emissive([0.0, 0.0, 1.0], 0.0)),
            Some(emissive([0.0, 1.0, 0.0], 0.0)),
        ];
        let orders = [
            vec![glass(transparency).0, behind.clone(), front.clone()],
            vec![front.clone(), behind.clone(), glass(transparency).0],
        ];
        for polygons in orders {
            let g = Geometry {
                polygons,
                ..Geometry::default()
            };
            let pm = draw(&g, &l, &small(60));
            let mixed = rgb(&pm, 20, 20);
            assert!(
                (0..3).all(|k| (i32::from(mixed[k]) - expected[k]).abs() <= 2),
                "transparency {transparency}: {mixed:?}"
            );
            assert_eq!(rgb(&pm, 30, 30), [0, 255, 0], "the opaque square in front");
        }
    }
}

#[test]
fn threads_drawing_runs_of_parts_lay_together_as_one_thread_drawing_all() {
    // Squares at one depth in turn (a tie each time: the first drawn must
    // win), nearer and farther ones, lines, spheres and a translucent
    // pane, cut into parts of a few things each: every thread count draws
    // the bytes one thread draws, and, flat and untapered (nothing held
    // from one part to the next), the bytes of the drawing in one part.
    let mut g = Geometry::default();
    // The same square first and last: exactly the same depths.
    let tie = |grey, index| {
        let mut p = square(1.5, 0.3, grey);
        p.index = index;
        p
    };
    g.polygon(tie(250, 60));
    for i in 0..40u8 {
        let z = f64::from(i % 3) - 1.0;
        let mut p = square(z, 0.2 + f64::from(i) * 0.02, 10 + i * 5);
        p.index = 2 + u16::from(i);
        g.polygon(p);
        g.segment(Segment {
            a: [-1.0, f64::from(i) * 0.05 - 1.0, z],
            b: [1.0, 1.0 - f64::from(i) * 0.05, z],
            width: 0.05,
            colour: Rgb(200, 40, i),
            index: 3,
            depth: 0,
        });
        if i % 7 == 0 {
            g.disc(Disc {
                centre: [f64::from(i) * 0.04 - 0.8, 0.5, 0.0],
                diameter: 0.3,
                colour: Rgb(30, 30, 200),
                pixels: false,
                index: 2,
            });
        }
    }
    g.polygon(tie(5, 61));
    let mut pane = square(2.0, 0.6, 1);
    pane.index = 1;
    g.polygon(pane);
    let mut l = lighting(Shading::Filled, LineStyle::Cylinder);
    // A colour of its own for each index; index 1 half transparent.
    l.materials = (0..64u8)
        .map(|i| {
            let k = f32::from(i) / 64.0;
            Some(Material {
                ambient: [0.2; 3],
                diffuse: [k, 1.0 - k, 0.5],
                specular: [0.0; 3],
                emission: [0.0; 3],
                shininess: 0.0,
                transparency: if i == 1 { 0.5 } else { 0.0 },
            })
        })
        .collect();
    let palette = [Rgb(1, 2, 3)];
    let opts = small(64);
    let draw = |drawing: &Drawing, threads| {
        let survey = survey(drawing, &l, &opts);
        let scene = Scene::new(&survey, false, &l, &palette, &opts);
        png_in_bands(
            drawing,
            &scene,
            survey.drawn,
            &opts,
            threads,
            &mut |_, _| {},
        )
        .expect("a picture")
    };
    let whole = draw(&Drawing::stored(&g), 1);
    let parts = Drawing {
        source: Source::Stored(&g, g.in_parts(3)),
        world_widths: false,
    };
    assert!(parts.pieced().count() > 20);

    for threads in [1, 2, 3, 7] {
        assert!(draw(&parts, threads) == whole, "{threads} threads");
    }
}
