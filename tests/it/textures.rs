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
    let (_, g) = driver::geometry(sys, &RunOptions::default()).unwrap();
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
