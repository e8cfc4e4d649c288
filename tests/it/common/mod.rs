//! What the test suites share: running `graftal` in-process, a
//! temporary directory per suite, golden files, tests run alone and the
//! gate of the slow suites.
#![allow(dead_code)]

mod alone;
pub mod random;

pub use alone::{alone, assert_within, slow, slow_timed};

use graftal::cli::{run, Io};
use std::path::Path;

/// What one run printed, and its exit status.
pub struct Out {
    pub status: i32,
    pub stdout: String,
    pub stderr: String,
}

/// Runs `graftal ARGS…` through `cli::run`, as a pipe (no terminal).
pub fn graftal(args: &[&str]) -> Out {
    let (status, stdout, stderr) = graftal_bytes(args, false);
    Out {
        status,
        stdout: String::from_utf8(stdout).unwrap(),
        stderr: String::from_utf8(stderr).unwrap(),
    }
}

/// Runs `graftal ARGS…` through `cli::run` with stderr a pipe and stdout a
/// terminal or not; the status and the bytes of stdout and stderr.
pub fn graftal_bytes(args: &[&str], stdout_terminal: bool) -> (i32, Vec<u8>, Vec<u8>) {
    let mut argv = vec!["graftal"];
    argv.extend_from_slice(args);
    let graftal = move || {
        let mut stdout = Vec::new();
        let mut stderr = Vec::new();
        let mut io = Io {
            stdout: &mut stdout,
            stderr: &mut stderr,
            terminal: false,
            stdout_terminal,
        };
        let status = run(argv, &mut io);
        (status, stdout, stderr)
    };
    // On a stack as big as the binary's (src/main.rs): a test thread's is
    // 2 MiB, and the deepest inputs graftal accepts need more unoptimised.
    std::thread::scope(|scope| {
        let thread = std::thread::Builder::new().stack_size(GRAFTAL_STACK_BYTES);
        let running = thread.spawn_scoped(scope, graftal).unwrap();
        running
            .join()
            .unwrap_or_else(|e| std::panic::resume_unwind(e))
    })
}

/// The stack `graftal` runs on (`STACK_BYTES` in src/main.rs).
const GRAFTAL_STACK_BYTES: usize = 64 << 20;

/// A path named `name` in the calling test's temporary directory: one a
/// source file of `tests/it/`, process and test (the test threads are named
/// after their tests), so that tests running side by side never write the
/// same file.
#[track_caller]
pub fn temp(name: &str) -> std::path::PathBuf {
    let caller = Path::new(std::panic::Location::caller().file());
    let suite = caller.file_stem().unwrap().to_string_lossy();
    let thread = std::thread::current();
    let test: String = (thread.name().unwrap_or("main").chars())
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    let dir = std::env::temp_dir()
        .join(format!("graftal-{suite}-{}", std::process::id()))
        .join(test);
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// A file `name` holding `text`, written in a folder of its own in the
/// calling test's temporary directory (a cpfg object's folder, for a
/// file with side files beside it); returns the file's path.
#[track_caller]
pub fn object_file(folder: &str, name: &str, text: &str) -> std::path::PathBuf {
    let dir = temp(folder);
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// The pixels of an 8-bit RGBA PNG (graftal's pictures).
pub fn rgba_pixels(png_bytes: &[u8]) -> Vec<[u8; 4]> {
    let mut reader = png::Decoder::new(std::io::Cursor::new(png_bytes))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgba, "an RGBA picture");
    buf[..info.buffer_size()]
        .chunks_exact(4)
        .map(|p| [p[0], p[1], p[2], p[3]])
        .collect()
}

/// Whether this run rewrites golden files instead of checking them:
/// `GRAFTAL_BLESS=1` (any other value, or none, checks).
pub fn blessing() -> bool {
    std::env::var_os("GRAFTAL_BLESS").is_some_and(|v| v == "1")
}

/// Texts up to this size are shown whole when they differ.
const SHOW_WHOLE: usize = 4096;

/// Checks `actual` against the golden file `path`, byte for byte. With
/// `GRAFTAL_BLESS=1` the file is written instead (only when it differs)
/// and the check passes. Otherwise a missing or different golden is an
/// error saying which file, where it first differs, and how to rewrite it
/// on purpose.
///
/// A test that must only bless what it has verified (an independent
/// derivation, say) asserts that before calling this.
pub fn check_golden(path: &Path, actual: &str) -> Result<(), String> {
    check_golden_bytes(path, actual.as_bytes())
}

/// [`check_golden`] for any bytes (a PNG, say): where a text differs is
/// shown as for [`check_golden`], other bytes by their sizes only.
pub fn check_golden_bytes(path: &Path, actual: &[u8]) -> Result<(), String> {
    let expected = std::fs::read(path);
    if blessing() {
        if expected.ok().as_deref() != Some(actual) {
            if let Some(dir) = path.parent() {
                std::fs::create_dir_all(dir).unwrap();
            }
            std::fs::write(path, actual).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            eprintln!("blessed {}", path.display());
        }
        return Ok(());
    }
    let expected = match expected {
        Ok(bytes) => bytes,
        Err(e) => {
            return Err(format!(
                "{} is missing ({e}); GRAFTAL_BLESS=1 writes it",
                path.display()
            ))
        }
    };
    if expected == actual {
        return Ok(());
    }
    let mut message = format!(
        "{} differs from the output (GRAFTAL_BLESS=1 rewrites it): {} bytes expected, {} actual",
        path.display(),
        expected.len(),
        actual.len()
    );
    if let (Ok(expected), Ok(actual)) =
        (std::str::from_utf8(&expected), std::str::from_utf8(actual))
    {
        message.push_str(&where_texts_differ(expected, actual));
    }
    Err(message)
}

/// Two texts whole when they are short, else their first differing line.
fn where_texts_differ(expected: &str, actual: &str) -> String {
    if expected.len() <= SHOW_WHOLE && actual.len() <= SHOW_WHOLE {
        return format!("\n--- expected\n{expected}\n--- actual\n{actual}");
    }
    let mut e = expected.split_inclusive('\n');
    let mut a = actual.split_inclusive('\n');
    let mut line = 1;
    loop {
        match (e.next(), a.next()) {
            (x, y) if x == y && x.is_some() => line += 1,
            (x, y) => {
                return format!(
                    "; first at line {line}:\n--- expected\n{}\n--- actual\n{}",
                    shorten(x.unwrap_or("(end of file)")),
                    shorten(y.unwrap_or("(end of file)"))
                )
            }
        }
    }
}

/// One line of a golden, without its newline, cut to a readable length.
fn shorten(line: &str) -> String {
    let line = line.trim_end_matches('\n');
    match line.char_indices().nth(300) {
        Some((at, _)) => format!("{}...", &line[..at]),
        None => line.to_string(),
    }
}

/// The `.l` file of a corpus object: the one its `specifications` names
/// on the `cpfg` line, else the only one. Every object has a
/// `specifications` file; a missing one fails the test.
pub fn main_l(dir: &std::path::Path) -> Option<std::path::PathBuf> {
    let spec_path = dir.join("specifications");
    let spec = std::fs::read_to_string(&spec_path)
        .unwrap_or_else(|e| panic!("{}: {e}", spec_path.display()));
    for line in spec.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.first() == Some(&"cpfg") {
            if let Some(l) = words.iter().find(|w| w.ends_with(".l")) {
                return Some(dir.join(l));
            }
        }
    }
    let mut ls: Vec<std::path::PathBuf> = std::fs::read_dir(dir)
        .ok()?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "l"))
        .collect();
    ls.sort();
    ls.into_iter().next()
}

pub fn corpus(part: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/corpus")
        .join(part)
}

/// The object folders of the cpfg corpus (tests/corpus/cpfg), sorted.
pub fn cpfg_object_dirs() -> Vec<std::path::PathBuf> {
    let mut dirs: Vec<std::path::PathBuf> = std::fs::read_dir(corpus("cpfg"))
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_dir())
        .collect();
    dirs.sort();
    dirs
}

/// Every entry of the Fractint corpus's libraries (tests/corpus/fractint,
/// the history included), compiled, named `FILE:ENTRY`.
pub fn fractint_corpus_entries() -> Vec<(String, graftal::driver::Compiled)> {
    use graftal::{driver, source::SourceFile};
    let files = [
        "fractint.l",
        "penrose.l",
        "tiling.l",
        "history/fractint.l.v15.0",
        "history/fractint.l.v16.0",
        "history/fractint.l.v19.0",
    ];
    let mut out = Vec::new();
    for file in files {
        let source = SourceFile::read(&corpus("fractint").join(file)).unwrap();
        let lib = driver::compile(source.clone()).library.expect("a library");
        for entry in &lib.entries {
            let c = driver::compile_entry(source.clone(), Some(&entry.name));
            out.push((format!("{file}:{}", entry.name), c));
        }
    }
    out
}

/// Whether graftal reads the files an emitter writes, so that a
/// translation can be compiled again (`.gft` once its front end is
/// registered; tests/it/gft_emitter.rs covers its emitter until then).
pub fn reads_back(to: &dyn graftal::back::Back) -> bool {
    (graftal::front::FRONTS.iter()).any(|f| f.extensions().contains(&to.extension()))
}

/// The emitters whose files graftal also reads ([`reads_back`]).
pub fn read_back_targets() -> Vec<&'static dyn graftal::back::Back> {
    (graftal::back::BACKS.iter().copied())
        .filter(|&b| reads_back(b))
        .collect()
}
