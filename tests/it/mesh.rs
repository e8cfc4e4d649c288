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
//! The tools run only with `GRAFTAL_SLOW=1` (graftal's own figures are
//! checked in every run).

use crate::common;

use common::{graftal, slow, temp};
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

/// What trimesh reads in `path`; `None` when it is not installed or the
/// slow suites do not run.
fn trimesh(path: &Path) -> Option<Value> {
    if !slow("mesh: reading meshes back with trimesh") {
        return None;
    }
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
/// not installed or the slow suites do not run.
fn validate(path: &Path) -> Option<Value> {
    if !slow("mesh: the Khronos glTF validator") {
        return None;
    }
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

/// A lit cpfg object whose material file has specular highlights, an
/// emission and a transparent material.
const LILAC: &str = "tests/corpus/cpfg/11-CPFG-Lilac/plant.l";

/// The records of a cpfg `.mat` file by colour index, read here on their
/// own: transparency, ambient, diffuse, emission and specular RGB, each
/// byte / 255, then the shininess byte / 255 × 128.
fn cpfg_materials(path: &str) -> std::collections::HashMap<u8, Vec<f64>> {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(bytes.len() % 15, 0);
    bytes
        .chunks(15)
        .map(|r| {
            let mut v: Vec<f64> = r[1..].iter().map(|&b| f64::from(b) / 255.0).collect();
            v[13] *= 128.0;
            (r[0], v)
        })
        .collect()
}

/// The materials of an `.mtl` text: name → keyword → numbers.
fn mtl_materials(text: &str) -> Vec<(String, std::collections::HashMap<String, Vec<f64>>)> {
    let mut out: Vec<(String, std::collections::HashMap<String, Vec<f64>>)> = Vec::new();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match (words.next(), out.last_mut()) {
            (Some("newmtl"), _) => out.push((words.next().unwrap().into(), Default::default())),
            (Some(k), Some((_, m))) if !k.starts_with('#') => {
                m.insert(k.into(), words.map(|w| w.parse().unwrap()).collect());
            }
            _ => {}
        }
    }
    out
}

fn near(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-4
}

#[test]
fn a_lit_objects_obj_carries_its_cpfg_materials() {
    let mat = cpfg_materials("tests/corpus/cpfg/11-CPFG-Lilac/materials.mat");
    let out = temp("lilac.obj");
    let ours = render(LILAC, &out, &[]);
    let mtl = mtl_materials(&std::fs::read_to_string(out.with_extension("mtl")).unwrap());
    assert_eq!(mtl.len() as u64, ours["materials"].as_u64().unwrap());
    let (mut emits, mut transparent, mut shiny) = (false, false, false);
    for (name, m) in &mtl {
        let index: u8 = name.strip_prefix('m').unwrap().parse().unwrap();
        let r = &mat[&index];
        let rgb = |k: &str| m[k].clone();
        for (key, at) in [("Ka", 1), ("Kd", 4), ("Ke", 7), ("Ks", 10)] {
            let want = &r[at..at + 3];
            assert!((0..3).all(|i| near(rgb(key)[i], want[i])), "{name} {key}");
        }
        assert!(near(m["Ns"][0], r[13]), "{name} Ns");
        assert!(near(m["d"][0], 1.0 - r[0]), "{name} d");
        let specular = r[10..13].iter().any(|&x| x > 0.0);
        assert_eq!(m["illum"][0], if specular { 2.0 } else { 1.0 }, "{name}");
        emits |= r[7..10].iter().any(|&x| x > 0.0);
        transparent |= r[0] > 0.0;
        shiny |= specular;
    }
    assert!(emits && transparent && shiny, "{mtl:?}");

    // trimesh reads each material under its name, with the same colours.
    let script = r#"
import sys, json, trimesh
s = trimesh.load(sys.argv[1], process=False, force='scene')
print(json.dumps({g.visual.material.name: {
    "Ka": g.visual.material.ambient[:3].tolist(),
    "Kd": g.visual.material.diffuse[:3].tolist(),
    "Ks": g.visual.material.specular[:3].tolist(),
    "Ns": float(g.visual.material.glossiness)} for g in s.geometry.values()}))
"#;
    if trimesh(&out).is_none() {
        return;
    }
    let theirs = json_of(Command::new("python3").args(["-c", script]).arg(&out));
    assert_eq!(theirs.as_object().unwrap().len(), mtl.len(), "{theirs}");
    for (name, m) in &mtl {
        let t = &theirs[name.as_str()];
        for key in ["Ka", "Kd", "Ks"] {
            for i in 0..3 {
                let byte = t[key][i].as_f64().unwrap();
                assert!(
                    (byte - (m[key][i] * 255.0).round()).abs() <= 1.0,
                    "{name} {t}"
                );
            }
        }
        assert!(near(t["Ns"].as_f64().unwrap(), m["Ns"][0]), "{name} {t}");
    }
}

/// The JSON chunk of a `.glb` file.
fn glb_json(path: &Path) -> Value {
    let bytes = std::fs::read(path).unwrap();
    let len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    serde_json::from_slice(&bytes[20..20 + len]).unwrap()
}

/// An sRGB component as a linear one.
fn linear(s: f64) -> f64 {
    if s <= 0.04045 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    }
}

#[test]
fn a_lit_objects_glb_carries_emission_roughness_and_transparency() {
    let mat = cpfg_materials("tests/corpus/cpfg/11-CPFG-Lilac/materials.mat");
    let out = temp("lilac.glb");
    render(LILAC, &out, &[]);
    let doc = glb_json(&out);
    let materials = doc["materials"].as_array().unwrap();
    assert!(materials.len() >= 2, "{doc}");
    for m in materials {
        let name = m["name"].as_str().unwrap();
        let r = &mat[&name.strip_prefix('m').unwrap().parse::<u8>().unwrap()];
        let pbr = &m["pbrMetallicRoughness"];
        let base = pbr["baseColorFactor"].as_array().unwrap();
        for i in 0..3 {
            assert!(near(base[i].as_f64().unwrap(), linear(r[4 + i])), "{m}");
        }
        assert!(near(base[3].as_f64().unwrap(), 1.0 - r[0]), "{m}");
        let blended = m["alphaMode"] == "BLEND";
        assert_eq!(blended, r[0] > 0.0, "{m}");
        let roughness = (2.0 / (r[13] + 2.0)).sqrt();
        assert!(
            near(pbr["roughnessFactor"].as_f64().unwrap(), roughness),
            "{m}"
        );
        assert_eq!(pbr["metallicFactor"], 0.0);
        let emission: Vec<f64> = (7..10).map(|k| linear(r[k])).collect();
        let e = &m["emissiveFactor"];
        for (i, want) in emission.iter().enumerate() {
            // glTF's default emission is black.
            assert!(near(e[i].as_f64().unwrap_or(0.0), *want), "{m}");
        }
    }
    assert!(materials.iter().any(|m| m["emissiveFactor"].is_array()));
    if let Some(issues) = validate(&out) {
        assert_eq!(issues["numErrors"], 0, "{issues}");
    }
}

/// A lit cpfg object whose leaves (surfaces) wear a PNG texture.
const MAPLE: &str = "tests/corpus/cpfg/11-CPFG-TexturedSurfaces/plant.l";

#[test]
fn a_textured_objects_obj_has_texture_coordinates_and_its_image() {
    let out = temp("maple.obj");
    render(MAPLE, &out, &[]);
    let obj = std::fs::read_to_string(&out).unwrap();
    let mtl = std::fs::read_to_string(out.with_extension("mtl")).unwrap();
    let vt = obj.lines().filter(|l| l.starts_with("vt ")).count();
    assert!(vt > 100, "{vt} vt lines");
    // Textured faces name their coordinates: `f v/vt/vn`, every index in
    // range.
    let textured: Vec<&str> = obj
        .lines()
        .filter(|l| l.starts_with("f ") && !l.contains("//"))
        .collect();
    assert!(!textured.is_empty());
    for f in &textured {
        for corner in f[2..].split(' ') {
            let t: usize = corner.split('/').nth(1).unwrap().parse().unwrap();
            assert!((1..=vt).contains(&t), "{f}");
        }
    }
    assert!(mtl.contains("map_Kd maple_t1.png\n"), "{mtl}");
    // The image beside it: the maple leaf, decoded as the source's.
    let png = std::fs::read(out.with_file_name("maple_t1.png")).unwrap();
    let source = std::fs::read("tests/corpus/cpfg/11-CPFG-TexturedSurfaces/maple.png").unwrap();
    assert_eq!(
        graftal::decode::decode(&png).unwrap(),
        graftal::decode::decode(&source).unwrap()
    );
    if let Some(theirs) = trimesh(&out) {
        agrees(&render(MAPLE, &temp("maple2.obj"), &[]), &theirs);
    }
}

#[test]
fn a_textured_objects_glb_embeds_its_image_and_texture_coordinates() {
    let out = temp("maple.glb");
    render(MAPLE, &out, &[]);
    let doc = glb_json(&out);
    let prims: Vec<&Value> = doc["meshes"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|m| m["primitives"].as_array().unwrap())
        .collect();
    let textured: Vec<&&Value> = prims
        .iter()
        .filter(|p| p["attributes"].get("TEXCOORD_0").is_some())
        .collect();
    assert!(!textured.is_empty());
    let accessor =
        &doc["accessors"][textured[0]["attributes"]["TEXCOORD_0"].as_u64().unwrap() as usize];
    assert_eq!(accessor["type"], "VEC2");
    let material = &doc["materials"][textured[0]["material"].as_u64().unwrap() as usize];
    let texture = material["pbrMetallicRoughness"]["baseColorTexture"]["index"]
        .as_u64()
        .unwrap() as usize;
    assert_eq!(material["alphaMode"], "MASK");
    let t = &doc["textures"][texture];
    let sampler = &doc["samplers"][t["sampler"].as_u64().unwrap() as usize];
    assert_eq!(
        (sampler["wrapS"].as_u64(), sampler["wrapT"].as_u64()),
        (Some(10497), Some(10497))
    );
    let image = &doc["images"][t["source"].as_u64().unwrap() as usize];
    assert_eq!(image["mimeType"], "image/png");
    // The image's bytes in the binary chunk decode to the maple leaf.
    let view = &doc["bufferViews"][image["bufferView"].as_u64().unwrap() as usize];
    let bytes = std::fs::read(&out).unwrap();
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let bin = &bytes[20 + json_len + 8..];
    let at = view["byteOffset"].as_u64().unwrap() as usize;
    let len = view["byteLength"].as_u64().unwrap() as usize;
    let im = graftal::decode::decode(&bin[at..at + len]).unwrap();
    assert_eq!((im.width(), im.height()), (256, 256));
    if let Some(issues) = validate(&out) {
        assert_eq!(issues["numErrors"], 0, "{issues}");
    }
}
