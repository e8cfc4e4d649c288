//! The cpfg readers over the whole vlab corpus (shared/corpus/cpfg: 95
//! objects): every L-system file preprocesses, every view, function and
//! surface file reads, with pinned values from real files.

use graftal::cpfg::preprocess::preprocess;
use std::fs;
use std::path::{Path, PathBuf};

fn corpus() -> PathBuf {
    PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../shared/corpus/cpfg"
    ))
}

/// Every file of the corpus with extension `ext`, sorted.
fn files(ext: &str) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for dir in fs::read_dir(corpus()).expect("shared/corpus/cpfg beside the repository") {
        let dir = dir.unwrap().path();
        if !dir.is_dir() {
            continue;
        }
        for f in fs::read_dir(&dir).unwrap() {
            let f = f.unwrap().path();
            if f.extension().is_some_and(|e| e == ext) {
                out.push(f);
            }
        }
    }
    out.sort();
    out
}

fn read(p: &Path) -> String {
    String::from_utf8_lossy(&fs::read(p).unwrap()).into_owned()
}

fn preprocess_file(path: &Path) -> graftal::cpfg::preprocess::Preprocessed {
    let dir = path.parent().unwrap().to_path_buf();
    preprocess(&read(path), &mut |name| {
        fs::read(dir.join(name))
            .ok()
            .map(|b| String::from_utf8_lossy(&b).into_owned())
    })
}

#[test]
fn every_l_file_preprocesses_without_errors() {
    let ls = files("l");
    assert_eq!(ls.len(), 98);
    let mut with_define = 0;
    for l in &ls {
        let src = read(l);
        let p = preprocess_file(l);
        let errors: Vec<_> = p.diagnostics.iter().filter(|d| d.is_error()).collect();
        assert!(errors.is_empty(), "{}: {errors:#?}", l.display());
        assert!(!p.text.contains("#define"), "{}", l.display());
        assert!(!p.text.contains("/*"), "{}", l.display());
        // Lines are kept (Sedge's main file includes others, which add lines).
        if !src.contains("#include") {
            assert_eq!(
                p.text.matches('\n').count(),
                src.matches('\n').count(),
                "{}",
                l.display()
            );
        }
        // The map stays inside the source.
        for start in (0..p.text.len()).step_by(97) {
            let r = p.map.to_source(start..(start + 5).min(p.text.len()));
            assert!(r.start <= r.end && r.end <= src.len());
        }
        if src.contains("#define") {
            with_define += 1;
        }
    }
    assert!(with_define >= 82, "{with_define}");
}

#[test]
fn only_the_fern_leaves_warn() {
    // The two fern-leaf objects end define lines with `\\`.
    let mut warned = Vec::new();
    for l in files("l") {
        let p = preprocess_file(&l);
        if !p.diagnostics.is_empty() {
            let codes: Vec<_> = p.diagnostics.iter().map(|d| d.code.0).collect();
            assert!(
                codes.iter().all(|c| *c == "W0802"),
                "{}: {codes:?}",
                l.display()
            );
            warned.push(
                l.parent()
                    .unwrap()
                    .file_name()
                    .unwrap()
                    .to_string_lossy()
                    .into_owned(),
            );
        }
    }
    assert_eq!(
        warned,
        ["03-inverse-modeling-02-fern-leaf", "15-VlabTools-FernLeaf"]
    );
}

#[test]
fn pinned_expansions() {
    let c = corpus();
    // A continuation-line, function-like macro with macro arguments.
    let p = preprocess_file(&c.join("03-inverse-modeling-02-fern-leaf/plant.l"));
    let src = read(&c.join("03-inverse-modeling-02-fern-leaf/plant.l"));
    assert!(
        p.text
            .contains("dx = (INT_LENGTH_SCALE * func(INT_LENGTH,x_rel) * L0^INT_LENGTH_GAMMA)")
            || p.text.contains("dx = (")
    );
    let line = p.text.lines().find(|l| l.contains("new_x = x+dx")).unwrap();
    assert!(!line.contains("int_length"), "{line}");
    assert!(!line.contains('\\'), "{line}");
    // The expansion maps back to the call `int_length(x_rel)`.
    let at = p.text.find(line).unwrap() + line.find("func(").unwrap();
    let back = p.map.to_source(at..at + 4);
    assert_eq!(&src[back], "int_length(x_rel)");

    // An `#if` branch: clover keeps the LEAVES==1 productions.
    let p = preprocess_file(&c.join("07-Open-13-clover/plant.l"));
    assert!(p.text.contains("L(la,age,rn) : ((rn)-floor(rn)) > 0.03"));
    assert!(!p.text.contains("@c(2.0*sqrt(la/3.14))"));

    // Two trees: nested #if with `==` and `>` on macros.
    let p = preprocess_file(&c.join("07-Open-12-two-trees/tree.l"));
    assert!(!p.text.contains("#if") && !p.text.contains("#else") && !p.text.contains("#endif"));

    // Sedge includes three files; their L-systems follow the main one.
    let p = preprocess_file(&c.join("11-CPFG-Sedge/sedge.l"));
    assert!(p.text.contains("?(2,1.25)spikef$"));
    let systems = p.text.to_lowercase().matches("lsystem:").count();
    assert_eq!(systems, 4);
}
