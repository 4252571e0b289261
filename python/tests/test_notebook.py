"""The example notebook runs (nbclient, small frames), draws its figures and its fit recovers the spin and the
inclination; it is its plain script's cells; and the script runs without Jupyter. The torus-by-order script runs
and its fluxes by order sum to the total."""

import os
import pathlib
import re
import subprocess
import sys

import nbformat
import pytest
from nbclient import NotebookClient

SOURCE = pathlib.Path(os.environ.get("GRTRACE_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
EXAMPLES = SOURCE / "examples" / "python"
SMALL = {"GRTRACE_EXAMPLE_SIZE": "64", "GRTRACE_EXAMPLE_FIT_SIZE": "64"}


def fit_result(text):
    m = re.search(r"fit: spin ([-0-9.]+) \(true ([0-9.]+)\), inclination ([0-9.]+) deg \(true ([0-9.]+)\)", text)
    assert m, text
    return [float(v) for v in m.groups()]


def test_the_notebook_runs_and_its_fit_recovers_spin_and_inclination(tmp_path, monkeypatch):
    for key, value in SMALL.items():
        monkeypatch.setenv(key, value)  # the kernel inherits the environment
    nb = nbformat.read(EXAMPLES / "kerr_disk_fit.ipynb", as_version=4)
    NotebookClient(nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}).execute()
    texts, images = [], 0
    for cell in nb.cells:
        for out in cell.get("outputs", []):
            texts.append(out.get("text", ""))
            images += "image/png" in out.get("data", {})
    spin, true_spin, theta, true_theta = fit_result("".join(texts))
    assert abs(spin - true_spin) < 0.02 and abs(theta - true_theta) < 0.5
    assert images >= 3  # the frame and its redshift, the rays, the fit's residual
    assert list(tmp_path.iterdir()) == []  # the notebook writes no files


def test_the_notebook_is_its_scripts_cells():
    sys.path.insert(0, str(EXAMPLES))
    try:
        from make_notebook import notebook_cells
    finally:
        sys.path.pop(0)
    script = notebook_cells((EXAMPLES / "kerr_disk_fit.py").read_text())
    nb = nbformat.read(EXAMPLES / "kerr_disk_fit.ipynb", as_version=4)
    assert [(c.cell_type, c.source) for c in nb.cells] == script, (
        "regenerate: python3 examples/python/make_notebook.py examples/python/kerr_disk_fit.py "
        "examples/python/kerr_disk_fit.ipynb")


def test_the_script_runs_without_jupyter(tmp_path):
    done = subprocess.run([sys.executable, str(EXAMPLES / "kerr_disk_fit.py")], cwd=tmp_path, capture_output=True,
                          text=True, timeout=600, env=dict(os.environ, **SMALL))
    assert done.returncode == 0, done.stderr
    spin, true_spin, theta, true_theta = fit_result(done.stdout)
    assert abs(spin - true_spin) < 0.02 and abs(theta - true_theta) < 0.5
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "kerr_disk_fit.png", "kerr_disk_frame.png", "kerr_disk_rays.png"]


def test_the_torus_by_order_script_draws_its_orders(tmp_path):
    done = subprocess.run([sys.executable, str(EXAMPLES / "torus_orders.py")], cwd=tmp_path, capture_output=True,
                          text=True, timeout=600, env=dict(os.environ, GRTRACE_EXAMPLE_SIZE="32"))
    assert done.returncode == 0, done.stderr
    m = re.search(r"flux ([-0-9.e+]+), by order n0 ([-0-9.e+]+) .*n1 ([-0-9.e+]+) .*n2 ([-0-9.e+]+) .*n3_up "
                  r"([-0-9.e+]+)", done.stdout)
    assert m, done.stdout
    total, *orders = [float(v) for v in m.groups()]
    assert sum(orders) == pytest.approx(total, rel=1e-3)  # four printed digits each
    assert orders[0] > orders[1] > 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["torus_orders.png"]
