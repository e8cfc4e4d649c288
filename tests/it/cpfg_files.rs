//! The cpfg readers over the whole vlab corpus (tests/corpus/cpfg: 95
//! objects): every L-system file preprocesses, every view, function and
//! surface file reads, with pinned values from real files.

use graftal::front::cpfg::preprocess::preprocess;
use std::fs;
use std::path::{Path, PathBuf};

fn corpus() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/corpus/cpfg"))
}

/// Every file of the corpus with extension `ext`, sorted.
fn files(ext: &str) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let root = corpus();
    let dirs = fs::read_dir(&root).unwrap_or_else(|e| panic!("{}: {e}", root.display()));
    for dir in dirs {
        let dir = dir.unwrap().path();
        if !dir.is_dir() {
            continue;
        }
        for f in fs::read_dir(&dir).unwrap() {
            let f = f.unwrap().path();
            if f.extension().is_some_and(|e| e == ext) {
                out.push(f);
            }
        }
    }
    out.sort();
    out
}

fn read(p: &Path) -> String {
    String::from_utf8_lossy(&fs::read(p).unwrap()).into_owned()
}

fn preprocess_file(path: &Path) -> graftal::front::cpfg::preprocess::Preprocessed {
    let dir = path.parent().unwrap().to_path_buf();
    preprocess(&read(path), &mut |name| {
        fs::read(dir.join(name))
            .ok()
            .map(|b| String::from_utf8_lossy(&b).into_owned())
    })
}

#[test]
fn every_l_file_preprocesses_without_errors() {
    let ls = files("l");
    assert_eq!(ls.len(), 98);
    let mut with_define = 0;
    for l in &ls {
        let src = read(l);
        let p = preprocess_file(l);
        let errors: Vec<_> = p.diagnostics.iter().filter(|d| d.is_error()).collect();
        assert!(errors.is_empty(), "{}: {errors:#?}", l.display());
        assert!(!p.text.contains("#define"), "{}", l.display());
        assert!(!p.text.contains("/*"), "{}", l.display());
        // Lines are kept (Sedge's main file includes others, which add lines).
        if !src.contains("#include") {
            assert_eq!(
                p.text.matches('\n').count(),
                src.matches('\n').count(),
                "{}",
                l.display()
            );
        }
        // The map stays inside the source.
        for start in (0..p.text.len()).step_by(97) {
            let r = p.map.to_source(start..(start + 5).min(p.text.len()));
            assert!(r.start <= r.end && r.end <= src.len());
        }
        if src.contains("#define") {
            with_define += 1;
        }
    }
    assert!(with_define >= 82, "{with_define}");
}

#[test]
fn only_the_fern_leaves_warn() {
    // The two fern-leaf objects end define lines with `\\`.
    let mut warned = Vec::new();
    for l in files("l") {
        let p = preprocess_file(&l);
        if !p.diagnostics.is_empty() {
            let codes: Vec<_> = p.diagnostics.iter().map(|d| d.code.0).collect();
            assert!(
                codes.iter().all(|c| *c == "W0802"),
                "{}: {codes:?}",
                l.display()
            );
            warned.push(
                l.parent()
                    .unwrap()
                    .file_name()
                    .unwrap()
                    .to_string_lossy()
                    .into_owned(),
            );
        }
    }
    assert_eq!(
        warned,
        ["03-inverse-modeling-02-fern-leaf", "15-VlabTools-FernLeaf"]
    );
}

#[test]
fn pinned_expansions() {
    let c = corpus();
    // A continuation-line, function-like macro with macro arguments.
    let p = preprocess_file(&c.join("03-inverse-modeling-02-fern-leaf/plant.l"));
    let src = read(&c.join("03-inverse-modeling-02-fern-leaf/plant.l"));
    assert!(
        p.text
            .contains("dx = (INT_LENGTH_SCALE * func(INT_LENGTH,x_rel) * L0^INT_LENGTH_GAMMA)")
            || p.text.contains("dx = (")
    );
    let line = p.text.lines().find(|l| l.contains("new_x = x+dx")).unwrap();
    assert!(!line.contains("int_length"), "{line}");
    assert!(!line.contains('\\'), "{line}");
    // The expansion maps back to the call `int_length(x_rel)`.
    let at = p.text.find(line).unwrap() + line.find("func(").unwrap();
    let back = p.map.to_source(at..at + 4);
    assert_eq!(&src[back], "int_length(x_rel)");

    // An `#if` branch: clover keeps the LEAVES==1 productions.
    let p = preprocess_file(&c.join("07-Open-13-clover/plant.l"));
    assert!(p.text.contains("L(la,age,rn) : ((rn)-floor(rn)) > 0.03"));
    assert!(!p.text.contains("@c(2.0*sqrt(la/3.14))"));

    // Two trees: nested #if with `==` and `>` on macros.
    let p = preprocess_file(&c.join("07-Open-12-two-trees/tree.l"));
    assert!(!p.text.contains("#if") && !p.text.contains("#else") && !p.text.contains("#endif"));

    // Sedge includes three files; their L-systems follow the main one.
    let p = preprocess_file(&c.join("11-CPFG-Sedge/sedge.l"));
    assert!(p.text.contains("?(2,1.25)spikef$"));
    let systems = p.text.to_lowercase().matches("lsystem:").count();
    assert_eq!(systems, 4);
}

use graftal::front::cpfg::view::{find_view, is_panel, read_view, View};

#[test]
fn every_view_file_reads_without_errors() {
    let vs = files("v");
    assert_eq!(vs.len(), 101);
    let mut panels = Vec::new();
    let mut views = 0;
    let mut default_angle = 0;
    let mut warnings = Vec::new();
    for v in &vs {
        let text = read(v);
        if is_panel(&text) {
            panels.push(v.file_name().unwrap().to_string_lossy().into_owned());
            continue;
        }
        views += 1;
        let (view, d) = read_view(&text);
        warnings.extend(d.iter().filter(|x| !x.is_error()).map(|x| x.code.0));
        let errors: Vec<_> = d.iter().filter(|x| x.is_error()).collect();
        if v.ends_with("01-Introduction-02-snowflake-exercise/fractal.v") {
            // An exercise: the student fills in `angle increment: ?`.
            assert_eq!(errors.len(), 1);
            assert_eq!(errors[0].code.0, "E0812");
            assert_eq!(&text[errors[0].span.clone().unwrap()], "?");
            continue;
        }
        assert!(errors.is_empty(), "{}: {errors:#?}", v.display());
        // The angle is the file's last angle command, else 45°.
        let last = text
            .lines()
            .rfind(|l| l.starts_with("angle factor:") || l.starts_with("angle increment:"));
        match last {
            None => {
                default_angle += 1;
                assert_eq!(view.angle, 45.0, "{}", v.display());
            }
            Some(l) => {
                let n: f64 = l
                    .split(':')
                    .nth(1)
                    .unwrap()
                    .split_whitespace()
                    .next()
                    .unwrap()
                    .parse()
                    .unwrap();
                let want = if l.starts_with("angle factor") {
                    360.0 / n
                } else {
                    n
                };
                assert!((view.angle - want).abs() < 1e-12, "{}", v.display());
            }
        }
        assert!(view.scale_factor > 0.0);
    }
    assert_eq!(panels, ["panel.v", "panel.v", "panel.v"]);
    assert_eq!(views, 98);
    assert!(default_angle >= 10, "{default_angle}");
    // No unknown commands (the one `tappered lines` is inside a comment);
    // what graftal does not draw would be said (textures and background
    // scenes are drawn; shadows are ray traced, so a shadow map needs no
    // warning).
    assert!(warnings.is_empty(), "{warnings:?}");
}

#[test]
fn pinned_view_values() {
    let c = corpus();
    let (v, _) = read_view(&read(
        &c.join("01-Introduction-01-quadratic-Koch/fractal.v"),
    ));
    assert_eq!(v.angle, 90.0);
    assert_eq!(v.initial_color, 1);
    assert_eq!(v.scale_factor, 0.9);
    let (v, _) = read_view(&read(&c.join("11-CPFG-TexturedSurfaces/plant.v")));
    assert_eq!(v.surfaces.len(), 1);
    assert_eq!(v.surfaces[0].file, "leaf.s");
    assert_eq!(v.functions.len(), 5);
    assert_ne!(v, View::default());
}

#[test]
fn every_l_file_finds_its_view() {
    let mut odd = Vec::new();
    for l in files("l") {
        let dir = l.parent().unwrap();
        let name = l.file_name().unwrap().to_string_lossy().into_owned();
        // Sedge's included sub-L-systems have no view of their own.
        if dir.ends_with("11-CPFG-Sedge") && name != "sedge.l" {
            continue;
        }
        let v = find_view(dir, &name).unwrap_or_else(|e| panic!("{}: {e:?}", l.display()));
        assert!(!is_panel(&read(&v)));
        if v.file_stem() != l.file_stem() {
            odd.push(format!(
                "{}/{} -> {}",
                dir.file_name().unwrap().to_string_lossy(),
                name,
                v.file_name().unwrap().to_string_lossy()
            ));
        }
    }
    assert_eq!(
        odd,
        [
            "11-CPFG-ArticulatedLamp/lamp.l -> view.v",
            "11-CPFG-JumpingLamp/lamp.l -> view.v",
            "11-CPFG-Tropisms/lsystem.l -> view.v",
            "20-EnviroPgms-CPFG-CelticKnot/lsystem.l -> viewfile.v",
        ]
    );
}

use graftal::front::cpfg::func::{read_fset, read_func, Function};

/// The function's value at 0 and 1 must be its first and last control
/// points' y (the spline is clamped), within cpfg's bisection tolerance
/// (|Δx| ≤ 0.001) times the curve's steepness there; and x must grow along
/// the curve when the control polygon's x does.
fn check_function(f: &Function, what: &str) {
    let first = f.points[0];
    let last = f.points[f.points.len() - 1];
    let slope = |a: [f64; 2], b: [f64; 2]| {
        if (b[0] - a[0]).abs() < 1e-9 {
            f64::INFINITY
        } else {
            ((b[1] - a[1]) / (b[0] - a[0])).abs()
        }
    };
    // The curve's slope is bounded by its control polygon's (x-monotone
    // curves): the bisection's x error turns into at most this much y error.
    let steepest = f
        .points
        .windows(2)
        .map(|w| slope(w[0], w[1]))
        .fold(0.0, f64::max);
    let tol0 = 0.001 * steepest * 3.0 + 1e-6;
    let tol1 = tol0;
    // Exact evaluation is what the endpoint property is about.
    let mut exact = f.clone();
    exact.set_samples(0);
    assert!(
        (exact.eval(0.0) - first[1]).abs() <= tol0,
        "{what}: f(0) = {} vs {}",
        exact.eval(0.0),
        first[1]
    );
    assert!(
        (exact.eval(1.0) - last[1]).abs() <= tol1,
        "{what}: f(1) = {} vs {}",
        exact.eval(1.0),
        last[1]
    );
    let p0 = f.point(0.0);
    assert!(
        (p0[0] - first[0]).abs() < 1e-9 && (p0[1] - first[1]).abs() < 1e-9,
        "{what}: {p0:?} vs {first:?}"
    );
    if f.is_monotone() {
        let xs: Vec<f64> = (0..=200).map(|i| f.point(i as f64 / 200.0)[0]).collect();
        assert!(xs.windows(2).all(|w| w[1] >= w[0] - 1e-12), "{what}");
    }
    for i in 0..=50 {
        assert!(f.eval(i as f64 / 50.0).is_finite());
    }
}

#[test]
fn every_function_file_reads() {
    let fs = files("func");
    assert_eq!(fs.len(), 100);
    let mut monotone = 0;
    for p in &fs {
        let f = read_func(&read(p)).unwrap_or_else(|d| panic!("{}: {d:#?}", p.display()));
        check_function(&f, &p.display().to_string());
        monotone += usize::from(f.is_monotone());
    }
    assert!(monotone >= 90, "{monotone}");
    let sets = files("fset");
    assert_eq!(sets.len(), 4);
    let mut total = 0;
    for p in &sets {
        let set = read_fset(&read(p)).unwrap_or_else(|d| panic!("{}: {d:#?}", p.display()));
        assert!(!set.is_empty());
        for (name, f) in &set {
            check_function(f, &format!("{} {name}", p.display()));
        }
        total += set.len();
    }
    assert!(total >= 8, "{total}");
}

#[test]
fn pinned_function_values() {
    let c = corpus();
    // JumpingLamp's set: 7 functions, the first named Ang_1, 100 samples.
    let set = read_fset(&read(&c.join("11-CPFG-JumpingLamp/functions.fset"))).unwrap();
    assert_eq!(set.len(), 7);
    assert_eq!(set[0].0, "Ang_1");
    assert_eq!(set[0].1.samples, 100);
    // internode.func: rises from 0 to about 1 with a step around x = 0.6.
    let f = read_func(&read(&c.join("02-Mod-vis-3D-05-monopodial/internode.func"))).unwrap();
    assert_eq!(f.samples, 10);
    assert!(f.eval(0.1) < 0.1 && f.eval(0.95) > 0.9);
}

use graftal::front::cpfg::surface::read_surface;

#[test]
fn every_surface_file_reads() {
    let ss = files("s");
    assert_eq!(ss.len(), 23);
    let mut patches = 0;
    for p in &ss {
        let text = read(p);
        let s = read_surface(&text).unwrap_or_else(|d| panic!("{}: {d:#?}", p.display()));
        assert_eq!(
            s.patches.len(),
            text.matches("TOP COLOR").count(),
            "{}",
            p.display()
        );
        for d in [1, 4] {
            let t = s.triangles(d);
            assert_eq!(t.len(), s.patches.len() * 2 * (d * d) as usize);
            // Every vertex lies in the control points' bounding box (the
            // convex-hull property of Bézier patches).
            let cps: Vec<[f64; 3]> = s
                .patches
                .iter()
                .flat_map(|q| q.points.iter().flatten().copied())
                .collect();
            for k in 0..3 {
                let lo = cps.iter().map(|c| c[k]).fold(f64::INFINITY, f64::min);
                let hi = cps.iter().map(|c| c[k]).fold(f64::NEG_INFINITY, f64::max);
                assert!(t
                    .iter()
                    .flatten()
                    .all(|v| v[k] >= lo - 1e-9 && v[k] <= hi + 1e-9));
            }
        }
        assert!(s.size > 0.0);
        // The contact point is the origin of the turtle frame.
        assert_eq!(s.to_turtle(s.contact), [0.0, 0.0, 0.0]);
        patches += s.patches.len();
    }
    assert_eq!(patches, 14 + 4 * 2 + 5 * 4);
    // A pinned file: the Sedge female spike has two patches.
    let s = read_surface(&read(&corpus().join("11-CPFG-Sedge/female.s"))).unwrap();
    assert_eq!(s.patches[1].name, "Patch_2");
    assert_eq!(s.contact, [0.32, -35.0, 0.0]);
    assert_eq!(s.size, 167.44);
    assert_eq!(s.precision, None);
    let s = read_surface(&read(
        &corpus().join("04-Signaling-10-mycelis-realistic/bud.s"),
    ))
    .unwrap();
    assert_eq!(s.precision, Some((5, 5)));
    assert_eq!(s.patches.len(), 4);
}

fn compile_object(dir: &str, l: &str) -> graftal::driver::Compiled {
    let path = corpus().join(dir).join(l);
    graftal::driver::compile(graftal::source::SourceFile::read(&path).unwrap())
}

/// The colour map named by `-m` on the object's `cpfg` line is the
/// palette, byte for byte, and its index 0 the background.
#[test]
fn the_colour_map_of_the_specifications_is_used() {
    let c = compile_object("01-Introduction-01-quadratic-Koch", "fractal.l");
    let sys = c.system.unwrap();
    let bytes = fs::read(corpus().join("01-Introduction-01-quadratic-Koch/fractal.map")).unwrap();
    assert_eq!(sys.colours.len(), 256);
    for (k, c) in sys.colours.iter().enumerate() {
        assert_eq!([c.0, c.1, c.2], bytes[3 * k..3 * k + 3], "index {k}");
    }
    let bg = sys.look.background.unwrap();
    assert_eq!([bg.0, bg.1, bg.2], bytes[0..3]);
    assert!(sys.look.lighting.as_ref().unwrap().materials.is_empty());
}

/// `-M`: the materials, with the emission of material 0 as the
/// background (Lilac's sky blue) and the diffuse colours as the palette.
#[test]
fn the_materials_of_the_specifications_are_used() {
    let c = compile_object("11-CPFG-Lilac", "plant.l");
    let sys = c.system.unwrap();
    assert_eq!(
        sys.look.background,
        Some(graftal::ir::Rgb(0xa0, 0xb9, 0xff))
    );
    assert_eq!(sys.colours[1], graftal::ir::Rgb(0xe4, 0xc5, 0xff));
    let lighting = sys.look.lighting.unwrap();
    let m = lighting.materials[1].unwrap();
    assert_eq!(m.specular, [0x43, 0x2f, 0x39].map(|b| b as f32 / 255.0));
    assert!(lighting.materials[5].is_none());
}

/// A surface is normalised by its `SIZE:`: Lilac's petal (SIZE 39.59,
/// view scale 2.75) spans about 2.75 turtle units, not 109.
#[test]
fn surfaces_are_scaled_by_their_size() {
    let c = compile_object("11-CPFG-Lilac", "plant.l");
    let sys = c.system.unwrap();
    let petal = sys.surfaces.iter().find(|s| s.name == "~p").unwrap();
    let ys: Vec<f64> = petal.triangles.iter().flatten().map(|p| p[1]).collect();
    let span =
        ys.iter().cloned().fold(f64::MIN, f64::max) - ys.iter().cloned().fold(f64::MAX, f64::min);
    assert!((2.0..3.5).contains(&span), "petal length {span}");
}

/// A colour map that is missing or not 768 bytes is a warning, and the
/// picture keeps cpfg's default colours.
#[test]
fn a_bad_colour_map_is_a_warning() {
    let dir = std::env::temp_dir().join(format!("graftal-map-{}", std::process::id()));
    fs::create_dir_all(&dir).unwrap();
    fs::write(dir.join("a.l"), "lsystem: 1\naxiom: F\nendlsystem\n").unwrap();
    fs::write(dir.join("specifications"), "cpfg -m short.map a.l a.v\n").unwrap();
    fs::write(dir.join("short.map"), [1u8; 700]).unwrap();
    fs::write(dir.join("a.v"), "angle factor: 8\n").unwrap();
    let c = graftal::driver::compile(graftal::source::SourceFile::read(&dir.join("a.l")).unwrap());
    let codes: Vec<&str> = c.diagnostics.iter().map(|d| d.code.0).collect();
    assert_eq!(codes, ["W0806"]);
    assert!(c.diagnostics.0[0].message.contains("768 bytes"));
    let sys = c.system.unwrap();
    assert_eq!(
        sys.colours,
        graftal::front::cpfg::view::default_colormap().to_vec()
    );
    fs::write(dir.join("specifications"), "cpfg -m gone.map a.l a.v\n").unwrap();
    let c = graftal::driver::compile(graftal::source::SourceFile::read(&dir.join("a.l")).unwrap());
    let codes: Vec<&str> = c.diagnostics.iter().map(|d| d.code.0).collect();
    assert_eq!(codes, ["W0806"]);
    fs::remove_dir_all(&dir).unwrap();
}

/// The files of the object `name` of the corpus copied into a fresh folder,
/// with `rename` applied to their names and `specifications` left out: the
/// layout L-studio writes.
fn l_studio_copy(name: &str, rename: &[(&str, &str)]) -> PathBuf {
    let to = crate::common::temp(name);
    fs::create_dir_all(&to).unwrap();
    for e in fs::read_dir(corpus().join(name)).unwrap() {
        let e = e.unwrap();
        let file = e.file_name().to_string_lossy().into_owned();
        if file == "specifications" {
            continue;
        }
        let new = (rename.iter().find(|(from, _)| *from == file)).map_or(file.as_str(), |r| r.1);
        fs::copy(e.path(), to.join(new)).unwrap();
    }
    to
}

fn compile_at(path: &Path) -> graftal::driver::Compiled {
    graftal::driver::compile(graftal::source::SourceFile::read(path).unwrap())
}

/// An L-studio folder (no `specifications`) is drawn with the materials
/// it holds, as vlab draws the same object with its `cpfg -M` line, and a
/// contour named `calyx.con` in the view file is read from `CALYX.con`;
/// warnings say which files were taken.
#[test]
fn an_l_studio_folder_draws_with_its_own_colours_and_any_case_names() {
    let vlab = compile_object("10-GettingStarted-01-Lychnis", "plant.l");
    let dir = l_studio_copy(
        "10-GettingStarted-01-Lychnis",
        &[("calyx.con", "CALYX.con"), ("material.mat", "Lychnis.mat")],
    );
    let studio = compile_at(&dir.join("plant.l"));
    let (vlab_sys, studio_sys) = (vlab.system.unwrap(), studio.system.unwrap());
    assert_eq!(studio_sys.colours, vlab_sys.colours);
    assert_eq!(studio_sys.look, vlab_sys.look);
    assert_eq!(studio_sys.contours, vlab_sys.contours);
    let said = |code: &str| {
        (studio.diagnostics.iter())
            .find(|d| d.code.0 == code)
            .unwrap_or_else(|| panic!("no {code} in {:?}", studio.diagnostics))
            .message
            .clone()
    };
    assert!(said("W0811").contains("`Lychnis.mat`"), "{}", said("W0811"));
    let case = said("W0809");
    assert!(
        case.contains("`calyx.con`") && case.contains("`CALYX.con`"),
        "{case}"
    );
    let codes: Vec<&str> = vlab.diagnostics.iter().map(|d| d.code.0).collect();
    assert!(
        !codes.contains(&"W0811") && !codes.contains(&"W0809"),
        "{codes:?}"
    );
    fs::remove_dir_all(&dir).unwrap();
}

/// With two colour maps and none named like the `.l`, none is taken (the
/// choice would be a guess); named like the `.l`, that one is.
#[test]
fn a_folder_colour_map_is_taken_only_when_it_is_the_objects() {
    let dir = crate::common::temp("maps");
    fs::create_dir_all(&dir).unwrap();
    fs::write(dir.join("a.l"), "lsystem: 1\naxiom: F\nendlsystem\n").unwrap();
    fs::write(dir.join("a.v"), "angle factor: 8\n").unwrap();
    let map = |b: u8| [b; 768];
    fs::write(dir.join("x.map"), map(7)).unwrap();
    fs::write(dir.join("y.map"), map(9)).unwrap();
    let c = compile_at(&dir.join("a.l"));
    assert!(c.diagnostics.is_empty(), "{:?}", c.diagnostics);
    let default = graftal::front::cpfg::view::default_colormap().to_vec();
    assert_eq!(c.system.unwrap().colours, default);
    fs::write(dir.join("A.map"), map(5)).unwrap();
    let c = compile_at(&dir.join("a.l"));
    assert_eq!(c.system.unwrap().colours[0], graftal::ir::Rgb(5, 5, 5));
    assert_eq!(c.diagnostics.0[0].code.0, "W0811");
}

/// No view file, or one named in `specifications` and absent, is a
/// warning naming cpfg's defaults the picture is drawn with.
#[test]
fn a_missing_view_file_is_a_warning_naming_the_defaults() {
    let dir = crate::common::temp("noview");
    fs::create_dir_all(&dir).unwrap();
    fs::write(dir.join("a.l"), "lsystem: 1\naxiom: F\nendlsystem\n").unwrap();
    let c = compile_at(&dir.join("a.l"));
    let d = &c.diagnostics.0[0];
    assert_eq!(
        (d.code.0, d.message.as_str()),
        ("W0810", "no view file for `a.l`")
    );
    assert!(d.notes[0].contains("angle 45°"), "{:?}", d.notes);
    fs::write(dir.join("specifications"), "cpfg a.l gone.v\n").unwrap();
    let c = compile_at(&dir.join("a.l"));
    let d = &c.diagnostics.0[0];
    assert_eq!(d.code.0, "W0810");
    assert!(d.message.contains("`gone.v`"), "{}", d.message);
    // Text with no folder behind it (standard input, an editor's buffer
    // not saved) has no view file to miss.
    let text = graftal::source::SourceFile::new("<stdin>", "lsystem: 1\naxiom: F\nendlsystem\n");
    assert!(graftal::driver::compile(text).diagnostics.is_empty());
}
