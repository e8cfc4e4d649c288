//! Mutation fuzzing of the graftal binary, for every notation it reads.
//!
//! Seeds: every file of `stdlib/`, `examples/`, `tests/in/`,
//! `tests/diagnostics/` and `tests/corpus/` (the Fractint libraries; every
//! `.l` of every cpfg object, with the files beside it; the goldens, written
//! as pfg files). A seeded mutator edits them byte- and token-wise (delete,
//! duplicate, splice from another seed, insert fragments of the notation,
//! nest brackets deep, repeat a fragment into a long line, insert control
//! bytes and invalid UTF-8, put odd numbers in place of numbers, truncate),
//! and for cpfg objects edits the view, function and surface files too. The
//! mutants are the same on every run: mutant `i` of a notation comes from
//! the seed `(GRAFTAL_FUZZ_SEED, notation, i)` alone.
//!
//! Each mutant goes through the graftal BINARY (`check`, `derive`,
//! `translate --to` each target, `render`), not the library: a stack
//! overflow or an abort on allocation kills the process, which
//! `catch_unwind` cannot catch. Each process runs under a wall-clock
//! timeout and an address-space limit. A finding is an exit by a signal, an
//! exit status other than 0, 1 or 2, a timeout, stdout or stderr over a
//! bound, a panic message, or stderr that is not clean text (invalid UTF-8,
//! raw control characters; with `--format json`, a line that is not JSON).
//!
//! A slow suite: `GRAFTAL_SLOW=1 cargo test` runs a brief, fixed set of
//! mutants (each run holding `common::timed`: it keeps every core busy). The
//! environment runs it for longer (see `tests/fuzz/README.md`):
//! `GRAFTAL_FUZZ_SECONDS`,
//! `GRAFTAL_FUZZ_CASES` (mutants per notation), `GRAFTAL_FUZZ_SEED`,
//! `GRAFTAL_FUZZ_JOBS`, `GRAFTAL_FUZZ_TIMEOUT` (seconds per process) and
//! `GRAFTAL_FUZZ_BIN` (another binary, e.g. the release build). A finding's
//! input is written to `target/fuzz-findings/` with the command that
//! reproduces it (and, for the first of each cause, an input shrunk by
//! deleting what the finding does not need).
//!
//! Every crash the fuzzer or anyone else found is kept under
//! `tests/fuzz/regressions/<notation>/` (or, when it is megabytes, as a
//! recipe in [`RECIPES`]), and every one of them runs through the same
//! commands on every `GRAFTAL_SLOW=1 cargo test`.
#![cfg(unix)]

use std::collections::BTreeMap;
use std::io::Read;
use std::os::unix::process::{CommandExt, ExitStatusExt};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{mpsc, Mutex};
use std::time::{Duration, Instant};

use crate::common::slow_timed;

/// Mutants per notation in the brief run of `cargo test`: a mutant that
/// runs clean takes about 80 ms of commands (debug build, on a busy 2-core
/// machine), so 750 mutants take about 30 s on 2 jobs.
const BRIEF_CASES: usize = 150;
/// The address space of one graftal process, in KiB (`ulimit -v`).
const ADDRESS_SPACE_KIB: u64 = 4_000_000;
/// More stderr than this is a flood. graftal shows at most `MAX_SHOWN`
/// diagnostics to people (the rest are counted in one line), and one with a
/// snippet cut to a window around its span takes well under 1 KiB (a file of
/// 300 short lines with an error on each gives 71 KB for 200 diagnostics):
/// more means snippets or messages that repeat the input.
const MAX_STDERR_HUMAN: usize = (graftal::diagnostics::MAX_SHOWN + 1) * 1024;
/// The longest line of `--format json`: a longer diagnostic quotes the
/// input at length. JSON lists every diagnostic by design (a file of 300
/// short lines gives 225 KB for 599; 10 000 `Name {` lines in a Fractint
/// library, 17 MB for 43 000), so only each line is bounded.
const MAX_JSON_LINE: usize = 4096;
/// More stdout than this is a flood: derived words are bounded by
/// `--max-symbols`, but a symbol may print as a module with long numbers.
const MAX_STDOUT: usize = 16 << 20;
/// `--max-symbols` of derive and render on mutants.
const MAX_SYMBOLS: &str = "20000";
/// Mutants are cut to this size (the megabyte inputs are recipes).
const MAX_INPUT: usize = 1 << 20;
/// Findings kept per cause and notation in `target/fuzz-findings/`.
const SAVED_PER_CAUSE: usize = 5;
/// Runs, and time, the shrinker may spend on one finding.
const SHRINK_RUNS: usize = 200;
const SHRINK_TIME: Duration = Duration::from_secs(30);
const REPO: &str = env!("CARGO_MANIFEST_DIR");

// ---------------------------------------------------------------------------
// Settings, randomness, notations
// ---------------------------------------------------------------------------

/// How long and against what the fuzzer runs (from the environment).
struct Settings {
    binary: PathBuf,
    seed: u64,
    /// Mutants per notation, unless `until` is set.
    cases: usize,
    /// Run until then instead (`GRAFTAL_FUZZ_SECONDS`).
    until: Option<Instant>,
    jobs: usize,
    /// Wall-clock limit of one graftal process.
    timeout: Duration,
    /// Shrink the first input of each cause (`GRAFTAL_FUZZ_SHRINK=1`).
    shrink: bool,
    /// Where findings are written (emptied first).
    findings: PathBuf,
    /// The notations whose mutants run (`GRAFTAL_FUZZ_NOTATION`: one).
    notations: Vec<Notation>,
}

fn env_number<T: std::str::FromStr>(name: &str) -> Option<T> {
    let value = std::env::var(name).ok()?;
    Some(
        value
            .trim()
            .parse()
            .unwrap_or_else(|_| panic!("{name}={value:?} is not a number")),
    )
}

impl Settings {
    fn from_env() -> Settings {
        let cores = std::thread::available_parallelism().map_or(2, |n| n.get());
        Settings {
            binary: std::env::var_os("GRAFTAL_FUZZ_BIN").map_or_else(
                || PathBuf::from(env!("CARGO_BIN_EXE_graftal")),
                PathBuf::from,
            ),
            seed: env_number("GRAFTAL_FUZZ_SEED").unwrap_or(0),
            cases: env_number("GRAFTAL_FUZZ_CASES").unwrap_or(BRIEF_CASES),
            until: env_number::<f64>("GRAFTAL_FUZZ_SECONDS")
                .map(|s| Instant::now() + Duration::from_secs_f64(s)),
            jobs: env_number("GRAFTAL_FUZZ_JOBS").unwrap_or(cores).max(1),
            timeout: Duration::from_secs_f64(env_number("GRAFTAL_FUZZ_TIMEOUT").unwrap_or(10.0)),
            shrink: env_number::<u8>("GRAFTAL_FUZZ_SHRINK") == Some(1),
            findings: PathBuf::new(),
            notations: match std::env::var("GRAFTAL_FUZZ_NOTATION") {
                Ok(name) => vec![Notation::from_name(&name)
                    .unwrap_or_else(|| panic!("GRAFTAL_FUZZ_NOTATION={name:?}: no such notation"))],
                Err(_) => NOTATIONS.to_vec(),
            },
        }
    }
}

/// SplitMix64: small, and the same sequence on every machine.
struct Rng(u64);

impl Rng {
    /// A generator for the tuple `parts` (seed, notation, index, …).
    fn new(parts: &[u64]) -> Rng {
        let mut rng = Rng(0x6772_6166_7461_6c21);
        for &p in parts {
            rng.0 = rng.next() ^ p;
        }
        rng
    }

    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A number in `0..n` (0 when `n` is 0).
    fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next() % n as u64) as usize
        }
    }

    fn chance(&mut self, percent: u64) -> bool {
        self.next() % 100 < percent
    }

    fn pick<'a, T>(&mut self, xs: &'a [T]) -> &'a T {
        &xs[self.below(xs.len())]
    }

    /// A size in `1..=max`, as likely in `1..2` as in `2^k..2^(k+1)`: mostly
    /// small, now and then as large as allowed.
    fn size(&mut self, max: usize) -> usize {
        let max = max.max(1);
        let bits = (usize::BITS - max.leading_zeros()) as usize;
        let low = 1usize << self.below(bits);
        (low + self.below(low)).min(max)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Notation {
    Pfg,
    Linf,
    Stl,
    Cpfg,
    Fractint,
    Gft,
    Ifs,
}

const NOTATIONS: [Notation; 7] = [
    Notation::Pfg,
    Notation::Linf,
    Notation::Stl,
    Notation::Cpfg,
    Notation::Fractint,
    Notation::Gft,
    Notation::Ifs,
];

impl Notation {
    /// The name as graftal's registry spells it (and the regression folder).
    fn name(self) -> &'static str {
        match self {
            Notation::Pfg => "pfg",
            Notation::Linf => "linf",
            Notation::Stl => "stl",
            Notation::Cpfg => "cpfg",
            Notation::Fractint => "fractint",
            Notation::Gft => "gft",
            Notation::Ifs => "ifs",
        }
    }

    fn from_name(name: &str) -> Option<Notation> {
        NOTATIONS.into_iter().find(|n| n.name() == name)
    }

    /// Pieces of this notation the mutator inserts.
    fn fragments(self) -> &'static [&'static str] {
        match self {
            Notation::Pfg => PFG_FRAGMENTS,
            Notation::Linf => LINF_FRAGMENTS,
            Notation::Stl => STL_FRAGMENTS,
            Notation::Cpfg => CPFG_FRAGMENTS,
            Notation::Fractint => FRACTINT_FRAGMENTS,
            Notation::Gft => GFT_FRAGMENTS,
            Notation::Ifs => IFS_FRAGMENTS,
        }
    }
}

#[rustfmt::skip]
const PFG_FRAGMENTS: &[&str] = &[
    "F", "f", "+", "-", "[", "]", "{", "}", "<", ">", "*", ":", "-->", "/*", "*/", "!", "'", "&",
    "^", "\\", "/", "|", "axiom: ", "axiom: F\n", "derivation length: 99999999999\n",
    "derivation length: 100000\n", "angle factor: 0\n", "angle factor: 99999999999\n",
    "scale factor: 1e300\n", "ignore: +-F\n", "F --> F\n", "F --> F[+F]F : 0.5\n", ": 0.5",
    "F < F > F --> FF\n", "* --> F\n",
];

#[rustfmt::skip]
const LINF_FRAGMENTS: &[&str] = &[
    "lines f\n", "angles t = (0.7*pi, 0)\n", "axiom f\n", "rules\n", "f = ff\n", "f = f[+t f]f\n",
    "(", ")", "pi", "*", "/", "+t", "-t", "[", "]", "{", "}", ".5?", ".75@", "colors (0,0,0)\n",
    "#: steps 99999999999\n", "#: steps 100000\n", "#: view 30,20\n", "#", "=", ",", "?", "@",
    "angles a = (", "lines F G\n", "$",
];

#[rustfmt::skip]
const STL_FRAGMENTS: &[&str] = &[
    "ANGLE 45\n", "ANGLE 1e308\n", "B = 2 (0.1)\n", "L = 20 (1)\n", "R1 = [-F][F]\n", "SEED\n",
    "ENDSEED\n", "F(1)", "F", "R1", "[", "]", "{", "}", "(", ")", "~", ",", "LAYOUT\n",
    "ENDLAYOUT\n", "(clWhite) Rectangle (0,0), 200, 100\n", "(clRed) Ellipse (0,0), 9, 9\n",
    "($00FFFFFF) Polygon (0,0), (1,1), (2,0)\n", "GROWTH BFS\n", "GROWTH DFS\n",
    "LEVELS 99999999999\n", "LEVELS 255\n", "[I 99999 F]", "[I 3 FLFRRFLF]", "#",
];

#[rustfmt::skip]
const CPFG_FRAGMENTS: &[&str] = &[
    "#define A(x) A(x)A(x)\n", "#define X X X\n", "#define N 99999999999\n",
    "#include \"leaf.l\"\n", "#include \"../../../../etc/passwd\"\n", "#include \"/dev/zero\"\n",
    "#if 1\n", "#else\n", "#endif\n", "#ifdef X\n", "Lsystem: 1\n", "endlsystem\n",
    "derivation length: 99999999999\n", "derivation length: 100000\n", "Axiom: A\n", "A --> A(1)\n",
    "homomorphism\n", "decomposition\n", "maximum depth: 99999\n", "consider: F\n", "ignore: +-\n",
    "F(", "(", ")", "?P(x,y)", "{", "}", ";", ":", "-->", "*", "A(x) : x>0 --> B(x+1)\n",
    "A(x) : { y = x*2; } x>0 --> A(y)A(y)\n", "func(1,x)", "~S", "angle increment: 0\n",
    "angle factor: 99999999999\n", "function: ../../../../etc/passwd\n", "function: /dev/zero\n",
    "surface: S x.s 1\n", "surface: S /dev/zero 1\n",
    "initial line width: 1e308 pixels\n", "scale factor: 0\n", "contact point: 0 0 0\n",
    "end point: 0 0 0\n", "heading: 0 0 1\n",
];

#[rustfmt::skip]
const FRACTINT_FRAGMENTS: &[&str] = &[
    "Name {\n", "}\n", "{", "}", "Angle 6\n", "Angle 0\n", "Angle 99999999999\n", "Axiom F\n",
    "F=F+F--F+F\n", "F=", "X=", "@1.5", "@I", "@Q", "@Q2", "|", "!", "\\30", "/30", "C1", "<5",
    ">5", "D", "M", "G", ";", "[", "]", "+", "-",
];

#[rustfmt::skip]
const GFT_FRAGMENTS: &[&str] = &[
    "axiom F\n", "F -> F+F\n", "  -> F : 0.5\n", "->", "turtle cpfg\n", "turtle fractint\n",
    "steps 99999999999\n", "angle 360/7\n", "A(x) : x < 10 -> F(x) A(x+1)\n", "(", ")", "{", "}",
    "`", "?", "0.5?", ":", "<", ">", "rotation t = (0, [0 2*pi])\n", "+t = frenet t\n",
    "decomposition depth 99999 {\nA -> AA\n}\n", "start { n = 0; }\n", "globals n\n",
    "symbol Apex\n", "X = turn 1e308deg\n", "colours #000000\n", "/*", "*/", "ring\n", "cut %\n",
];

#[rustfmt::skip]
const IFS_FRAGMENTS: &[&str] = &[
    "Name {\n", "Name (3D) {\n", "(3D)", "}\n", "{", "}", ";", ".5 0 0 .5 0 0 .5\n",
    ".5 0 0 0 .5 0 0 0 .5 0 0 1 .5\n", "0 0 0 0 0 0 1\n", "1 0 0 1 0 0 1\n",
    ".999 -.01 .01 .999 .001 0 .5\n", "0 1 -1 0 0 0 .5\n", "1e-300 0 0 1e300 0 0 1\n", " .5", " 0",
    " -1", " 1e308", ",", "=",
];

/// Fragments of every notation: numbers at the edges, odd characters.
#[rustfmt::skip]
const COMMON_FRAGMENTS: &[&str] = &[
    "\n", " ", "\t", "\r\n", "\r", "(", ")", "[", "]", "{", "}", "\u{feff}", "é", "\u{1F331}",
    "\u{202e}", "\u{85}", "\u{2028}", "99999999999999999999", "1e308", "-1e308", "NaN", "inf", "-0",
    "0.0000000001", "18446744073709551616", "-9223372036854775809", "4294967296", "65536",
];

/// Numbers that the mutator puts in place of a number of the text.
#[rustfmt::skip]
const NUMBERS: &[&str] = &[
    "0", "-0", "-1", "1.5", "1e308", "-1e308", "1e-320", "99999999999", "18446744073709551616",
    "-9223372036854775809", "4294967296", "2147483648", "65536", "100000", "NaN", "inf", "0.5", ".",
    "1e", "0x10",
];

/// Bytes that are not text: NUL, control characters, invalid UTF-8.
#[rustfmt::skip]
const CONTROL_BYTES: &[&[u8]] = &[
    b"\0", b"\x01", b"\x07", b"\x08", b"\x0b", b"\x0c", b"\x1b[31m", b"\x7f", b"\x80", b"\xc3",
    b"\xff", b"\xfe\xff", b"\xe2\x82", b"\xed\xa0\x80", b"\0\0\0\0",
];

/// Bracket pairs the mutator nests.
const NESTINGS: &[(&str, &str)] = &[("(", ")"), ("[", "]"), ("{", "}")];

// ---------------------------------------------------------------------------
// Inputs and seeds
// ---------------------------------------------------------------------------

/// One input: the file graftal is given, and the files beside it.
#[derive(Clone, Debug, PartialEq)]
struct Input {
    /// The main file's name; its extension picks the front end.
    name: String,
    text: Vec<u8>,
    /// The files in its folder (a cpfg object's view, functions, surfaces,
    /// included files, …).
    beside: Vec<(String, Vec<u8>)>,
    /// Instead of `text`, the main file is a symbolic link to this (a
    /// device, say).
    link: Option<PathBuf>,
}

impl Input {
    fn file(name: impl Into<String>, text: impl Into<Vec<u8>>) -> Input {
        Input {
            name: name.into(),
            text: text.into(),
            beside: Vec::new(),
            link: None,
        }
    }

    /// Writes the input into `dir`, emptied first.
    fn write_to(&self, dir: &Path) {
        let _ = std::fs::remove_dir_all(dir);
        std::fs::create_dir_all(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
        for (name, text) in &self.beside {
            std::fs::write(dir.join(name), text).unwrap();
        }
        let main = dir.join(&self.name);
        match &self.link {
            Some(target) => std::os::unix::fs::symlink(target, &main).unwrap(),
            None => std::fs::write(&main, &self.text).unwrap(),
        }
    }
}

fn repo(path: &str) -> PathBuf {
    Path::new(REPO).join(path)
}

/// The regular files of `dir`, sorted by name.
fn files_in(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_file())
        .collect();
    files.sort();
    files
}

fn file_name(path: &Path) -> String {
    path.file_name().unwrap().to_string_lossy().into_owned()
}

/// The notation graftal reads a file as: by extension, and for `.l` by
/// content, as graftal itself decides.
fn notation_of(name: &str, text: &[u8]) -> Option<Notation> {
    let ext = name.rsplit_once('.')?.1;
    match ext {
        "linf" => Some(Notation::Linf),
        "gft" => Some(Notation::Gft),
        "stl" => Some(Notation::Stl),
        "ifs" => Some(Notation::Ifs),
        "l" => {
            Notation::from_name(graftal::front::detect("l", &String::from_utf8_lossy(text)).name())
        }
        _ => None,
    }
}

/// The seeds of every notation, indexed by `Notation as usize`.
fn load_seeds() -> Vec<Vec<Input>> {
    let mut seeds = vec![Vec::new(); NOTATIONS.len()];
    let single_files = [
        "stdlib/pfg",
        "stdlib/linf",
        "stdlib/stl",
        "examples",
        "tests/in/pfg",
        "tests/in/linf",
        "tests/diagnostics",
        "tests/corpus/fractint",
        "tests/corpus/gft",
    ];
    for dir in single_files {
        for path in files_in(&repo(dir)) {
            let text = std::fs::read(&path).unwrap();
            let name = file_name(&path);
            if let Some(n) = notation_of(&name, &text) {
                seeds[n as usize].push(Input::file(name, text));
            }
        }
    }
    // Each entry of the IFS library alone, as a file of one entry.
    let ifs = std::fs::read_to_string(repo("tests/corpus/fractint/fractint.ifs")).unwrap();
    let file = graftal::front::ifs::parse(&ifs, &mut Default::default());
    for e in &file.entries {
        let name = format!("{}.ifs", e.name);
        seeds[Notation::Ifs as usize].push(Input::file(name, &ifs[e.span.clone()]));
    }
    for path in files_in(&repo("tests/corpus/fractint/history")) {
        let name = format!("{}.l", file_name(&path).replace('.', "-"));
        seeds[Notation::Fractint as usize].push(Input::file(name, std::fs::read(&path).unwrap()));
    }
    seeds[Notation::Pfg as usize].extend(golden_seeds());
    let mut objects: Vec<PathBuf> = std::fs::read_dir(repo("tests/corpus/cpfg"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .collect();
    objects.sort();
    for object in objects {
        seeds[Notation::Cpfg as usize].extend(object_inputs(&object));
    }
    seeds
}

/// Every `.l` of a folder, each with the other files of the folder beside
/// it.
fn object_inputs(dir: &Path) -> Vec<Input> {
    let files: Vec<(String, Vec<u8>)> = files_in(dir)
        .iter()
        .map(|p| (file_name(p), std::fs::read(p).unwrap()))
        .collect();
    files
        .iter()
        .filter(|(name, _)| name.ends_with(".l"))
        .map(|(name, text)| Input {
            beside: files.iter().filter(|(n, _)| n != name).cloned().collect(),
            ..Input::file(name.clone(), text.clone())
        })
        .collect()
}

/// The goldens of `tests/corpus/goldens/goldens.json` as pfg files.
fn golden_seeds() -> Vec<Input> {
    let json = std::fs::read_to_string(repo("tests/corpus/goldens/goldens.json")).unwrap();
    let cases: Vec<serde_json::Value> = serde_json::from_str(&json).unwrap();
    cases
        .iter()
        .enumerate()
        .map(|(i, case)| {
            let mut text = format!("axiom: {}\n", case["axiom"].as_str().unwrap_or(""));
            if let Some(rules) = case["rules"].as_object() {
                for (from, to) in rules {
                    text += &format!("{from} --> {}\n", to.as_str().unwrap_or(""));
                }
            }
            Input::file(format!("golden-{i}.l"), text)
        })
        .collect()
}

// ---------------------------------------------------------------------------
// The mutator
// ---------------------------------------------------------------------------

/// Mutant `index` of `notation`: a seed, edited one to eight times.
fn mutant(seeds: &[Vec<Input>], notation: Notation, index: usize, seed: u64) -> Input {
    let mut rng = Rng::new(&[seed, notation as u64, index as u64]);
    let mut input = rng.pick(&seeds[notation as usize]).clone();
    if matches!(notation, Notation::Fractint | Notation::Ifs) && rng.chance(80) {
        input.text = some_entries(&input.text, &mut rng);
    }
    let edits = 1 + if rng.chance(20) {
        rng.below(8)
    } else {
        rng.below(3)
    };
    for _ in 0..edits {
        let text = edit_target(&mut input, &mut rng);
        edit(text, notation, seeds, &mut rng);
    }
    input
}

/// The text an edit changes: now and then a file beside the main one that
/// graftal reads (a cpfg object's view, function, surface, included file).
fn edit_target<'a>(input: &'a mut Input, rng: &mut Rng) -> &'a mut Vec<u8> {
    const READ_BESIDE: &[&str] = &[".v", ".func", ".fset", ".s", ".l", ".h", "specifications"];
    let read: Vec<usize> = (0..input.beside.len())
        .filter(|&i| READ_BESIDE.iter().any(|e| input.beside[i].0.ends_with(e)))
        .collect();
    if !read.is_empty() && rng.chance(30) {
        &mut input.beside[*rng.pick(&read)].1
    } else {
        &mut input.text
    }
}

/// A range of `len` bytes: a start, and a length that is mostly short
/// (empty at the end).
fn some_range(rng: &mut Rng, len: usize) -> std::ops::Range<usize> {
    let start = rng.below(len + 1);
    let end = start + rng.size(len - start).min(len - start);
    start..end
}

/// A few whole entries of a Fractint library: a mutant of the whole library
/// mostly changes what `check` lists, and derives only the chosen entry.
fn some_entries(text: &[u8], rng: &mut Rng) -> Vec<u8> {
    let starts: Vec<usize> = line_starts(text)
        .filter(|&s| {
            let line = text[s..].split(|&b| b == b'\n').next().unwrap_or_default();
            line.contains(&b'{') && !line.starts_with(b";")
        })
        .collect();
    if starts.is_empty() {
        return text.to_vec();
    }
    let first = rng.below(starts.len());
    let end = starts
        .get(first + 1 + rng.below(3))
        .copied()
        .unwrap_or(text.len());
    text[starts[first]..end].to_vec()
}

fn line_starts(text: &[u8]) -> impl Iterator<Item = usize> + '_ {
    std::iter::once(0).chain(
        text.iter()
            .enumerate()
            .filter(|(_, &b)| b == b'\n')
            .map(|(i, _)| i + 1)
            .filter(move |&i| i < text.len()),
    )
}

/// A fragment of `notation` (or of every notation).
fn fragment(notation: Notation, rng: &mut Rng) -> &'static str {
    let pool = if rng.chance(75) {
        notation.fragments()
    } else {
        COMMON_FRAGMENTS
    };
    pool[rng.below(pool.len())]
}

/// One edit of `text`, in place.
fn edit(text: &mut Vec<u8>, notation: Notation, seeds: &[Vec<Input>], rng: &mut Rng) {
    let at = rng.below(text.len() + 1);
    match rng.below(12) {
        0 => {
            text.drain(some_range(rng, text.len()));
        }
        1 => {
            let copy = text[some_range(rng, text.len())].to_vec();
            text.splice(at..at, copy);
        }
        2 | 3 => {
            text.splice(at..at, fragment(notation, rng).bytes());
        }
        4 => {
            let donors = if rng.chance(85) {
                &seeds[notation as usize]
            } else {
                rng.pick(seeds)
            };
            let donor = &rng.pick(donors).text;
            let piece = donor[some_range(rng, donor.len())].to_vec();
            let replaced = at..at + rng.below(text.len() - at + 1).min(piece.len());
            text.splice(replaced, piece);
        }
        5 => {
            let run = long_run(text, notation, rng);
            text.splice(at..at, run);
        }
        6 => {
            text.splice(at..at, deep_nesting(notation, rng));
        }
        7 => {
            for _ in 0..rng.size(16) {
                let at = rng.below(text.len() + 1);
                let bytes = if rng.chance(70) {
                    rng.pick(CONTROL_BYTES).to_vec()
                } else {
                    vec![rng.next() as u8]
                };
                text.splice(at..at, bytes);
            }
        }
        8 => text.truncate(at),
        9 => replace_number(text, rng),
        10 => swap_lines(text, rng),
        _ => {
            if let Some(b) = text.get_mut(at) {
                *b = rng.next() as u8;
            }
        }
    }
    text.truncate(MAX_INPUT);
}

/// A fragment or a short piece of the text, repeated into a long run (a
/// long line, a long name, a long successor).
fn long_run(text: &[u8], notation: Notation, rng: &mut Rng) -> Vec<u8> {
    let unit: Vec<u8> = if rng.chance(50) || text.is_empty() {
        fragment(notation, rng).bytes().collect()
    } else {
        let r = some_range(rng, text.len());
        text[r.start..r.end.min(r.start + 16)].to_vec()
    };
    let count = rng.size(200_000).min(MAX_INPUT / 2 / unit.len().max(1));
    unit.repeat(count)
}

/// Brackets nested deep around a fragment, now and then left unclosed.
fn deep_nesting(notation: Notation, rng: &mut Rng) -> Vec<u8> {
    let (open, close) = rng.pick(NESTINGS);
    let depth = rng.size(100_000);
    let mut nested = open.repeat(depth);
    nested += if rng.chance(50) {
        "1"
    } else {
        fragment(notation, rng)
    };
    if rng.chance(75) {
        nested += &close.repeat(depth);
    }
    nested.into_bytes()
}

/// A run of digits of the text replaced by a number at the edges.
fn replace_number(text: &mut Vec<u8>, rng: &mut Rng) {
    let starts: Vec<usize> = (0..text.len())
        .filter(|&i| text[i].is_ascii_digit() && (i == 0 || !text[i - 1].is_ascii_digit()))
        .collect();
    if starts.is_empty() {
        return;
    }
    let start = *rng.pick(&starts);
    let end = start
        + text[start..]
            .iter()
            .take_while(|b| b.is_ascii_digit())
            .count();
    text.splice(start..end, rng.pick(NUMBERS).bytes());
}

fn swap_lines(text: &mut Vec<u8>, rng: &mut Rng) {
    let mut lines: Vec<Vec<u8>> = text.split(|&b| b == b'\n').map(<[u8]>::to_vec).collect();
    let (a, b) = (rng.below(lines.len()), rng.below(lines.len()));
    lines.swap(a, b);
    *text = lines.join(&b'\n');
}

// ---------------------------------------------------------------------------
// The commands
// ---------------------------------------------------------------------------

/// The choices of one run of the commands over an input.
#[derive(Clone, Debug, PartialEq)]
struct Knobs {
    /// `-n` of derive and render (none: the file's own length).
    steps: Option<&'static str>,
    /// `-n` of translate (the target's length, or the steps STL writes).
    translate_steps: Option<&'static str>,
    /// `--max-symbols` of derive and render (none: graftal's default).
    max_symbols: Option<&'static str>,
    lossy: bool,
    json: bool,
    seed: u64,
    /// The Fractint entry, and whether it is given as `FILE:NAME` (else
    /// `--entry NAME`).
    entry: Option<(String, bool)>,
    svg: bool,
    view: bool,
}

const SMALL_STEPS: &[&str] = &["0", "1", "2", "3", "4", "5"];
const HUGE_STEPS: &[&str] = &["1000", "100000", "99999999999"];

/// The names of the entries (`Name {` lines) of an input graftal reads as
/// a Fractint library, of L-systems or IFS codes (none for other inputs).
fn entry_names(input: &Input) -> Vec<String> {
    let library = matches!(
        notation_of(&input.name, &input.text),
        Some(Notation::Fractint | Notation::Ifs)
    );
    if input.link.is_some() || !library {
        return Vec::new();
    }
    String::from_utf8_lossy(&input.text)
        .lines()
        .filter_map(|line| {
            let name = line.split_once('{')?.0.trim();
            // A name that can be a command-line argument (no NUL), on
            // one line of a `check` listing.
            let plain = !name.is_empty() && !name.starts_with(';') && name.len() < 1000;
            let odd = |c: char| c.is_whitespace() || c.is_control();
            (plain && !name.contains(odd)).then(|| name.to_string())
        })
        .collect()
}

/// Choices at random for a mutant. Derivations are bounded: small steps or
/// the file's own, and [`MAX_SYMBOLS`] (huge steps that do not grow the word
/// are work no symbol limit bounds: `each-step-block` in the regressions).
/// Translation takes huge steps too (issue 16's case 2).
fn random_knobs(rng: &mut Rng, input: &Input) -> Knobs {
    // `small` and `own` percent of small steps and of none.
    let mut pick_steps = |small: u64, own: u64| match rng.below(100) as u64 {
        p if p < small => Some(*rng.pick(SMALL_STEPS)),
        p if p < small + own => None,
        _ => Some(*rng.pick(HUGE_STEPS)),
    };
    let steps = pick_steps(75, 25);
    let translate_steps = pick_steps(30, 40);
    let names = entry_names(input);
    let entry =
        (!names.is_empty() && rng.chance(80)).then(|| (rng.pick(&names).clone(), rng.chance(50)));
    Knobs {
        steps,
        translate_steps,
        max_symbols: Some(MAX_SYMBOLS),
        lossy: rng.chance(60),
        json: rng.chance(25),
        seed: rng.below(4) as u64,
        entry,
        svg: rng.chance(30),
        view: rng.chance(20),
    }
}

/// The runs every regression input goes through: small steps with
/// graftal's own symbol limit (issue 16's case 4 is `derive -n 2`), the
/// file's own lengths, and huge steps (case 2 is `translate --to stl -n
/// 100000`).
fn regression_knobs(input: &Input) -> Vec<Knobs> {
    let entry = entry_names(input).first().map(|n| (n.clone(), false));
    let base = Knobs {
        steps: Some("2"),
        translate_steps: Some("3"),
        max_symbols: None,
        lossy: false,
        json: false,
        seed: 0,
        entry,
        svg: false,
        view: false,
    };
    vec![
        base.clone(),
        Knobs {
            steps: None,
            translate_steps: None,
            max_symbols: Some(MAX_SYMBOLS),
            lossy: true,
            json: true,
            svg: true,
            ..base.clone()
        },
        Knobs {
            steps: Some("99999999999"),
            translate_steps: Some("100000"),
            max_symbols: Some(MAX_SYMBOLS),
            lossy: true,
            ..base
        },
    ]
}

/// The command lines for one input (`./NAME` in the current folder) and
/// one set of choices: check, derive, translate to every target, render.
fn commands(name: &str, k: &Knobs) -> Vec<Vec<String>> {
    let file = format!("./{name}");
    let args = |xs: &[&str]| xs.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    let given = |yes: bool, xs: &[&str]| if yes { args(xs) } else { Vec::new() };
    let flag = |name: &str, value: Option<&str>| value.map_or(Vec::new(), |v| args(&[name, v]));
    let target = match &k.entry {
        Some((entry, true)) => args(&[&format!("{file}:{entry}")]),
        Some((entry, false)) => args(&[&file, "--entry", entry]),
        None => args(&[&file]),
    };
    let format = given(k.json, &["--format", "json"]);
    let derivation = [
        flag("-n", k.steps),
        flag("--max-symbols", k.max_symbols),
        args(&["--seed", &k.seed.to_string()]),
    ]
    .concat();
    let mut runs = vec![
        [args(&["check", &file]), format.clone()].concat(),
        [args(&["derive"]), target.clone(), derivation.clone()].concat(),
    ];
    for to in ["pfg", "linf", "stl"] {
        let steps = flag("-n", k.translate_steps);
        let lossy = given(k.lossy, &["--lossy"]);
        runs.push(
            [
                args(&["translate", "--to", to]),
                target.clone(),
                steps,
                lossy,
            ]
            .concat(),
        );
    }
    let out = if k.svg { "out.svg" } else { "out.png" };
    let render = args(&["render", "-o", out, "--size", "64x64"]);
    let view = given(k.view, &["--view", "30,20"]);
    runs.push([render, target, derivation, view].concat());
    for run in &mut runs[1..] {
        run.extend(format.iter().cloned());
    }
    runs
}

// ---------------------------------------------------------------------------
// Running one process, and judging what it did
// ---------------------------------------------------------------------------

/// What one bounded run of a process did.
struct Outcome {
    status: ExitStatus,
    stdout_bytes: usize,
    /// All of stderr, of which `stderr` is the beginning.
    stderr_bytes: usize,
    /// Stderr, up to its bound.
    stderr: Vec<u8>,
    /// The stream that went over its bound, and the bound (the process
    /// was killed then).
    over: Option<(&'static str, usize)>,
    /// Killed at the timeout.
    timed_out: bool,
    took: Duration,
}

enum Pipe {
    /// This stream went over its bound.
    Over(&'static str, usize),
    /// This stream closed: the bytes kept, and how many there were.
    Closed(&'static str, Vec<u8>, usize),
}

/// Reads a child's stream to its end, keeping the first `bound` bytes (or,
/// unbounded, the first [`MAX_STDOUT`]) and saying when it goes over.
fn drain(
    mut pipe: impl Read + Send + 'static,
    stream: &'static str,
    bound: Option<usize>,
    tx: mpsc::Sender<Pipe>,
) {
    let kept_at_most = bound.unwrap_or(MAX_STDOUT);
    std::thread::spawn(move || {
        let (mut kept, mut total, mut buf) = (Vec::new(), 0usize, vec![0u8; 1 << 16]);
        loop {
            match pipe.read(&mut buf) {
                Ok(0) => break,
                Ok(n) => {
                    if let Some(b) = bound.filter(|&b| total <= b && total + n > b) {
                        let _ = tx.send(Pipe::Over(stream, b));
                    }
                    let keep = n.min(kept_at_most.saturating_sub(kept.len()));
                    kept.extend_from_slice(&buf[..keep]);
                    total += n;
                }
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                Err(_) => break,
            }
        }
        let _ = tx.send(Pipe::Closed(stream, kept, total));
    });
}

/// How long the pipes of a killed process may stay open.
const KILL_GRACE: Duration = Duration::from_secs(2);

/// Kills the child and every process of its group (it leads its own).
fn kill_group(child: &mut std::process::Child) {
    let _ = Command::new("kill")
        .args(["-KILL", "--", &format!("-{}", child.id())])
        .stderr(Stdio::null())
        .status();
    let _ = child.kill();
}

/// Runs `program ARGS…` in `dir` under the address-space limit, killed at
/// `timeout` or when stdout goes over [`MAX_STDOUT`] or stderr over
/// `stderr_bound` (if any).
fn run_bounded(
    program: &Path,
    args: &[String],
    dir: &Path,
    stderr_bound: Option<usize>,
    timeout: Duration,
) -> Outcome {
    let start = Instant::now();
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v {ADDRESS_SPACE_KIB} && exec \"$0\" \"$@\""
        ))
        .arg(program)
        .args(args)
        .current_dir(dir)
        .env("RUST_BACKTRACE", "0")
        .process_group(0)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot run {}: {e}", program.display()));
    let (tx, rx) = mpsc::channel();
    drain(
        child.stdout.take().unwrap(),
        "stdout",
        Some(MAX_STDOUT),
        tx.clone(),
    );
    drain(child.stderr.take().unwrap(), "stderr", stderr_bound, tx);
    let (mut over, mut timed_out) = (None, false);
    let (mut stderr, mut stdout_bytes, mut stderr_bytes, mut open) = (Vec::new(), 0, 0, 2);
    let mut deadline = start + timeout;
    while open > 0 {
        match rx.recv_timeout(deadline.saturating_duration_since(Instant::now())) {
            Ok(Pipe::Over(stream, bound)) => {
                over.get_or_insert((stream, bound));
                kill_group(&mut child);
                deadline = Instant::now() + KILL_GRACE;
            }
            Ok(Pipe::Closed(stream, kept, total)) => {
                open -= 1;
                match stream {
                    "stderr" => (stderr, stderr_bytes) = (kept, total),
                    _ => stdout_bytes = total,
                }
            }
            Err(mpsc::RecvTimeoutError::Timeout) if over.is_none() && !timed_out => {
                timed_out = true;
                kill_group(&mut child);
                deadline = Instant::now() + KILL_GRACE;
            }
            // Killed, and the pipes still open (held by a child of the
            // child?): the readers are left behind.
            Err(_) => break,
        }
    }
    let status = child.wait().expect("waiting for graftal");
    Outcome {
        status,
        stdout_bytes,
        stderr,
        stderr_bytes,
        over,
        timed_out,
        took: start.elapsed(),
    }
}

/// What is wrong with a run: the cause as far as the output tells (for
/// grouping), and the details.
#[derive(Clone, Debug)]
struct Symptom {
    cause: String,
    detail: String,
}

/// Where a panic happened (`src/…:LINE:COL`) and its message's first line:
/// Rust prints `thread 'NAME' (ID) panicked at PLACE:\nMESSAGE`.
fn panic_place(stderr: &str) -> Option<String> {
    let thread = stderr.find("thread '")?;
    let rest = &stderr[thread..];
    let rest = &rest[rest.find(" panicked at ")? + " panicked at ".len()..];
    let (place, message) = rest.split_once(":\n").unwrap_or((rest, ""));
    let message: String = message
        .lines()
        .next()
        .unwrap_or("")
        .chars()
        .take(100)
        .collect();
    Some(format!("{place}: {message}"))
}

/// Whether a run is a finding, and which.
fn judge(o: &Outcome, json: bool, timeout: Duration) -> Option<Symptom> {
    let text = String::from_utf8_lossy(&o.stderr);
    let signal = o.status.signal();
    // Where in stderr the trouble shows (the details quote from there).
    let mut focus = 0;
    let control = text.find(|c: char| c.is_control() && c != '\n' && c != '\t');
    let cause = if o.timed_out {
        format!("no exit within {timeout:?}")
    } else if let Some((stream, bound)) = o.over {
        format!("{stream} over {bound} bytes")
    } else if let Some(sig) = signal {
        let why = if text.contains("has overflowed its stack") {
            "stack overflow, "
        } else if text.contains("memory allocation of") {
            "allocation failure, "
        } else {
            ""
        };
        format!("killed ({why}signal {sig})")
    } else if let Some(place) = panic_place(&text) {
        format!("panic at {place}")
    } else if !matches!(o.status.code(), Some(0..=2)) {
        format!("exit status {:?}", o.status.code())
    } else if text.contains("out of memory") {
        // An allocation of 4 GB was tried (and refused, and reported):
        // one sized from the input before it was checked.
        format!("out of memory ({ADDRESS_SPACE_KIB} KiB of address space)")
    } else if let Err(e) = std::str::from_utf8(&o.stderr) {
        focus = e.valid_up_to();
        "invalid UTF-8 on stderr".to_string()
    } else if let Some(at) = control {
        focus = at;
        "a raw control character on stderr".to_string()
    } else if let Some(line) = (json && o.status.code() != Some(2))
        .then(|| bad_json_line(&text, o.stderr.len() < o.stderr_bytes))
        .flatten()
    {
        focus = line;
        format!("stderr is not JSON lines of at most {MAX_JSON_LINE} bytes")
    } else {
        return None;
    };
    let mut start = focus.saturating_sub(100);
    while !text.is_char_boundary(start) {
        start -= 1;
    }
    let shown: String = text[start..].chars().take(400).collect();
    Some(Symptom {
        cause,
        detail: format!(
            "status {:?}, signal {signal:?}, {} bytes of stdout, {} bytes of stderr, {:.2} s; stderr from byte {start}: {shown:?}",
            o.status.code(),
            o.stdout_bytes,
            o.stderr_bytes,
            o.took.as_secs_f64()
        ),
    })
}

/// Where the first line of `text` starts that is not one JSON value of at
/// most [`MAX_JSON_LINE`] bytes (the last line is not checked when the text
/// was `cut`).
fn bad_json_line(text: &str, cut: bool) -> Option<usize> {
    let mut at = 0;
    let mut lines: Vec<&str> = text.split_inclusive('\n').collect();
    if cut {
        lines.pop();
    }
    for line in lines {
        let body = line.trim_end_matches('\n');
        if body.len() > MAX_JSON_LINE || serde_json::from_str::<serde_json::Value>(body).is_err() {
            return Some(at);
        }
        at += line.len();
    }
    None
}

// ---------------------------------------------------------------------------
// Running inputs, in parallel, and reporting
// ---------------------------------------------------------------------------

/// One input to run, where it came from, and the choices of each run of the
/// commands over it.
struct Task {
    notation: Notation,
    label: String,
    input: Input,
    knobs: Vec<Knobs>,
}

/// A command that did something wrong on an input.
struct Finding {
    notation: Notation,
    label: String,
    args: Vec<String>,
    /// Whether the command prints diagnostics as JSON.
    json: bool,
    symptom: Symptom,
    /// Where the input was written, if it was.
    saved: Option<PathBuf>,
}

impl Finding {
    /// The command, named by what it does (`derive`, `translate --to stl`).
    fn command(&self) -> String {
        match self.args.iter().position(|a| a == "--to") {
            Some(i) => format!("translate --to {}", self.args[i + 1]),
            None => self.args[0].clone(),
        }
    }

    /// A shell line that reproduces the finding.
    fn reproduce(&self, binary: &Path) -> String {
        let folder = self
            .saved
            .as_ref()
            .map_or(String::from("<not saved>"), |p| p.display().to_string());
        let args: Vec<String> = self.args.iter().map(|a| shell_quote(a)).collect();
        format!(
            "cd {} && (ulimit -v {ADDRESS_SPACE_KIB}; {} {})",
            shell_quote(&folder),
            binary.display(),
            args.join(" ")
        )
    }
}

fn shell_quote(s: &str) -> String {
    if s.bytes()
        .all(|b| b.is_ascii_alphanumeric() || b"./_-:,".contains(&b))
    {
        s.to_string()
    } else {
        format!("'{}'", s.replace('\'', "'\\''"))
    }
}

/// Inputs, commands and findings of one notation.
#[derive(Default)]
struct Tally {
    inputs: usize,
    commands: usize,
    /// Inputs with at least one finding.
    failed_inputs: usize,
    /// Commands that were findings.
    findings: usize,
    slowest: Duration,
    /// The time of the commands of the inputs that ran clean.
    clean_busy: Duration,
}

/// The findings of one cause in one notation.
#[derive(Default)]
struct Cause {
    inputs: usize,
    findings: usize,
    commands: std::collections::BTreeSet<String>,
    /// The last input counted (one task's findings are counted together).
    last_label: String,
}

#[derive(Default)]
struct Report {
    tallies: BTreeMap<Notation, Tally>,
    findings: Vec<Finding>,
    causes: BTreeMap<(Notation, String), Cause>,
}

/// Runs graftal with `args` in `dir` (where the input is), and judges what
/// it did.
fn run_graftal(
    settings: &Settings,
    args: &[String],
    json: bool,
    dir: &Path,
) -> (Outcome, Option<Symptom>) {
    let stderr_bound = (!json).then_some(MAX_STDERR_HUMAN);
    let outcome = run_bounded(&settings.binary, args, dir, stderr_bound, settings.timeout);
    let symptom = judge(&outcome, json, settings.timeout);
    (outcome, symptom)
}

/// What running the commands over one input gave.
#[derive(Default)]
struct Ran {
    findings: Vec<Finding>,
    commands: usize,
    /// The time of all commands, and of the longest.
    busy: Duration,
    slowest: Duration,
}

/// Runs every command of `task` in `dir` (after a timeout, no more: the
/// others would most likely hang too).
fn run_task(settings: &Settings, task: &Task, dir: &Path) -> Ran {
    task.input.write_to(dir);
    let mut runs: Vec<(Vec<String>, bool)> = Vec::new();
    for k in &task.knobs {
        for args in commands(&task.input.name, k) {
            if !runs.iter().any(|(a, _)| *a == args) {
                runs.push((args, k.json));
            }
        }
    }
    let mut ran = Ran::default();
    for (args, json) in runs {
        let (outcome, symptom) = run_graftal(settings, &args, json, dir);
        ran.commands += 1;
        ran.busy += outcome.took;
        ran.slowest = ran.slowest.max(outcome.took);
        if let Some(symptom) = symptom {
            ran.findings.push(Finding {
                notation: task.notation,
                label: task.label.clone(),
                args,
                json,
                symptom,
                saved: None,
            });
        }
        if outcome.timed_out {
            break;
        }
    }
    ran
}

fn findings_root() -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .expect("the target folder")
        .join("fuzz-findings")
}

/// Writes the input of a task with findings into `target/fuzz-findings/`,
/// with `reproduce.sh`, a command line for each finding; with `shrink`, the
/// first finding's input shrunk to what its cause needs, into `shrunk/`
/// (the same command lines reproduce it there).
fn save(settings: &Settings, task: &Task, findings: &mut [Finding], shrink: bool, scratch: &Path) {
    let name: String = format!("{}-{}", task.notation.name(), task.label)
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    let folder = settings.findings.join(name);
    task.input.write_to(&folder);
    let mut lines = String::new();
    for f in findings.iter_mut() {
        f.saved = Some(folder.clone());
        let (cause, detail) = (&f.symptom.cause, &f.symptom.detail);
        lines += &format!("# {cause}: {detail}\n{}\n", f.reproduce(&settings.binary));
    }
    std::fs::write(folder.join("reproduce.sh"), lines).unwrap();
    let first = &findings[0];
    if shrink && !first.symptom.cause.starts_with("no exit") {
        if let Some(text) = shrunk(settings, &task.input, first, scratch) {
            Input {
                text,
                ..task.input.clone()
            }
            .write_to(&folder.join("shrunk"));
        }
    }
}

/// The main file of `input` with as much deleted as keeps the finding's
/// cause (chunks of halving size, at most [`SHRINK_RUNS`] runs and
/// [`SHRINK_TIME`]); `None` when nothing could go.
fn shrunk(settings: &Settings, input: &Input, finding: &Finding, dir: &Path) -> Option<Vec<u8>> {
    if input.link.is_some() {
        return None;
    }
    let keeps_cause = |text: &[u8]| {
        Input {
            text: text.to_vec(),
            ..input.clone()
        }
        .write_to(dir);
        let (_, symptom) = run_graftal(settings, &finding.args, finding.json, dir);
        symptom.is_some_and(|s| s.cause == finding.symptom.cause)
    };
    let (mut text, mut runs, mut chunk) = (input.text.clone(), 0, input.text.len() / 2);
    let start = Instant::now();
    let more = |runs: usize| runs < SHRINK_RUNS && start.elapsed() < SHRINK_TIME;
    while chunk >= 1 && more(runs) {
        let mut at = 0;
        while at < text.len() && more(runs) {
            let mut candidate = text.clone();
            candidate.drain(at..(at + chunk).min(text.len()));
            runs += 1;
            if keeps_cause(&candidate) {
                text = candidate;
            } else {
                at += chunk;
            }
        }
        chunk /= 2;
    }
    (text.len() < input.text.len()).then_some(text)
}

/// Runs task 0, 1, 2, … (until `next_task` gives none) on `settings.jobs`
/// threads, each in its own folder.
fn run_tasks(settings: &Settings, next_task: impl Fn(usize) -> Option<Task> + Sync) -> Report {
    let counter = AtomicUsize::new(0);
    let report = Mutex::new(Report::default());
    let _ = std::fs::remove_dir_all(&settings.findings);
    // One folder per call: the tests of this file run at the same time.
    static CALLS: AtomicUsize = AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, Ordering::Relaxed);
    let root =
        Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("fuzz-{}-{call}", std::process::id()));
    std::thread::scope(|scope| {
        for worker in 0..settings.jobs {
            let (dir, scratch) = (
                root.join(format!("w{worker}")),
                root.join(format!("s{worker}")),
            );
            let (counter, report, next_task) = (&counter, &report, &next_task);
            scope.spawn(move || {
                while let Some(task) = next_task(counter.fetch_add(1, Ordering::Relaxed)) {
                    let mut ran = run_task(settings, &task, &dir);
                    let (keep, first) = report.lock().unwrap().count(&task, &ran);
                    if keep {
                        let shrink = first && settings.shrink;
                        save(settings, &task, &mut ran.findings, shrink, &scratch);
                    }
                    report.lock().unwrap().findings.extend(ran.findings);
                }
            });
        }
    });
    let _ = std::fs::remove_dir_all(&root);
    let mut report = report.into_inner().unwrap();
    report
        .findings
        .sort_by(|a, b| (a.notation, &a.label).cmp(&(b.notation, &b.label)));
    report
}

impl Report {
    /// Counts a task's run. Whether to save its input (it is one of the
    /// first few of some cause), and whether it is the first of the cause
    /// of its first finding.
    fn count(&mut self, task: &Task, ran: &Ran) -> (bool, bool) {
        let findings = &ran.findings;
        let tally = self.tallies.entry(task.notation).or_default();
        tally.inputs += 1;
        tally.commands += ran.commands;
        tally.failed_inputs += usize::from(!findings.is_empty());
        tally.findings += findings.len();
        tally.slowest = tally.slowest.max(ran.slowest);
        if findings.is_empty() {
            tally.clean_busy += ran.busy;
        }
        let (mut keep, mut first) = (false, false);
        for (i, f) in findings.iter().enumerate() {
            let cause = self
                .causes
                .entry((f.notation, f.symptom.cause.clone()))
                .or_default();
            cause.findings += 1;
            cause.commands.insert(f.command());
            if cause.last_label != task.label {
                cause.last_label = task.label.clone();
                cause.inputs += 1;
                keep |= cause.inputs <= SAVED_PER_CAUSE;
                first |= i == 0 && cause.inputs == 1;
            }
        }
        (keep, first)
    }

    /// Inputs and findings per notation, then the findings by cause, each
    /// with a command line that reproduces one.
    fn summary(&self, settings: &Settings, took: Duration) -> String {
        let mut s = format!(
            "seed {}, {} jobs, {:.1} s, binary {}\n",
            settings.seed,
            settings.jobs,
            took.as_secs_f64(),
            settings.binary.display()
        );
        for (n, t) in &self.tallies {
            s += &format!(
                "  {:<9}{:>7} inputs: {:>7} ran clean (commands {:.1} s), {:>5} with findings ({} of {} commands); slowest command {:.2} s\n",
                n.name(),
                t.inputs,
                t.inputs - t.failed_inputs,
                t.clean_busy.as_secs_f64(),
                t.failed_inputs,
                t.findings,
                t.commands,
                t.slowest.as_secs_f64()
            );
        }
        for ((notation, cause), c) in &self.causes {
            let commands: Vec<&str> = c.commands.iter().map(String::as_str).collect();
            s += &format!(
                "\n[{}] {cause}: {} inputs, {} commands ({})\n",
                notation.name(),
                c.inputs,
                c.findings,
                commands.join(", ")
            );
            let example = self
                .findings
                .iter()
                .find(|f| f.notation == *notation && f.symptom.cause == *cause);
            if let Some(f) = example {
                s += &format!(
                    "    e.g. {}: {}\n    {}\n",
                    f.label,
                    f.symptom.detail,
                    f.reproduce(&settings.binary)
                );
            }
        }
        s
    }
}

// ---------------------------------------------------------------------------
// Regression inputs
// ---------------------------------------------------------------------------

/// A regression input too large to keep as a file: made by code.
struct Recipe {
    notation: Notation,
    name: &'static str,
    make: fn() -> Input,
}

/// The issue-16 inputs of megabytes, and the ones that are not files.
const RECIPES: &[Recipe] = &[
    Recipe {
        notation: Notation::Pfg,
        name: "successor-of-a-million-symbols",
        make: || {
            let big = "F".repeat(1_000_000);
            Input::file(
                "big.l",
                format!("axiom: F\nF --> F[+F]F : 0.5\nF --> {big} : 0.5\n"),
            )
        },
    },
    Recipe {
        notation: Notation::Pfg,
        name: "brackets-100000-deep",
        make: || {
            let deep = format!("{}F{}", "[".repeat(100_000), "]".repeat(100_000));
            Input::file("deep.l", format!("axiom: {deep}\nF --> F{deep}\n"))
        },
    },
    Recipe {
        notation: Notation::Stl,
        name: "seed-of-a-million-modules",
        make: || {
            Input::file(
                "long.stl",
                format!("SEED\n{}\nENDSEED\n", "F(1)".repeat(1_000_000)),
            )
        },
    },
    Recipe {
        notation: Notation::Stl,
        name: "brackets-100000-deep",
        make: || {
            let deep = format!("{}F{}", "[".repeat(100_000), "]".repeat(100_000));
            Input::file("deep.stl", format!("SEED\nF{deep}\nENDSEED\n"))
        },
    },
    Recipe {
        notation: Notation::Linf,
        name: "long-line-of-errors",
        make: || {
            let errors = "f $ ".repeat(1_000_000);
            Input::file(
                "long.linf",
                format!("lines f\naxiom f\nrules f = {errors}\n"),
            )
        },
    },
    Recipe {
        notation: Notation::Cpfg,
        name: "view-of-60000-unknown-lines",
        make: || Input {
            beside: vec![("plant.v".into(), "xx\n".repeat(60_000).into_bytes())],
            ..Input::file(
                "plant.l",
                "Lsystem: 1\nderivation length: 2\nAxiom: F\nF --> F[+F]F\nendlsystem\n",
            )
        },
    },
    Recipe {
        notation: Notation::Stl,
        name: "rule-of-200000-open-parentheses",
        make: || Input::file("long.stl", format!("R1 = {}\n", "(cl".repeat(200_000))),
    },
    Recipe {
        notation: Notation::Pfg,
        name: "link-to-dev-zero",
        make: || Input {
            link: Some("/dev/zero".into()),
            ..Input::file("zero.l", "")
        },
    },
    Recipe {
        notation: Notation::Stl,
        name: "link-to-dev-urandom",
        make: || Input {
            link: Some("/dev/urandom".into()),
            ..Input::file("random.stl", "")
        },
    },
];

/// Every input of `tests/fuzz/regressions/<notation>/` (a file, or a folder
/// whose every `.l` is an input with the rest beside it), then the recipes.
fn regression_tasks() -> Vec<Task> {
    let mut tasks = Vec::new();
    for notation in NOTATIONS {
        let dir = repo("tests/fuzz/regressions").join(notation.name());
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        let mut paths: Vec<PathBuf> = entries.map(|e| e.unwrap().path()).collect();
        paths.sort();
        for path in paths {
            let inputs = if path.is_dir() {
                object_inputs(&path)
            } else {
                vec![Input::file(file_name(&path), std::fs::read(&path).unwrap())]
            };
            for input in inputs {
                let label = if path.is_dir() {
                    format!("{}/{}", file_name(&path), input.name)
                } else {
                    input.name.clone()
                };
                tasks.push(Task {
                    notation,
                    label,
                    knobs: regression_knobs(&input),
                    input,
                });
            }
        }
    }
    for r in RECIPES {
        let input = (r.make)();
        let label = format!("recipe-{}", r.name);
        tasks.push(Task {
            notation: r.notation,
            label,
            knobs: regression_knobs(&input),
            input,
        });
    }
    tasks
}

// ---------------------------------------------------------------------------
// Tests
// ---------------------------------------------------------------------------

/// The mutants of every notation run without a finding. Brief under `cargo
/// test`; as long as `GRAFTAL_FUZZ_SECONDS` or `GRAFTAL_FUZZ_CASES` say.
#[test]
fn mutants_of_every_notation_run_without_a_finding() {
    let Some(_timed) = slow_timed("fuzz: mutants and regression inputs through the binary") else {
        return;
    };
    let mut settings = Settings::from_env();
    settings.findings = findings_root().join(format!("seed{}", settings.seed));
    let seeds = load_seeds();
    let start = Instant::now();
    let report = run_tasks(&settings, |t| {
        let n = settings.notations.len();
        let (notation, index) = (settings.notations[t % n], t / n);
        let done = match settings.until {
            Some(until) => Instant::now() >= until,
            None => index >= settings.cases,
        };
        if done {
            return None;
        }
        let input = mutant(&seeds, notation, index, settings.seed);
        let mut rng = Rng::new(&[settings.seed, notation as u64, index as u64, 1]);
        let knobs = vec![random_knobs(&mut rng, &input)];
        Some(Task {
            notation,
            label: format!("mutant-{index}"),
            input,
            knobs,
        })
    });
    let summary = report.summary(&settings, start.elapsed());
    if report.findings.is_empty() {
        eprintln!("fuzz: {summary}");
    }
    assert!(
        report.findings.is_empty(),
        "{} findings (inputs in {}):\n{summary}",
        report.findings.len(),
        settings.findings.display()
    );
}

/// Every crash ever found (and every case of issue 16) runs through the
/// same commands without a finding.
#[test]
fn every_regression_input_runs_without_a_finding() {
    let Some(_timed) = slow_timed("fuzz: mutants and regression inputs through the binary") else {
        return;
    };
    let settings = Settings {
        findings: findings_root().join("regressions"),
        ..Settings::from_env()
    };
    let tasks = regression_tasks();
    for notation in NOTATIONS {
        assert!(
            tasks.iter().any(|t| t.notation == notation),
            "no regression input for {} in tests/fuzz/regressions",
            notation.name()
        );
    }
    let start = Instant::now();
    let tasks = Mutex::new(tasks.into_iter().map(Some).collect::<Vec<_>>());
    let report = run_tasks(&settings, |t| {
        tasks.lock().unwrap().get_mut(t).and_then(Option::take)
    });
    let summary = report.summary(&settings, start.elapsed());
    if report.findings.is_empty() {
        eprintln!("fuzz regressions: {summary}");
    }
    assert!(
        report.findings.is_empty(),
        "{} findings:\n{summary}",
        report.findings.len()
    );
}

#[test]
fn mutants_are_the_same_every_run_and_differ_from_each_other() {
    let seeds = load_seeds();
    for notation in NOTATIONS {
        let pool = &seeds[notation as usize];
        assert!(
            pool.len() >= 5,
            "{} has only {} seeds",
            notation.name(),
            pool.len()
        );
        let mutants: Vec<Input> = (0..50).map(|i| mutant(&seeds, notation, i, 7)).collect();
        let again: Vec<Input> = (0..50).map(|i| mutant(&seeds, notation, i, 7)).collect();
        assert!(
            mutants == again,
            "{}: the same seed gave other mutants",
            notation.name()
        );
        let changed = mutants.iter().filter(|m| !pool.contains(m)).count();
        assert!(
            changed >= 45,
            "{}: only {changed} of 50 mutants differ from every seed",
            notation.name()
        );
        let other_seed = mutant(&seeds, notation, 0, 8);
        assert!(other_seed != mutants[0] || mutant(&seeds, notation, 1, 8) != mutants[1]);
    }
    let objects = &seeds[Notation::Cpfg as usize];
    assert!(
        objects
            .iter()
            .filter(|i| i.beside.iter().any(|(n, _)| n.ends_with(".v")))
            .count()
            >= 90
    );
    let side_edits = (0..200)
        .map(|i| mutant(&seeds, Notation::Cpfg, i, 7))
        .filter(|m| {
            !objects
                .iter()
                .any(|s| s.name == m.name && s.beside == m.beside)
        })
        .count();
    assert!(
        side_edits >= 20,
        "only {side_edits} of 200 cpfg mutants edit a file beside the .l"
    );
}

/// The regression runs include the command lines of issue 16's cases, and
/// name a Fractint library's entry.
#[test]
fn regression_runs_include_the_commands_of_the_issue() {
    let lines = |input: &Input| -> Vec<String> {
        regression_knobs(input)
            .iter()
            .flat_map(|k| commands(&input.name, k))
            .map(|args| args.join(" "))
            .collect()
    };
    let pfg = lines(&Input::file("a.l", "axiom: F\nF --> F\n"));
    for expected in [
        "check ./a.l",
        "derive ./a.l -n 2 --seed 0",
        "translate --to stl ./a.l -n 100000 --lossy",
        "translate --to linf ./a.l --lossy --format json",
        "render -o out.svg --size 64x64 ./a.l --max-symbols 20000 --seed 0 --format json",
    ] {
        assert!(
            pfg.iter().any(|l| l == expected),
            "no `{expected}` in {pfg:#?}"
        );
    }
    let library = Input::file("lib.l", "Koch {\n Axiom F\n}\nDragon {\n Axiom F\n}\n");
    let fractint = lines(&library);
    assert!(fractint
        .iter()
        .any(|l| l == "derive ./lib.l --entry Koch -n 2 --seed 0"));
    assert!(lines(&Input::file("a.l", "Koch {\n Axiom F\n --> F\n}\n"))
        .iter()
        .all(|l| !l.contains("--entry")));
}

/// The judge calls a crash, a hang, a flood, a panic and dirty stderr
/// findings, and a clean exit with errors none.
#[test]
fn the_judge_names_crashes_hangs_floods_and_panics() {
    let sh = |script: &str, seconds: f64| {
        let json = script.contains("# json");
        let timeout = Duration::from_secs_f64(seconds);
        let args = ["-c".to_string(), script.to_string()];
        let bound = (!json).then_some(MAX_STDERR_HUMAN);
        let o = run_bounded(Path::new("/bin/sh"), &args, Path::new("/"), bound, timeout);
        (judge(&o, json, timeout).map(|s| s.cause), o)
    };
    let cause = |script: &str| sh(script, 5.0).0.unwrap_or_default();
    assert_eq!(cause("echo error >&2; exit 1"), "");
    assert_eq!(cause("echo '{\"code\":\"E0001\"}' >&2; exit 1 # json"), "");
    // A usage or I/O problem (exit 2) is told in plain text, JSON or not.
    assert_eq!(cause("echo 'error: cannot read' >&2; exit 2 # json"), "");
    assert_eq!(cause("kill -SEGV $$"), "killed (signal 11)");
    let overflow = "echo \"thread 'main' has overflowed its stack\" >&2; kill -ABRT $$";
    assert_eq!(cause(overflow), "killed (stack overflow, signal 6)");
    let start = Instant::now();
    // The shell waits for `sleep`, which holds the pipes: the whole group
    // is killed.
    assert_eq!(sh("sleep 30; echo", 0.3).0.unwrap(), "no exit within 300ms");
    assert!(
        start.elapsed() < Duration::from_secs(5),
        "the timeout did not kill"
    );
    let flood = "while :; do echo flood >&2; done";
    assert_eq!(
        cause(flood),
        format!("stderr over {MAX_STDERR_HUMAN} bytes")
    );
    assert_eq!(cause("yes"), format!("stdout over {MAX_STDOUT} bytes"));
    let panic = "printf \"thread 'main' (7) panicked at src/x.rs:1:2:\\nboom\\n\" >&2; exit 101";
    assert_eq!(cause(panic), "panic at src/x.rs:1:2: boom");
    assert_eq!(cause("exit 3"), "exit status Some(3)");
    let oom = "echo 'error: cannot read `/dev/zero`: out of memory' >&2; exit 2";
    assert!(cause(oom).starts_with("out of memory"));
    let escape = "printf 'a\\033[31mb' >&2; exit 1";
    assert_eq!(cause(escape), "a raw control character on stderr");
    assert_eq!(
        cause("printf 'a\\377b' >&2; exit 1"),
        "invalid UTF-8 on stderr"
    );
    // JSON lists every diagnostic: no bound on all of them, one on each.
    let many = "yes '{\"code\":\"E0001\"}' | head -n 1000000 >&2; exit 1 # json";
    assert_eq!(cause(many), "");
    let not_json = "echo not json >&2; exit 1 # json";
    assert!(cause(not_json).starts_with("stderr is not JSON lines"));
    let long_json = format!(
        "echo '\"{}\"' >&2; exit 1 # json",
        "x".repeat(MAX_JSON_LINE)
    );
    assert!(cause(&long_json).starts_with("stderr is not JSON lines"));
    // The address-space limit is set.
    let (none, limited) = sh("ulimit -v >&2", 5.0);
    assert_eq!(none, None);
    let limit = String::from_utf8_lossy(&limited.stderr).trim().to_string();
    assert_eq!(limit, ADDRESS_SPACE_KIB.to_string());
}
