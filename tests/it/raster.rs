//! Systems whose look is lit are drawn by the z-buffer renderer, on their
//! look's background, through their camera unless a view is asked for;
//! the others as before.

use graftal::driver::picture::{self, Method, Quiet, Request, Target};
use graftal::driver::{self, Format, RunOptions};
use graftal::ir::look::{Camera, Lighting};
use graftal::ir::{Rgb, System};
use graftal::render::{RenderOptions, View};

fn system(spec: &str) -> System {
    let c = driver::compile(driver::load(spec).unwrap());
    c.system.expect("a system")
}

fn pixels(bytes: &[u8]) -> Vec<[u8; 3]> {
    let pm = tiny_skia::Pixmap::decode_png(bytes).expect("a PNG");
    pm.pixels()
        .iter()
        .map(|p| {
            let c = p.demultiply();
            [c.red(), c.green(), c.blue()]
        })
        .collect()
}

fn render(sys: &System, format: Format, ropts: RenderOptions) -> Vec<u8> {
    let (_, g) = driver::geometry(sys, &RunOptions::default()).unwrap();
    driver::render_bytes(sys, &g, format, ropts).unwrap()
}

fn small() -> RenderOptions {
    RenderOptions {
        width: 64,
        height: 64,
        ..RenderOptions::default()
    }
}

#[test]
fn a_lit_look_draws_on_its_background() {
    let mut sys = system("std:plant-e");
    sys.look.background = Some(Rgb(0, 0, 40));
    sys.look.lighting = Some(Lighting::default());
    let px = pixels(&render(&sys, Format::Png, small()));
    // The corners are the background; something else is drawn.
    assert_eq!(px[0], [0, 0, 40]);
    assert_eq!(px[64 * 64 - 1], [0, 0, 40]);
    assert!(px.iter().any(|p| *p != [0, 0, 40]));
    // The shared-subtree path is not taken for it.
    let req = Request {
        width: 64,
        height: 64,
        ..Request::new(Target::Still(Format::Png))
    };
    let drawn = picture::draw_system(&sys, &req, &mut Quiet).unwrap();
    assert_ne!(drawn.method, Method::SharedSubtrees);
    // SVG: the same background.
    let svg = String::from_utf8(render(&sys, Format::Svg, small())).unwrap();
    assert!(svg.contains(r##"fill="#000028""##), "{svg:.300}");
}

#[test]
fn a_flat_look_keeps_its_picture_but_takes_its_background() {
    let plain = system("std:plant-e");
    let mut dark = plain.clone();
    dark.look.background = Some(Rgb(10, 10, 10));
    let (a, b) = (
        pixels(&render(&plain, Format::Png, small())),
        pixels(&render(&dark, Format::Png, small())),
    );
    assert_eq!(a[0], [255, 255, 255]);
    assert_eq!(b[0], [10, 10, 10]);
    // Where the plant is drawn, both draw it (edges blend with the
    // background).
    let drawn = a.iter().zip(&b).filter(|(p, _)| p[0] < 50).count();
    assert!(drawn > 50);
    assert!(a
        .iter()
        .zip(&b)
        .filter(|(p, _)| p[0] < 50)
        .all(|(_, q)| q[0] < 80));
}

#[test]
fn an_asked_for_view_overrides_the_camera() {
    let mut sys = system("std:plant-e");
    sys.look.lighting = Some(Lighting::default());
    let face_on = render(&sys, Format::Png, small());
    // Seen from the side (+x), the flat plant is a line.
    sys.look.camera = Some(Camera {
        eye: [10.0, 0.0, 0.0],
        target: [0.0; 3],
        up: [0.0, 1.0, 0.0],
        perspective: None,
    });
    let side = render(&sys, Format::Png, small());
    assert_ne!(face_on, side);
    let given = RenderOptions {
        view: View::default(),
        view_given: true,
        ..small()
    };
    assert_eq!(render(&sys, Format::Png, given), face_on);
}
