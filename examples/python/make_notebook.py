"""Writes a notebook from a script's cells ('# %%' code, '# %% [markdown]' text), so that the notebook and its plain
script twin say the same thing:

    python3 examples/python/make_notebook.py examples/python/kerr_disk_fit.py examples/python/kerr_disk_fit.ipynb

(the tests check that the committed notebook is the script's cells: python/tests/test_notebook.py).
"""
import sys

import nbformat


def notebook_cells(src):
    """The script's cells as (kind, source): the module docstring before the first marker is the script's alone."""
    body = src[src.index("# %%"):]
    cells = []
    for chunk in body.split("# %%")[1:]:
        header, _, text = chunk.partition("\n")
        text = text.strip("\n")
        if header.strip() == "[markdown]":
            cells.append(("markdown", "\n".join(l[2:] if l.startswith("# ") else l.lstrip("#") for l in text.splitlines())))
        else:
            cells.append(("code", text))
    return cells


def main(script, notebook):
    cells = [nbformat.v4.new_markdown_cell(text) if kind == "markdown" else nbformat.v4.new_code_cell(text)
             for kind, text in notebook_cells(open(script).read())]
    for i, cell in enumerate(cells):
        cell.id = f"cell-{i}"  # stable ids: the same script gives the same file
    nb = nbformat.v4.new_notebook(cells=cells)
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nb.metadata["language_info"] = {"name": "python"}
    nbformat.write(nb, notebook)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
