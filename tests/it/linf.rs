//! LinF end to end: the paper's semantics (Frenet rotations, randomness,
//! colours, lengths), 3D pictures, and agreement with pfg.

use graftal::driver::{self, RunOptions};
use graftal::front::linf::read_ok;
use graftal::ir::{Rgb, System};
use graftal::render::{self, RenderOptions, View};
use graftal::turtle::{Geometry, Vec3};

fn run(sys: &System, steps: u64, seed: u64) -> Geometry {
    let opts = RunOptions {
        steps: Some(steps),
        seed,
        ..RunOptions::default()
    };
    driver::geometry(sys, &opts).expect("derives and draws").1
}

fn word(sys: &System, steps: u64, seed: u64) -> String {
    let opts = RunOptions {
        steps: Some(steps),
        seed,
        ..RunOptions::default()
    };
    graftal::front::linf::display(sys, &driver::derive(sys, &opts).expect("derives"))
}

fn dir(g: &Geometry, k: usize) -> Vec3 {
    let s = &g.segments[k];
    [s.b[0] - s.a[0], s.b[1] - s.a[1], s.b[2] - s.a[2]]
}

fn close(a: Vec3, b: Vec3) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() < 1e-12)
}

fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[test]
fn fig_10_as_printed_runs_unchanged() {
    let sys = read_ok("lines f\nangles (0, [0 2*pi])\naxiom f\nrules f = f+f\n");
    assert_eq!(word(&sys, 3, 0), "f+f+f+f+f+f+f+f");
    let g = run(&sys, 10, 7);
    assert_eq!(g.segments.len(), 1024);
    // A random walk: unit steps, turning by a different angle each time.
    let turns: Vec<f64> = (1..50)
        .map(|k| dot(dir(&g, k - 1), dir(&g, k)).clamp(-1.0, 1.0).acos())
        .collect();
    assert!(g.segments.iter().all(|s| {
        let d = [s.b[0] - s.a[0], s.b[1] - s.a[1], s.b[2] - s.a[2]];
        (dot(d, d) - 1.0).abs() < 1e-12
    }));
    let mut distinct = turns.clone();
    distinct.sort_by(f64::total_cmp);
    distinct.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    assert!(distinct.len() > 45, "{turns:?}");
    // The walk stays in the plane: no torsion.
    assert!(g.segments.iter().all(|s| s.b[2] == 0.0));
}

#[test]
fn curvature_turns_counter_clockwise_and_torsion_comes_first() {
    // Curvature alone: t turns towards n (left, −x).
    let sys = read_ok("lines f\nangles c = (0, pi/2) r = (pi/2, pi/2)\naxiom f+cf-cf\n");
    let g = run(&sys, 0, 0);
    assert!(close(dir(&g, 0), [0.0, 1.0, 0.0]));
    assert!(close(dir(&g, 1), [-1.0, 0.0, 0.0]));
    assert!(close(dir(&g, 2), [0.0, 1.0, 0.0]));
    // Torsion π/2 first turns n into −b = −z, then curvature π/2 turns t
    // into that n: the step goes down −z. (Curvature first would go −x.)
    let sys = read_ok("lines f\nangles r = (pi/2, pi/2)\naxiom +rf\n");
    let g = run(&sys, 0, 0);
    assert!(close(dir(&g, 0), [0.0, 0.0, -1.0]), "{:?}", dir(&g, 0));
    // `-r` applies the negated pair, which undoes nothing here but mirrors:
    // torsion −π/2 makes n = +b = +z, then curvature −π/2 turns t to −n.
    let sys = read_ok("lines f\nangles r = (pi/2, pi/2)\naxiom -rf\n");
    let g = run(&sys, 0, 0);
    assert!(close(dir(&g, 0), [0.0, 0.0, -1.0]), "{:?}", dir(&g, 0));
    // The equation (2) rotation, composed by hand for a generic pair.
    let (tau, kappa) = (0.3f64, 0.9f64);
    let sys = read_ok("lines f\nangles (0.3, 0.9)\naxiom f+f\n");
    let g = run(&sys, 0, 0);
    // Start: t = +y, n = −x, b = +z. Torsion: n' = −sin τ b + cos τ n.
    let n1 = [-tau.cos(), 0.0, -tau.sin()];
    // Curvature: t' = cos κ t + sin κ n'.
    let t2 = [
        kappa.sin() * n1[0],
        kappa.cos() + kappa.sin() * n1[1],
        kappa.sin() * n1[2],
    ];
    assert!(close(dir(&g, 1), t2), "{:?} vs {t2:?}", dir(&g, 1));
}

#[test]
fn sign_runs_named_angles_and_swapped_turns() {
    let sys = read_ok("lines f\nangles (0, pi/2) h = (0, pi/4)\naxiom ++hf!+f\n");
    let g = run(&sys, 0, 0);
    // ++h: two quarter-of-π/… turns of π/4 each = π/2 left.
    assert!(close(dir(&g, 0), [-1.0, 0.0, 0.0]));
    // ! swaps: + turns right by the default π/2, back to +y.
    assert!(close(dir(&g, 1), [0.0, 1.0, 0.0]));
}

#[test]
fn a_linf_file_and_its_pfg_twin_have_the_same_bounding_box() {
    // LinF `+` turns left (counter-clockwise), pfg `+` right.
    let linf = read_ok("lines f\nangles (0, pi/3)\naxiom f--f--f\nrules f = f+f--f+f\n");
    let pfg = graftal::front::pfg::read_ok("angle factor: 6\naxiom: F++F++F\nF --> F-F++F-F\n");
    for n in 0..5 {
        let opts = RunOptions {
            steps: Some(n),
            ..RunOptions::default()
        };
        let a = driver::stats(&linf, &opts).unwrap();
        let b = driver::stats(&pfg, &opts).unwrap();
        assert_eq!(a.segments, b.segments);
        assert_eq!(a.segments, 3 * 4u128.pow(n as u32));
        let (ab, bb) = (a.bbox.unwrap(), b.bbox.unwrap());
        let size = (bb[3] - bb[0]).max(bb[4] - bb[1]);
        for k in 0..6 {
            assert!(
                (ab[k] - bb[k]).abs() <= 1e-9 * size,
                "n {n}: {ab:?} vs {bb:?}"
            );
        }
    }
}

#[test]
fn interval_angles_are_drawn_per_application_from_the_seed() {
    let sys = read_ok("lines f\nangles w = (0, [0.2 0.5])\naxiom f+wf+wf+wf+wf+wf\n");
    let turns = |seed: u64| -> Vec<f64> {
        let g = run(&sys, 0, seed);
        (1..6)
            .map(|k| dot(dir(&g, k - 1), dir(&g, k)).clamp(-1.0, 1.0).acos())
            .collect()
    };
    let a = turns(1);
    assert!(
        a.iter().all(|t| (0.2 - 1e-12..=0.5 + 1e-12).contains(t)),
        "{a:?}"
    );
    let mut sorted = a.clone();
    sorted.sort_by(f64::total_cmp);
    sorted.dedup();
    assert_eq!(sorted.len(), 5, "one draw per application: {a:?}");
    assert_eq!(turns(1), a, "same seed, same angles");
    assert_ne!(turns(2), a, "another seed, other angles");
}

#[test]
fn guarded_expansion_frequency_matches_its_probability() {
    // 20 000 occurrences of 0.3?a; a -> b. After one step each is b with
    // probability 0.3; after two, 1 − 0.7² = 0.51.
    let axiom = "0.3?a".repeat(20_000);
    let sys = read_ok(&format!("blanks a b\naxiom {axiom}\nrules a = b\n"));
    let count_b = |steps: u64, seed: u64| {
        let opts = RunOptions {
            steps: Some(steps),
            seed,
            ..RunOptions::default()
        };
        let w = driver::derive(&sys, &opts).unwrap();
        let b = sys.symbols.get("b").unwrap();
        w.0.iter().filter(|&&s| s == b).count() as f64
    };
    let n = 20_000.0;
    for (steps, p) in [(1u64, 0.3f64), (2, 0.51)] {
        let got = count_b(steps, 42);
        let sigma = (n * p * (1.0 - p)).sqrt();
        assert!(
            (got - n * p).abs() < 4.0 * sigma,
            "after {steps} steps: {got} of {n}, expected {} ± {sigma:.0}",
            n * p
        );
    }
    // Same seed, same word; another seed, another word.
    assert_eq!(word(&sys, 1, 5), word(&sys, 1, 5));
    assert_ne!(word(&sys, 1, 5), word(&sys, 1, 6));
}

#[test]
fn guarded_symbols_stay_guarded_until_expanded() {
    let sys = read_ok("lines f\naxiom 0.5?i\nrules i = fi\n");
    // Each step the one guarded occurrence expands or stays; once expanded,
    // the new i is unguarded and expands every step.
    for seed in 0..20 {
        let w = word(&sys, 6, seed);
        let fs = w.matches('f').count();
        assert!(w.ends_with('i'), "{w}");
        assert!(fs <= 6, "{w}");
        if w.starts_with("0.5?i") {
            assert_eq!(fs, 0);
        }
    }
    let lengths: std::collections::BTreeSet<usize> =
        (0..40).map(|seed| word(&sys, 6, seed).len()).collect();
    assert!(lengths.len() > 3, "{lengths:?}");
}

#[test]
fn colours_step_forward_stay_on_the_last_and_go_back() {
    let sys = read_ok("lines f\naxiom f{f{f{f}f}f}f[{f]f\ncolors (10,0,0) (20,0,0) (30,0,0)\n");
    let g = run(&sys, 0, 0);
    let reds: Vec<u8> = g.segments.iter().map(|s| s.colour.0).collect();
    // `{` past the last colour stays on it; `}` goes back one `{` at a time;
    // `]` restores the colour of its `[`.
    assert_eq!(reds, [10, 20, 30, 30, 30, 20, 10, 20, 10]);
}

#[test]
fn no_colour_list_draws_black() {
    let sys = read_ok("lines f\naxiom f{f{f\n");
    let g = run(&sys, 0, 0);
    assert!(g.segments.iter().all(|s| s.colour == Rgb(0, 0, 0)));
}

#[test]
fn length_factors_multiply_and_brackets_restore_everything() {
    let sys =
        read_ok("lines f\nangles (0, pi/2)\naxiom f0.5@f[0.5@+{ff]f\ncolors (0,0,0) (9,9,9)\n");
    let g = run(&sys, 0, 0);
    let len = |k: usize| dot(dir(&g, k), dir(&g, k)).sqrt();
    assert!((len(0) - 1.0).abs() < 1e-12);
    assert!((len(1) - 0.5).abs() < 1e-12);
    assert!((len(2) - 0.25).abs() < 1e-12);
    assert_eq!(g.segments[2].colour, Rgb(9, 9, 9));
    // After `]`: the length, heading, position and colour of the `[`.
    assert!((len(4) - 0.5).abs() < 1e-12);
    assert!(close(dir(&g, 4), [0.0, 0.5, 0.0]));
    assert!(close(g.segments[4].a, [0.0, 1.5, 0.0]));
    assert_eq!(g.segments[4].colour, Rgb(0, 0, 0));
}

#[test]
fn colours_reach_svg_and_png() {
    let sys =
        read_ok("lines f\nangles (0, pi/2)\naxiom f{+f{+f\ncolors (200,0,0) (0,200,0) (0,0,200)\n");
    let g = run(&sys, 0, 0);
    let opts = RenderOptions {
        width: 64,
        height: 64,
        ..RenderOptions::default()
    };
    let svg = String::from_utf8(driver::render_bytes(&sys, &g, driver::Format::Svg, opts).unwrap())
        .unwrap();
    for c in ["#c80000", "#00c800", "#0000c8"] {
        assert!(svg.to_lowercase().contains(c), "{c} missing from\n{svg}");
    }
    let pic = render::layout(&g, &opts);
    let pixmap = render::png::draw(&pic).unwrap();
    // Anti-aliased strokes blend with the white background: look for pixels
    // where the colour's channel clearly dominates.
    let has = |channel: usize| {
        pixmap.pixels().iter().any(|p| {
            let c = [p.red() as i32, p.green() as i32, p.blue() as i32];
            (0..3).all(|k| k == channel || c[channel] - c[k] > 120)
        })
    };
    assert!(has(0) && has(1) && has(2));
}

#[test]
fn three_d_views_are_fitted_to_the_projected_box() {
    // A 3D stair: steps along y, then −z (torsion + curvature), then x.
    let sys = read_ok("lines f\nangles r = (pi/2, pi/2) c = (0, pi/2)\naxiom f+rf+cf\n");
    let g = run(&sys, 0, 0);
    assert!(g.bbox().unwrap()[2] < -0.5, "the picture is 3D");
    for (az, el) in [(0.0, 0.0), (30.0, 20.0), (90.0, 0.0), (-60.0, 45.0)] {
        let opts = RenderOptions {
            width: 200,
            height: 100,
            view: View::degrees(az, el),
            ..RenderOptions::default()
        };
        let pic = render::layout(&g, &opts);
        let pts: Vec<[f64; 2]> = pic
            .runs
            .iter()
            .flat_map(|r| r.lines.iter().flatten().copied())
            .collect();
        let (minx, maxx) = pts
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p[0]), b.max(p[0])));
        let (miny, maxy) = pts
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p[1]), b.max(p[1])));
        // Centred, and filling 90% of the picture along the limiting axis.
        assert!(((minx + maxx) / 2.0 - 100.0).abs() < 1e-6, "view {az},{el}");
        assert!(((miny + maxy) / 2.0 - 50.0).abs() < 1e-6, "view {az},{el}");
        let fill = ((maxx - minx) / 200.0).max((maxy - miny) / 100.0);
        assert!((fill - 0.9).abs() < 1e-6, "view {az},{el}: fill {fill}");
    }
}

#[test]
fn nearer_segments_cover_farther_ones_in_the_png() {
    // A red cross-bar at z = +1, drawn first, and a blue one at z = −1,
    // drawn last, crossing at the centre of the picture.
    let sys = read_ok(
        "lines f\nblanks m\n\
         angles r = (pi/2, pi/2) s = (-pi/2, pi/2) c = (0, pi/2) back = (0, pi)\n\
         axiom [{+sm-c+backm+backff][+rm+r+backm+backff]\n\
         colors (0,0,255) (255,0,0)\n",
    );
    let g = run(&sys, 0, 0);
    assert_eq!(g.segments.len(), 4);
    assert!(
        close(g.segments[0].a, [0.0, -1.0, 1.0]),
        "{:?}",
        g.segments[0]
    );
    assert!(
        close(g.segments[3].b, [1.0, 0.0, -1.0]),
        "{:?}",
        g.segments[3]
    );
    let centre = |view: View| {
        let opts = RenderOptions {
            width: 101,
            height: 101,
            view,
            ..RenderOptions::default()
        };
        let pixmap = render::png::draw(&render::layout(&g, &opts)).unwrap();
        let p = pixmap.pixel(50, 50).unwrap();
        (i32::from(p.red()), i32::from(p.blue()))
    };
    let front = centre(View::default());
    assert!(
        front.0 > front.1 + 100,
        "seen from +z the red bar is nearer: {front:?}"
    );
    let back = centre(View::degrees(180.0, 0.0));
    assert!(
        back.1 > back.0 + 100,
        "seen from −z the blue bar is nearer: {back:?}"
    );
}

#[test]
fn derived_words_read_back_as_the_same_symbols() {
    let src =
        "lines f fg g\nangles (0, pi/2) ab = (0, 1)\naxiom x\nrules x = f g fg+abf0.7@[0.5?x]\n";
    let sys = read_ok(src);
    let text = word(&sys, 2, 3);
    let again = read_ok(&format!(
        "lines f fg g\nangles (0, pi/2) ab = (0, 1)\naxiom {text}\nrules x = f\n"
    ));
    let names = |s: &System, w: &graftal::ir::Word| -> Vec<String> {
        w.0.iter()
            .map(|&id| s.symbols.name(id).to_string())
            .collect()
    };
    let opts = RunOptions {
        steps: Some(2),
        seed: 3,
        ..RunOptions::default()
    };
    let w = driver::derive(&sys, &opts).unwrap();
    assert_eq!(names(&sys, &w), names(&again, &again.axiom), "{text}");
    // One-character names are written side by side, as in the paper.
    let koch = read_ok("lines f\nangles (0, pi/3)\naxiom f\nrules f = f+f--f+f\n");
    assert_eq!(word(&koch, 1, 0), "f+f--f+f");
}

#[test]
fn frames_stay_orthonormal_through_a_long_random_walk_in_3d() {
    // Fig. 10 in 3D: 2^18 random Frenet rotations with torsion.
    let sys = read_ok("lines f\nangles ([0 2*pi], [0 2*pi])\naxiom f\nrules f = f+f\n");
    let g = run(&sys, 18, 1);
    assert_eq!(g.segments.len(), 1 << 18);
    let worst = g
        .segments
        .iter()
        .map(|s| {
            let d = [s.b[0] - s.a[0], s.b[1] - s.a[1], s.b[2] - s.a[2]];
            (dot(d, d).sqrt() - 1.0).abs()
        })
        .fold(0.0, f64::max);
    assert!(worst < 1e-12, "step length drifted by {worst:e}");
}

/// The codes and helps of a LinF file's diagnostics.
fn linf_diagnostics(src: &str) -> Vec<(&'static str, String)> {
    let mut d = graftal::diagnostics::Diagnostics::default();
    graftal::front::linf::read(src, &mut d);
    d.iter()
        .map(|d| (d.code.0, d.help.clone().unwrap_or_default()))
        .collect()
}

#[test]
fn a_misspelt_block_keyword_is_one_error_that_suggests_the_keyword() {
    let found = linf_diagnostics("lines f\nangels (0, pi/2)\naxiom f+f\nrules\nf = f+f\n");
    assert_eq!(
        found,
        vec![("E0419", "did you mean `angles`?".to_string())],
        "{found:?}"
    );
}

#[test]
fn an_arrow_for_equals_is_reported_once_and_the_next_line_is_read() {
    let found = linf_diagnostics("lines f\nangles (0, pi/2)\naxiom f\nrules\nf -> f+f\nf = f+g\n");
    let codes: Vec<&str> = found.iter().map(|(c, _)| *c).collect();
    // The arrow once; the rule is read (f defined twice); the next line's
    // own mistake (`g` is no angle) is still found.
    assert_eq!(codes, vec!["E0005", "W0402", "E0403"], "{found:?}");
}

#[test]
fn an_unknown_rotation_suggests_rotation_names_only() {
    let src = "lines stem leaf\nangles (0, pi/2) tilt = (0, 1)\naxiom stem+laef+tilx\n";
    let found = linf_diagnostics(src);
    let helps: Vec<&str> = found.iter().map(|(_, h)| h.as_str()).collect();
    assert!(!helps.iter().any(|h| h.contains("leaf")), "{found:?}");
    assert!(helps.contains(&"did you mean `+tilt`?"), "{found:?}");
}
