//! Input that is not what its extension says: the notation assumed is
//! named, another that reads the file cleanly is suggested, `--notation`
//! reads it so, and an empty file gets one answer in every notation.

use crate::common;
use common::{graftal, temp};

const LINF_PLANT: &str = include_str!("../../stdlib/linf/fig06-plant.linf");
const STL_KOCH: &str = include_str!("../../stdlib/stl/fig02-koch-curve.stl");

/// The JSON diagnostics of `check FILE` (with `extra` arguments).
fn check_json(path: &str, extra: &[&str]) -> (i32, Vec<serde_json::Value>) {
    let mut args = vec!["check", "--format", "json", path];
    args.extend_from_slice(extra);
    let o = graftal(&args);
    let ds = o
        .stderr
        .lines()
        .map(|l| serde_json::from_str(l).expect("one JSON object per line"))
        .collect();
    (o.status, ds)
}

/// The diagnostics of `check` on `path`, asserted to be one E0015 error
/// saying `message`.
fn the_one_error(path: &str, message: &str) -> Vec<serde_json::Value> {
    let (status, ds) = check_json(path, &[]);
    assert_eq!(status, 1);
    assert_eq!(ds.len(), 1, "{ds:?}");
    assert_eq!(ds[0]["code"], "E0015");
    assert_eq!(ds[0]["message"], message);
    ds
}

#[test]
fn a_linf_file_saved_as_l_says_it_reads_as_linf() {
    let path = temp("plant-linf.l");
    std::fs::write(&path, LINF_PLANT).unwrap();
    let path = path.to_str().unwrap();
    // Said once, as the one error, not as a note on the first of many.
    let ds = the_one_error(path, "this file reads as LinF, not as pfg (from `.l`)");
    assert_eq!(ds[0]["help"], "rename it `.linf` or pass `--notation linf`");
    assert!(
        ds[0]["notes"].to_string().contains("as pfg: [E0"),
        "the first error of the pfg reading is quoted: {ds:?}"
    );
    // And `--notation linf` reads it.
    let o = graftal(&["check", path, "--notation", "linf"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert!(o.stdout.contains("dialect: LinF, "), "{}", o.stdout);
    let o = graftal(&["derive", path, "--notation", "linf", "-n", "1"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
}

#[test]
fn an_stl_file_saved_as_l_or_linf_is_recognised() {
    for name in ["koch-stl.l", "koch-stl.linf"] {
        let path = temp(name);
        std::fs::write(&path, STL_KOCH).unwrap();
        let (status, ds) = check_json(path.to_str().unwrap(), &[]);
        assert_eq!(status, 1);
        // Read as pfg, many errors: the one error says it. Read as LinF,
        // one error (the file's own slip, perhaps): a note on it says it.
        let said = |d: &serde_json::Value| {
            (d["message"].to_string() + &d["notes"].to_string())
                .contains("this file reads as STL, not as")
        };
        assert_eq!(ds.iter().filter(|d| said(d)).count(), 1, "{name}: {ds:?}");
        let errors = ds.iter().filter(|d| d["severity"] == "error").count();
        assert_eq!(errors, 1, "{name}: {ds:?}");
    }
}

#[test]
fn a_pfg_file_with_a_slip_is_not_sent_elsewhere() {
    let path = temp("slip.l");
    std::fs::write(
        &path,
        "angle factor: 4\naxiom: F+F+F+F\nF -> F+F-F-FF+F+F-F\nF --> F+F\n",
    )
    .unwrap();
    let (status, ds) = check_json(path.to_str().unwrap(), &[]);
    assert_eq!(status, 1);
    assert!(!ds.is_empty());
    assert!(ds.iter().all(|d| d["code"] != "E0015"), "{ds:?}");
}

#[test]
fn a_pfg_file_saved_as_linf_points_back_to_pfg() {
    let path = temp("koch-pfg.linf");
    std::fs::write(&path, include_str!("../../examples/koch-island.l")).unwrap();
    let (_, ds) = check_json(path.to_str().unwrap(), &[]);
    assert_eq!(ds.len(), 1, "{ds:?}");
    assert_eq!(
        ds[0]["message"],
        "this file reads as pfg, not as LinF (from `.linf`)"
    );
    assert_eq!(ds[0]["help"], "pass `--notation pfg`");
}

/// With `--notation` the reader is told, and nothing else is tried.
#[test]
fn a_notation_given_is_not_second_guessed() {
    let path = temp("plant-as-pfg.linf");
    std::fs::write(&path, LINF_PLANT).unwrap();
    let (status, ds) = check_json(path.to_str().unwrap(), &["--notation", "pfg"]);
    assert_eq!(status, 1);
    assert!(
        ds.len() > 1 && ds.iter().all(|d| d["code"] != "E0015"),
        "{ds:?}"
    );
    let o = graftal(&["check", path.to_str().unwrap(), "--notation", "nope"]);
    assert_eq!(o.status, 2);
}

/// An empty file (or one of white space) is one error, the same in every
/// notation: by extension and by `--notation`.
#[test]
fn empty_files_are_the_same_error_in_every_notation() {
    let mut seen = Vec::new();
    for (name, text) in [
        ("empty.l", ""),
        ("empty.linf", ""),
        ("empty.stl", "\n"),
        ("blank.l", "  \n\t\n"),
    ] {
        let path = temp(name);
        std::fs::write(&path, text).unwrap();
        let path = path.to_str().unwrap().to_string();
        for notation in [
            None,
            Some("pfg"),
            Some("linf"),
            Some("stl"),
            Some("cpfg"),
            Some("fractint"),
        ] {
            let extra: Vec<&str> = notation.map_or(vec![], |n| vec!["--notation", n]);
            let (status, ds) = check_json(&path, &extra);
            assert_eq!(ds.len(), 1, "{name} {notation:?}: {ds:?}");
            let message = ds[0]["message"].as_str().unwrap().replace(&path, "FILE");
            seen.push((status, ds[0]["code"].to_string(), message));
        }
    }
    assert_eq!(seen[0].0, 1);
    assert_eq!(seen[0].1, "\"E0014\"");
    assert!(seen.iter().all(|s| s == &seen[0]), "{seen:?}");
}

/// A LinF file whose `{` makes it look like a Fractint library: the
/// Fractint reading has errors at a few names only, and still the one
/// error says what the file is.
#[test]
fn a_linf_file_read_as_a_fractint_library_says_it_reads_as_linf() {
    let path = temp("plant-3d.l");
    std::fs::write(&path, include_str!("../in/linf/linf-plant-3d.linf")).unwrap();
    the_one_error(
        path.to_str().unwrap(),
        "this file reads as LinF, not as Fractint (from `.l`)",
    );
}
