//! What the command-line tests share: running `graftal` in-process and a
//! temporary directory per test binary.

use graftal::cli::{run, Io};

/// What one run printed, and its exit status.
pub struct Out {
    pub status: i32,
    pub stdout: String,
    pub stderr: String,
}

/// Runs `graftal ARGS…` through `cli::run`, as a pipe (no terminal).
pub fn graftal(args: &[&str]) -> Out {
    let mut stdout = Vec::new();
    let mut stderr = Vec::new();
    let mut io = Io {
        stdout: &mut stdout,
        stderr: &mut stderr,
        terminal: false,
    };
    let mut argv = vec!["graftal"];
    argv.extend_from_slice(args);
    let status = run(argv, &mut io);
    Out {
        status,
        stdout: String::from_utf8(stdout).unwrap(),
        stderr: String::from_utf8(stderr).unwrap(),
    }
}

/// A path named `name` in this test binary's temporary directory.
pub fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "graftal-{}-{}",
        env!("CARGO_CRATE_NAME"),
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}
