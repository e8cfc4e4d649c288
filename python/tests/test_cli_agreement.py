"""The module says what the command line says: the same word, figures,
picture bytes, translations and diagnostics, for files of every notation
(and files with errors), each compared with `graftal` run on the same file."""

import graftal
import pytest

from conftest import records

# A file of each notation graftal reads, with errors or without.
FILES = [
    "examples/koch-island.l",  # pfg
    "std:hogeweg-hesper-a",  # pfg, branching
    "examples/koch-island.linf",  # LinF
    "std:linf/fig07-plant-3d",  # LinF, 3D
    "examples/koch-island.stl",  # STL
    "std:stl/fig04-plant",  # STL, with a layout
    "examples/koch-island.gft",  # gft
    "std:gft/stochastic-tree",  # gft, stochastic
    "examples/fractint.l:Dragon",  # a Fractint library's entry
    "examples/fractint.l",  # a Fractint library, no entry chosen
    "examples/fractint.ifs:fern",  # a Fractint IFS: an instancing graph
    "examples/fractint.ifs:3dfern",  # a 3D one, ray traced
    "examples/cpfg-leaf/leaf.l",  # cpfg, with its side files
    "std:smith/table1",  # Smith's 2L-systems
    "tests/diagnostics/bad-probability.l",  # errors
    "tests/diagnostics/bracket-in-predecessor.l",  # errors
]

# Files that draw, and the formats compared byte for byte.
DRAWN = [f for f in FILES if not f.startswith("tests/") and f != "examples/fractint.l"]

FIELDS = ("code", "severity", "message", "file", "line", "column", "start", "end", "help", "notes")


def fields(d):
    """A diagnostic as the command line's JSON record says it."""
    start, end = d.span or (None, None)
    return {
        "code": d.code,
        "severity": d.severity,
        "message": d.message,
        "file": d.file,
        "line": d.line,
        "column": d.column,
        "start": start,
        "end": end,
        "help": d.help,
        "notes": d.notes,
    }


def said(stderr):
    """The diagnostics the command line printed, as `fields` gives them."""
    return [{k: r[k] for k in FIELDS} for r in records(stderr, "diagnostic")]


def listed(diagnostics):
    return [fields(d) for d in diagnostics]


def raised(call):
    """The diagnostics of the GraftalError `call` raises."""
    with pytest.raises(graftal.GraftalError) as e:
        call()
    return listed(e.value.diagnostics)


def loaded_warnings(m):
    """What the command line prints when it reads the file, before anything
    else: the file's own diagnostics (warnings, for a file that compiles)."""
    return listed(m.diagnostics) if m.ok else []


@pytest.mark.parametrize("spec", FILES)
def test_check_says_what_graftal_check_says(cli, spec):
    status, _, err = cli("check", spec, "--format", "json")
    found = graftal.load(spec).check()
    assert listed(found) == said(err)
    assert (status == 1) == found.has_errors


@pytest.mark.parametrize("spec,steps", [(f, None) for f in FILES] + [("examples/koch-island.l", 40)])
def test_derive_gives_the_word_graftal_derive_prints(cli, spec, steps):
    more = ["-n", str(steps)] if steps is not None else []
    status, out, err = cli("derive", spec, "--format", "json", *more)
    m = graftal.load(spec)
    if status == 0:
        assert (m.derive(steps=steps) + "\n").encode() == out
        assert loaded_warnings(m) == said(err)
    else:
        assert out == b""
        assert loaded_warnings(m) + raised(lambda: m.derive(steps=steps)) == said(err)


def test_a_streamed_word_is_the_word(cli):
    m = graftal.load("examples/koch-island.l")
    chunks = list(m.derive(steps=6, stream=True))
    assert len(chunks) > 1
    _, out, _ = cli("derive", "examples/koch-island.l", "-n", "6")
    assert ("".join(chunks) + "\n").encode() == out
    too_long = graftal.load("examples/koch-island.l").derive(steps=40, stream=True)
    with pytest.raises(graftal.GraftalError) as e:
        list(too_long)
    assert [d.code for d in e.value.diagnostics] == ["E0301"]


@pytest.mark.parametrize("spec", FILES)
def test_stats_are_graftal_stats(cli, spec):
    status, out, err = cli("stats", spec, "--format", "json")
    m = graftal.load(spec)
    if status != 0:
        assert loaded_warnings(m) + raised(m.stats) == said(err)
        return
    (expected,) = records(out.decode(), "stats")
    figures = m.stats()
    assert loaded_warnings(m) + listed(figures.pop("warnings")) == said(err)
    for kept in (expected, figures):
        kept.pop("type", None)
        assert set(kept.pop("time")) == {"parse", "derive", "interpret"}
    assert figures == expected


@pytest.mark.parametrize("spec", DRAWN)
@pytest.mark.parametrize("fmt", ["png", "svg"])
def test_render_gives_the_bytes_graftal_render_writes(cli, tmp_path, spec, fmt):
    out = tmp_path / f"picture.{fmt}"
    status, _, err = cli("render", spec, "-o", str(out), "--size", "160x120", "--format", "json")
    assert status == 0, err
    m = graftal.load(spec)
    p = m.picture(fmt, size=(160, 120))
    assert p.data == out.read_bytes()
    assert m.render(fmt, size="160x120") == p.data
    assert loaded_warnings(m) + listed(p.warnings) == said(err)


@pytest.mark.parametrize(
    "spec,fmt,options,flags",
    [
        ("std:linf/fig07-plant-3d", "obj", {}, []),
        ("std:linf/fig07-plant-3d", "glb", {}, []),
        ("examples/cpfg-leaf/leaf.l", "ply", {}, []),
        ("std:hogeweg-hesper-a", "png", {"view": (30, 20), "seed": 3, "steps": 3}, ["--view", "30,20", "--seed", "3", "-n", "3"]),
        ("std:linf/fig07-plant-3d", "png", {"raytrace": True, "samples": 1}, ["--raytrace", "--samples", "1"]),
        ("std:hogeweg-hesper-a", "svg", {"background": "#ffeedd", "palette": "depth", "margin": "10%", "rotate": 15, "stroke_width": 2}, ["--background", "#ffeedd", "--palette", "depth", "--margin", "10%", "--rotate", "15", "--stroke-width", "2"]),
        ("examples/koch-island.l", "gif", {"steps": 3, "fps": 5}, ["--animate", "-n", "3", "--fps", "5"]),
        ("examples/koch-island.l", "apng", {"steps": 3}, ["--animate", "-n", "3"]),
    ],
)
def test_meshes_animations_and_options_are_graftal_render_s(cli, tmp_path, spec, fmt, options, flags):
    ext = "png" if fmt == "apng" else fmt
    out = tmp_path / f"picture.{ext}"
    status, _, err = cli("render", spec, "-o", str(out), "--size", "128x128", *flags)
    assert status == 0, err
    m = graftal.load(spec)
    p = m.picture(fmt, size=128, material_library="picture.mtl", **options)
    assert p.data == out.read_bytes()
    for name, data in p.side_files.items():
        assert (tmp_path / name).read_bytes() == data
    assert set(p.side_files) == ({"picture.mtl"} if fmt == "obj" else set())
    if fmt in ("gif", "apng"):
        assert m.animate(fmt, size=128, **options).data == p.data
        p.save(str(tmp_path / "again.gif"))
        assert (tmp_path / "again.gif").read_bytes() == p.data


@pytest.mark.parametrize("spec", FILES)
@pytest.mark.parametrize("to", graftal.targets())
def test_translate_gives_graftal_translate_s_text_and_diagnostics(cli, spec, to):
    status, out, err = cli("translate", spec, "--to", to, "--format", "json")
    m = graftal.load(spec)
    if status != 0:
        assert loaded_warnings(m) + raised(lambda: m.translate(to)) == said(err)
        return
    (expected,) = records(out.decode(), "translation")
    text, found = m.translate(to)
    assert text == expected["text"]
    assert loaded_warnings(m) + listed(found) == said(err)


def test_lossy_translation_is_graftal_translate_lossy(cli):
    spec = "std:linf/fig07-plant-3d"
    assert cli("translate", spec, "--to", "pfg")[0] == 1
    status, out, err = cli("translate", spec, "--to", "pfg", "--lossy", "--format", "json")
    assert status == 0, err
    (expected,) = records(out.decode(), "translation")
    m = graftal.load(spec)
    text, found = m.translate("pfg", lossy=True)
    assert text == expected["text"]
    assert found and loaded_warnings(m) + listed(found) == said(err)


@pytest.mark.parametrize("code", ["E0004", "W0001", "E0301", "E0305"])
def test_explain_is_graftal_explain(cli, code):
    status, out, _ = cli("explain", code)
    assert status == 0
    assert (graftal.explain(code) + "\n").encode() == out


def test_broken_files_of_every_notation_are_checked_as_graftal_check_does(cli, tmp_path):
    broken = {
        "pfg": ("plant.l", "axiom: F\nF --> F[+F\n"),
        "linf": ("plant.linf", "axiom: F\nF -> F[+F\n"),
        "stl": ("plant.stl", "axiom: F\nF -> F[+F\n"),
        "gft": ("plant.gft", "axiom: F\nF -> F[+F\n"),
        "cpfg": ("plant.l", "Lsystem: 1\nderivation length: 2\nAxiom: F(1\nendlsystem\n"),
        "smith": ("plant.smith", "F => F[+F\n"),
        "fractint": ("plant.l", "Plant {\n Axiom F\n F=F[+F\n"),
        "ifs": ("plant.ifs", "fern {\n 0 0 0 .16 0 0\n}\n"),
    }
    assert set(broken) == set(graftal.notations())
    for notation, (name, text) in broken.items():
        path = tmp_path / notation / name
        path.parent.mkdir()
        path.write_text(text)
        status, _, err = cli("check", str(path), "--notation", notation, "--format", "json")
        found = graftal.load(str(path), notation=notation).check()
        assert listed(found) == said(err), notation
        parsed = graftal.parse(text, notation, name=str(path)).check()
        assert listed(parsed) == said(err), notation
        assert status == 1 and found.has_errors, notation
