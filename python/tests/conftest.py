"""What the tests share: the command line built from the same checkout (the
binary GRAFTAL_BIN names, else `cargo build --release` at the repository's
root), and a way to run it."""

import json
import os
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def _built_cli():
    subprocess.run(
        ["cargo", "build", "--release", "--bin", "graftal", "--quiet"],
        cwd=REPO,
        check=True,
    )
    meta = subprocess.run(
        ["cargo", "metadata", "--format-version", "1", "--no-deps"],
        cwd=REPO,
        check=True,
        capture_output=True,
        text=True,
    )
    target = pathlib.Path(json.loads(meta.stdout)["target_directory"])
    return target / "release" / "graftal"


@pytest.fixture(scope="session")
def cli():
    """Runs the command line with these arguments from the repository's root:
    its exit status, stdout (bytes) and stderr (text)."""
    named = os.environ.get("GRAFTAL_BIN")
    binary = pathlib.Path(named).resolve() if named else _built_cli()
    assert binary.is_file(), f"no graftal binary at {binary}"

    def run(*args):
        done = subprocess.run(
            [str(binary), *args],
            cwd=REPO,
            capture_output=True,
            env={**os.environ, "NO_COLOR": "1"},
        )
        return done.returncode, done.stdout, done.stderr.decode()

    return run


@pytest.fixture(autouse=True)
def at_the_root(monkeypatch):
    """Paths are the repository's, as the command line is run from there."""
    monkeypatch.chdir(REPO)


def records(text, kind):
    """The JSON records of one type in `--format json` output."""
    lines = (json.loads(line) for line in text.splitlines() if line.strip())
    return [r for r in lines if r.get("type") == kind]
