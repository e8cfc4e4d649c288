//! Textures (cpfg's `texture:` view lines and `@Tx`): the corpus images
//! decode, a lit picture of 11-CPFG-TexturedSurfaces wears the maple
//! image on its leaves, and a missing image is a warning at its view line
//! with the rest drawn untextured.

use graftal::driver::{self, Format, RunOptions};
use graftal::ir::System;
use graftal::render::RenderOptions;
use graftal::source::SourceFile;
use std::path::{Path, PathBuf};

fn corpus(object: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/corpus/cpfg")
        .join(object)
}

fn compile(path: &Path) -> (Option<System>, Vec<(&'static str, String)>) {
    let c = driver::compile(SourceFile::read(path).unwrap());
    let codes = c
        .diagnostics
        .iter()
        .map(|d| (d.code.0, d.message.clone()))
        .collect();
    (c.system, codes)
}

/// The picture's RGB pixels.
fn draw(sys: &System, size: u32) -> Vec<[u8; 3]> {
    draw_steps_of(sys, size, None)
}

/// The picture's RGB pixels at `steps`.
fn draw_steps(sys: &System, size: u32, steps: u64) -> Vec<[u8; 3]> {
    draw_steps_of(sys, size, Some(steps))
}

fn draw_steps_of(sys: &System, size: u32, steps: Option<u64>) -> Vec<[u8; 3]> {
    let run = RunOptions {
        steps,
        ..RunOptions::default()
    };
    let (_, g) = driver::geometry(sys, &run).unwrap();
    let opts = RenderOptions {
        width: size,
        height: size,
        ..RenderOptions::default()
    };
    let png = driver::render_bytes(sys, &g, Format::Png, opts).unwrap();
    crate::common::rgba_pixels(&png)
        .into_iter()
        .map(|[r, g, b, _]| [r, g, b])
        .collect()
}

#[test]
fn every_texture_image_of_the_corpus_decodes() {
    let images = [
        ("11-CPFG-TexturedSurfaces/maple.png", 256, 256),
        ("02-Mod-vis-3D-06-comp-leaf-perspective/leaft.png", 128, 256),
        ("11-CPFG-GeneralizedCylinder/squares.png", 252, 252),
        ("07-Open-13-clover/light08.rgb", 512, 512),
        ("20-EnviroPgms-CPFG-Clover/light.rgb", 256, 256),
    ];
    for (name, w, h) in images {
        let bytes = std::fs::read(corpus(name)).unwrap();
        let im = graftal::decode::decode(&bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!((im.width(), im.height()), (w, h), "{name}");
    }
    // The maple leaf's image is cut out by its alpha: corners transparent,
    // the middle opaque and red.
    let maple = graftal::decode::decode(
        &std::fs::read(corpus("11-CPFG-TexturedSurfaces/maple.png")).unwrap(),
    )
    .unwrap();
    assert!(maple.texel(0, 0)[3] < 128);
    let mid = maple.texel(128, 128);
    assert!(mid[3] > 128 && mid[0] > mid[1], "{mid:?}");
}

#[test]
fn the_maple_leaves_wear_their_texture() {
    let (sys, codes) = compile(&corpus("11-CPFG-TexturedSurfaces/plant.l"));
    let sys = sys.unwrap();
    assert!(
        !codes.iter().any(|c| c.0 == "W0807" || c.0 == "W0814"),
        "{codes:?}"
    );
    let textures = sys.look.textures();
    assert_eq!(textures.len(), 1);
    assert!(textures[0].image.is_some() && textures[0].per_surface);
    let textured = draw(&sys, 200);
    let mut plain = sys.clone();
    plain.look.lighting.as_mut().unwrap().textures.clear();
    let untextured = draw(&plain, 200);
    let background = textured[0];
    let differ = textured
        .iter()
        .zip(&untextured)
        .filter(|(a, b)| a != b)
        .count();
    assert!(differ > 1000, "{differ} pixels differ");
    // Modulated by the red maple image, the leaves turn red: more red
    // than green where they are drawn, and fewer pixels than the whole
    // surfaces cover (the image's transparent parts are cut out).
    let fg = |p: &Vec<[u8; 3]>| p.iter().filter(|&&c| c != background).count();
    assert!(
        fg(&textured) < fg(&untextured),
        "{} !< {}",
        fg(&textured),
        fg(&untextured)
    );
    let red = textured
        .iter()
        .filter(|c| **c != background && c[0] > c[1].saturating_add(40))
        .count();
    assert!(red * 2 > fg(&textured), "{red} red of {}", fg(&textured));
}

#[test]
fn a_missing_texture_image_warns_at_its_line_and_draws_untextured() {
    let dir = std::env::temp_dir().join(format!("graftal-texture-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let from = corpus("11-CPFG-TexturedSurfaces");
    for f in std::fs::read_dir(&from).unwrap() {
        let f = f.unwrap().path();
        if f.extension().is_some_and(|e| e != "png") {
            std::fs::copy(&f, dir.join(f.file_name().unwrap())).unwrap();
        }
    }
    let (sys, codes) = compile(&dir.join("plant.l"));
    let sys = sys.expect("drawn without the image");
    let warned: Vec<_> = codes.iter().filter(|c| c.0 == "W0814").collect();
    assert_eq!(warned.len(), 1, "{codes:?}");
    assert!(warned[0].1.contains("maple.png"));
    assert!(sys.look.textures()[0].image.is_none());
    // A broken image is the same warning, saying why.
    std::fs::write(dir.join("maple.png"), b"\x89PNG\r\n\x1a\nbroken").unwrap();
    let (sys, codes) = compile(&dir.join("plant.l"));
    assert!(
        codes
            .iter()
            .any(|c| c.0 == "W0814" && c.1.contains("decoded")),
        "{codes:?}"
    );
    assert!(!draw(&sys.unwrap(), 64).is_empty());
    let _ = std::fs::remove_dir_all(&dir);
}

/// `object`'s `.gft` translation (no diagnostic: textures are written).
fn to_gft(object: &str, l: &str) -> (System, String) {
    let c = driver::compile(SourceFile::read(&corpus(object).join(l)).unwrap());
    let sys = c.system.clone().unwrap();
    let req = graftal::back::Request {
        target: graftal::back::by_name("gft").unwrap(),
        lossy: false,
        steps: None,
    };
    let t = driver::translate(&c, &sys, &req);
    assert!(t.diagnostics.is_empty(), "{object}: {:?}", t.diagnostics);
    (sys, t.text.unwrap())
}

/// Reads `.gft` text as a file of `folder` (nothing is written there).
fn read_gft(folder: &Path, text: &str) -> driver::Compiled {
    let name = folder.join("translated.gft");
    driver::compile(SourceFile::new(name.to_string_lossy(), text))
}

#[test]
fn textured_objects_read_back_from_gft_the_same_images_included() {
    for (object, l, file) in [
        ("11-CPFG-TexturedSurfaces", "plant.l", "maple.png"),
        ("11-CPFG-GeneralizedCylinder", "fractal.l", "squares.png"),
        (
            "02-Mod-vis-3D-06-comp-leaf-perspective",
            "leaf.l",
            "leaft.png",
        ),
    ] {
        let (sys, text) = to_gft(object, l);
        assert!(
            text.contains(&format!("texture \"{file}\" filter ")),
            "{object}:\n{text}"
        );
        // Beside the object's images: decoded again, the same pixels.
        let back = read_gft(&corpus(object), &text);
        assert!(
            back.diagnostics.is_empty(),
            "{object}: {:?}",
            back.diagnostics.0
        );
        let back = back.system.unwrap();
        assert!(back.look.textures().iter().all(|t| t.image.is_some()));
        sys.same_as(&back)
            .unwrap_or_else(|e| panic!("{object}: {e}"));
        // Elsewhere: each image a warning at its line (W0904), the
        // system the same but for the pixels it could not read.
        let elsewhere = read_gft(&std::env::temp_dir().join("graftal-no-such-folder"), &text);
        let codes: Vec<&str> = elsewhere.diagnostics.iter().map(|d| d.code.0).collect();
        assert!(
            !codes.is_empty() && codes.iter().all(|&c| c == "W0904"),
            "{codes:?}"
        );
        sys.same_as(&elsewhere.system.unwrap()).unwrap();
    }
    // The surface names its texture and carries its patches' coordinates.
    let (_, text) = to_gft("11-CPFG-TexturedSurfaces", "plant.l");
    let surface = text.lines().find(|l| l.starts_with("surface ")).unwrap();
    assert!(
        surface.ends_with(" texture 1 {") || text.contains("set-texture"),
        "{surface}"
    );
    let first = text
        .lines()
        .skip_while(|l| !l.starts_with("surface "))
        .nth(1)
        .unwrap();
    assert_eq!(first.matches('(').count(), 6, "{first}");
}

#[test]
fn texture_settings_and_coordinates_make_another_system() {
    let (sys, _) = to_gft("11-CPFG-TexturedSurfaces", "plant.l");
    let mut other = sys.clone();
    other.look.lighting.as_mut().unwrap().textures[0].ratio = 2.0;
    assert!(sys.same_as(&other).unwrap_err().contains("look"));
    let mut other = sys.clone();
    other.look.lighting.as_mut().unwrap().textures[0].file = "oak.png".into();
    assert!(sys.same_as(&other).is_err());
    let mut other = sys.clone();
    let m = other
        .surfaces
        .iter_mut()
        .find(|m| !m.patch_uvs.is_empty())
        .unwrap();
    m.patch_uvs[0][0][0] += 0.25;
    assert!(sys.same_as(&other).unwrap_err().contains("surfaces"));
    // Decoded pixels that differ are another system too.
    let mut other = sys.clone();
    let t = &mut other.look.lighting.as_mut().unwrap().textures[0];
    let blank = graftal::ir::texture::Image::new(1, 1, vec![0; 4]).unwrap();
    t.image = Some(std::sync::Arc::new(blank));
    assert!(sys.same_as(&other).unwrap_err().contains("image"));
}

#[test]
fn other_targets_still_say_they_drop_textures() {
    let path = corpus("11-CPFG-TexturedSurfaces/plant.l");
    let c = driver::compile(SourceFile::read(&path).unwrap());
    let sys = c.system.clone().unwrap();
    for to in ["pfg", "linf", "stl"] {
        let req = graftal::back::Request {
            target: graftal::back::by_name(to).unwrap(),
            lossy: false,
            steps: None,
        };
        let t = driver::translate(&c, &sys, &req);
        assert!(
            t.diagnostics.iter().any(|d| d.code.0 == "W0615"),
            "{to}: {:?}",
            t.diagnostics
        );
    }
}

/// The fills of an SVG picture of `sys`.
fn svg_fills(sys: &System) -> Vec<[u8; 3]> {
    let (_, g) = driver::geometry(sys, &RunOptions::default()).unwrap();
    let opts = RenderOptions {
        width: 200,
        height: 200,
        ..RenderOptions::default()
    };
    let svg = String::from_utf8(driver::render_bytes(sys, &g, Format::Svg, opts).unwrap()).unwrap();
    svg.split("fill=\"#")
        .skip(1)
        .filter_map(|rest| {
            let h = |i: usize| u8::from_str_radix(rest.get(i..i + 2)?, 16).ok();
            Some([h(0)?, h(2)?, h(4)?])
        })
        .collect()
}

#[test]
fn an_svg_fills_textured_leaves_with_their_images_shown_colour() {
    let (sys, _) = compile(&corpus("11-CPFG-TexturedSurfaces/plant.l"));
    let sys = sys.unwrap();
    let mut plain = sys.clone();
    plain.look.lighting.as_mut().unwrap().textures.clear();
    let red = |fills: &[[u8; 3]]| {
        fills
            .iter()
            .filter(|c| c[0] > c[1].saturating_add(40))
            .count()
    };
    let (textured, untextured) = (svg_fills(&sys), svg_fills(&plain));
    assert_eq!(textured.len(), untextured.len());
    // The maple image's red modulates the leaves' colour.
    assert!(
        red(&textured) > red(&untextured) + 100,
        "{} red fills textured, {} untextured",
        red(&textured),
        red(&untextured)
    );
}

#[test]
fn generalized_cylinders_wear_their_texture_around_and_along() {
    let (sys, codes) = compile(&corpus("11-CPFG-GeneralizedCylinder/fractal.l"));
    let sys = sys.unwrap();
    assert!(!codes.iter().any(|c| c.0 == "W0814"), "{codes:?}");
    let (_, g) = driver::geometry(&sys, &RunOptions::default()).unwrap();
    let textured: Vec<_> = g
        .polygons
        .iter()
        .filter_map(|p| p.texture.as_ref())
        .collect();
    assert!(
        textured.len() > 100,
        "{} textured quadrilaterals",
        textured.len()
    );
    // `@Tx(2)`: the second texture, circles.png.
    assert!(textured.iter().all(|t| t.texture == 1 && t.uvs.len() == 4));
    let uvs = || textured.iter().flat_map(|t| &t.uvs);
    // Once around the girth; up the cylinder further than one image.
    assert!(uvs().all(|uv| (0.0..=1.0).contains(&uv[0])));
    assert!(uvs().any(|uv| uv[0] == 1.0));
    let top = uvs().map(|uv| uv[1]).fold(0.0, f64::max);
    assert!(top > 1.0, "v reaches {top}");
    // Each quadrilateral's v grows from one ring to the next.
    assert!(textured.iter().all(|t| t.uvs[3][1] >= t.uvs[0][1]));
    // Drawn: the picture differs from the untextured one.
    let mut plain = sys.clone();
    plain.look.lighting.as_mut().unwrap().textures.clear();
    let (a, b) = (draw(&sys, 120), draw(&plain, 120));
    let differ = a.iter().zip(&b).filter(|(x, y)| x != y).count();
    assert!(differ > 500, "{differ} pixels differ");
}

/// cpfg lays a texture on a `{ }` polygon as `SetPolygonTextureParams`
/// does: s across the first vertex's −L, t along its H, the polygon's
/// extent spanning the image once. Clover's ground is light08.rgb so laid.
#[test]
fn polygons_wear_their_texture_across_their_extent() {
    let (sys, _) = compile(&corpus("07-Open-13-clover/plant.l"));
    let sys = sys.unwrap();
    let opts = RunOptions {
        steps: Some(0),
        ..RunOptions::default()
    };
    let (_, g) = driver::geometry(&sys, &opts).unwrap();
    let ground: Vec<_> = g.polygons.iter().filter(|p| p.texture.is_some()).collect();
    assert_eq!(ground.len(), 1, "one textured polygon, the ground");
    let t = ground[0].texture.as_ref().unwrap();
    assert_eq!(t.texture, 0);
    // The square from (-51.25, -51.25): up the turtle's H first (t from 0
    // to 1), then right, along -L (s from 0 to 1).
    let corners: Vec<[i64; 2]> = t
        .uvs
        .iter()
        .map(|[s, t]| [s.round() as i64, t.round() as i64])
        .collect();
    assert_eq!(corners, [[0, 1], [1, 1], [1, 0], [0, 0]]);
    for ([s, t], p) in t.uvs.iter().zip(&ground[0].points) {
        assert!((s - (p[0] + 51.25) / 102.5).abs() < 1e-9, "{s} at {p:?}");
        assert!((t - (p[1] + 51.25) / 102.5).abs() < 1e-9, "{t} at {p:?}");
    }
    // The picture shows the image: its dark middle (a black disc in
    // light08.rgb) and its light crescents, on one flat-coloured polygon.
    let px = draw_steps(&sys, 200, 0);
    let at = |x: usize, y: usize| px[y * 200 + x];
    let middle = at(100, 100);
    assert!(middle.iter().all(|&c| c < 20), "{middle:?}");
    let crescent = at(170, 30);
    assert!(
        crescent[0] > 100 && crescent[0] > crescent[2],
        "{crescent:?}"
    );
}
