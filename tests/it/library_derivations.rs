//! The 34 derivations of tests/corpus/goldens/goldens.json, transcribed from
//! four independent L-system libraries, each written as a pfg file and
//! derived by graftal: the strings must match character for character.

use graftal::driver::{compile, derive, RunOptions};
use graftal::source::SourceFile;
use serde_json::Value;

fn corpus() -> Vec<Value> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/corpus/goldens/goldens.json"
    );
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    serde_json::from_str::<Value>(&text)
        .expect("valid JSON")
        .as_array()
        .expect("a list of cases")
        .clone()
}

/// `left<pred>right` -> `left < pred > right` (pfg).
fn production(key: &str, succ: &str) -> String {
    let (left, rest) = match key.split_once('<') {
        Some((l, r)) => (Some(l), r),
        None => (None, key),
    };
    let (pred, right) = match rest.split_once('>') {
        Some((p, r)) => (p, Some(r)),
        None => (rest, None),
    };
    let mut s = String::new();
    if let Some(l) = left {
        s += &format!("{l} < ");
    }
    s += pred;
    if let Some(r) = right {
        s += &format!(" > {r}");
    }
    let succ = if succ.is_empty() { "*" } else { succ };
    s + &format!(" --> {succ}\n")
}

fn pfg_file(case: &Value) -> String {
    let mut src = format!("axiom: {}\n", case["axiom"].as_str().unwrap());
    src += &format!("ignore: {}\n", case["ignore"].as_str().unwrap_or("+-"));
    if let Some(rules) = case["rules_ordered"].as_array() {
        for r in rules {
            src += &production(r[0].as_str().unwrap(), r[1].as_str().unwrap());
        }
    } else {
        for (k, v) in case["rules"].as_object().unwrap() {
            src += &production(k, v.as_str().unwrap());
        }
    }
    src
}

#[test]
fn all_34_goldens_derive_exactly() {
    let cases = corpus();
    assert_eq!(cases.len(), 34);
    let mut failures = Vec::new();
    for case in &cases {
        let name = case["name"].as_str().unwrap();
        let src = pfg_file(case);
        let c = compile(SourceFile::new(format!("{name}.l"), src.clone()));
        let sys = c
            .system
            .unwrap_or_else(|| panic!("{name}: {:#?}\n{src}", c.diagnostics));
        let n = case["n"].as_u64().unwrap();
        let opts = RunOptions {
            steps: Some(n),
            ..RunOptions::default()
        };
        let got = derive(&sys, &opts).unwrap().display(&sys.symbols);
        let want = case["expected"].as_str().unwrap();
        if got != want {
            failures.push(format!("{name}:\n  got  {got}\n  want {want}\n{src}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_rules_are_transcribed_as_pfg() {
    assert_eq!(production("A<B>C", "Z"), "A < B > C --> Z\n");
    assert_eq!(production("B-<F", "Z"), "B- < F --> Z\n");
    assert_eq!(production("S>GM", "Z"), "S > GM --> Z\n");
    assert_eq!(production("F", ""), "F --> *\n");
}
