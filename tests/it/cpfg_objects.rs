//! cpfg objects run as a new user runs them: the binary in the object's
//! folder, the `.l` named as it is there. Each test reads only
//! `tests/corpus/cpfg/...` (or a copy of it in a temporary folder).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn object(name: &str) -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/corpus/cpfg")).join(name)
}

/// Runs the binary with `args` from the folder `dir`.
fn run_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_graftal"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the graftal binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A fresh temporary folder for one test.
fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("graftal-cpfg-objects-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `plant.l` named bare from Lilac's folder finds its view file and the
/// surfaces it names: none is reported undefined.
#[test]
fn a_bare_file_name_finds_the_view_file_beside_it() {
    let dir = object("11-CPFG-Lilac");
    let o = run_in(&dir, &["check", "plant.l", "--format", "json"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(!err.contains("is not defined"), "{err}");
}

/// WeepingBirch's `fractal.l` named bare draws with its view file (its
/// widths and colours): the same picture as the full path gives, and not
/// the picture of the `.l` alone.
#[test]
fn a_bare_file_name_draws_with_the_view_file() {
    let dir = object("11-CPFG-WeepingBirch");
    let out = temp_dir("birch");
    let svg = |from: &Path, file: &str, name: &str| {
        let target = out.join(name);
        let o = run_in(from, &["render", file, "-o", target.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        std::fs::read_to_string(target).unwrap()
    };
    let bare = svg(&dir, "fractal.l", "bare.svg");
    let full = svg(
        Path::new("/"),
        dir.join("fractal.l").to_str().unwrap(),
        "full.svg",
    );
    let alone_dir = out.join("alone");
    std::fs::create_dir_all(&alone_dir).unwrap();
    std::fs::copy(dir.join("fractal.l"), alone_dir.join("fractal.l")).unwrap();
    let alone = svg(&alone_dir, "fractal.l", "alone.svg");
    assert!(bare == full, "the bare name draws another picture");
    assert!(bare != alone, "the view file changes nothing");
    let _ = std::fs::remove_dir_all(&out);
}

/// The system read from `path` (a corpus file or a temporary one), with
/// its diagnostics.
fn compile(path: &Path) -> graftal::driver::Compiled {
    let file = graftal::source::SourceFile::read(path).unwrap();
    graftal::driver::compile(file)
}

/// Derives and interprets the system of `path`.
fn geometry(path: &Path) -> graftal::turtle::Geometry {
    let c = compile(path);
    let sys = c.system.as_ref().expect("the file reads");
    let opts = graftal::driver::RunOptions::default();
    graftal::driver::geometry(sys, &opts).unwrap().1
}

/// A cpfg text written to a temporary folder as `name`.
fn write_l(tag: &str, name: &str, text: &str) -> PathBuf {
    let dir = temp_dir(tag);
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// A global set in `Start:` is read by the homomorphism and by the
/// decomposition as by the productions: `F(R)` is 5 long in each.
#[test]
fn start_globals_are_read_in_every_phase() {
    let phases = [
        ("homomorphism", "Axiom: B\nhomomorphism\nB --> F(R)\n"),
        (
            "decomposition",
            "Axiom: B\nB --> A\ndecomposition\nA --> F(R)\n",
        ),
        ("productions", "Axiom: B\nB --> F(R)\n"),
    ];
    for (phase, body) in phases {
        let text =
            format!("Lsystem: 1\nderivation length: 1\nStart: {{R = 5;}}\n{body}endlsystem\n");
        let p = write_l(phase, "g.l", &text);
        let g = geometry(&p);
        assert_eq!(g.segments.len(), 1, "{phase}");
        let s = &g.segments[0];
        let len: f64 = (0..3)
            .map(|k| (s.b[k] - s.a[k]).powi(2))
            .sum::<f64>()
            .sqrt();
        assert!((len - 5.0).abs() < 1e-9, "{phase}: {len}");
    }
}

/// Three-spheres sets the radius `R` in `Start:` and draws `@O(R)` in its
/// homomorphism (`R = 0.9`): three spheres of that size, not three points.
#[test]
fn three_spheres_have_their_start_radius() {
    let g = geometry(&object("07-Open-10-light-three-spheres").join("balls.l"));
    assert_eq!(g.discs.len(), 3);
    for d in &g.discs {
        assert!(d.diameter > 0.5, "{}", d.diameter);
    }
}

/// Insect-realistic draws `~b`, a surface its view file does not name:
/// the rest is drawn, and one warning (not an error) names the surface.
#[test]
fn an_undefined_surface_is_one_warning_and_the_rest_is_drawn() {
    let dir = object("04-Signaling-22-insect-realistic");
    let out = temp_dir("insect");
    let target = out.join("insect.svg");
    let o = run_in(
        &dir,
        &["render", "fractal.l", "-o", target.to_str().unwrap()],
    );
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert_eq!(err.matches("is not defined").count(), 1, "{err}");
    assert!(err.contains("surface `b`"), "{err}");
    assert!(!err.contains("Error"), "{err}");
    assert!(!err.contains("W0003"), "{err}");
    let _ = std::fs::remove_dir_all(&out);
}

/// The snowflake exercise leaves `?` for the student to fill in: one
/// error says so, not a pile of follow-on errors and not an empty picture.
#[test]
fn an_exercise_with_blanks_says_so_once() {
    let dir = object("01-Introduction-02-snowflake-exercise");
    let o = run_in(&dir, &["check", "fractal.l", "--format", "json"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("exercise"), "{err}");
}

/// Sierpinski grows only where its environment program answers `?E`:
/// graftal runs honda81 itself, so the triangle grows, and nothing warns
/// that no one answered.
#[test]
fn sierpinski_grows_where_honda81_answers() {
    let dir = object("20-EnviroPgms-CPFG-Sierpinski");
    let out = temp_dir("sierpinski");
    let target = out.join("s.svg");
    let o = run_in(
        &dir,
        &["render", "fractal.l", "-o", target.to_str().unwrap()],
    );
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(!err.contains("W0821") && !err.contains("W0003"), "{err}");
    let svg = std::fs::read_to_string(&target).unwrap();
    // 15 steps of growth where tips meet no other: hundreds of lines.
    assert!(svg.matches("<path").count() > 100, "{svg}");
    let _ = std::fs::remove_dir_all(&out);
}

/// An object whose `.e` file names a program graftal does not have: the
/// `?E` warning names it, and the empty picture says why.
#[test]
fn an_environment_program_graftal_lacks_is_named() {
    let out = temp_dir("arvo");
    let dir = object("20-EnviroPgms-CPFG-Sierpinski");
    for f in ["fractal.l", "fractal.v", "fractal.map", "density.spec"] {
        std::fs::copy(dir.join(f), out.join(f)).unwrap();
    }
    std::fs::write(
        out.join("fractal.e"),
        "executable: arvo light.spec\nturtle position: %f %f %f\n",
    )
    .unwrap();
    let o = run_in(&out, &["render", "fractal.l", "-o", "s.svg"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert_eq!(err.matches("[W0821]").count(), 1, "{err}");
    assert!(err.contains("`arvo` (named in fractal.e)"), "{err}");
    assert!(err.contains("W0003"), "{err}");
    let _ = std::fs::remove_dir_all(&out);
}

/// Sedge calls sub-L-systems (`?(n, s)`, `$`) that its included files
/// define: it checks with no error, and its one warning is the colour map
/// its `specifications` names and the object lacks (`sedge.map2`).
#[test]
fn sedge_checks_with_its_sub_lsystems() {
    let dir = object("11-CPFG-Sedge");
    let o = run_in(&dir, &["check", "sedge.l", "--format", "json"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{err}");
    let codes: Vec<&str> = err
        .match_indices("\"code\":\"")
        .map(|(i, _)| &err[i + 8..i + 13])
        .collect();
    assert_eq!(codes, ["W0806"], "{err}");
    assert!(err.contains("sedge.map2"), "{err}");
}
