//! The snapshot driver, in naga's style: every input
//! `tests/in/<notation>/NAME.EXT` (a cpfg object is a folder,
//! `tests/in/cpfg/NAME/`, read from the `.l` its `specifications` names)
//! goes through graftal's command line, in process, once for each target
//! its parameter file `NAME.toml` beside it asks for; each output must equal
//! `tests/out/<target>/NAME.<ext>` byte for byte ([`check_golden_bytes`]).
//! Regenerate on purpose with `GRAFTAL_BLESS=1 cargo test snapshots`.
//!
//! The targets, and what writes each:
//! - `word`: `graftal derive` (`tests/out/word/NAME.txt`);
//! - `stats`: `graftal stats --format json`, its timings left out
//!   (`tests/out/stats/NAME.json`);
//! - `svg`, `png`: `graftal render` (`tests/out/svg/NAME.svg`,
//!   `tests/out/png/NAME.png`);
//! - `diagnostics`: `graftal check`'s diagnostics as text and as JSON
//!   (`tests/out/diagnostics/NAME.txt`, `NAME.json`);
//! - each notation of `translate`: `graftal translate --to NOTATION`
//!   (`tests/out/NOTATION/NAME.EXT`).
//!
//! `svg_method` and `png_method` in a parameter file name the way of
//! drawing the library's one call for a picture chooses for that picture
//! (`shared subtrees`, `streamed`, `lit`, `stored`), and it must: the inputs
//! cover every way. `tests/in/README.md` says which input takes which.

use graftal::back::BACKS;
use graftal::driver::picture::{self, Format, Quiet, Request};
use graftal::driver::{compile, load, RunOptions};
use graftal::render::View;
use serde::Deserialize;
use std::path::{Path, PathBuf};

use crate::common;
use common::{check_golden_bytes, graftal_bytes, main_l};

/// What a parameter file `NAME.toml` may say; every field has a default.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    /// The targets written and compared [default: word, stats, svg].
    #[serde(default = "default_targets")]
    targets: Vec<Target>,
    /// Derivation steps [default: the file's own].
    steps: Option<u64>,
    /// The seed of every command [default: 42].
    #[serde(default = "default_seed")]
    seed: u64,
    /// `--view AZIMUTH,ELEVATION` of the pictures [default: the file's].
    view: Option<String>,
    /// `--size` of the SVG [default: 400x400].
    #[serde(default = "default_svg_size")]
    svg_size: String,
    /// `--size` of the PNG, small to keep the repository small [default:
    /// 128x128].
    #[serde(default = "default_png_size")]
    png_size: String,
    /// The notations the input is translated to, each a target.
    #[serde(default)]
    translate: Vec<String>,
    /// The way the SVG is drawn ([`picture::Method::name`]), checked.
    svg_method: Option<String>,
    /// The way the PNG is drawn, checked.
    png_method: Option<String>,
}

fn default_targets() -> Vec<Target> {
    vec![Target::Word, Target::Stats, Target::Svg]
}

fn default_seed() -> u64 {
    42
}

fn default_svg_size() -> String {
    "400x400".into()
}

fn default_png_size() -> String {
    "128x128".into()
}

#[derive(Deserialize, Clone, Copy, PartialEq, Debug)]
#[serde(rename_all = "lowercase")]
enum Target {
    Word,
    Stats,
    Svg,
    Png,
    Diagnostics,
}

impl Target {
    /// The folder of its snapshots under `tests/out/`, and their extensions.
    fn folder(self) -> (&'static str, &'static [&'static str]) {
        match self {
            Target::Word => ("word", &["txt"]),
            Target::Stats => ("stats", &["json"]),
            Target::Svg => ("svg", &["svg"]),
            Target::Png => ("png", &["png"]),
            Target::Diagnostics => ("diagnostics", &["txt", "json"]),
        }
    }
}

const TARGETS: [Target; 5] = [
    Target::Word,
    Target::Stats,
    Target::Svg,
    Target::Png,
    Target::Diagnostics,
];

/// One input: its name (the stem of its outputs), the path graftal reads
/// (relative to the repository, as diagnostics print it) and its
/// parameters.
struct Input {
    name: String,
    path: String,
    params: Params,
}

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Every input under `tests/in/`, sorted by notation and name.
fn inputs() -> Vec<Input> {
    let mut inputs = Vec::new();
    for notation in sorted_entries(&repo().join("tests/in")) {
        if !notation.is_dir() {
            continue;
        }
        for entry in sorted_entries(&notation) {
            let ext = entry.extension().and_then(|e| e.to_str());
            if matches!(ext, Some("toml" | "md")) {
                continue;
            }
            let name = entry.file_stem().unwrap().to_string_lossy().into_owned();
            let file = if entry.is_dir() {
                main_l(&entry).unwrap_or_else(|| panic!("{}: no .l", entry.display()))
            } else {
                entry.clone()
            };
            let path = file
                .strip_prefix(repo())
                .unwrap()
                .to_string_lossy()
                .into_owned();
            let params = params(&entry.with_extension("toml"));
            inputs.push(Input { name, path, params });
        }
    }
    inputs
}

/// `tests/out/FOLDER/FILE`.
fn snapshot(folder: &str, file: &str) -> PathBuf {
    repo().join("tests/out").join(folder).join(file)
}

fn sorted_entries(dir: &Path) -> Vec<PathBuf> {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    entries
}

/// The parameters at `path`, or the defaults when there is no such file.
fn params(path: &Path) -> Params {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    toml::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

impl Input {
    /// `graftal COMMAND INPUT …` with the parameters the command takes
    /// (`check` none, `translate` the steps, the others the seed too) and
    /// `extra`: its status, stdout and stderr.
    fn run(&self, command: &str, extra: &[&str]) -> (i32, Vec<u8>, Vec<u8>) {
        let mut args = vec![command, &self.path];
        let seed = self.params.seed.to_string();
        if !matches!(command, "check" | "translate") {
            args.extend(["--seed", &seed]);
        }
        let steps = self.params.steps.map(|n| n.to_string());
        if let Some(steps) = steps.as_deref().filter(|_| command != "check") {
            args.extend(["-n", steps]);
        }
        args.extend_from_slice(extra);
        graftal_bytes(&args, false)
    }

    /// The stdout of `graftal COMMAND INPUT …`, which must succeed.
    fn output(&self, command: &str, extra: &[&str]) -> Vec<u8> {
        let (status, stdout, stderr) = self.run(command, extra);
        let stderr = String::from_utf8_lossy(&stderr);
        assert_eq!(status, 0, "{} {command}: {stderr}", self.path);
        stdout
    }

    /// The picture `graftal render` writes to standard output.
    fn picture(&self, to: &str, size: &str) -> Vec<u8> {
        let mut extra = vec!["-o", "-", "--to", to, "--size", size];
        if let Some(view) = &self.params.view {
            extra.extend(["--view", view]);
        }
        self.output("render", &extra)
    }

    /// Each output of `target`: the golden file it is compared with and
    /// its bytes.
    fn outputs(&self, target: Target) -> Vec<(PathBuf, Vec<u8>)> {
        let bytes = match target {
            Target::Word => vec![self.output("derive", &[])],
            Target::Stats => vec![self.stats()],
            Target::Svg => vec![self.picture("svg", &self.params.svg_size)],
            Target::Png => vec![self.picture("png", &self.params.png_size)],
            Target::Diagnostics => vec![
                self.run("check", &[]).2,
                self.run("check", &["--format", "json"]).2,
            ],
        };
        self.snapshots(target).into_iter().zip(bytes).collect()
    }

    /// The golden files of `target`.
    fn snapshots(&self, target: Target) -> Vec<PathBuf> {
        let (folder, extensions) = target.folder();
        (extensions.iter())
            .map(|ext| snapshot(folder, &format!("{}.{ext}", self.name)))
            .collect()
    }

    /// `graftal stats --format json` without its timings, pretty-printed.
    fn stats(&self) -> Vec<u8> {
        let json = self.output("stats", &["--format", "json"]);
        let mut stats: serde_json::Value = serde_json::from_slice(&json).unwrap();
        stats.as_object_mut().unwrap().remove("time");
        let mut text = serde_json::to_string_pretty(&stats).unwrap();
        text.push('\n');
        text.into_bytes()
    }

    /// The way the library's one call for a picture draws the picture
    /// `graftal render` draws in `format` at `size` (`WxH`).
    fn method(&self, format: Format, size: &str) -> &'static str {
        let c = compile(load(&self.path).unwrap());
        let (w, h) = size.split_once('x').expect("WxH");
        let view = (self.params.view.as_deref()).map(|v| {
            let (az, el) = v.split_once(',').expect("AZ,EL");
            View::degrees(az.parse().unwrap(), el.parse().unwrap())
        });
        let req = Request {
            run: RunOptions {
                steps: self.params.steps,
                seed: self.params.seed,
                ..RunOptions::default()
            },
            width: w.parse().unwrap(),
            height: h.parse().unwrap(),
            view,
            ..Request::new(picture::Target::Still(format))
        };
        let p = picture::draw(&c, &req, &mut Quiet).unwrap();
        p.method.name()
    }

    /// Where a picture is not drawn the way its parameters say.
    fn wrong_methods(&self) -> Vec<String> {
        let asked = [
            (Format::Svg, &self.params.svg_method, &self.params.svg_size),
            (Format::Png, &self.params.png_method, &self.params.png_size),
        ];
        let mut out = Vec::new();
        for (format, method, size) in asked {
            let Some(method) = method else { continue };
            let drawn = self.method(format, size);
            if drawn != method {
                out.push(format!(
                    "{}: the {} is drawn {drawn}, not {method}",
                    self.name,
                    format.name()
                ));
            }
        }
        out
    }

    /// The translation to `notation` and its golden file.
    fn translation(&self, notation: &str) -> (PathBuf, Vec<u8>) {
        let bytes = self.output("translate", &["--to", notation]);
        (self.translation_path(notation), bytes)
    }

    /// `tests/out/NOTATION/NAME.EXT`.
    fn translation_path(&self, notation: &str) -> PathBuf {
        let back = (BACKS.iter())
            .find(|b| b.name() == notation)
            .unwrap_or_else(|| panic!("{}: no notation `{notation}` to translate to", self.name));
        snapshot(notation, &format!("{}.{}", self.name, back.extension()))
    }
}

#[test]
fn every_input_gives_its_snapshots() {
    let inputs = inputs();
    let mut names: Vec<&str> = inputs.iter().map(|i| i.name.as_str()).collect();
    names.sort();
    names.dedup();
    assert_eq!(names.len(), inputs.len(), "two inputs share a name");
    let mut failures = Vec::new();
    for input in &inputs {
        let params = &input.params;
        let outputs = (params.targets.iter()).flat_map(|&t| input.outputs(t));
        failures.extend(input.wrong_methods());
        let translations = (params.translate.iter()).map(|to| input.translation(to));
        for (golden, actual) in outputs.chain(translations) {
            if let Err(e) = check_golden_bytes(&golden, &actual) {
                failures.push(e);
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every file of a target's folder is some input's snapshot: one whose
/// input went away (or stopped asking for it) fails here.
#[test]
fn every_snapshot_has_its_input() {
    let mut expected = Vec::new();
    for input in inputs() {
        for &target in &input.params.targets {
            expected.extend(input.snapshots(target));
        }
        for to in &input.params.translate {
            expected.push(input.translation_path(to));
        }
    }
    let folders = TARGETS.iter().map(|t| t.folder().0);
    for folder in folders.chain(BACKS.iter().map(|b| b.name())) {
        let Ok(entries) = std::fs::read_dir(repo().join("tests/out").join(folder)) else {
            continue;
        };
        for entry in entries {
            let path = entry.unwrap().path();
            assert!(
                expected.contains(&path),
                "{} is no input's snapshot",
                path.display()
            );
        }
    }
}
