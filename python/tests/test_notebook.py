"""The example notebook runs from top to bottom in a Jupyter kernel (nbclient) and its frames
show as images."""

import os
from pathlib import Path

import pytest

NOTEBOOK = Path(__file__).resolve().parents[1] / "examples" / "tour.ipynb"


def test_the_example_notebook_runs_and_shows_frames(tmp_path):
    try:
        import nbclient
        import nbformat
    except ImportError:
        if os.environ.get("CI"):
            raise
        pytest.skip("nbclient and nbformat are not installed")
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    assert not any(c.get("outputs") for c in notebook.cells if c.cell_type == "code"), (
        "the notebook is kept without outputs"
    )
    nbclient.NotebookClient(
        notebook,
        timeout=600,
        kernel_name="python3",
        resources={"metadata": {"path": str(tmp_path)}},
    ).execute()
    images = [
        cell.source.splitlines()[-1]
        for cell in notebook.cells
        for out in cell.get("outputs", [])
        if "image/png" in out.get("data", {})
    ]
    # The two frames shown as the cells' values, and the two plots.
    assert len(images) == 4, images
    errors = [o for c in notebook.cells for o in c.get("outputs", []) if o.output_type == "error"]
    assert not errors
