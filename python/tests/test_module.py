"""The module's own face: errors raised as GraftalError with their
diagnostics (never a crash), options checked, geometry as NumPy arrays,
diagnostics and pictures shown in a notebook, the GIL released while the
library works."""

import base64
import html
import re
import threading
import time

import graftal
import numpy as np
import pytest

from conftest import REPO


def test_a_file_that_cannot_be_read_raises_without_diagnostics():
    with pytest.raises(graftal.GraftalError) as e:
        graftal.load("no/such/file.l")
    assert "cannot read `no/such/file.l`" in str(e.value)
    assert list(e.value.diagnostics) == []
    with pytest.raises(graftal.GraftalError, match="koch-island"):
        graftal.load("std:koch-islnd")


def test_a_file_with_errors_is_a_model_whose_every_call_raises_its_diagnostics():
    m = graftal.parse("axiom: F\nF -> F+F\n", "pfg")
    assert not m.ok
    codes = [d.code for d in m.diagnostics]
    assert "E0005" in codes
    calls = [
        m.derive,
        m.stats,
        m.render,
        m.geometry,
        lambda: m.translate("gft"),
        lambda: m.derive(stream=True),
        m.animate,
    ]
    for call in calls:
        with pytest.raises(graftal.GraftalError) as e:
            call()
        assert [d.code for d in e.value.diagnostics] == codes
        assert str(e.value) == str(m.diagnostics).rstrip()


def test_a_diagnostic_has_its_place_help_and_fix():
    text = "axiom: F\nF -> F+F\n"
    m = graftal.parse(text, "pfg")
    (d,) = [d for d in m.check() if d.code == "E0005"]
    assert (d.severity, d.line, d.column, d.file) == ("error", 2, 3, "<text>.l")
    start, end = d.span
    assert text.encode()[start:end] == b"->"
    assert d.help and "-->" in d.help
    assert isinstance(d.notes, list)
    ((fstart, fend, replacement),) = d.fixes
    fixed = text.encode()[:fstart] + replacement.encode() + text.encode()[fend:]
    assert graftal.parse(fixed.decode(), "pfg").ok
    assert "E0005" in repr(d) and str(d).startswith("[E0005] Error")


def test_diagnostics_show_as_html_with_the_command_line_s_text_and_colours():
    found = graftal.parse("axiom: F\nF -> F+F\n<&>\n", "pfg").diagnostics
    shown = found._repr_html_()
    assert shown.startswith("<pre") and '<span style="color:#cd0000">' in shown
    # Without its tags, the HTML is the command line's text, character for
    # character.
    assert html.unescape(re.sub(r"<[^>]+>", "", shown)) == str(found)
    assert found[0]._repr_html_().count("[" + found[0].code + "]") == 1
    assert graftal.load("std:koch-island").diagnostics._repr_html_() is None


def test_options_are_checked_as_the_command_line_checks_its_flags():
    m = graftal.load("std:koch-island")
    for bad in [dict(size=0), dict(size=10**6), dict(size="12by12"), dict(samples=3),
                dict(fps=0), dict(palette="sepia"), dict(background="nocolour"),
                dict(view=(float("nan"), 0)), dict(detail="most")]:
        with pytest.raises(ValueError):
            m.render("png", **bad)
    with pytest.raises(TypeError, match="the options are"):
        m.render("png", colour="red")
    with pytest.raises(ValueError, match="png, svg"):
        m.render("bmp")
    with pytest.raises(ValueError, match="graftal reads"):
        graftal.parse("F", "lsys")
    with pytest.raises(ValueError, match="graftal writes"):
        m.translate("cpfg")
    with pytest.raises(graftal.GraftalError, match="no diagnostic code"):
        graftal.explain("E9999")
    # None is an option not given.
    assert m.render("svg", size=None, view=None) == m.render("svg")


def test_limits_raise_the_library_s_diagnostics():
    m = graftal.load("std:koch-island")
    with pytest.raises(graftal.GraftalError) as e:
        m.derive(steps=40)
    assert [d.code for d in e.value.diagnostics] == ["E0301"]
    with pytest.raises(graftal.GraftalError):
        m.derive(steps=5, max_symbols=100)


NASTY = [
    "[" * 100_000,
    "(" * 50_000 + "F",
    "axiom: " + "[" * 20_000 + "F" + "]" * 20_000 + "\nF --> FF\n",
    "\x00\x01\x02" * 1000,
    "".join(chr(c) for c in range(1, 0x3000, 7)),
    "axiom F\nF -> F(1e308)F(nan)\n",
    "#define X X\nLsystem: 1\nAxiom: X\nendlsystem\n",
]


@pytest.mark.parametrize("notation", graftal.notations())
def test_no_input_crashes_the_interpreter(notation):
    for text in NASTY:
        m = graftal.parse(text, notation)
        m.check()
        for call in (lambda: m.derive(steps=4, max_symbols=100_000),
                     lambda: m.render("png", size=32, steps=4, max_symbols=100_000),
                     lambda: m.stats(steps=4, max_symbols=100_000)):
            try:
                call()
            except graftal.GraftalError:
                pass


def test_geometry_is_what_stats_counts():
    for spec in ["std:hogeweg-hesper-a", "examples/cpfg-leaf/leaf.l"]:
        m = graftal.load(spec)
        g = m.geometry()
        s = m.stats()
        n, p = s["segments"], s["polygons"]
        assert g["segments"].shape == (n, 2, 3) and g["segments"].dtype == np.float64
        assert g["widths"].shape == (n,) and g["colours"].shape == (n, 3)
        assert g["colours"].dtype == np.uint8
        offsets = g["polygon_offsets"]
        assert offsets.shape == (p + 1,) and offsets[0] == 0
        assert np.all(np.diff(offsets) >= 3) and offsets[-1] == len(g["polygon_points"])
        assert g["polygon_colours"].shape == (p, 3)
        points = np.concatenate([g["segments"].reshape(-1, 3), g["polygon_points"]])
        box = np.concatenate([points.min(axis=0), points.max(axis=0)])
        assert np.allclose(box, s["bbox"])
    assert graftal.load("std:koch-island").geometry(steps=1)["segments"].shape == (32, 2, 3)


def test_a_model_shows_its_picture_inline_as_svg_or_png():
    m = graftal.load("std:hogeweg-hesper-a")
    assert m.inline == "svg"
    svg = m._repr_svg_()
    assert svg.lstrip().startswith("<svg") or svg.startswith("<?xml")
    assert svg.encode() == m.render("svg", size=m.inline_size)
    assert m._repr_png_() is None and m._repr_html_() is None
    m.inline, m.inline_size = "png", 200
    assert m._repr_png_() == m.render("png", size=200)
    assert m._repr_svg_() is None
    with pytest.raises(ValueError):
        m.inline = "gif"
    assert "std:hogeweg-hesper-a" in repr(m)


def test_a_model_without_a_picture_shows_why():
    bad = graftal.parse("axiom: F\nF -> F+F\n", "pfg")
    assert bad._repr_svg_() is None
    assert "E0005" in bad._repr_html_()
    library = graftal.load("examples/fractint.l")
    assert library.entries and "Dragon" in library.entries
    assert library._repr_svg_() is None
    assert library._repr_html_() is not None
    past = graftal.parse("steps 60\naxiom F\nF -> F F : 0.5\n  -> F F F : 0.5\n", "gft")
    assert past.ok and past._repr_svg_() is None and "E0303" in past._repr_html_()


def test_a_picture_shows_inline_in_its_own_format():
    m = graftal.load("std:koch-island")
    gif = m.animate(steps=2, size=64)
    assert gif.data.startswith(b"GIF89a") and gif.format == "gif"
    bundle = gif._repr_mimebundle_()
    assert base64.b64decode(bundle["image/gif"]) == gif.data
    apng = m.animate("apng", steps=2, size=64)
    assert apng.data.startswith(b"\x89PNG") and b"acTL" in apng.data
    assert base64.b64decode(apng._repr_mimebundle_()["image/png"]) == apng.data
    svg = m.picture("svg", size=64)
    assert svg._repr_mimebundle_()["image/svg+xml"] == svg.data.decode()
    assert "image/png" not in m.picture("obj")._repr_mimebundle_()
    assert bytes(svg) == svg.data


def test_the_gil_is_released_while_the_library_works():
    m = graftal.load("std:hogeweg-hesper-a")
    state = {"running": False}

    def work():
        state["running"] = True
        start = time.perf_counter()
        m.render("png", size=4096, steps=7)
        state["took"] = time.perf_counter() - start
        state["running"] = False

    worker = threading.Thread(target=work)
    worker.start()
    gaps, last = [], None
    while worker.is_alive():
        now = time.perf_counter()
        if state["running"]:
            if last is not None:
                gaps.append(now - last)
            last = now
    worker.join()
    # Held, the GIL would stop this thread for the whole call.
    assert gaps and max(gaps) < state["took"] / 2, (max(gaps, default=0), state)


def test_a_stream_dropped_early_stops_the_writing():
    m = graftal.load("std:koch-island")
    chunks = m.derive(steps=8, stream=True)
    first = next(chunks)
    assert first.startswith("F+F-F-FF+F+F-F") and len(first) > 1000
    del chunks
    assert m.derive(steps=1) == "F+F-F-FF+F+F-F+F+F-F-FF+F+F-F+F+F-F-FF+F+F-F+F+F-F-FF+F+F-F"


def test_the_readme_s_python_example_runs(capsys):
    readme = (REPO / "README.md").read_text()
    (example,) = re.findall(r"```python\n(.*?)```", readme, re.S)
    exec(compile(example, "README.md", "exec"), {})
    printed = capsys.readouterr().out
    assert printed.startswith("E0005 2 [(") and "E0005 (error)" in printed
