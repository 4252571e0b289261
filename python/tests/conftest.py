"""Shared pieces of the Python module's tests: the grtrace-render binary (the tool the module must agree with) and a
command line for a dict of keywords."""

import os
import subprocess

import pytest


def keyword_to_option(name: str) -> str:
    """The tool's option for a keyword: camera_r -> --camera-r, lambda_ -> --lambda."""
    return "--" + name.rstrip("_").replace("_", "-")


def number_text(v) -> str:
    """A number as the module writes it for the library (the shortest text of the double: 1, 0.5, 1e-20)."""
    text = repr(float(v))
    return text[:-2] if text.endswith(".0") else text


def command_line(options: dict) -> list:
    """The tool's arguments for Python keywords (flags given when true, sequences comma-separated)."""
    args = []
    for name, value in options.items():
        if isinstance(value, bool):
            if value:
                args.append(keyword_to_option(name))
            continue
        if isinstance(value, (list, tuple)):
            value = ",".join(number_text(v) for v in value)
        args += [keyword_to_option(name), str(value)]
    return args


@pytest.fixture(scope="session")
def render_binary():
    path = os.environ.get("GRTRACE_RENDER_BINARY", "")
    if not path or not os.path.exists(path):
        pytest.skip("GRTRACE_RENDER_BINARY does not name grtrace-render (ctest sets it)")
    return path


@pytest.fixture
def run_tool(render_binary, tmp_path):
    """Runs grtrace-render with the keywords' options and --out in tmp_path; returns (exit code, stdout, stderr,
    the EXR path)."""

    def run(options: dict, name: str = "tool.exr"):
        out = tmp_path / name
        done = subprocess.run([render_binary, *command_line(options), "--out", str(out)], capture_output=True,
                              text=True, timeout=600)
        return done.returncode, done.stdout, done.stderr, out

    return run
