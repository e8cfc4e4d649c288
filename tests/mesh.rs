//! `graftal render -o OUT.obj|OUT.ply|OUT.glb`: meshes read back by
//! independent tools (Python's trimesh, the Khronos glTF validator),
//! whose counts and bounds must equal graftal's own; and the glTF of a
//! context-free system stays small through its shared subtrees.
//!
//! The tools are looked for on this machine (trimesh with `python3`, the
//! validator as the npm package `gltf-validator` under
//! `~/.cache/graftal-gltf-validator` or `GRAFTAL_GLTF_VALIDATOR`); a test
//! whose tool is missing says so and passes, unless
//! `GRAFTAL_NEED_MESH_TOOLS=1` (set by `.ci/run`, which installs them).

mod common;

use common::{graftal, temp};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

/// A tool is missing: fine on a fresh machine, not in CI.
fn missing(tool: &str) {
    assert!(
        std::env::var("GRAFTAL_NEED_MESH_TOOLS").as_deref() != Ok("1"),
        "{tool} is missing and GRAFTAL_NEED_MESH_TOOLS=1: `.ci/run` installs it"
    );
    eprintln!("{tool} is missing: this mesh check did not run");
}

/// graftal's own figures for a mesh it writes to `out`.
fn render(spec: &str, out: &Path, extra: &[&str]) -> Value {
    let out_s = out.to_str().unwrap();
    let mut args = vec!["render", spec, "-o", out_s, "--format", "json"];
    args.extend_from_slice(extra);
    let r = graftal(&args);
    assert_eq!(r.status, 0, "{}", r.stderr);
    serde_json::from_str(r.stdout.trim()).unwrap()
}

const TRIMESH: &str = r#"
import sys, json, trimesh
s = trimesh.load(sys.argv[1], process=False, force='scene')
m = s.to_geometry() if hasattr(s, 'to_geometry') else s.dump(concatenate=True)
print(json.dumps({"vertices": len(m.vertices), "faces": len(m.faces),
                  "bounds": m.bounds.reshape(-1).tolist()}))
"#;

/// The JSON a tool prints, after it succeeds.
fn json_of(cmd: &mut Command) -> Value {
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// What trimesh reads in `path`; `None` when it is not installed.
fn trimesh(path: &Path) -> Option<Value> {
    let probe = Command::new("python3")
        .args(["-c", "import trimesh"])
        .output();
    if !probe.is_ok_and(|o| o.status.success()) {
        missing("Python's trimesh (pip install trimesh numpy)");
        return None;
    }
    Some(json_of(
        Command::new("python3").args(["-c", TRIMESH]).arg(path),
    ))
}

/// Counts and bounds as trimesh reads them equal graftal's.
fn agrees(ours: &Value, theirs: &Value) {
    assert_eq!(ours["vertices"], theirs["vertices"], "{ours} {theirs}");
    assert_eq!(ours["triangles"], theirs["faces"], "{ours} {theirs}");
    for k in 0..6 {
        let (a, b) = (
            ours["bounds"][k].as_f64().unwrap(),
            theirs["bounds"][k].as_f64().unwrap(),
        );
        // The files hold 32-bit floats.
        assert!(
            (a - b).abs() <= 1e-5 * (1.0 + a.abs()),
            "{k}: {ours} {theirs}"
        );
    }
}

fn validator_dir() -> PathBuf {
    if let Some(d) = std::env::var_os("GRAFTAL_GLTF_VALIDATOR") {
        return PathBuf::from(d);
    }
    let home = std::env::var_os("HOME").unwrap_or_default();
    Path::new(&home).join(".cache/graftal-gltf-validator")
}

const VALIDATE: &str = r#"
const v = require(process.argv[1] + '/node_modules/gltf-validator');
const bytes = new Uint8Array(require('fs').readFileSync(process.argv[2]));
v.validateBytes(bytes).then(r => console.log(JSON.stringify(r.issues)))
 .catch(e => { console.error(e); process.exit(1); });
"#;

/// The validator's issues with the `.glb` at `path`; `None` when it is
/// not installed.
fn validate(path: &Path) -> Option<Value> {
    let dir = validator_dir();
    if !dir.join("node_modules/gltf-validator").exists()
        || Command::new("node").arg("--version").output().is_err()
    {
        missing("the glTF validator (npm install gltf-validator, with node)");
        return None;
    }
    Some(json_of(
        Command::new("node")
            .args(["-e", VALIDATE])
            .arg(&dir)
            .arg(path),
    ))
}

#[test]
fn obj_ply_and_glb_read_back_as_graftal_counts_them() {
    // A plant of tubes, and a cpfg model with polygons, surfaces and
    // colours.
    let cases = [
        ("std:plant-e", "plant"),
        ("tests/corpus/cpfg/11-CPFG-WeepingBirch/fractal.l", "birch"),
    ];
    for (spec, name) in cases {
        for ext in ["obj", "ply", "glb"] {
            let out = temp(&format!("{name}.{ext}"));
            let ours = render(spec, &out, &[]);
            assert!(ours["triangles"].as_u64().unwrap() > 100, "{ours}");
            if ext == "obj" {
                let mtl = std::fs::read_to_string(out.with_extension("mtl")).unwrap();
                let obj = std::fs::read_to_string(&out).unwrap();
                assert!(obj.contains(&format!("mtllib {name}.mtl\n")));
                assert_eq!(
                    mtl.matches("newmtl ").count() as u64,
                    ours["materials"].as_u64().unwrap()
                );
            }
            let Some(theirs) = trimesh(&out) else { return };
            agrees(&ours, &theirs);
        }
    }
}

#[test]
fn the_validator_finds_no_errors() {
    for (spec, name, extra) in [
        ("std:plant-e", "plant", &[][..]),
        ("std:koch-island-quadratic", "island", &["-n", "3"][..]),
        (
            "tests/corpus/cpfg/11-CPFG-WeepingBirch/fractal.l",
            "birch",
            &[][..],
        ),
    ] {
        let out = temp(&format!("{name}-valid.glb"));
        render(spec, &out, extra);
        let Some(issues) = validate(&out) else { return };
        assert_eq!(issues["numErrors"], 0, "{spec}: {issues}");
    }
}

/// The Koch curve: 4^n segments.
const KOCH: &str = "angle factor: 6\naxiom: F\nF --> F+F--F+F\n";

#[test]
fn a_glb_of_a_million_segments_is_kilobytes() {
    let src = temp("koch.l");
    std::fs::write(&src, KOCH).unwrap();
    let out = temp("koch.glb");
    let ours = render(src.to_str().unwrap(), &out, &["-n", "10"]);
    let size = std::fs::metadata(&out).unwrap().len();
    let triangles = ours["triangles"].as_u64().unwrap();
    assert_eq!(triangles, 4u64.pow(10) * 12, "{ours}");
    // Stored whole, each triangle would take at least its three corners
    // (12 bytes each, without normals): over 100 MB.
    assert!(triangles * 36 > 100_000_000);
    assert!(size < 1_000_000, "{size} bytes: {ours}");
    if let Some(issues) = validate(&out) {
        assert_eq!(issues["numErrors"], 0, "{issues}");
    }
    // Fewer steps, so that trimesh can place every node: the same counts.
    let out = temp("koch6.glb");
    let ours = render(src.to_str().unwrap(), &out, &["-n", "6"]);
    assert!(ours["nodes"].as_u64().unwrap() > 1, "{ours}");
    if let Some(theirs) = trimesh(&out) {
        agrees(&ours, &theirs);
    }
}

#[test]
fn render_to_an_obj_prints_its_counts_and_writes_its_material_library() {
    let out = temp("noext.obj");
    let r = graftal(&["render", "std:plant-e", "-o", out.to_str().unwrap()]);
    assert_eq!(r.status, 0, "{}", r.stderr);
    assert!(r.stdout.contains("vertices"), "{}", r.stdout);
    assert!(out.with_extension("mtl").exists());
}
