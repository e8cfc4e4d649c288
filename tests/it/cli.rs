//! The command-line contract: commands, exit statuses, output formats,
//! `std:NAME`, seeds and byte-identical output.

use crate::common;
use common::{graftal, graftal_bytes, temp};

#[test]
fn derive_prints_the_word() {
    let o = graftal(&["derive", "std:algae", "-n", "5"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert_eq!(o.stdout, "abaababa\n");
    // Default: the file's own derivation length (anabaena: 4).
    assert_eq!(graftal(&["derive", "std:anabaena"]).stdout, "bAbAAbAA\n");
}

#[test]
fn exit_statuses() {
    let bad = temp("bad.l");
    std::fs::write(&bad, "axiom: F\nF -> F\n").unwrap();
    let o = graftal(&["check", bad.to_str().unwrap()]);
    assert_eq!(o.status, 1);
    assert!(o.stderr.contains("E0005"), "{}", o.stderr);
    assert_eq!(graftal(&["check", "std:koch-island"]).status, 0);
    assert_eq!(graftal(&["check", "/no/such/file.l"]).status, 2);
    assert_eq!(graftal(&["check", "std:no-such-thing"]).status, 2);
    assert_eq!(graftal(&["derive"]).status, 2);
    assert_eq!(
        graftal(&["render", "std:koch-island", "-o", "x.gif"]).status,
        2
    );
    // Warnings alone do not fail.
    let warn = temp("warn.l");
    std::fs::write(&warn, "axiom: F\nderivation length: 1\n").unwrap();
    let o = graftal(&["derive", warn.to_str().unwrap()]);
    assert_eq!(o.status, 0);
    assert!(o.stderr.contains("W0001"));
}

#[test]
fn too_many_symbols_is_an_error_with_status_1() {
    let o = graftal(&[
        "derive",
        "std:koch-island",
        "-n",
        "12",
        "--max-symbols",
        "100000",
    ]);
    assert_eq!(o.status, 1);
    assert!(o.stderr.contains("E0301"), "{}", o.stderr);
    assert!(o.stdout.is_empty());
    // The axiom counts too.
    let o = graftal(&["derive", "std:koch-island", "-n", "0", "--max-symbols", "5"]);
    assert_eq!(o.status, 1);
    assert!(o.stderr.contains("E0301"), "{}", o.stderr);
    assert_eq!(
        graftal(&[
            "render",
            "std:koch-island",
            "-o",
            "x.png",
            "--size",
            "9000x10"
        ])
        .status,
        2
    );
}

#[test]
fn check_json_gives_one_object_per_diagnostic() {
    let bad = temp("two.l");
    std::fs::write(&bad, "angle factor: 0\naxiom: F[\n").unwrap();
    let o = graftal(&["check", bad.to_str().unwrap(), "--format", "json"]);
    assert_eq!(o.status, 1);
    let objs: Vec<serde_json::Value> = o
        .stderr
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let codes: Vec<&str> = objs.iter().map(|v| v["code"].as_str().unwrap()).collect();
    assert_eq!(codes, ["E0103", "E0203"]);
    assert_eq!(objs[1]["line"], 2);
    assert_eq!(objs[1]["column"], 9);
}

#[test]
fn stats_json_has_the_contract_fields() {
    let o = graftal(&["stats", "std:koch-island", "-n", "2", "--format", "json"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let v: serde_json::Value = serde_json::from_str(o.stdout.trim()).unwrap();
    assert_eq!(v["segments"], 256);
    assert_eq!(v["polygons"], 0);
    assert_eq!(v["max_depth"], 0);
    for stage in ["parse", "derive", "interpret"] {
        assert!(v["time"][stage].as_f64().unwrap() >= 0.0, "{stage}");
    }
    assert!(v["symbols"].as_u64().unwrap() > 256);
    let bbox: Vec<f64> = v["bbox"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(bbox.len(), 6);
    assert_eq!(bbox[2], 0.0);
    assert!(
        (bbox[3] - bbox[0] - (bbox[4] - bbox[1])).abs() < 1e-9,
        "an island is square"
    );
    let o = graftal(&["stats", "std:fibonacci-bush", "-n", "3", "--format", "json"]);
    let v: serde_json::Value = serde_json::from_str(o.stdout.trim()).unwrap();
    assert!(v["polygons"].as_u64().unwrap() > 0);
    assert!(v["max_depth"].as_u64().unwrap() >= 2);
    assert!(
        v["bbox"][5].as_f64().unwrap() > v["bbox"][2].as_f64().unwrap(),
        "3D"
    );
}

#[test]
fn render_writes_png_and_svg_and_same_seed_same_bytes() {
    let a = temp("a.png");
    let b = temp("b.png");
    let c = temp("c.png");
    for (out, seed) in [(&a, "7"), (&b, "7"), (&c, "8")] {
        let o = graftal(&[
            "render",
            "std:stochastic-bush",
            "-o",
            out.to_str().unwrap(),
            "--seed",
            seed,
            "--size",
            "200x150",
        ]);
        assert_eq!(o.status, 0, "{}", o.stderr);
    }
    let (a, b, c) = (
        std::fs::read(a).unwrap(),
        std::fs::read(b).unwrap(),
        std::fs::read(c).unwrap(),
    );
    assert_eq!(&a[..8], b"\x89PNG\r\n\x1a\n");
    // Width and height in the IHDR chunk.
    assert_eq!(u32::from_be_bytes(a[16..20].try_into().unwrap()), 200);
    assert_eq!(u32::from_be_bytes(a[20..24].try_into().unwrap()), 150);
    assert_eq!(a, b, "same seed, same picture");
    assert_ne!(a, c, "another seed, another plant");
    let svg = temp("k.svg");
    let o = graftal(&[
        "render",
        "std:paper-tape",
        "-o",
        svg.to_str().unwrap(),
        "--view",
        "30,-20",
    ]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert!(std::fs::read_to_string(svg).unwrap().starts_with("<svg"));
}

#[test]
fn derive_is_identical_across_runs_for_a_seed() {
    let one = graftal(&["derive", "std:stochastic-bush", "-n", "4", "--seed", "123"]);
    let two = graftal(&["derive", "std:stochastic-bush", "-n", "4", "--seed", "123"]);
    let other = graftal(&["derive", "std:stochastic-bush", "-n", "4", "--seed", "124"]);
    assert_eq!(one.stdout, two.stdout);
    assert_ne!(one.stdout, other.stdout);
}

#[test]
fn explain_every_code() {
    for info in graftal::diagnostics::codes::all() {
        let o = graftal(&["explain", info.code.0]);
        assert_eq!(o.status, 0);
        assert!(o.stdout.starts_with(info.code.0));
        assert!(o.stdout.contains(info.explanation));
    }
    assert_eq!(graftal(&["explain", "E9999"]).status, 2);
    assert_eq!(graftal(&["explain", "e0004"]).status, 0);
}

#[test]
fn empty_picture_is_a_warning_not_an_error() {
    let out = temp("empty.svg");
    let o = graftal(&["render", "std:algae", "-o", out.to_str().unwrap()]);
    assert_eq!(o.status, 0);
    assert!(o.stderr.contains("W0003"), "{}", o.stderr);
}

#[test]
fn every_stdlib_entry_renders() {
    for e in graftal::stdlib::ENTRIES {
        let out = temp(&format!("std-{}.png", e.name.replace('/', "-")));
        let o = graftal(&[
            "render",
            &format!("std:{}", e.name),
            "-o",
            out.to_str().unwrap(),
            "--size",
            "128x128",
        ]);
        assert_eq!(o.status, 0, "{}: {}", e.name, o.stderr);
        let png = std::fs::read(&out).unwrap();
        assert_eq!(&png[..4], b"\x89PNG");
        assert!(!o.stderr.contains("Error"), "{}: {}", e.name, o.stderr);
    }
}

#[test]
fn kolams_are_drawn_as_splines_through_the_turtle_positions() {
    for name in ["kolam-snake", "kolam-anklets", "kolam-bag-of-candies"] {
        let plain = temp(&format!("{name}.svg"));
        let o = graftal(&[
            "render",
            &format!("std:{name}"),
            "-o",
            plain.to_str().unwrap(),
            "--detail",
            "full",
        ]);
        // Only f moves: the stdlib marks the kolams `graftal: spline`, so
        // they are drawn as the book draws them without `--spline`.
        assert_eq!(o.status, 0);
        assert!(!o.stderr.contains("W0003"), "{}", o.stderr);
        let curved = temp(&format!("{name}-spline.svg"));
        let o = graftal(&[
            "render",
            &format!("std:{name}"),
            "-o",
            curved.to_str().unwrap(),
            "--spline",
            // Every sample of the curve, each an `L`.
            "--detail",
            "full",
        ]);
        assert_eq!(o.status, 0, "{}", o.stderr);
        assert!(!o.stderr.contains("W0003"), "{}", o.stderr);
        let svg = std::fs::read_to_string(curved).unwrap();
        assert!(svg.matches('L').count() > 100, "{name}: a long curve");
        assert_eq!(std::fs::read_to_string(plain).unwrap(), svg);
    }
}

#[test]
fn geometry_too_large_to_draw_is_an_error_not_an_out_of_memory() {
    use graftal::driver::{compile, geometry, load, RunOptions};
    let c = compile(load("std:koch-island").unwrap());
    let sys = c.system.unwrap();
    let opts = RunOptions {
        steps: Some(3),
        max_moves: 1000,
        ..RunOptions::default()
    };
    let err = geometry(&sys, &opts).unwrap_err();
    assert_eq!(err.code, graftal::diagnostics::codes::TOO_MUCH_GEOMETRY);
    let opts = RunOptions {
        max_moves: 2048,
        ..opts
    };
    assert_eq!(geometry(&sys, &opts).unwrap().1.segments.len(), 2048);
}

#[test]
fn a_huge_file_is_refused_with_a_diagnostic() {
    let big = temp("big.l");
    let mut text = String::from("axiom: ");
    text.push_str(&"F".repeat(graftal::driver::MAX_SOURCE_BYTES));
    std::fs::write(&big, text).unwrap();
    let o = graftal(&["check", big.to_str().unwrap()]);
    assert_eq!(o.status, 1);
    assert!(o.stderr.contains("E0011"), "{}", o.stderr);
}

#[test]
fn help_names_every_notation_of_the_registry() {
    let out = graftal(&["--help"]);
    assert_eq!(out.status, 0);
    for f in graftal::front::FRONTS {
        let named = format!("{} .{}", f.title(), f.extensions()[0]);
        assert!(out.stdout.contains(&named), "{named}: {}", out.stdout);
    }
}

/// Runs the `graftal` binary in a fresh directory `dir` (so a stray file
/// named `-` would show), stdout and stderr piped.
fn binary_in(dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    std::fs::create_dir_all(dir).unwrap();
    std::process::Command::new(env!("CARGO_BIN_EXE_graftal"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

/// The names in `dir`, sorted.
fn files_in(dir: &std::path::Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn render_dash_writes_the_picture_to_stdout_in_the_format_of_to() {
    let dir = temp("render-stdout");
    let args = ["render", "std:koch-island", "--size", "60x40", "-o"];
    let png = binary_in(&dir, &[&args[..], &["-", "--to", "png"]].concat());
    assert_eq!(png.status.code(), Some(0), "{png:?}");
    assert_eq!(&png.stdout[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(
        u32::from_be_bytes(png.stdout[16..20].try_into().unwrap()),
        60
    );
    // The same bytes as the file.
    let file = binary_in(&dir, &[&args[..], &["k.png"]].concat());
    assert_eq!(file.status.code(), Some(0), "{file:?}");
    assert_eq!(std::fs::read(dir.join("k.png")).unwrap(), png.stdout);
    let svg = binary_in(&dir, &[&args[..], &["-", "--to", "svg"]].concat());
    assert_eq!(svg.status.code(), Some(0), "{svg:?}");
    assert!(String::from_utf8(svg.stdout).unwrap().starts_with("<svg"));
    // `--to` also names the format of a file without an extension.
    let named = binary_in(&dir, &[&args[..], &["picture", "--to", "svg"]].concat());
    assert_eq!(named.status.code(), Some(0), "{named:?}");
    assert!(std::fs::read_to_string(dir.join("picture"))
        .unwrap()
        .starts_with("<svg"));
    assert_eq!(files_in(&dir), ["k.png", "picture"], "no file named `-`");
}

#[test]
fn render_dash_without_a_format_is_a_usage_error_with_help() {
    let dir = temp("render-no-format");
    let o = binary_in(&dir, &["render", "std:koch-island", "-o", "-"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(o.stdout.is_empty());
    let err = String::from_utf8(o.stderr).unwrap();
    assert!(err.contains("standard output"), "{err}");
    assert!(err.contains("help: add `--to png` or `--to svg`"), "{err}");
    // A `--to` that contradicts the file's extension is refused.
    let o = graftal(&["render", "std:koch-island", "-o", "x.png", "--to", "svg"]);
    assert_eq!(o.status, 2);
    assert!(o.stderr.contains("names a png file"), "{}", o.stderr);
    assert!(o.stderr.contains("help:"), "{}", o.stderr);
    // `--format` is still the diagnostics' format.
    let o = graftal(&["render", "std:koch-island", "-o", "-", "--format", "png"]);
    assert_eq!(o.status, 2);
    assert!(files_in(&dir).is_empty(), "{:?}", files_in(&dir));
}

/// What `render` writes but cannot do is a usage error, not ignored: an
/// animation into a mesh's file, a frame rate with no animation.
#[test]
fn animation_options_that_cannot_apply_are_usage_errors() {
    let dir = temp("render-animate-misuse");
    let args = ["render", "std:koch-island", "-n", "1", "--size", "20x20"];
    for (extra, wrong, what_to_do) in [
        (
            &["--animate", "-o", "x.obj"][..],
            "names a mesh (.obj)",
            "drop `--animate`",
        ),
        (
            &["--animate", "-o", "x.glb"][..],
            "names a mesh (.glb)",
            "….gif",
        ),
        (
            &["--fps", "5", "-o", "x.png"][..],
            "no `--animate`",
            "add `--animate`",
        ),
        (
            &["--fps", "5", "-o", "x.ply"][..],
            "no `--animate`",
            "drop `--fps`",
        ),
    ] {
        let o = binary_in(&dir, &[&args[..], extra].concat());
        let err = String::from_utf8(o.stderr).unwrap();
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {err}");
        assert!(err.contains(wrong), "{extra:?}: {err}");
        assert!(
            err.contains("help:") && err.contains(what_to_do),
            "{extra:?}: {err}"
        );
    }
    assert!(files_in(&dir).is_empty(), "{:?}", files_in(&dir));
    // With `--animate`, `--fps` is taken.
    let o = binary_in(
        &dir,
        &[&args[..], &["--animate", "--fps", "5", "-o", "a.gif"]].concat(),
    );
    assert_eq!(o.status.code(), Some(0), "{o:?}");
}

/// `render --help` and the error for an extension graftal does not write
/// name every format it writes, from the list the code looks names up in.
#[test]
fn render_help_and_a_bad_extension_name_every_format_written() {
    use graftal::driver::picture::Target;
    let help = graftal(&["render", "--help"]);
    assert_eq!(help.status, 0, "{}", help.stderr);
    let bad = graftal(&["render", "std:koch-island", "-o", "x.bmp"]);
    assert_eq!(bad.status, 2, "{}", bad.stderr);
    assert!(bad.stderr.contains("help:"), "{}", bad.stderr);
    let targets: Vec<Target> = Target::all().collect();
    assert_eq!(targets.len(), 8, "PNG, SVG, POV, OBJ, PLY, GLB, GIF, APNG");
    for t in targets {
        let named = format!("{} (.{}", t.name(), t.extension());
        assert!(help.stdout.contains(&named), "{named}: {}", help.stdout);
        assert!(bad.stderr.contains(&named), "{named}: {}", bad.stderr);
    }
}

#[test]
fn a_binary_png_is_not_written_to_a_terminal() {
    let args = ["render", "std:koch-island", "--size", "20x20", "-o", "-"];
    let (status, out, err) = graftal_bytes(&[&args[..], &["--to", "png"]].concat(), true);
    assert_eq!(status, 2);
    assert!(out.is_empty(), "nothing on the terminal");
    let err = String::from_utf8(err).unwrap();
    assert!(
        err.contains("terminal") && err.contains("redirect"),
        "{err}"
    );
    // SVG is text: fine on a terminal.
    let (status, out, _) = graftal_bytes(&[&args[..], &["--to", "svg"]].concat(), true);
    assert_eq!(status, 0);
    assert!(out.starts_with(b"<svg"));
}

#[test]
fn translate_dash_is_stdout_not_a_file_named_dash() {
    let dir = temp("translate-stdout");
    let plain = binary_in(&dir, &["translate", "std:koch-island", "--to", "linf"]);
    let dash = binary_in(
        &dir,
        &["translate", "std:koch-island", "--to", "linf", "-o", "-"],
    );
    assert_eq!(dash.status.code(), Some(0), "{dash:?}");
    let text = String::from_utf8(dash.stdout).unwrap();
    assert!(text.contains("koch-island"), "{text}");
    assert_eq!(text.as_bytes(), plain.stdout);
    assert!(files_in(&dir).is_empty(), "{:?}", files_in(&dir));
    // As JSON the text is in the document, and there is no output file.
    let o = graftal(&[
        "translate",
        "std:koch-island",
        "--to",
        "linf",
        "-o",
        "-",
        "--format",
        "json",
    ]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let v: serde_json::Value = serde_json::from_str(o.stdout.trim()).unwrap();
    assert_eq!(v["output"], serde_json::Value::Null);
    assert_eq!(v["text"].as_str(), Some(text.as_str()));
}

#[test]
fn derive_writes_to_o_file_or_dash_for_stdout() {
    let dir = temp("derive-o");
    let o = binary_in(&dir, &["derive", "std:algae", "-n", "5", "-o", "-"]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    assert_eq!(o.stdout, b"abaababa\n");
    let o = binary_in(&dir, &["derive", "std:algae", "-n", "5", "-o", "word.txt"]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    assert!(o.stdout.is_empty());
    let word = std::fs::read_to_string(dir.join("word.txt")).unwrap();
    assert_eq!(word, "abaababa\n");
    // A derivation that fails leaves no file behind.
    let o = binary_in(
        &dir,
        &[
            "derive",
            "std:koch-island",
            "-n",
            "9",
            "--max-symbols",
            "1000",
            "-o",
            "big.txt",
        ],
    );
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8(o.stderr).unwrap().contains("E0301"));
    assert_eq!(files_in(&dir), ["word.txt"]);
    let o = graftal(&["derive", "std:algae", "-o", "/no/such/dir/word.txt"]);
    assert_eq!(o.status, 2);
    assert!(o.stderr.contains("cannot write"), "{}", o.stderr);
}

#[test]
fn derive_prints_parameters_as_people_write_them() {
    // Ten subtractions of 0.1 from 1 leave 1.4e-16, and three leave
    // 0.7000000000000001: both are binary artefacts, printed as 0 and 0.7.
    let path = temp("artefacts.l");
    std::fs::write(
        &path,
        "Lsystem: 1\nderivation length: 3\nAxiom: A(1)B(0.000025)\nA(x) --> A(x-0.1)\nendlsystem\n",
    )
    .unwrap();
    let file = path.to_str().unwrap();
    let o = graftal(&["derive", file]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert_eq!(o.stdout, "A(0.7)B(2.5e-5)\n");
    let o = graftal(&["derive", file, "-n", "10"]);
    assert_eq!(o.stdout, "A(0)B(2.5e-5)\n");
}

#[test]
fn stl_angle_of_an_angle_factor_is_exact_and_names_the_factor() {
    let path = temp("fourteen.l");
    std::fs::write(&path, "angle factor: 14\naxiom: F\nF --> F+F\n").unwrap();
    let o = graftal(&["translate", path.to_str().unwrap(), "--to", "stl"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let angle = o.stdout.lines().find(|l| l.starts_with("ANGLE")).unwrap();
    assert_eq!(angle, "ANGLE 25.714285714285715 # 360/14");
    let degrees: f64 = angle["ANGLE ".len()..]
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(degrees.to_radians(), std::f64::consts::TAU / 14.0);
    // A short angle needs no comment.
    std::fs::write(&path, "angle factor: 8\naxiom: F\nF --> F+F\n").unwrap();
    let o = graftal(&["translate", path.to_str().unwrap(), "--to", "stl"]);
    assert!(o.stdout.contains("\nANGLE 45\n"), "{}", o.stdout);
}

#[test]
fn check_json_of_a_library_lists_its_entries_in_one_document() {
    let lib = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/fractint.l");
    let o = graftal(&["check", "--format", "json", lib, "std:algae"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let doc: serde_json::Value = serde_json::from_str(&o.stdout).unwrap();
    let files = doc["files"].as_array().unwrap();
    assert_eq!(files.len(), 2);
    let entries = files[0]["entries"].as_array().unwrap();
    assert_eq!(files[0]["total"], 69);
    assert_eq!(entries.len(), 69);
    assert_eq!(entries[0]["name"], "Koch1");
    assert_eq!(entries[0]["line"], 2);
    assert_eq!(entries[0]["errors"], 0);
    assert_eq!(entries[0]["chosen"], false);
    assert!(files[0]["dialect"].as_str().unwrap().contains("69 entries"));
    // A file of one system: no entries.
    assert_eq!(files[1]["file"], "std:algae.l");
    assert!(files[1]["entries"].is_null());
}

#[test]
fn list_shows_each_entry_figure_and_whether_it_draws() {
    let o = graftal(&["list"]);
    assert_eq!(o.status, 0);
    let line = |name: &str| {
        o.stdout
            .lines()
            .find(|l| l.split_whitespace().next() == Some(name))
            .unwrap_or_else(|| panic!("{name} in {}", o.stdout))
            .to_string()
    };
    assert!(line("std:algae").contains("Fig. 1.3"));
    assert!(line("std:algae").ends_with("schema"));
    assert!(line("std:dragon").ends_with("draws"));
    assert!(line("std:kolam-snake").ends_with("draws (spline)"));
    let json = graftal(&["list", "--format", "json"]);
    let doc: serde_json::Value = serde_json::from_str(&json.stdout).unwrap();
    let entries = doc["entries"].as_array().unwrap();
    assert_eq!(entries.len(), o.stdout.lines().count());
    let algae = entries.iter().find(|e| e["name"] == "std:algae").unwrap();
    assert_eq!(algae["kind"], "schema");
    assert_eq!(algae["draws"], false);
    assert!(algae["figure"].as_str().unwrap().contains("Fig. 1.3"));
}

#[test]
fn show_prints_an_entry_source_and_unknown_names_suggest() {
    let o = graftal(&["show", "std:algae"]);
    assert_eq!(o.status, 0);
    assert!(o.stdout.starts_with("/* algae"), "{}", o.stdout);
    assert!(o.stdout.contains("axiom: b"));
    let o = graftal(&["show", "koch"]);
    assert_eq!(o.status, 2);
    assert!(o.stderr.contains("did you mean `std:koch-"), "{}", o.stderr);
    let o = graftal(&["render", "std:fig08-tree-3d", "-o", "tree.png"]);
    assert_eq!(o.status, 2);
    assert!(
        o.stderr.contains("did you mean `std:linf/fig08-tree-3d`?"),
        "{}",
        o.stderr
    );
    assert!(o.stderr.contains("`graftal list`"), "{}", o.stderr);
}

#[test]
fn rendering_a_schema_or_a_kolam_says_why_or_draws() {
    let png = temp("schema.png");
    let o = graftal(&["render", "std:algae", "-o", png.to_str().unwrap()]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert!(o.stderr.contains("W0003"), "{}", o.stderr);
    assert!(o.stderr.contains("`std:algae` is a schema"), "{}", o.stderr);
    // The kolams draw as splines without `--spline`.
    let o = graftal(&["render", "std:kolam-snake", "-o", png.to_str().unwrap()]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert!(!o.stderr.contains("W0003"), "{}", o.stderr);
    // Outside the stdlib, a turtle that only moves is told to try `--spline`,
    // and a word of symbols that do not move it is a string example.
    let kolam = temp("kolam.l");
    std::fs::write(&kolam, "derivation length: 2\naxiom: f+Xf\nX --> Xf-f+X\n").unwrap();
    let o = graftal(&[
        "render",
        kolam.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
    ]);
    assert!(o.stderr.contains("try `--spline`"), "{}", o.stderr);
    let words = temp("words.l");
    std::fs::write(&words, "derivation length: 3\naxiom: a\na --> ab\n").unwrap();
    let o = graftal(&[
        "render",
        words.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
    ]);
    assert!(
        o.stderr.contains("no symbol of the derived word moves"),
        "{}",
        o.stderr
    );
    let o = graftal(&[
        "render",
        words.to_str().unwrap(),
        "-n",
        "0",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert!(o.stderr.contains("0 steps"), "{}", o.stderr);
}

/// Every argument and subcommand of the command line says what it is for
/// in `--help`.
#[test]
fn every_argument_and_subcommand_has_help() {
    use clap::CommandFactory;
    fn walk(cmd: &clap::Command, path: &str, missing: &mut Vec<String>) {
        for arg in cmd.get_arguments() {
            if arg.get_help().is_none() && arg.get_long_help().is_none() {
                missing.push(format!("{path} {}", arg.get_id()));
            }
        }
        for sub in cmd.get_subcommands() {
            let path = format!("{path} {}", sub.get_name());
            if sub.get_about().is_none() && sub.get_long_about().is_none() {
                missing.push(path.clone());
            }
            walk(sub, &path, missing);
        }
    }
    let mut cmd = graftal::cli::Cli::command();
    // Help and version arguments are added when the command is built.
    cmd.build();
    let mut missing = Vec::new();
    walk(&cmd, "graftal", &mut missing);
    assert!(missing.is_empty(), "without help: {missing:?}");
}

/// The top-level help names every notation and its extensions.
#[test]
fn top_level_help_names_the_notations() {
    let o = graftal(&["--help"]);
    assert_eq!(o.status, 0);
    for name in ["pfg .l", "LinF .linf", "STL .stl", "cpfg .l", "Fractint .l"] {
        assert!(o.stdout.contains(name), "{name}: {}", o.stdout);
    }
    assert!(o.stdout.contains("--notation"), "{}", o.stdout);
}

/// `graftal explain` without a code lists every code with its title.
#[test]
fn explain_without_a_code_lists_the_codes() {
    let o = graftal(&["explain"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let listed: Vec<&str> = o
        .stdout
        .lines()
        .filter_map(|l| l.split_once("  ").map(|(code, _)| code))
        .collect();
    let mut all: Vec<&str> = graftal::diagnostics::codes::all()
        .map(|i| i.code.0)
        .collect();
    all.sort_unstable();
    assert_eq!(listed, all);
    assert!(o.stdout.contains("E0014  empty file\n"), "{}", o.stdout);
    assert!(o
        .stdout
        .contains("W0808  malformed view-file value ignored\n"));
}

/// `graftal explain`'s listing is sorted: every error, then every warning,
/// each by its number, so that E0001 comes first and a code is found where
/// its number says (the registry keeps them by front end).
#[test]
fn explain_lists_errors_then_warnings_each_by_number() {
    let o = graftal(&["explain"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let listed: Vec<(char, u32)> = o
        .stdout
        .lines()
        .filter_map(|l| l.split_once("  "))
        .map(|(code, _)| {
            let (kind, number) = code.split_at(1);
            (kind.chars().next().unwrap(), number.parse().unwrap())
        })
        .collect();
    assert_eq!(listed.first(), Some(&('E', 1)), "{}", o.stdout);
    let out_of_order: Vec<_> = listed.windows(2).filter(|w| w[0] >= w[1]).collect();
    assert!(out_of_order.is_empty(), "{out_of_order:?}");
    let first_warning = listed.iter().position(|(kind, _)| *kind == 'W');
    assert!(
        listed[first_warning.unwrap()..]
            .iter()
            .all(|(k, _)| *k == 'W'),
        "errors first, then warnings"
    );
}

/// `check` of a valid file says which notation it read, and how much.
#[test]
fn check_says_what_it_read() {
    let o = graftal(&["check", "std:koch-island"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert!(
        o.stdout.ends_with(": dialect: pfg, 1 production\n"),
        "{}",
        o.stdout
    );
    let o = graftal(&["check", "std:linf/fig06-plant"]);
    assert!(o.stdout.contains(": dialect: LinF, "), "{}", o.stdout);
}

/// `check` shows a mistake inside a cpfg `#include`d file in that file, at
/// its own line (as rustc shows one inside a macro of another file), with
/// a note naming the `#include` line.
#[test]
fn check_shows_a_mistake_of_an_included_file_in_that_file() {
    let dir = std::env::temp_dir().join(format!("graftal-cli-include-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("leaf.h"), "B --> F(1\n#bogus\n").unwrap();
    let plant =
        "Lsystem: 1\n#include \"leaf.h\"\nderivation length: 2\nAxiom: A\nA --> B\nendlsystem\n";
    std::fs::write(dir.join("plant.l"), plant).unwrap();
    let out = binary_in(&dir, &["check", "plant.l"]);
    let _ = std::fs::remove_dir_all(&dir);
    let text =
        String::from_utf8_lossy(&out.stderr).to_string() + &String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("leaf.h:2:1") && text.contains("leaf.h:1:10"),
        "{text}"
    );
    assert!(text.contains("#bogus"), "{text}");
    assert!(
        text.contains("`leaf.h` is included at line 2 of the L-system file"),
        "{text}"
    );
}

/// A natural number in decimal, worked out apart from graftal's own
/// counts: digits of base 10⁹, least significant first.
struct Decimal(Vec<u64>);

impl Decimal {
    const BASE: u64 = 1_000_000_000;

    /// `self · k + add`, for `k` and `add` below 10⁹.
    fn times_plus(mut self, k: u64, add: u64) -> Decimal {
        let mut carry = add;
        for d in &mut self.0 {
            let v = *d * k + carry;
            *d = v % Self::BASE;
            carry = v / Self::BASE;
        }
        while carry > 0 {
            self.0.push(carry % Self::BASE);
            carry /= Self::BASE;
        }
        self
    }

    fn power_of_two(k: u32) -> Decimal {
        (0..k).fold(Decimal(vec![1]), |d, _| d.times_plus(2, 0))
    }

    fn digits(&self) -> String {
        let mut groups = self.0.iter().rev();
        let top = groups.next().map_or("0".to_string(), u64::to_string);
        groups.fold(top, |s, g| format!("{s}{g:09}"))
    }
}

/// The Koch island's figures after `n` steps: `4 · 8ⁿ` segments, and
/// `4 (1 + 13 (8ⁿ − 1) / 7) + 3` symbols, where `(8ⁿ − 1) / 7` is
/// `1 + 8 + … + 8ⁿ⁻¹`.
fn koch_island_counts(n: u32) -> (String, String) {
    let segments = Decimal::power_of_two(3 * n + 2);
    let g = (0..n).fold(Decimal(vec![0]), |g, _| g.times_plus(8, 1));
    (g.times_plus(52, 7).digits(), segments.digits())
}

/// The `stats` figure named `name`, from its human output.
fn stats_line<'a>(stdout: &'a str, name: &str) -> &'a str {
    let line = stdout.lines().find(|l| l.starts_with(name));
    line.unwrap_or_else(|| panic!("no {name} in {stdout}"))[name.len()..].trim()
}

#[test]
fn stats_counts_are_exact_past_u128() {
    // 2^128 segments at 42 steps: u128's largest plus one.
    let (symbols, segments) = koch_island_counts(42);
    assert_eq!(segments, "340282366920938463463374607431768211456");
    for n in [42, 100] {
        let (symbols_n, segments_n) = koch_island_counts(n);
        let o = graftal(&["stats", "std:koch-island", "-n", &n.to_string()]);
        assert_eq!(o.status, 0, "{}", o.stderr);
        assert_eq!(stats_line(&o.stdout, "segments"), segments_n, "n={n}");
        assert_eq!(stats_line(&o.stdout, "symbols"), symbols_n, "n={n}");
    }
    // JSON numbers of every digit (a reader that keeps integers exact reads
    // them exactly; serde_json's `Value` would round them to `f64`).
    let o = graftal(&["stats", "std:koch-island", "-n", "42", "--format", "json"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert!(
        o.stdout.contains(&format!("\"segments\":{segments},")),
        "{}",
        o.stdout
    );
    assert!(o.stdout.contains(&format!("\"symbols\":{symbols},")));
}

#[test]
fn stats_says_a_box_beyond_floating_point_cannot_be_given() {
    // The island is 4 times wider a step: about 1.7 · 4ⁿ, the largest
    // f64 (2^1024) passed at 512 steps.
    let o = graftal(&["stats", "std:koch-island", "-n", "511"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert!(o.stderr.is_empty(), "{}", o.stderr);
    assert!(
        stats_line(&o.stdout, "bbox").contains("e307"),
        "{}",
        o.stdout
    );
    for n in ["512", "1000"] {
        let o = graftal(&["stats", "std:koch-island", "-n", n]);
        // The counts are given, exact: a warning, not an error.
        assert_eq!(o.status, 0, "{}", o.stderr);
        assert!(o.stderr.contains("W0010"), "{}", o.stderr);
        assert!(!o.stdout.contains("inf"), "{}", o.stdout);
        let bbox = stats_line(&o.stdout, "bbox");
        assert_eq!(bbox, "beyond floating point (W0010)");
    }
    let o = graftal(&["stats", "std:koch-island", "-n", "1000"]);
    assert!(
        o.stderr.contains("about 1.9e602 turtle units across"),
        "{}",
        o.stderr
    );
    let (_, segments) = koch_island_counts(1000);
    assert_eq!(stats_line(&o.stdout, "segments"), segments);
    let o = graftal(&["stats", "std:koch-island", "-n", "1000", "--format", "json"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert!(o.stdout.contains("\"bbox\":null"), "{}", o.stdout);
    assert!(o.stdout.contains(&format!("\"segments\":{segments},")));
    assert!(o.stderr.contains("\"code\":\"W0010\""), "{}", o.stderr);
}

#[test]
fn stats_refuses_counts_too_long_to_add_up_exactly() {
    // 52 symbols each rewritten into all 52, 4096 steps: numbers of some
    // 7000 digits, 2704 products of them a step.
    let letters: String = ('A'..='Z').chain('a'..='z').collect();
    let rules: String = letters
        .chars()
        .map(|c| format!("{c} --> {letters}\n"))
        .collect();
    let f = temp("many.l");
    std::fs::write(&f, format!("axiom: {letters}\n{rules}")).unwrap();
    let o = graftal(&["stats", f.to_str().unwrap(), "-n", "4096"]);
    assert_eq!(o.status, 1, "{}", o.stdout);
    assert!(o.stderr.contains("E0304"), "{}", o.stderr);
    assert!(o.stdout.is_empty(), "{}", o.stdout);
}
