//! The environment of an open L-system: the `.e` file beside the `.l`
//! (what cpfg, started with `-e file.e`, reads: the program of its
//! `executable:` line, how the turtle's position is sent) and the
//! program's specification file. graftal runs the program's computation
//! itself (`crate::enviro`); a program it does not have is named in the
//! `?E` warning (W0821), so that a plant drawn half because nothing
//! answered says what would have answered.
//!
//! Both files are read as cpfg's and vlab's readers read them: a line's
//! keyword is its text before the first `:` or tab, matched exactly (case
//! and all; an unknown one is skipped), numbers as C's `atof` reads them.

use super::{push_side_file, Beside};
use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::ir::environment::{
    Canopy, Circles, Density, Environment, Light, LightSource, Obstacles, Program,
};
use crate::ir::Span;
use std::path::Path;

/// The programs graftal runs, by the name of their executable.
const BUILT_IN: &[&str] = &["honda81", "chiba", "clover", "ecosystem", "obcheck"];

/// The environment of the object whose `.l` is at `l_file`, with the view
/// file's say on when it is asked (`after_each_step`: `environment
/// display: on`; `past_cut`: `interpretation past %`). The `?E` warning in
/// `diags` is dropped when graftal runs the program, and names the
/// program when it does not.
pub(super) fn read(
    beside: &Beside,
    l_file: &Path,
    when: (bool, bool),
    diags: &mut Diagnostics,
) -> Option<Environment> {
    let (file, text) = e_file(beside, l_file)?;
    let e = read_e(&text);
    let command = e.executable.as_deref()?;
    let (name, spec) = program_of(command);
    if !BUILT_IN.contains(&name.as_str()) {
        note_missing(diags, &file, &name);
        return None;
    }
    let program = read_program(beside, &name, spec.as_deref(), diags)?;
    diags.0.retain(|d| d.code != codes::CPFG_NO_ENVIRONMENT);
    Some(Environment {
        program,
        position: e.position,
        after_each_step: when.0,
        past_cut: when.1,
    })
}

/// The `.e` file of the object (named after the `.l`, else the folder's
/// only `.e` file) and its text.
fn e_file(beside: &Beside, l_file: &Path) -> Option<(String, String)> {
    let stem = l_file.file_stem()?.to_string_lossy().into_owned();
    let file = super::folder::named_like_or_only(beside.dir?, &stem, "e")?;
    let text = beside.read(&file)?;
    Some((file, text))
}

/// Names the program graftal does not run in the `?E` warning.
fn note_missing(diags: &mut Diagnostics, file: &str, name: &str) {
    if let Some(d) = (diags.0.iter_mut()).find(|d| d.code == codes::CPFG_NO_ENVIRONMENT) {
        d.notes.push(format!(
            "cpfg runs the environment program `{name}` (named in {file}) to answer them; \
             graftal has {} built in, not `{name}`: what grows or is drawn only on its \
             answer is missing here",
            BUILT_IN.join(", ")
        ));
    }
}

/// What a `.e` file says that graftal uses.
#[derive(Debug, Default, PartialEq)]
struct EFile {
    executable: Option<String>,
    /// The `turtle position` format, verbatim after the keyword's `:`.
    position: Option<String>,
}

/// Reads a `.e` file's lines.
fn read_e(text: &str) -> EFile {
    let mut e = EFile::default();
    for line in text.lines().take(MAX_LINES) {
        let Some((keyword, value)) = split(line) else {
            continue;
        };
        match keyword {
            "executable" => e.executable = Some(bounded(value.trim())),
            "turtle position" => e.position = Some(bounded(value.trim_end())),
            _ => {}
        }
    }
    e
}

/// The most lines of a `.e` or specification file read.
const MAX_LINES: usize = 10_000;

/// A value cut to a sane length.
fn bounded(v: &str) -> String {
    v.chars().take(200).collect()
}

/// A line's keyword (the text before its first `:` or tab) and the rest.
fn split(line: &str) -> Option<(&str, &str)> {
    let at = line.find([':', '\t'])?;
    Some((&line[..at], &line[at + 1..]))
}

/// The program of an `executable:` command (the base name of its first
/// word: `./obcheck` is `obcheck`) and its specification file (its first
/// argument that is not a switch of the communication library).
fn program_of(command: &str) -> (String, Option<String>) {
    let mut words = command.split_whitespace();
    let first = words.next().unwrap_or("");
    let name = first.rsplit('/').next().unwrap_or(first).to_string();
    let mut spec = None;
    while let Some(w) = words.next() {
        if matches!(w, "-e" | "-k" | "-ext" | "-h" | "-C") {
            words.next();
        } else if spec.is_none() && w != "&" {
            spec = Some(w.to_string());
        }
    }
    (name, spec)
}

/// The settings of program `name` from its specification file `spec`
/// (the defaults where it has none, as the programs keep them).
fn read_program(
    beside: &Beside,
    name: &str,
    spec: Option<&str>,
    diags: &mut Diagnostics,
) -> Option<Program> {
    let text = spec.and_then(|s| beside.read(s)).unwrap_or_default();
    let mut local = Diagnostics::default();
    let mut lines = Lines {
        text: &text,
        diags: &mut local,
    };
    let program = match name {
        "honda81" => Program::Density(density(&mut lines)),
        "chiba" => Program::Light(light(&mut lines)),
        "clover" => Program::Canopy(canopy(&mut lines, beside, diags)),
        "ecosystem" => Program::Circles(circles(&mut lines)),
        _ => Program::Obstacles(obstacles(&mut lines)),
    };
    if let Some(path) = spec.and_then(|s| beside.path(s)) {
        push_side_file(diags, &local, &path, &text);
    }
    Some(program)
}

/// A specification file's lines, with the warnings about them.
struct Lines<'a> {
    text: &'a str,
    diags: &'a mut Diagnostics,
}

impl Lines<'_> {
    /// Each line's keyword, value and the value's span; keywords not in
    /// `known` are warned about and skipped, as the programs skip them.
    fn each(&mut self, known: &[&str], mut f: impl FnMut(&str, &str, Span, &mut Diagnostics)) {
        let mut at = 0;
        for line in self.text.split_inclusive('\n').take(MAX_LINES) {
            let start = at;
            at += line.len();
            let line = line.trim_end_matches(['\n', '\r']);
            if line.trim().is_empty() {
                continue;
            }
            let Some((keyword, value)) = split(line) else {
                self.unknown(start..start + line.len(), line, known);
                continue;
            };
            if !known.contains(&keyword) {
                self.unknown(start..start + keyword.len(), keyword, known);
                continue;
            }
            let from = start + keyword.len() + 1;
            f(keyword, value, from..from + value.len(), self.diags);
        }
    }

    fn unknown(&mut self, span: Span, keyword: &str, known: &[&str]) {
        let near = known
            .iter()
            .find(|k| k.eq_ignore_ascii_case(keyword.trim()))
            .map(|k| format!(" (the program reads `{k}`, in that case)"))
            .unwrap_or_default();
        self.diags.push(
            Diagnostic::at(
                codes::CPFG_ENVIRONMENT_LINE,
                span,
                format!(
                    "the environment program does not read `{}`{near}",
                    keyword.trim()
                ),
            )
            .with_label("skipped, as the program skips it")
            .with_help(format!("it reads: {}", known.join(", "))),
        );
    }
}

/// The numbers of a value as C's `atof` reads each token split at
/// `delims`: a token's leading number (none: no number).
fn numbers(value: &str, delims: &[char]) -> Vec<Option<f64>> {
    value
        .split(|c: char| delims.contains(&c) || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .map(leading_number)
        .collect()
}

/// The finite number a token begins with (`100view.pnl` is 100).
fn leading_number(t: &str) -> Option<f64> {
    crate::number::leading(t).filter(|x| x.is_finite())
}

/// The first number of a value, warning when it has none.
fn first_number(value: &str, span: &Span, d: &mut Diagnostics) -> Option<f64> {
    let n = numbers(value, &[',', ';', ':']).first().copied().flatten();
    if n.is_none() {
        d.push(
            Diagnostic::at(codes::CPFG_ENVIRONMENT_LINE, span.clone(), "no number here")
                .with_label("the program reads 0")
                .with_help("write a number"),
        );
    }
    n
}

/// Whether a flag's value is on (`on`, or `yes` where the program takes it).
fn on(value: &str) -> bool {
    matches!(value.split_whitespace().next(), Some("on" | "yes"))
}

fn density(lines: &mut Lines) -> Density {
    let mut d = Density {
        radius: 0.0,
        three_d: false,
    };
    lines.each(
        &["verbose", "radius", "3d case"],
        |k, v, span, diags| match k {
            "radius" => d.radius = first_number(v, &span, diags).unwrap_or(0.0),
            "3d case" => d.three_d = v.split_whitespace().next() == Some("on"),
            _ => {}
        },
    );
    d
}

fn light(lines: &mut Lines) -> Light {
    let mut l = Light {
        grid: [1, 1, 1],
        transmittance: 0.6,
        lower_to_upper: 0.7,
        samples: 20,
        radius: 25.0,
        beam_radius: 0.0,
        sources: Vec::new(),
        estimate_area: false,
        cie: false,
    };
    let known = [
        "grid size",
        "verbose",
        "lower to upper ratio",
        "transmittance",
        "number of samples",
        "radius",
        "beam radius",
        "source direction",
        "estimate intersection area",
        "use CIE formula",
    ];
    lines.each(&known, |k, v, span, diags| {
        let n = |diags: &mut Diagnostics| first_number(v, &span, diags).unwrap_or(0.0);
        match k {
            "grid size" => {
                let g = numbers(v, &[',', ';', ':', 'x']);
                for (slot, x) in l.grid.iter_mut().zip(g) {
                    *slot = x.unwrap_or(1.0).clamp(1.0, 256.0) as u32;
                }
            }
            "lower to upper ratio" => l.lower_to_upper = n(diags),
            "transmittance" => l.transmittance = n(diags),
            "number of samples" => l.samples = n(diags).clamp(1.0, 1e5) as u32,
            "radius" => l.radius = n(diags),
            "beam radius" => l.beam_radius = n(diags),
            "source direction" => l.sources.extend(source(v)),
            "estimate intersection area" => l.estimate_area = on(v),
            "use CIE formula" => l.cie = v.split_whitespace().next() == Some("yes"),
            _ => {}
        }
    });
    if l.estimate_area {
        // The program draws its beams a cluster wide when it estimates areas.
        l.beam_radius = 1.0;
    }
    l.sources.truncate(100);
    l
}

/// A `source direction: x y z intensity` line; one without its fourth
/// number is dropped, as the program drops it.
fn source(v: &str) -> Option<LightSource> {
    match numbers(v, &[',', ';', ':'])[..] {
        [Some(x), Some(y), Some(z), Some(w), ..] => Some(LightSource {
            direction: [x, y, z],
            intensity: w,
        }),
        _ => None,
    }
}

fn canopy(lines: &mut Lines, beside: &Beside, diags: &mut Diagnostics) -> Canopy {
    let mut c = Canopy {
        grid: [512, 512],
        position: [-1.0, -1.0],
        range: [2.0, 2.0],
        transmittance: 0.6,
        image_file: None,
        image: None,
        remove_old_leaves: false,
        z_is_up: true,
    };
    let known = [
        "grid size",
        "grid position",
        "grid range",
        "verbose",
        "transmittance",
        "input image",
        "remove old leaves",
        "z is up",
    ];
    let mut image = None;
    lines.each(&known, |k, v, span, ds| {
        let two = |fallback: [f64; 2]| {
            let n = numbers(v, &[',', ';', ':', 'x']);
            [0, 1].map(|i| n.get(i).copied().flatten().unwrap_or(fallback[i]))
        };
        match k {
            "grid size" => c.grid = two([512.0, 512.0]).map(|x| x.clamp(1.0, 4096.0) as u32),
            "grid position" => c.position = two(c.position),
            "grid range" => c.range = two(c.range),
            "transmittance" => c.transmittance = first_number(v, &span, ds).unwrap_or(0.0),
            "input image" => image = v.split_whitespace().next().map(str::to_string),
            "remove old leaves" => c.remove_old_leaves = on(v),
            "z is up" => c.z_is_up = !matches!(v.split_whitespace().next(), Some("no" | "off")),
            _ => {}
        }
    });
    if let Some(name) = image {
        c.image_file = Some(name.clone());
        let bytes = beside.read_bytes(&name);
        c.image = bytes.and_then(|b| crate::decode::decode(&b).ok());
        if c.image.is_none() {
            diags.push(
                Diagnostic::global(
                    codes::CPFG_ENVIRONMENT_LINE,
                    format!("the environment's image `{name}` is missing or cannot be decoded"),
                )
                .with_note("the program then sees full light everywhere"),
            );
        }
    }
    c
}

fn circles(lines: &mut Lines) -> Circles {
    let mut c = Circles {
        three_d: false,
        vigor: false,
    };
    let known = ["verbose", "grid size", "3d case", "vigor"];
    lines.each(&known, |k, v, _, _| match k {
        "3d case" => c.three_d = on(v),
        "vigor" => c.vigor = v.split_whitespace().next() == Some("on"),
        _ => {}
    });
    c
}

/// `obstacles.dat`: a `line width:` line, `coordinates:`, then segments
/// `xa ya xb yb` until a number fails (at most 100, as the program).
fn obstacles(lines: &mut Lines) -> Obstacles {
    let after = lines
        .text
        .find("coordinates:")
        .map_or("", |at| &lines.text[at + "coordinates:".len()..]);
    let mut values = Vec::new();
    for t in after.split_whitespace() {
        match t.parse::<f64>() {
            Ok(x) if x.is_finite() => values.push(x),
            _ => break,
        }
    }
    let segments = values
        .chunks_exact(4)
        .take(100)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect();
    Obstacles { segments }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_e_file_gives_the_program_its_spec_and_the_position_format() {
        let e = read_e("executable: honda81 -e plant.e density.spec\ncommunication type: memory\nturtle position:P:%.4f %.0f %.4f\n");
        assert_eq!(e.position.as_deref(), Some("P:%.4f %.0f %.4f"));
        let (name, spec) = program_of(e.executable.as_deref().unwrap());
        assert_eq!(
            (name.as_str(), spec.as_deref()),
            ("honda81", Some("density.spec"))
        );
        let (name, spec) = program_of("./obcheck -e enviro.e obstacles.dat");
        assert_eq!(
            (name.as_str(), spec.as_deref()),
            ("obcheck", Some("obstacles.dat"))
        );
        // The leading blank of a format is the program's to skip.
        let e = read_e("turtle position: %.4f %.4f %.4f\n");
        assert_eq!(e.position.as_deref(), Some(" %.4f %.4f %.4f"));
    }

    #[test]
    fn spec_lines_are_read_as_the_programs_read_them() {
        let mut d = Diagnostics::default();
        let mut lines = Lines {
            text: "verbose: off\nradius:  0.5\n3D case: on\n",
            diags: &mut d,
        };
        let density = density(&mut lines);
        assert_eq!(
            density,
            Density {
                radius: 0.5,
                three_d: false
            }
        );
        // `3D case` is not `3d case`: warned, at its place, and skipped.
        assert_eq!(d.0.len(), 1);
        assert_eq!(d.0[0].code, codes::CPFG_ENVIRONMENT_LINE);
        assert_eq!(d.0[0].span, Some(26..33));
        assert!(d.0[0].message.contains("`3d case`"), "{}", d.0[0].message);
    }

    #[test]
    fn numbers_stop_where_atof_stops() {
        assert_eq!(
            numbers("100x100view.pnl", &['x']),
            vec![Some(100.0), Some(100.0)]
        );
        assert_eq!(leading_number("-50"), Some(-50.0));
        assert_eq!(leading_number("abc"), None);
        let light = light(&mut Lines {
            text: "grid size: 32,32,32\nsource direction: 50 100 0 4\nsource direction: 1 2 3\nestimate intersection area: on\n",
            diags: &mut Diagnostics::default(),
        });
        assert_eq!(light.grid, [32, 32, 32]);
        assert_eq!(light.sources.len(), 1);
        assert_eq!(light.beam_radius, 1.0);
    }

    #[test]
    fn obstacles_are_read_four_numbers_a_segment() {
        let o = obstacles(&mut Lines {
            text: "line width: 0.05\ncoordinates:\n0 0 24 0\n0 6 24 6\n\n1 1 1 5\nend",
            diags: &mut Diagnostics::default(),
        });
        assert_eq!(
            o.segments,
            vec![
                [0.0, 0.0, 24.0, 0.0],
                [0.0, 6.0, 24.0, 6.0],
                [1.0, 1.0, 1.0, 5.0]
            ]
        );
    }
}
