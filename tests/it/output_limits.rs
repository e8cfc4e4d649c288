//! No input floods the terminal or makes reading run away (issue 16, items
//! 1, 5 and 6): the binary is run on inputs generated here, each under a
//! deadline, and what it prints is measured.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Output kept from a run; more is counted, not kept (a flood must fail
/// the test, not fill the memory).
const KEPT: usize = 1 << 20;

/// The most a run may print on stderr for people: a few kilobytes.
const FEW_KB: usize = 16 << 10;

struct Run {
    status: Option<i32>,
    stdout: String,
    stderr: String,
    stdout_bytes: usize,
    stderr_bytes: usize,
    took: Duration,
}

/// Reads `r` to its end, keeping the first [`KEPT`] bytes; how many in all.
fn drain(mut r: impl Read + Send + 'static) -> std::thread::JoinHandle<(Vec<u8>, usize)> {
    std::thread::spawn(move || {
        let (mut kept, mut total, mut buf) = (Vec::new(), 0, vec![0; 1 << 16]);
        while let Ok(n @ 1..) = r.read(&mut buf) {
            total += n;
            let room = KEPT.saturating_sub(kept.len()).min(n);
            kept.extend_from_slice(&buf[..room]);
        }
        (kept, total)
    })
}

/// Runs the binary with `args`, killed after `deadline`.
fn run(args: &[&str], deadline: Duration) -> Run {
    let t = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_graftal"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the graftal binary runs");
    let out = drain(child.stdout.take().unwrap());
    let err = drain(child.stderr.take().unwrap());
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s.code();
        }
        if t.elapsed() > deadline {
            child.kill().unwrap();
            child.wait().unwrap();
            break None;
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let took = t.elapsed();
    let (stdout, stdout_bytes) = out.join().unwrap();
    let (stderr, stderr_bytes) = err.join().unwrap();
    Run {
        status,
        stdout: String::from_utf8_lossy(&stdout).into_owned(),
        stderr: String::from_utf8_lossy(&stderr).into_owned(),
        stdout_bytes,
        stderr_bytes,
        took,
    }
}

/// Generous for a debug build on a busy machine; the release build takes
/// a fraction of it (see the figures in the closing note).
const DEADLINE: Duration = Duration::from_secs(30);

fn dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("graftal-output-limits-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn write(name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    let p = dir().join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Bytes from a fixed xorshift sequence: the same "random" file each run.
fn noise(len: usize, mut seed: u64) -> Vec<u8> {
    (0..len)
        .map(|_| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 24) as u8
        })
        .collect()
}

/// Asserts a run ended by itself with status 1, quickly, printing a few
/// kilobytes, with no control character but line breaks on stderr.
fn assert_bounded(r: &Run, what: &str) {
    assert!(
        r.status == Some(1),
        "{what}: status {:?} after {:?}; stderr starts {}",
        r.status,
        r.took,
        &r.stderr[..r.stderr.len().min(2000)]
    );
    assert!(
        r.stderr_bytes <= FEW_KB && r.stdout_bytes <= FEW_KB,
        "{what}: {} bytes on stderr, {} on stdout",
        r.stderr_bytes,
        r.stdout_bytes
    );
    let raw = r.stderr.chars().find(|&c| c.is_control() && c != '\n');
    assert_eq!(raw, None, "{what}: a raw control character on stderr");
}

#[test]
fn a_fractint_entry_name_of_any_length_is_listed_shortened() {
    let name = format!("fr{}", "a".repeat(70_000));
    let p = write("name.l", format!("{name} {{\n Axiom F\n F=F+F\n}}\n"));
    let r = run(&["check", s(&p)], DEADLINE);
    assert_bounded(&r, "a 70,000-character entry name");
    // The listing shows the name's start and end around an ellipsis.
    let listed = r.stdout.lines().find(|l| l.contains("line 1")).unwrap();
    assert!(listed.trim_start().starts_with("fraaa"), "{listed}");
    assert!(
        listed.contains('…') && listed.chars().count() < 100,
        "{listed}"
    );
}

#[test]
fn a_long_stl_line_of_mistakes_prints_a_few_kilobytes() {
    let p = write("seed.stl", format!("SEED {}", "F(1)".repeat(100_000)));
    let r = run(&["check", s(&p)], DEADLINE);
    assert_bounded(&r, "SEED F(1)F(1)…");
    // The unterminated block, the repeated mistake three times, then a
    // note that counts the rest of the run on that line.
    assert_eq!(r.stderr.matches("Error:").count(), 4, "{}", r.stderr);
    assert_eq!(r.stderr.matches("[E0003]").count(), 3, "{}", r.stderr);
    assert!(
        r.stderr
            .contains("299997 more E0003 diagnostics on this line are not shown one by one"),
        "{}",
        r.stderr
    );
}

#[test]
fn a_long_linf_line_is_cut_around_the_problem_with_real_columns() {
    let items = "f@".repeat(100_000);
    let p = write(
        "long.linf",
        format!("lines f\naxiom f\nrules f = {items}\n"),
    );
    let r = run(&["check", s(&p)], DEADLINE);
    assert_bounded(&r, "a 200 KB LinF rule");
    // The first `@` is at column 12 of line 3: the header says so, and the
    // snippet's margin numbers the line 3.
    assert!(r.stderr.contains("long.linf:3:12 ]"), "{}", r.stderr);
    assert!(r.stderr.contains(" 3 │ rules f = f@f@"), "{}", r.stderr);
    // A problem deep in the line: its real column, a window around it.
    let mut deep = format!("lines f\naxiom f\nrules f = {}", "f".repeat(100_000));
    deep.push_str("@ f\n");
    let p = write("deep.linf", deep);
    let r = run(&["check", s(&p)], DEADLINE);
    assert_bounded(&r, "a problem at column 100,011");
    assert!(r.stderr.contains("deep.linf:3:100011 ]"), "{}", r.stderr);
    let shown = r.stderr.lines().find(|l| l.starts_with(" 3 │ ")).unwrap();
    assert!(shown.starts_with(" 3 │ …fff"), "{shown}");
    assert!(shown.contains("f@ f"), "{shown}");
    assert!(shown.chars().count() < 200, "{shown}");
}

#[test]
fn a_file_that_is_not_text_gets_one_diagnostic_in_every_command() {
    let mut elf = b"\x7fELF\x02\x01\x01\0\0\0\0\0\0\0\0\0".to_vec();
    elf.extend(noise(3000, 7));
    // Mostly control characters, no NUL: not text either.
    let controls: Vec<u8> = b"F\x01\x02\x03\x04".repeat(600);
    let files = [
        write("rand.l", noise(3000, 1)),
        write("elf.l", elf),
        write("controls.linf", controls),
    ];
    let out = s(&dir()).to_string() + "/x.svg";
    for f in &files {
        let f = s(f);
        for args in [
            vec!["check", f],
            vec!["derive", f],
            vec!["stats", f],
            vec!["render", f, "-o", &out],
            vec!["translate", f, "--to", "stl"],
        ] {
            let r = run(&args, DEADLINE);
            assert_bounded(&r, &args.join(" "));
            assert_eq!(r.stderr.matches("E0012").count(), 1, "{}", r.stderr);
            // The message, `--> file` (it has no place in the file), note, help.
            assert_eq!(r.stderr.lines().count(), 4, "{}", r.stderr);
            assert!(r.stderr.contains("is not a text file"), "{}", r.stderr);
            assert!(r.stderr.contains("help: graftal reads"), "{}", r.stderr);
            assert!(r.stdout.is_empty(), "{}", r.stdout);
        }
    }
}

#[test]
fn a_view_file_of_random_bytes_is_echoed_escaped() {
    let corpus = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/corpus/cpfg/01-Introduction-01-quadratic-Koch");
    let obj = dir().join("koch");
    std::fs::create_dir_all(&obj).unwrap();
    for e in std::fs::read_dir(&corpus).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), obj.join(e.file_name())).unwrap();
    }
    // Lines of bytes with no NUL, so that the view file is read.
    let bytes: Vec<u8> = noise(3000, 3)
        .into_iter()
        .map(|b| if b == 0 { b'\n' } else { b })
        .collect();
    std::fs::write(obj.join("fractal.v"), bytes).unwrap();
    let r = run(&["check", s(&obj.join("fractal.l"))], DEADLINE);
    assert_eq!(r.status, Some(0), "warnings only: {}", r.stderr);
    assert!(r.stderr.contains("W0804"), "{}", r.stderr);
    assert!(r.stderr.contains("\\u{"), "escaped: {}", r.stderr);
    let raw = r.stderr.chars().find(|&c| c.is_control() && c != '\n');
    assert_eq!(raw, None, "a raw control character on stderr");
    // At most MAX_SHOWN (20) warnings, each with its side file's snippet
    // cut to about 100 columns, where one escaped byte takes up to 8.
    assert!(r.stderr_bytes <= 2 * FEW_KB, "{} bytes", r.stderr_bytes);
}

#[cfg(unix)]
#[test]
fn a_device_is_read_no_further_than_the_limit() {
    let r = run(&["check", "/dev/zero"], DEADLINE);
    assert_bounded(&r, "/dev/zero");
    assert!(r.stderr.contains("E0011"), "{}", r.stderr);
    assert!(
        r.stderr.contains("more than the 8388608 bytes"),
        "{}",
        r.stderr
    );
    // A link to it is the same.
    let link = dir().join("zero.l");
    let _ = std::fs::remove_file(&link);
    std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
    let r = run(&["derive", s(&link)], DEADLINE);
    assert_bounded(&r, "a link to /dev/zero");
    assert!(r.stderr.contains("E0011"), "{}", r.stderr);
}

#[test]
fn many_different_mistakes_show_twenty_and_count_the_rest_by_code() {
    // An invalid character and a missing arrow on each line: two codes.
    let text: String = (0..500).map(|_| "axiom: F\u{7}\nF F\n").collect();
    let p = write("many.l", text);
    let r = run(&["check", s(&p)], DEADLINE);
    assert_bounded(&r, "500 lines of mistakes");
    let shown = r.stderr.matches("] Error:").count() + r.stderr.matches("] Warning:").count();
    assert_eq!(shown, 20, "{}", r.stderr);
    let last = r.stderr.lines().last().unwrap();
    assert!(last.starts_with("... and "), "{last}");
    assert!(last.contains("E0001 (invalid character)"), "{last}");
    let json = run(&["check", "--format", "json", s(&p)], DEADLINE);
    let listed = json.stderr.lines().count();
    let counted: usize = last["... and ".len()..]
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(listed, counted + 20, "{last}");
}
