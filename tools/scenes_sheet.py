#!/usr/bin/python3
"""scenes_sheet.py OUT.png [BINARY] — docs/images/scenes-sheet.png: every file
that tests/scenes_manifest.json names (Debian's assimp-testmodels), drawn
by `softrast render FILE` with the default camera and lambert shading, in
the manifest's order, left to right and top to bottom, eight to a row.
Needs the package's files (tools/deps.sh installs them), hence not a make
target; the PNGs are read and written with pinhole_sheet.py's zlib-only
helpers."""

import json
import os
import subprocess
import sys
import tempfile

import numpy as np

from pinhole_sheet import read_rgb_png, write_rgb_png

MANIFEST = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "scenes_manifest.json")
SIZE = (160, 120)
COLUMNS = 8
GAP = 4


def main():
    out = sys.argv[1]
    binary = sys.argv[2] if len(sys.argv) > 2 else "build/softrast"
    manifest = json.load(open(MANIFEST))
    files = [e["file"] for e in manifest["files"]]
    rows = (len(files) + COLUMNS - 1) // COLUMNS
    w, h = SIZE
    sheet = np.full((rows * (h + GAP) - GAP, COLUMNS * (w + GAP) - GAP, 3), 255, np.uint8)
    with tempfile.TemporaryDirectory() as tmp:
        for i, name in enumerate(files):
            png = os.path.join(tmp, "%d.png" % i)
            subprocess.run([binary, "render", os.path.join(manifest["root"], name), "--size", "%dx%d" % SIZE,
                            "--out", png, "--quiet"], check=True, stderr=subprocess.DEVNULL)
            r, c = divmod(i, COLUMNS)
            sheet[r * (h + GAP):r * (h + GAP) + h, c * (w + GAP):c * (w + GAP) + w] = read_rgb_png(png)
    write_rgb_png(out, sheet)


if __name__ == "__main__":
    main()
