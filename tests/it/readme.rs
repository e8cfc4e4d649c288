//! Every command block of the README runs as written, from a clone.
//!
//! A block fenced as ```sh is a list of commands a reader will paste. Each
//! `graftal …` command (and `cargo run --release -- …`, which is the same
//! program) runs here through `sh -c` with the binary under test first on the
//! `PATH`, in a scratch folder, with the repository's `examples/` and `tests/`
//! reachable under the same relative names. A command exits 0 unless its
//! comment says `exit N`, and every file it names with `-o` is written and not
//! empty. Other `cargo` commands (`cargo test`, `cargo bench`) are not run
//! here: they are what runs this test. Synopses with placeholders are fenced
//! as ```text and are not commands.

use std::path::{Path, PathBuf};
use std::process::Command;

const README: &str = include_str!("../../README.md");

/// One command of a block: its text (continuation lines joined) and the line
/// of the README it starts on.
struct BlockCommand {
    line: usize,
    text: String,
}

/// The commands of every ```sh block, in order.
fn sh_commands(readme: &str) -> Vec<BlockCommand> {
    let mut commands = Vec::new();
    let mut in_sh = false;
    let mut pending: Option<BlockCommand> = None;
    for (index, line) in readme.lines().enumerate() {
        let trimmed = line.trim();
        if trimmed.starts_with("```") {
            in_sh = !in_sh && trimmed == "```sh";
            continue;
        }
        if !in_sh || trimmed.is_empty() {
            continue;
        }
        let mut command = pending.take().unwrap_or(BlockCommand {
            line: index + 1,
            text: String::new(),
        });
        match trimmed.strip_suffix('\\') {
            Some(head) => {
                command.text.push_str(head);
                command.text.push(' ');
                pending = Some(command);
            }
            None => {
                command.text.push_str(trimmed);
                commands.push(command);
            }
        }
    }
    commands
}

/// The command without its trailing `# comment`, and the comment.
fn split_comment(text: &str) -> (&str, &str) {
    match text.find(" #") {
        Some(at) => (text[..at].trim(), text[at + 2..].trim()),
        None => (text.trim(), ""),
    }
}

/// The exit status the comment promises (`# exit 1: …`), 0 otherwise.
fn expected_status(comment: &str) -> i32 {
    comment
        .strip_prefix("exit ")
        .and_then(|rest| rest.split(|c: char| !c.is_ascii_digit()).next())
        .and_then(|digits| digits.parse().ok())
        .unwrap_or(0)
}

/// The program a command runs, after any `NAME=value` assignments.
fn program(command: &str) -> &str {
    command
        .split_whitespace()
        .find(|word| !word.contains('='))
        .unwrap_or("")
}

/// The files a command writes with `-o FILE` (standard output `-` aside).
fn outputs(command: &str) -> Vec<String> {
    let words: Vec<&str> = command.split_whitespace().collect();
    words
        .windows(2)
        .filter(|pair| pair[0] == "-o" && pair[1] != "-")
        .map(|pair| pair[1].to_string())
        .collect()
}

fn scratch_dir() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("graftal-readme-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

/// Runs one command the way a reader at the root of a clone would.
fn run(command: &str, repo: &Path, scratch: &Path) -> std::process::Output {
    let binary = PathBuf::from(env!("CARGO_BIN_EXE_graftal"));
    let path = format!(
        "{}:{}",
        binary.parent().expect("binary folder").display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let as_written = command.replace("cargo run --release --", "graftal");
    let rooted = as_written
        .replace(" examples/", &format!(" {}/examples/", repo.display()))
        .replace(" tests/", &format!(" {}/tests/", repo.display()));
    Command::new("sh")
        .arg("-c")
        .arg(&rooted)
        .current_dir(scratch)
        .env("PATH", path)
        .env("NO_COLOR", "1")
        .output()
        .expect("sh runs")
}

#[test]
fn every_command_block_of_the_readme_runs_as_written() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scratch = scratch_dir();
    let mut ran = 0;
    let mut failures = Vec::new();
    for block_command in sh_commands(README) {
        let (command, comment) = split_comment(&block_command.text);
        let is_graftal =
            program(command) == "graftal" || command.starts_with("cargo run --release -- ");
        if !is_graftal {
            assert_eq!(
                program(command),
                "cargo",
                "README line {}: `{command}` is neither graftal nor cargo",
                block_command.line
            );
            continue;
        }
        ran += 1;
        let output = run(command, repo, &scratch);
        let status = output.status.code().unwrap_or(-1);
        let expected = expected_status(comment);
        if status != expected {
            failures.push(format!(
                "README line {}: `{command}` exited {status}, expected {expected}\n{}",
                block_command.line,
                String::from_utf8_lossy(&output.stderr)
            ));
        }
        for file in outputs(command) {
            let written = std::fs::metadata(scratch.join(&file)).map_or(0, |m| m.len());
            if written == 0 {
                failures.push(format!(
                    "README line {}: `{command}` did not write `{file}`",
                    block_command.line
                ));
            }
        }
    }
    let _ = std::fs::remove_dir_all(&scratch);
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    assert!(
        ran >= 10,
        "only {ran} README commands found: is the parser right?"
    );
}

#[test]
fn blocks_split_into_commands_with_continuations_and_exit_comments() {
    let text = "intro\n```sh\ngraftal a # exit 1: why\nA=1 \\\n  cargo test x\n```\n```text\ngraftal FILE\n```\n";
    let commands = sh_commands(text);
    let texts: Vec<&str> = commands.iter().map(|c| c.text.as_str()).collect();
    assert_eq!(texts, ["graftal a # exit 1: why", "A=1  cargo test x"]);
    assert_eq!(commands[1].line, 4);
    let (command, comment) = split_comment(texts[0]);
    assert_eq!((command, expected_status(comment)), ("graftal a", 1));
    assert_eq!(program(texts[1]), "cargo");
    assert_eq!(outputs("graftal render x -o a.png -o -"), ["a.png"]);
}
