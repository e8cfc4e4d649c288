//! `graftal render --animate`: growth animations as GIF and APNG, every
//! frame framed as the last, the last equal to the still picture, and the
//! limits that keep huge animations from hanging.

use crate::common;
use common::{graftal, temp};
use graftal::driver::picture::{self, DrawError, Quiet, Request, Target};
use graftal::driver::{self, RunOptions};
use graftal::render::animate::Container;
use graftal::render::RenderOptions;

/// The frames of a GIF: size, delay (hundredths of a second) and RGBA
/// pixels of each, composed as a viewer shows them.
fn gif_frames(path: &std::path::Path) -> Vec<(u16, u16, u16, Vec<u8>)> {
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::RGBA);
    let mut d = opts
        .read_info(std::fs::File::open(path).unwrap())
        .expect("a GIF");
    let mut out = Vec::new();
    while let Some(f) = d.read_next_frame().unwrap() {
        out.push((f.width, f.height, f.delay, f.buffer.to_vec()));
    }
    out
}

/// An APNG's frames (RGBA), its frame count as its animation control
/// states it, its frame delay and its size.
struct Apng {
    frames: Vec<Vec<u8>>,
    count: u32,
    delay: (u16, u16),
    size: (u32, u32),
}

fn apng_frames(bytes: &[u8]) -> Apng {
    let d = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut r = d.read_info().unwrap();
    let info = r.info();
    let actl = info.animation_control.expect("an animated PNG");
    let size = (info.width, info.height);
    let mut frames = Vec::new();
    let mut delay = (0, 0);
    for _ in 0..actl.num_frames {
        let mut buf = vec![0; r.output_buffer_size().unwrap()];
        r.next_frame(&mut buf).unwrap();
        let fc = r.info().frame_control.expect("a frame control");
        delay = (fc.delay_num, fc.delay_den);
        frames.push(buf);
    }
    Apng {
        frames,
        count: actl.num_frames,
        delay,
        size,
    }
}

/// The RGBA pixels of a still PNG.
fn still(path: &std::path::Path) -> Vec<u8> {
    let bytes = std::fs::read(path).unwrap();
    graftal::render::animate::Frame::from_png(&bytes)
        .unwrap()
        .rgba
}

fn render(args: &[&str]) {
    let o = graftal(args);
    assert_eq!(o.status, 0, "{args:?}: {}", o.stderr);
}

#[test]
fn a_gif_has_a_frame_per_step_at_the_size_and_rate_asked() {
    let out = temp("plant.gif");
    let p = out.to_str().unwrap();
    render(&[
        "render",
        "std:plant-e",
        "-n",
        "3",
        "--animate",
        "--fps",
        "20",
        "--size",
        "120x90",
        "-o",
        p,
    ]);
    let frames = gif_frames(&out);
    // Step 0 (the axiom X) draws nothing: the animation starts at step 1.
    assert_eq!(frames.len(), 3, "steps 1, 2, 3");
    for (w, h, delay, _) in &frames {
        assert_eq!((*w, *h, *delay), (120, 90, 5));
    }
    // A black-and-white drawing has few enough colours for a GIF: the
    // last frame is the still picture.
    let still_path = temp("plant-still.png");
    render(&[
        "render",
        "std:plant-e",
        "-n",
        "3",
        "--size",
        "120x90",
        "-o",
        still_path.to_str().unwrap(),
    ]);
    assert!(frames.last().unwrap().3 == still(&still_path));
}

#[test]
fn the_last_apng_frame_is_the_still_picture() {
    // A context-sensitive plant (drawn from its word), a context-free one
    // (drawn from shared subtrees) and a 3D one.
    for (entry, steps) in [
        ("std:hogeweg-hesper-a", "12"),
        ("std:plant-a", "4"),
        ("std:linf/fig07-plant-3d", "3"),
    ] {
        let out = temp("anim.png");
        let s = temp("still.png");
        let args = ["render", entry, "-n", steps, "--size", "160x128", "-o"];
        let mut animated = args.to_vec();
        animated.extend([out.to_str().unwrap(), "--animate", "--fps", "4"]);
        render(&animated);
        let mut plain = args.to_vec();
        plain.push(s.to_str().unwrap());
        render(&plain);
        let Apng {
            frames,
            count,
            delay,
            size,
        } = apng_frames(&std::fs::read(&out).unwrap());
        let n: usize = steps.parse().unwrap();
        assert_eq!((frames.len(), count as usize), (n + 1, n + 1), "{entry}");
        assert_eq!(size, (160, 128));
        assert_eq!(f64::from(delay.0) / f64::from(delay.1), 0.25, "{entry}");
        assert!(frames.last().unwrap() == &still(&s), "{entry}");
    }
}

/// An animation whose axiom draws nothing (`X`) starts at the first step
/// that draws, not on a blank frame, in a GIF as in an APNG; its last frame
/// is still the still picture.
#[test]
fn an_animation_starts_at_the_first_step_that_draws() {
    let source = temp("bush.l");
    std::fs::write(
        &source,
        "derivation length: 3\nangle factor: 8\naxiom: X\nX --> F[+X]F[-X]+X\n",
    )
    .unwrap();
    let args = ["render", source.to_str().unwrap(), "--size", "64x64", "-o"];
    let (gif, apng, s) = (temp("bush.gif"), temp("bush-anim.png"), temp("bush.png"));
    render(&[&args[..], &[gif.to_str().unwrap(), "--animate"]].concat());
    render(&[&args[..], &[apng.to_str().unwrap(), "--animate"]].concat());
    render(&[&args[..], &[s.to_str().unwrap()]].concat());
    let gif: Vec<Vec<u8>> = gif_frames(&gif).into_iter().map(|f| f.3).collect();
    let apng = apng_frames(&std::fs::read(&apng).unwrap()).frames;
    assert!(
        apng.last() == Some(&still(&s)),
        "the last frame is the still"
    );
    for (name, frames) in [("GIF", gif), ("APNG", apng)] {
        assert_eq!(frames.len(), 3, "{name}: steps 1, 2, 3");
        let first = &frames[0];
        let background = &first[..4];
        assert!(
            first.chunks_exact(4).any(|p| p != background),
            "{name}: the first frame is all background"
        );
        assert!(
            ink(first).contains(&true),
            "{name}: no dark pixel in frame 1"
        );
    }
}

/// The dark pixels of an RGBA frame.
fn ink(rgba: &[u8]) -> Vec<bool> {
    rgba.chunks_exact(4).map(|p| p[0] < 128).collect()
}

/// A Smith plant keeps each branch where it was drawn (its angles are
/// nailed): wherever step n+1 draws every segment of step n, frame n's
/// ink is still there in frame n+1, because every frame is fitted as the
/// last one. Fitted each on its own, the young plant would fill the
/// picture and shrink from frame to frame.
#[test]
fn a_smith_plant_grows_in_place() {
    let c = driver::compile(driver::load("std:smith/white-sands").unwrap());
    let sys = c.system.as_ref().unwrap();
    let steps = 20;
    let segments = |n: u64| {
        let opts = RunOptions {
            steps: Some(n),
            ..RunOptions::default()
        };
        let (_, g) = driver::geometry(sys, &opts).unwrap();
        let key = |p: [f64; 3]| p.map(|x| (x * 1e6).round() as i64);
        g.segments
            .iter()
            .map(|s| (key(s.a), key(s.b)))
            .collect::<std::collections::BTreeSet<_>>()
    };
    let out = temp("smith.gif");
    render(&[
        "render",
        "std:smith/white-sands",
        "-n",
        &steps.to_string(),
        "--animate",
        "--size",
        "160x160",
        "-o",
        out.to_str().unwrap(),
    ]);
    let frames = gif_frames(&out);
    assert_eq!(frames.len(), steps + 1);
    let mut grown_in_place = 0;
    for n in 1..steps as u64 {
        if !segments(n).is_subset(&segments(n + 1)) {
            continue;
        }
        grown_in_place += 1;
        let (before, after) = (ink(&frames[n as usize].3), ink(&frames[n as usize + 1].3));
        let lost = before
            .iter()
            .zip(&after)
            .filter(|(b, a)| **b && !**a)
            .count();
        assert_eq!(
            lost,
            0,
            "frame {n}: {lost} pixels of ink gone in frame {}",
            n + 1
        );
    }
    let inked = |k: usize| ink(&frames[k].3).iter().filter(|i| **i).count();
    assert!(inked(steps) > 4 * inked(2), "the plant grows");
    assert!(
        grown_in_place >= 4,
        "{grown_in_place} steps grow at the tips only"
    );
}

#[test]
fn an_animation_is_bounded_in_frames_and_moves() {
    // Too many frames: refused before anything is derived.
    let out = temp("long.gif");
    let o = graftal(&[
        "render",
        "std:algae",
        "-n",
        "5000",
        "--animate",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status, 2, "{}", o.stderr);
    assert!(o.stderr.contains("frames"), "{}", o.stderr);
    // A last frame too large to draw: known before deriving.
    let o = graftal(&[
        "render",
        "std:koch-island",
        "-n",
        "9",
        "--animate",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status, 1, "{}", o.stderr);
    assert!(o.stderr.contains("E0303"), "{}", o.stderr);
    // Frames that together move the turtle too often: the last fits the
    // limit, all of them do not.
    let c = driver::compile(driver::load("std:smith/white-sands").unwrap());
    let sys = c.system.as_ref().unwrap();
    let at = |n| RunOptions {
        steps: Some(n),
        ..RunOptions::default()
    };
    let last = driver::geometry(sys, &at(20)).unwrap().1.segments.len();
    let opts = RunOptions {
        max_moves: last + 1,
        ..at(20)
    };
    let req = Request {
        run: opts,
        width: 32,
        height: 32,
        ..Request::new(Target::Animation(Container::Gif))
    };
    let Err(DrawError::Stopped(d)) = picture::draw_system(sys, &req, &mut Quiet) else {
        panic!("over the limit in all");
    };
    assert_eq!(d.code, graftal::diagnostics::codes::TOO_MUCH_GEOMETRY);
    assert!(
        d.notes.iter().any(|n| n.contains("in all its frames")),
        "{d:?}"
    );
}

#[test]
fn an_animation_needs_a_gif_or_png_output() {
    let o = graftal(&["render", "std:plant-e", "--animate", "-o", "x.svg"]);
    assert_eq!(o.status, 2);
    assert!(o.stderr.contains("GIF"), "{}", o.stderr);
}

/// The progress bars (derive, draw, frames) show on a terminal only: a
/// run with stderr to a pipe writes nothing there, one in a
/// pseudo-terminal (`script`) shows the frames counted.
#[test]
fn progress_shows_on_a_terminal_never_in_a_pipe() {
    let out = temp("progress.gif");
    let args = [
        "render",
        "std:hogeweg-hesper-a",
        "--animate",
        "--size",
        "64x64",
        "-o",
        out.to_str().unwrap(),
    ];
    let piped = std::process::Command::new(env!("CARGO_BIN_EXE_graftal"))
        .args(args)
        .env_remove("CI")
        .output()
        .unwrap();
    assert!(piped.status.success());
    assert!(
        piped.stderr.is_empty(),
        "{:?}",
        String::from_utf8_lossy(&piped.stderr)
    );
    // util-linux's `script` runs the command in a pseudo-terminal.
    let line = format!("{} {}", env!("CARGO_BIN_EXE_graftal"), args.join(" "));
    let Ok(tty) = std::process::Command::new("script")
        .args(["-q", "-e", "-c", &line, "/dev/null"])
        .env_remove("CI")
        .output()
    else {
        eprintln!("no `script` here: the terminal half is not checked");
        return;
    };
    assert!(tty.status.success(), "{tty:?}");
    let shown = String::from_utf8_lossy(&tty.stdout);
    assert!(shown.contains("/31 frames"), "{shown}");
}

/// An outline's growth (STL, Yeh, Chien & Lee's Figs. 9 and 10) has no
/// derivation steps: its frames replay the stems in the order growth made
/// them, each frame keeping every stem of the one before, the last the
/// still picture.
#[test]
fn an_outline_grows_stem_by_stem() {
    for entry in ["std:stl/fig09-outline-bfs", "std:stl/fig10-outline-dfs"] {
        let c = driver::compile(driver::load(entry).unwrap());
        let sys = c.system.as_ref().unwrap();
        let st = sys.structure.as_ref().unwrap();
        let order = graftal::layout::seed::growth_order(&mut sys.clone(), st)
            .unwrap()
            .expect("an outline grows");
        assert_eq!(order.word, sys.axiom, "{entry}");
        let expected = u64::from(order.stems).min(graftal::render::animate::GROWTH_FRAMES);
        assert!(expected > 20, "{entry}: {} stems", order.stems);
        let (out, s) = (temp("grow.png"), temp("grow-still.png"));
        let args = ["render", entry, "--size", "96x96", "-o"];
        let mut animated = args.to_vec();
        animated.extend([out.to_str().unwrap(), "--animate"]);
        render(&animated);
        let mut plain = args.to_vec();
        plain.push(s.to_str().unwrap());
        render(&plain);
        let Apng { frames, count, .. } = apng_frames(&std::fs::read(&out).unwrap());
        assert_eq!(
            (frames.len() as u64, u64::from(count)),
            (expected, expected)
        );
        assert!(frames.last().unwrap() == &still(&s), "{entry}");
        let inked: Vec<Vec<bool>> = frames.iter().map(|f| ink(f)).collect();
        for k in 1..inked.len() {
            let lost = (inked[k - 1].iter().zip(&inked[k]))
                .filter(|(b, a)| **b && !**a)
                .count();
            assert_eq!(lost, 0, "{entry}: frame {k} loses {lost} pixels of ink");
        }
        let count = |k: usize| inked[k].iter().filter(|i| **i).count();
        assert!(
            count(0) > 0 && count(0) * 4 < count(inked.len() - 1),
            "{entry}"
        );
    }
}

/// A lit system is drawn by the z-buffer renderer, whose fit counts the
/// cylinders' radii: the animation frames as that renderer does, so that
/// its last frame is the still picture.
#[test]
fn the_last_frame_of_a_lit_system_is_its_still() {
    use graftal::ir::look::{Lighting, LineStyle};
    let c = driver::compile(driver::load("std:plant-e").unwrap());
    let mut sys = c.system.unwrap();
    sys.settings.width = 3.0;
    sys.look.lighting = Some(Lighting {
        line_style: LineStyle::Cylinder,
        ..Lighting::default()
    });
    let opts = RunOptions {
        steps: Some(2),
        ..RunOptions::default()
    };
    let ropts = RenderOptions {
        width: 64,
        height: 48,
        ..RenderOptions::default()
    };
    let req = Request {
        run: opts.clone(),
        width: 64,
        height: 48,
        layout: false,
        ..Request::new(Target::Animation(Container::Apng))
    };
    let bytes = picture::draw_system(&sys, &req, &mut Quiet).unwrap().bytes;
    let Apng { frames, .. } = apng_frames(&bytes);
    assert_eq!(frames.len(), 2, "steps 1 and 2: the axiom X draws nothing");
    let (_, g) = driver::geometry(&sys, &opts).unwrap();
    let png = driver::render_bytes(&sys, &g, driver::Format::Png, ropts).unwrap();
    let still = graftal::render::animate::Frame::from_png(&png)
        .unwrap()
        .rgba;
    assert!(frames.last().unwrap() == &still);
}
