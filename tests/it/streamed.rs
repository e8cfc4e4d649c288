//! Drawings streamed from the turtle into a coverage buffer
//! (`driver::picture`'s streamed way) against the same drawings with every
//! segment stored and stroked ([`driver::render_bytes`]), pixel by pixel as
//! the shared-subtree path is tested; and the narrow words that the
//! streamed path and `derive` to a pipe hold.

use graftal::driver::picture::{self, Method, Quiet, Request, Target};
use graftal::driver::{self, Format, RunOptions};
use graftal::ir::System;
use graftal::render::coverage::Coverage;
use graftal::render::{Palette, RenderOptions, Style};

fn system(spec: &str) -> System {
    let c = driver::compile(driver::load(spec).unwrap());
    c.system.expect("a system")
}

/// Grey levels (0 black .. 255 white) of a PNG.
fn greys(bytes: &[u8]) -> Vec<f64> {
    let pm = tiny_skia::Pixmap::decode_png(bytes).expect("a PNG");
    pm.pixels()
        .iter()
        .map(|p| {
            let c = p.demultiply();
            (f64::from(c.red()) + f64::from(c.green()) + f64::from(c.blue())) / 3.0
        })
        .collect()
}

fn opts(steps: u64) -> RunOptions {
    RunOptions {
        steps: Some(steps),
        ..RunOptions::default()
    }
}

fn sized(size: u32) -> RenderOptions {
    RenderOptions {
        width: size,
        height: size,
        ..RenderOptions::default()
    }
}

/// The PNG `ropts` asks for, when the one call for a picture draws it
/// streamed.
fn streamed(sys: &System, run: &RunOptions, ropts: RenderOptions) -> Option<Vec<u8>> {
    let req = Request {
        run: run.clone(),
        width: ropts.width,
        height: ropts.height,
        view: Some(ropts.view),
        style: ropts.style,
        ..Request::new(Target::Still(Format::Png))
    };
    let p = picture::draw_system(sys, &req, &mut Quiet).unwrap();
    (p.method == Method::Streamed).then_some(p.bytes)
}

fn stored(sys: &System, run: &RunOptions, ropts: RenderOptions) -> Vec<u8> {
    let (_, g) = driver::geometry(sys, run).unwrap();
    driver::render_bytes(sys, &g, Format::Png, ropts).unwrap()
}

/// The mean of `px` over blocks of `k` × `k` pixels of a `size`-wide
/// picture: what the eye sees of detail finer than `k` pixels.
fn blocks(px: &[f64], size: usize, k: usize) -> Vec<f64> {
    let n = size / k;
    let mut out = vec![0.0; n * n];
    for y in 0..n * k {
        for x in 0..n * k {
            out[(y / k) * n + x / k] += px[y * size + x] / (k * k) as f64;
        }
    }
    out
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

/// A context-sensitive plant is drawn streamed, and looks as the stored
/// drawing of every segment does: the same ink in all, and the same ink
/// in each 8 × 8 block within a few grey levels on average.
#[test]
fn a_streamed_plant_looks_as_every_segment_stroked() {
    let sys = system("std:hogeweg-hesper-a");
    for (steps, size) in [(20, 128), (30, 256)] {
        let run = opts(steps);
        let a = greys(&streamed(&sys, &run, sized(size)).expect("streamed"));
        let b = greys(&stored(&sys, &run, sized(size)));
        let (ink_a, ink_b) = (255.0 - mean(&a), 255.0 - mean(&b));
        assert!(ink_b > 1.0, "the stored drawing draws something");
        assert!(
            (ink_a - ink_b).abs() < 0.12 * ink_b,
            "n={steps}: ink {ink_a:.2} streamed vs {ink_b:.2} stored"
        );
        let (ba, bb) = (blocks(&a, size as usize, 8), blocks(&b, size as usize, 8));
        let diff = ba.iter().zip(&bb).map(|(x, y)| (x - y).abs()).sum::<f64>() / ba.len() as f64;
        assert!(
            diff < 3.0,
            "n={steps}: blocks differ by {diff:.2} grey levels"
        );
    }
}

/// Lines closer together than a pixel's width show their density as grey,
/// in proportion to the area they cover: half-pixel lines a pixel apart
/// are mid grey, not black.
#[test]
fn lines_finer_than_a_pixel_are_grey_in_proportion() {
    let mut c = Coverage::new(40, 40, graftal::ir::Rgb(255, 255, 255), 255).unwrap();
    let k = c.paint(graftal::ir::Rgb(0, 0, 0)).unwrap();
    for i in 0..40 {
        let x = f64::from(i) + 0.5;
        c.line([x, -5.0], [x, 45.0], 0.5, k);
    }
    let rgba = c.rgba();
    let grey: Vec<u8> = rgba.chunks(4).map(|p| p[0]).collect();
    assert!(grey.iter().all(|&g| (100..=156).contains(&g)), "{grey:?}");
    // Lines a whole pixel wide at the same places cover it all.
    for i in 0..40 {
        let x = f64::from(i) + 0.5;
        c.line([x, -5.0], [x, 45.0], 1.0, k);
    }
    assert!(c.rgba().chunks(4).all(|p| p[0] == 0));
}

/// A line covers the pixels a stroke of its width covers: a horizontal
/// line 2 pixels wide on pixel boundaries blackens exactly two rows, and
/// its round ends reach half its width past its end points.
#[test]
fn a_line_covers_its_width_and_round_ends() {
    let mut c = Coverage::new(20, 20, graftal::ir::Rgb(255, 255, 255), 255).unwrap();
    let k = c.paint(graftal::ir::Rgb(0, 0, 0)).unwrap();
    c.line([5.0, 10.0], [15.0, 10.0], 2.0, k);
    let rgba = c.rgba();
    let at = |x: usize, y: usize| rgba[(y * 20 + x) * 4];
    for x in 5..15 {
        assert_eq!((at(x, 9), at(x, 10)), (0, 0), "x={x}");
        assert_eq!((at(x, 8), at(x, 11)), (255, 255), "x={x}");
    }
    // The ends are round: grey past the end points, white beyond.
    assert!(at(4, 9) > 0 && at(4, 9) < 255, "{}", at(4, 9));
    assert_eq!(at(2, 9), 255);
}

/// What needs storage is handed back: a 3D drawing seen from the side
/// (the painter's order), polygons. What is flat streams, rotated or not.
#[test]
fn drawings_that_need_storage_are_not_streamed() {
    let run = RunOptions::default();
    let side = RenderOptions {
        view: graftal::render::View::degrees(30.0, 20.0),
        ..sized(64)
    };
    let tape = system("std:paper-tape");
    assert!(streamed(&tape, &run, side).is_none());
    let polygons = system("std:filled-polygon");
    assert!(streamed(&polygons, &run, sized(64)).is_none());
    let flat = system("std:hogeweg-hesper-a");
    let turned = RenderOptions {
        style: Style {
            rotate: 30.0,
            palette: Some(Palette::Mono),
            ..Style::default()
        },
        ..sized(64)
    };
    let (a, b) = (
        greys(&streamed(&flat, &opts(12), turned).expect("streamed")),
        greys(&stored(&flat, &opts(12), turned)),
    );
    let (ink_a, ink_b) = (255.0 - mean(&a), 255.0 - mean(&b));
    assert!((ink_a - ink_b).abs() < 0.15 * ink_b, "{ink_a} vs {ink_b}");
}

/// The narrow word is the word: the same symbols as the derivation's
/// [`graftal::ir::Word`], for a byte alphabet and a context-free system.
#[test]
fn narrow_words_are_the_derived_words() {
    for (spec, steps) in [("std:hogeweg-hesper-a", 12), ("std:koch-island", 3)] {
        let sys = system(spec);
        let w = driver::derive(&sys, &opts(steps)).unwrap();
        let narrow = driver::derive_symbols(&sys, &opts(steps), |_, _| {}).unwrap();
        assert_eq!(narrow.len(), w.len());
        assert!(narrow.iter().eq(w.0.iter().copied()), "{spec}");
    }
}

/// The 8 × 8 blocks of a `size`-wide picture that have ink: the crown.
fn crown(px: &[f64], size: usize) -> Vec<f64> {
    blocks(px, size, 8)
        .into_iter()
        .filter(|&g| g < 254.0)
        .collect()
}

/// A dense crown shows its density: Fig. 3.11a drawn so densely that its
/// lines at their default width would cover it many times over is drawn
/// with thinner lines, as hairlines whose coverage is their width, so its
/// crown is grey (between 20 % and 80 % ink on average) and darker where
/// more lines run, not a solid black mass; and the stored drawing of every
/// segment agrees with the streamed one.
#[test]
fn a_dense_crown_shows_its_density() {
    let sys = system("std:hogeweg-hesper-a");
    let (run, size) = (opts(DENSE_STEPS), 256);
    let a = greys(&streamed(&sys, &run, sized(size)).expect("streamed"));
    let crown_a = crown(&a, size as usize);
    let ink = 1.0 - mean(&crown_a) / 255.0;
    assert!((0.2..=0.8).contains(&ink), "crown ink {ink:.2}");
    let spread = crown_a
        .iter()
        .map(|g| (g - mean(&crown_a)).abs())
        .sum::<f64>()
        / crown_a.len() as f64;
    assert!(
        spread > 15.0,
        "the crown is uniform: {spread:.1} grey levels"
    );
    let solid = crown_a.iter().filter(|&&g| g < 13.0).count();
    assert!(
        solid * 20 < crown_a.len(),
        "{solid} of {} blocks black",
        crown_a.len()
    );
    let b = greys(&stored(&sys, &run, sized(size)));
    let (ink_a, ink_b) = (255.0 - mean(&a), 255.0 - mean(&b));
    assert!(
        (ink_a - ink_b).abs() < 0.12 * ink_b,
        "ink {ink_a:.2} streamed vs {ink_b:.2} stored"
    );
    let (ba, bb) = (blocks(&a, size as usize, 8), blocks(&b, size as usize, 8));
    let diff = ba.iter().zip(&bb).map(|(x, y)| (x - y).abs()).sum::<f64>() / ba.len() as f64;
    assert!(diff < 4.0, "blocks differ by {diff:.2} grey levels");
}

/// Steps at which Fig. 3.11a's crown is dense at 256 pixels.
const DENSE_STEPS: u64 = 40;
