//! The one call for a picture (`driver::picture`): every face draws
//! through it, so the gallery's pictures and an animation's last frame are
//! the ones `graftal render` writes for the same request, and the method
//! it chooses follows from the system and the request.

use graftal::diagnostics::codes;
use graftal::driver::picture::{self, Format, Method, Quiet, Request, Source, Target};
use graftal::driver::{compile, load, RunOptions};
use std::path::{Path, PathBuf};
use std::process::Command;

fn graftal(args: &[&str]) -> std::process::Output {
    let out = Command::new(env!("CARGO_BIN_EXE_graftal"))
        .args(args)
        .env("CI", "1")
        .output()
        .expect("graftal runs");
    assert!(
        out.status.success(),
        "graftal {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("graftal-picture-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// The pixels of a PNG (its first frame, for an animated one), and of each
/// frame of an animated PNG.
fn frames(png_bytes: &[u8]) -> Vec<Vec<u8>> {
    let decoder = png::Decoder::new(std::io::Cursor::new(png_bytes));
    let mut reader = decoder.read_info().unwrap();
    let count = reader
        .info()
        .animation_control()
        .map_or(1, |a| a.num_frames as usize);
    let mut out = Vec::new();
    for _ in 0..count {
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        buf.truncate(info.buffer_size());
        out.push(buf);
    }
    out
}

fn cpfg(object: &str) -> String {
    format!(
        "{}/tests/corpus/cpfg/{object}/plant.l",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// What method `spec` is drawn by, to `target`, with `steps`.
fn method(spec: &str, steps: Option<u64>, target: Target) -> Method {
    let c = compile(load(spec).unwrap());
    let req = Request {
        run: RunOptions {
            steps,
            ..RunOptions::default()
        },
        width: 256,
        height: 256,
        ..Request::new(target)
    };
    picture::draw(&c, &req, &mut Quiet).unwrap().method
}

#[test]
fn the_method_follows_from_the_system_and_the_request() {
    let png = Target::Still(Format::Png);
    let svg = Target::Still(Format::Svg);
    // A context-free 2D system: its shared tree, for PNG and SVG alike.
    assert_eq!(
        method("std:koch-island", Some(4), png),
        Method::SharedSubtrees
    );
    assert_eq!(
        method("std:koch-island", Some(4), svg),
        Method::SharedSubtrees
    );
    // A context-sensitive one to PNG: streamed; to SVG: stored.
    assert_eq!(
        method("std:hogeweg-hesper-a", Some(20), png),
        Method::Streamed
    );
    assert_eq!(
        method("std:hogeweg-hesper-a", Some(20), svg),
        Method::Stored
    );
    // A lit cpfg object to PNG: lit; to SVG: stored.
    let lychnis = cpfg("10-GettingStarted-01-Lychnis");
    assert_eq!(method(&lychnis, Some(30), png), Method::Lit);
    assert_eq!(method(&lychnis, Some(30), svg), Method::Stored);
    // Meshes: a context-free tree instanced in glTF, flat in OBJ.
    let glb = Target::Mesh(graftal::mesh::MeshFormat::Glb);
    let obj = Target::Mesh(graftal::mesh::MeshFormat::Obj);
    assert_eq!(method("std:plant-e", Some(3), glb), Method::InstancedMesh);
    assert_eq!(method("std:plant-e", Some(3), obj), Method::Mesh);
}

/// The box of the inked pixels of a PNG: `[left, top, right, bottom]`.
fn inked_box(png: &[u8]) -> [u32; 4] {
    let p = tiny_skia::Pixmap::decode_png(png).expect("a PNG");
    let mut b = [u32::MAX, u32::MAX, 0, 0];
    for (i, c) in p.pixels().iter().enumerate() {
        if u32::from(c.red()) + u32::from(c.green()) + u32::from(c.blue()) < 3 * 128 {
            let (x, y) = (i as u32 % p.width(), i as u32 / p.width());
            b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
        }
    }
    b
}

#[test]
fn a_picture_larger_than_floating_point_is_drawn_as_it_converges() {
    // The Koch island 4 times wider a step: past the largest f64 in turtle
    // units from 512 steps. Drawn in the unit of its top level, its shape
    // is the one it converges to: the picture of 400 steps, and of 5 steps
    // in outline.
    let c = compile(load("std:koch-island").unwrap());
    let draw = |n| {
        let req = Request {
            run: RunOptions {
                steps: Some(n),
                ..RunOptions::default()
            },
            width: 128,
            height: 128,
            ..Request::new(Target::Still(Format::Png))
        };
        let p = picture::draw(&c, &req, &mut Quiet).unwrap_or_else(|e| panic!("n={n}: {e}"));
        assert_eq!(p.method, Method::SharedSubtrees, "n={n}");
        p.bytes
    };
    let deep = draw(600);
    assert!(deep == draw(400), "600 steps drawn unlike 400");
    assert!(deep == draw(4096), "4096 steps drawn unlike 600");
    let [l, t, r, b] = inked_box(&deep);
    let [l5, t5, r5, b5] = inked_box(&draw(5));
    assert!(r > l + 100 && b > t + 100, "{:?}", [l, t, r, b]);
    for (a, a5) in [(l, l5), (t, t5), (r, r5), (b, b5)] {
        assert!(
            a.abs_diff(a5) <= 2,
            "{:?} vs {:?}",
            [l, t, r, b],
            [l5, t5, r5, b5]
        );
    }
}

#[test]
fn a_gallery_picture_is_what_render_writes() {
    // One entry drawn from its shared tree, one streamed, one stored (a
    // kolam, drawn as a spline).
    for name in ["koch-island", "hogeweg-hesper-a", "kolam-anklets"] {
        let entry = graftal::stdlib::get(name).unwrap_or_else(|| panic!("std:{name}"));
        let gallery = graftal::gallery::pictures(entry);
        let out = scratch(&format!("{name}.png"));
        let size = format!("{0}x{0}", graftal::gallery::SIZE);
        graftal(&[
            "render",
            &format!("std:{name}"),
            "--size",
            &size,
            "-o",
            out.to_str().unwrap(),
        ]);
        let rendered = std::fs::read(&out).unwrap();
        assert!(
            gallery.png.as_deref() == Some(rendered.as_slice()),
            "std:{name}: the gallery's PNG is not what `graftal render` writes"
        );
    }
}

#[test]
fn an_animations_last_frame_is_what_render_writes() {
    let lychnis = cpfg("10-GettingStarted-01-Lychnis");
    // With the first step that draws: plant-e's axiom X and Lychnis's
    // apex A(0) draw nothing, so their animations start at step 1.
    let cases = [
        ("std:koch-island", "3", 0),
        ("std:hogeweg-hesper-a", "12", 0),
        ("std:plant-e", "4", 1),
        (lychnis.as_str(), "12", 1),
    ];
    for (spec, steps, first) in cases {
        let still = scratch("still.png");
        let anim = scratch("anim.png");
        let common = ["-n", steps, "--size", "200x160"];
        let path = |p: &Path| p.to_str().unwrap().to_string();
        let mut args = vec!["render", spec];
        args.extend(common);
        let (still_path, anim_path) = (path(&still), path(&anim));
        graftal(&[args.as_slice(), &["-o", &still_path]].concat());
        graftal(&[args.as_slice(), &["--animate", "-o", &anim_path]].concat());
        let still_frames = frames(&std::fs::read(&still).unwrap());
        let anim_frames = frames(&std::fs::read(&anim).unwrap());
        assert_eq!(
            anim_frames.len(),
            steps.parse::<usize>().unwrap() + 1 - first,
            "{spec}"
        );
        assert!(
            anim_frames.last() == still_frames.first(),
            "{spec}: the animation's last frame is not the still `graftal render` draws"
        );
    }
}

#[test]
fn make_reads_text_and_says_what_is_wrong() {
    let req = Request::new(Target::Still(Format::Svg));
    let good = Source::Text {
        name: "koch.l".into(),
        text: "derivation length: 2\nangle factor: 4\naxiom: F-F-F-F\nF --> F+F-F-F+F\n".into(),
    };
    let made = picture::make(&good, None, None, &req, &mut Quiet);
    let p = made.picture.unwrap();
    assert!(String::from_utf8(p.bytes).unwrap().starts_with("<svg"));
    let bad = Source::Text {
        name: "bad.l".into(),
        text: "axiom: F\nF -> F\n".into(),
    };
    let made = picture::make(&bad, None, None, &req, &mut Quiet);
    assert!(matches!(made.picture, Err(picture::DrawError::NotCompiled)));
    assert!(made.compiled.unwrap().diagnostics.has_errors());
    let missing = Source::Spec("std:no-such-entry".into());
    let made = picture::make(&missing, None, None, &req, &mut Quiet);
    assert!(matches!(made.picture, Err(picture::DrawError::NotRead(_))));
    // An empty picture says so.
    let empty = Source::Text {
        name: "empty.l".into(),
        text: "derivation length: 2\naxiom: A\nA --> AB\n".into(),
    };
    let made = picture::make(&empty, None, None, &req, &mut Quiet);
    let p = made.picture.unwrap();
    assert!(p.warnings.iter().any(|d| d.code == codes::NOTHING_DRAWN));
}
