"""The notebook, executed headless: each model shows its picture inline (an
SVG, a PNG), a file with errors its diagnostics as HTML, an animation a
GIF."""

import base64
import json
import pathlib
import sys

import nbformat
from nbclient import NotebookClient

NOTEBOOK = pathlib.Path(__file__).with_name("notebook.ipynb")


def outputs_of(cell):
    """The data of each output of a code cell, by media type."""
    shown = {}
    for out in cell.get("outputs", []):
        assert out["output_type"] != "error", out
        for kind, data in out.get("data", {}).items():
            shown[kind] = data
        if out["output_type"] == "stream":
            shown.setdefault("stream", "")
            shown["stream"] += out["text"]
    return shown


def this_interpreter_as_a_kernel(folder, monkeypatch):
    """A kernel spec that runs this Python (whose graftal is under test),
    whatever kernels the machine has; its name."""
    spec = folder / "kernels" / "graftal-tests"
    spec.mkdir(parents=True)
    argv = [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"]
    kernel = {"argv": argv, "display_name": "graftal tests", "language": "python"}
    (spec / "kernel.json").write_text(json.dumps(kernel))
    monkeypatch.setenv("JUPYTER_PATH", str(folder))
    return "graftal-tests"


def test_the_notebook_shows_pictures_diagnostics_and_an_animation_inline(tmp_path, monkeypatch):
    nb = nbformat.read(NOTEBOOK, as_version=4)
    kernel = this_interpreter_as_a_kernel(tmp_path, monkeypatch)
    NotebookClient(nb, timeout=120, kernel_name=kernel).execute()
    code = [outputs_of(c) for c in nb.cells if c.cell_type == "code"]
    plant, check, island, broken, animation, word, translated, geometry = code
    assert plant["image/svg+xml"].lstrip().startswith("<svg")
    assert "image/png" not in plant
    assert "text/html" not in check  # no diagnostics: nothing to show
    assert base64.b64decode(island["image/png"]).startswith(b"\x89PNG")
    assert "image/svg+xml" not in island
    assert "E0005" in broken["text/html"] and "<span style=" in broken["text/html"]
    assert "image/svg+xml" not in broken
    assert base64.b64decode(animation["image/gif"]).startswith(b"GIF89a")
    assert word["stream"].startswith("475 F+F-F-FF+F+F-F")
    assert "axiom" in translated["stream"]
    assert geometry["text/plain"].startswith("(")
