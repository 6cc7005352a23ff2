#!/usr/bin/env python3
"""Executes a notebook top to bottom with nbclient (as a new user would, from its own folder) and
fails on the first cell that raises. The notebook in the repository must have no outputs (they are
stripped: `python3 scripts/run-notebook.py --strip NOTEBOOK` does it); the executed copy is written
to `--out` if given, else nowhere.

    python3 scripts/run-notebook.py docs/examples/tour.ipynb [--out executed.ipynb]
"""

import argparse
import sys
import time
from pathlib import Path

import nbformat


def stripped(nb):
    return all(
        c.cell_type != "code" or (not c.outputs and c.execution_count is None) for c in nb.cells
    )


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("notebook", type=Path)
    ap.add_argument("--out", type=Path)
    ap.add_argument("--strip", action="store_true", help="strip the outputs in place and exit")
    ap.add_argument("--timeout", type=int, default=600, help="seconds per cell")
    a = ap.parse_args()
    nb = nbformat.read(a.notebook, as_version=4)
    if a.strip:
        for c in nb.cells:
            if c.cell_type == "code":
                c.outputs, c.execution_count = [], None
        nbformat.write(nb, a.notebook)
        return 0
    if not stripped(nb):
        print(f"{a.notebook}: has outputs; strip them with --strip before committing", file=sys.stderr)
        return 1
    from nbclient import NotebookClient

    t0 = time.time()
    client = NotebookClient(
        nb, timeout=a.timeout, kernel_name="python3",
        resources={"metadata": {"path": str(a.notebook.parent.resolve())}},
    )
    client.execute()
    if a.out:
        nbformat.write(nb, a.out)
    print(f"{a.notebook}: {len(nb.cells)} cells executed in {time.time() - t0:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
