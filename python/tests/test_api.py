"""What the module offers and says about itself: its version is the C++ package's, its lists are the library's, its
stubs and help name every keyword."""

import ast
import os
import pathlib
import pydoc
import subprocess

import grtrace


def test_version_is_the_cpp_packages(render_binary):
    tool = subprocess.run([render_binary, "--version"], capture_output=True, text=True, check=True).stdout.split()
    assert tool == ["grtrace-render", grtrace.__version__]


def test_lists_are_the_librarys():
    names = [m["name"] for m in grtrace.metrics()]
    assert names == ["schwarzschild", "minkowski", "kerr", "rn", "sds", "wormhole", "schwarzschild-ef"]
    kerr = next(m for m in grtrace.metrics() if m["name"] == "kerr")
    assert kerr["charts"] == ["bl", "ks"] and kerr["has_mass"]
    assert [p["name"] for p in kerr["parameters"]] == ["spin"]
    sds = next(m for m in grtrace.metrics() if m["name"] == "sds")
    assert [p["name"] for p in sds["parameters"]] == ["lambda_"]
    assert grtrace.scenes() == ["checker", "sky", "redshift", "disk", "accretion", "riaf", "torus"]
    assert {"tableau": "rkf78", "control": "i"}.items() <= grtrace.methods()[0].items()
    assert len(grtrace.methods()) == 6
    assert grtrace.tracers() == ["auto", "general", "planar", "kerr-mino", "kerr-closed-form", "straight-line"]
    assert grtrace.devices() == ["auto", "cpu", "cuda"]
    gpu = grtrace.gpu()
    assert set(gpu) == {"built", "present", "name", "why_not"}
    assert gpu["present"] or gpu["why_not"]


def test_options_are_the_tools(render_binary):
    """Every keyword is one of grtrace-render's options, with its default."""
    help_text = subprocess.run([render_binary, "--help"], capture_output=True, text=True, check=True).stdout
    for o in grtrace.options():
        assert "  --" + o["option"] + (" VALUE" if not o["flag"] else "") in help_text, o["option"]
        if not o["flag"] and o["default"]:
            assert f"(default: {o['default']})" in help_text
    camera_r = next(o for o in grtrace.options() if o["name"] == "camera_r")
    assert camera_r["default"] == "200" and camera_r["option"] == "camera-r"


def stub_keywords(function: str):
    stub = pathlib.Path(grtrace.__file__).with_name("__init__.pyi")
    tree = ast.parse(stub.read_text())
    node = next(n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == function)
    return [a.arg for a in node.args.args + node.args.kwonlyargs]


def test_stubs_list_every_keyword():
    keywords = [o["name"] for o in grtrace.options()]
    assert stub_keywords("render") == ["progress"] + keywords
    assert stub_keywords("trace_ray") == ["pixel", "position", "momentum", "samples_per_step", "scene_objects"] + keywords
    assert (pathlib.Path(grtrace.__file__).with_name("py.typed")).exists()


def test_help_shows_the_docstrings():
    text = pydoc.render_doc(grtrace, renderer=pydoc.plaintext)
    for words in ["general-relativistic ray tracing", "render(*, progress", "camera_r (default '200')",
                  "KeyboardInterrupt", "trace_ray(pixel", "read_exr(path", "class Frame"]:
        assert words in text, words
    assert "ValueError" in grtrace.render.__doc__
    assert grtrace.Frame.channel.__doc__ and grtrace.Ray.__doc__


def test_the_package_is_the_installed_one():
    """The tests import the package cmake/install-python.sh installed (ctest's python_install), not a source copy."""
    where = pathlib.Path(grtrace.__file__).resolve()
    source = pathlib.Path(os.environ.get("GRTRACE_SOURCE_DIR", "/nonexistent")).resolve() / "python"
    assert source not in where.parents
    assert (where.parent / "__init__.pyi").exists()
    assert any(p.name.startswith("_grtrace") for p in where.parent.iterdir())


def test_the_readmes_example_runs_and_says_what_it_shows(tmp_path, monkeypatch):
    readme = (pathlib.Path(os.environ.get("GRTRACE_SOURCE_DIR", pathlib.Path(__file__).parents[2])) / "README.md")
    text = readme.read_text()
    section = text[text.index("## From Python"):text.index("## Command-line tools")]
    code = section[section.index("```python") + len("```python"):]
    code = code[:code.index("```")]
    monkeypatch.chdir(tmp_path)
    scope = {}
    exec(compile(code.replace("progress=True", "progress=None"), "README.md", "exec"), scope)
    assert scope["frame"].report["tracer"] == "kerr-closed-form"
    assert scope["g"].shape == (256, 256)
    assert scope["ray"].outcome["status"] == "hit" and scope["ray"].outcome["object"] == "disk"
    assert (tmp_path / "disk.exr").exists() and (tmp_path / "disk.png").exists()
