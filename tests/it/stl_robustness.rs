//! Robustness of the STL front end: mutated, random and generated `.stl`
//! inputs go through compile, derive, render (with the layout) and the
//! BED round trip, and none may panic, hang, or give a diagnostic that
//! points outside its file. When a file compiles, its BED (`translate --to
//! stl`) must compile too and draw the same number of stems.
//!
//! Inputs: the STL stdlib files mutated by edits (delete a range, insert an
//! STL-flavoured fragment, duplicate a range, truncate); random strings
//! over the STL alphabet; structured random files (settings with extreme
//! numbers, random rules, seeds with nested branching terms, layouts).
//! Each input runs on its own thread with a deadline. Runs are
//! reproducible: fixed proptest seeds.

use graftal::diagnostics::{codes, render_human, Diagnostic};
use graftal::driver::{self, Format, RunOptions};
use graftal::render::RenderOptions;
use graftal::source::SourceFile;
use graftal::stdlib::ENTRIES;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestRng, TestRunner};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// The most one input may take: a hang detector. Growth is bounded (256
/// levels, 1 000 000 stems). The worst input (the grown tree of 123 746
/// stems with no clearance, translated to pfg and LinF and read back) takes
/// 16 s in the test profile on a 2-core machine, more when the machine is
/// busy; a hang never ends.
const TIME_LIMIT: Duration = Duration::from_secs(60);

fn check_span(s: &std::ops::Range<usize>, text: &str) -> Result<(), String> {
    if s.start > s.end
        || s.end > text.len()
        || !text.is_char_boundary(s.start)
        || !text.is_char_boundary(s.end)
    {
        return Err(format!(
            "span {s:?} is not inside the text (length {})",
            text.len()
        ));
    }
    Ok(())
}

fn check_diagnostic(d: &Diagnostic, file: &SourceFile) -> Result<(), String> {
    if !codes::all().any(|c| c.code == d.code) {
        return Err(format!("unregistered code {}", d.code));
    }
    if let Some(s) = &d.span {
        check_span(s, &file.text)?;
    }
    for l in &d.labels {
        check_span(&l.span, &file.text)?;
    }
    if d.code.0.starts_with("E05")
        && (d.span.is_none() && d.code != codes::STL_TOO_DEEP || d.help.is_none())
    {
        return Err(format!("STL diagnostic without a span or help: {d:?}"));
    }
    if !render_human(d, file, false).contains(d.code.0) {
        return Err("rendering lacks the code".into());
    }
    Ok(())
}

/// Compile, check, draw, render and round-trip one text; the stem count.
fn pipeline(text: String) -> Result<Option<usize>, String> {
    let c = driver::compile(SourceFile::new("fuzz.stl", text));
    for d in c.diagnostics.iter() {
        check_diagnostic(d, &c.file).map_err(|e| format!("{e}\n  in {:?}", c.file.text))?;
    }
    let Some(sys) = &c.system else {
        if !c.diagnostics.has_errors() {
            return Err("no system, but no error either".into());
        }
        return Ok(None);
    };
    let (_, mut g) = match driver::geometry(sys, &RunOptions::default()) {
        Ok(x) => x,
        Err(d) => {
            check_diagnostic(&d, &c.file)?;
            return Ok(None);
        }
    };
    let stems = g.segments.len();
    driver::add_layout(sys, &mut g);
    let opts = RenderOptions {
        width: 64,
        height: 64,
        ..RenderOptions::default()
    };
    driver::render_bytes(sys, &g, Format::Svg, opts).map_err(|e| e.to_string())?;
    driver::render_bytes(sys, &g, Format::Png, opts).map_err(|e| e.to_string())?;
    // Translation to pfg and LinF: never a panic, and what is written
    // reads back without errors.
    for target in ["pfg", "linf"].map(|n| graftal::back::by_name(n).unwrap()) {
        let req = graftal::back::Request {
            target,
            lossy: true,
            steps: None,
        };
        let t = driver::translate(&c, sys, &req);
        for d in t.diagnostics.iter() {
            check_diagnostic(d, &c.file)?;
        }
        if let Some(text) = &t.text {
            let ext = target.extension();
            let back = driver::compile(SourceFile::new(format!("out.{ext}"), text.clone()));
            if back.diagnostics.has_errors() {
                return Err(format!(
                    "the {target:?} translation does not compile: {:?}\n{text}",
                    back.diagnostics
                ));
            }
        }
    }
    let bed = graftal::back::stl::write(sys).ok_or("no BED for an STL system")?;
    let back = driver::compile(SourceFile::new("bed.stl", bed.clone()));
    let Some(back_sys) = &back.system else {
        return Err(format!(
            "the BED does not compile: {:?}\n{bed}",
            back.diagnostics
        ));
    };
    let n = driver::geometry(back_sys, &RunOptions::default())
        .map_err(|d| format!("the BED does not draw: {d:?}"))?
        .1
        .segments
        .len();
    if n != stems {
        return Err(format!("the BED draws {n} stems, the file {stems}\n{bed}"));
    }
    Ok(Some(stems))
}

fn with_deadline(text: String) -> Result<Option<usize>, String> {
    let (tx, rx) = mpsc::channel();
    let shown = text.clone();
    std::thread::Builder::new()
        .stack_size(8 << 20)
        .spawn(move || {
            let r = std::panic::catch_unwind(|| pipeline(text));
            let _ = tx.send(r);
        })
        .map_err(|e| e.to_string())?;
    match rx.recv_timeout(TIME_LIMIT) {
        Ok(Ok(r)) => r,
        Ok(Err(_)) => Err(format!("panicked on {shown:?}")),
        Err(_) => Err(format!(
            "no result within {TIME_LIMIT:?} (a hang?) on {shown:?}"
        )),
    }
}

fn runner(cases: u32, seed: u8) -> TestRunner {
    let config = Config {
        cases,
        failure_persistence: None,
        max_shrink_iters: 256,
        ..Config::default()
    };
    TestRunner::new_with_rng(
        config,
        TestRng::from_seed(RngAlgorithm::ChaCha, &[seed; 32]),
    )
}

fn run_all(name: &str, cases: u32, seed: u8, strategy: impl Strategy<Value = String>) {
    let t = Instant::now();
    let compiled = std::cell::Cell::new(0usize);
    let total = std::cell::Cell::new(0usize);
    let result = runner(cases, seed).run(&strategy, |text| {
        total.set(total.get() + 1);
        match with_deadline(text) {
            Ok(Some(_)) => {
                compiled.set(compiled.get() + 1);
                Ok(())
            }
            Ok(None) => Ok(()),
            Err(e) => Err(TestCaseError::fail(e)),
        }
    });
    if let Err(e) = result {
        panic!("{name}: {e}");
    }
    eprintln!(
        "{name}: {} inputs, {} compiled and round-tripped, in {:?}",
        total.get(),
        compiled.get(),
        t.elapsed()
    );
}

/// STL-flavoured fragments for insertion.
fn fragment() -> impl Strategy<Value = String> {
    prop::sample::select(vec![
        "[",
        "]",
        "{",
        "}",
        ",",
        "~",
        "F",
        "R1",
        "R2",
        "R9",
        "+",
        "-",
        "L",
        "R",
        "\n",
        " ",
        "#",
        "=",
        "[I 3 ",
        "[I -1 ",
        "[I 99999 ",
        "SEED",
        "ENDSEED",
        "LAYOUT",
        "ENDLAYOUT",
        "GROWTH DFS",
        "LEVELS 0",
        "LEVELS 300",
        "LEVELS 40",
        "B = 0",
        "B = -1",
        "L = 0.001",
        "L = 1e9",
        "ANGLE 0",
        "ANGLE 180",
        "(clGreen)",
        "($00FF00FF)",
        "Polygon (0,0), (1,0)",
        "Ellipse (0,0), 0, 0",
        "R1{R1{R1{",
        "}}}",
        "R1 = R1",
        "R3 = [I 12 R1]",
        "\u{7}",
        "é",
        "$",
        "9999999999999999999999",
    ])
    .prop_map(str::to_string)
}

fn stl_entries() -> Vec<&'static str> {
    ENTRIES
        .iter()
        .filter(|e| e.name.starts_with("stl/"))
        .map(|e| e.text)
        .collect()
}

fn mutated() -> impl Strategy<Value = String> {
    let entries = stl_entries();
    let n = entries.len();
    (
        0..n,
        prop::collection::vec(
            (
                0usize..4,
                any::<prop::sample::Index>(),
                any::<prop::sample::Index>(),
                fragment(),
            ),
            1..5,
        ),
    )
        .prop_map(move |(i, edits)| {
            let mut t: Vec<char> = entries[i].chars().collect();
            for (kind, a, b, frag) in edits {
                let len = t.len();
                let (x, y) = (a.index(len + 1), b.index(len + 1));
                let (lo, hi) = (x.min(y), x.max(y).min(lo_max(x, len)));
                match kind {
                    0 => {
                        t.drain(lo..hi);
                    }
                    1 => {
                        let f: Vec<char> = frag.chars().collect();
                        t.splice(x..x, f);
                    }
                    2 => {
                        let piece: Vec<char> = t[lo..hi].to_vec();
                        t.splice(hi..hi, piece);
                    }
                    _ => t.truncate(x),
                }
            }
            t.into_iter().collect()
        })
}

fn lo_max(x: usize, len: usize) -> usize {
    (x + 40).min(len)
}

fn random_text() -> impl Strategy<Value = String> {
    prop::collection::vec(
        prop_oneof![
            8 => fragment(),
            1 => any::<char>().prop_map(|c| c.to_string()),
        ],
        0..40,
    )
    .prop_map(|v| v.concat())
}

fn structured() -> impl Strategy<Value = String> {
    let num = prop_oneof![
        6 => (0u32..200).prop_map(|n| n.to_string()),
        1 => Just("0".to_string()),
        1 => Just("-5".to_string()),
        1 => Just("1e".to_string()),
        1 => Just("123456789012345678901234567890".to_string()),
        1 => (0u32..1000).prop_map(|n| format!("{}.{}", n / 10, n % 10)),
    ];
    let body = prop::collection::vec(
        prop::sample::select(vec![
            "[F]",
            "[+F]",
            "[-F]",
            "[++F]",
            "F",
            "[FF]",
            "[F[+F]]",
            "R1",
            "[I 2 F[+F]]",
            "L",
            "R",
        ]),
        1..5,
    )
    .prop_map(|v| v.concat());
    let rules = prop::collection::vec(body, 1..4).prop_map(|bodies| {
        bodies
            .iter()
            .enumerate()
            .map(|(i, b)| {
                format!(
                    "R{} = {}\n",
                    i + 1,
                    b.replace("R1", if i == 0 { "F" } else { "R1" })
                )
            })
            .collect::<String>()
    });
    let entry = prop::sample::select(vec![
        "",
        "~",
        "R1",
        "R2",
        "R1{}",
        "R2{~}",
        "R1{R1, ~, R2}",
        "R3{,}",
    ]);
    let seed = prop::collection::vec(
        prop_oneof![
            3 => Just("F ".to_string()),
            2 => (0usize..3).prop_map(|i| format!("R{} ", i + 1)),
            2 => (0usize..3, prop::collection::vec(entry, 0..4)).prop_map(|(i, es)| format!("R{}{{{}}} ", i + 1, es.join(", "))),
        ],
        1..4,
    )
    .prop_map(|v| v.concat());
    let shape =
        (num.clone(), num.clone(), num.clone(), 0usize..5).prop_map(|(a, b, c, k)| match k {
            0 => format!("(clGreen) Ellipse (-{a}, 0), {b}, {c}\n"),
            1 => format!("(clOlive) Rectangle (-{a}, 0), {b}, {c}\n"),
            2 => format!("($00C0FFC0) RoundRect (-{a}, 0), {b}, {c}, {a}\n"),
            3 => format!("(clAqua) Polygon (-{a}, 0), ({b}, 0), (0, {c})\n"),
            _ => String::new(),
        });
    let layout = prop::option::of(prop::collection::vec(shape, 1..3)).prop_map(|o| match o {
        Some(v) => format!("LAYOUT\n{}ENDLAYOUT\n", v.concat()),
        None => String::new(),
    });
    (num.clone(), num.clone(), num.clone(), num, prop::bool::ANY, (0u32..40), rules, seed, layout).prop_map(
        |(angle, b, l, dec, dfs, levels, rules, seed, layout)| {
            format!(
                "ANGLE {angle}\nB = {b} ({dec})\nL = {l} (1)\nGROWTH {}\nLEVELS {levels}\n{rules}SEED\n{seed}\nENDSEED\n{layout}",
                if dfs { "DFS" } else { "BFS" }
            )
        },
    )
}

#[test]
fn stl_stdlib_files_pass_and_round_trip() {
    for e in ENTRIES.iter().filter(|e| e.name.starts_with("stl/")) {
        let r = with_deadline(e.text.to_string());
        assert!(matches!(r, Ok(Some(n)) if n > 0), "std:{}: {r:?}", e.name);
    }
}

#[test]
fn mutated_stl_files_never_panic_or_hang() {
    run_all("stl-mutated", 300, 11, mutated());
}

#[test]
fn random_stl_strings_never_panic_or_hang() {
    run_all("stl-random", 300, 12, random_text());
}

#[test]
fn structured_random_stl_files_never_panic_or_hang() {
    run_all("stl-structured", 300, 13, structured());
}

#[test]
fn hand_written_edge_cases() {
    let deep = format!("SEED\n{}F{}\nENDSEED\n", "[".repeat(3000), "]".repeat(3000));
    let braces = format!("R1 = [F][+F]\nSEED\n{}\nENDSEED\n", "R1{".repeat(3000));
    let big_count = "R1 = [F][+F][-F]\nR2 = [I 4000000000 R1]\nSEED\nR2\nENDSEED\n".to_string();
    let one_f = "R2 = [I 4000000000 F+]\nSEED\nR2\nENDSEED\n".to_string();
    let doubling = (1..40)
        .map(|i| format!("R{} = R{}R{}\n", i + 1, i, i))
        .collect::<String>();
    let doubling = format!("R1 = [F]\n{doubling}SEED\nR40\nENDSEED\n");
    let no_clearance = "B = 0\nL = 10\nLEVELS 256\nR1 = [-F][+F]\nSEED\nF R1\nENDSEED\nLAYOUT\n(clGreen) Ellipse (-1500, 0), 3000, 3000\nENDLAYOUT\n".to_string();
    for text in [
        deep,
        braces,
        big_count,
        one_f,
        doubling,
        no_clearance,
        String::new(),
        "SEED".into(),
        "LAYOUT".into(),
    ] {
        let t = Instant::now();
        let r = with_deadline(text.clone());
        assert!(r.is_ok(), "{r:?}");
        eprintln!(
            "{:?}…: {r:?} in {:?}",
            &text[..text.len().min(30)],
            t.elapsed()
        );
    }
}
