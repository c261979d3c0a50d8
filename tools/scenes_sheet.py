#!/usr/bin/python3
"""scenes_sheet.py OUT.png [BINARY] — docs/images/scenes-sheet.png: every file
that tests/scenes_manifest.json names (Debian's assimp-testmodels), drawn
by `softrast render FILE` with the default camera and lambert shading, in
the manifest's order, left to right and top to bottom, eight to a row.
scenes_sheet.py --coverage [BINARY] prints instead each file's share of a
frame of the sheet's size that the default render covers (id shading, so
a dark colour counts), then the median and the files below 5 %: the
evidence for the default camera (docs/cli.md, "The default camera").
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


def render(binary, manifest, name, png, extra=()):
    subprocess.run([binary, "render", os.path.join(manifest["root"], name), "--size", "%dx%d" % SIZE,
                    "--out", png, "--quiet", *extra], check=True, stderr=subprocess.DEVNULL)
    return read_rgb_png(png)


def sheet(out, binary, manifest, files, tmp):
    rows = (len(files) + COLUMNS - 1) // COLUMNS
    w, h = SIZE
    image = np.full((rows * (h + GAP) - GAP, COLUMNS * (w + GAP) - GAP, 3), 255, np.uint8)
    for i, name in enumerate(files):
        r, c = divmod(i, COLUMNS)
        image[r * (h + GAP):r * (h + GAP) + h, c * (w + GAP):c * (w + GAP) + w] = \
            render(binary, manifest, name, os.path.join(tmp, "%d.png" % i))
    write_rgb_png(out, image)


def coverage(binary, manifest, files, tmp):
    shares = []
    for name in files:
        ids = render(binary, manifest, name, os.path.join(tmp, "ids.png"), ("--shade", "id"))
        shares.append(float(ids.reshape(-1, 3).any(axis=1).mean()))
        print("%.3f %s" % (shares[-1], name))
    low = [name for name, s in zip(files, shares) if s < 0.05]
    print("median %.3f; %d below 0.05: %s" % (float(np.median(shares)), len(low), ", ".join(low)))


def main():
    args = sys.argv[1:]
    counting = args[:1] == ["--coverage"]
    if counting:
        args = args[1:]
    elif not args:
        sys.exit(__doc__)
    manifest = json.load(open(MANIFEST))
    files = [e["file"] for e in manifest["files"]]
    with tempfile.TemporaryDirectory() as tmp:
        if counting:
            coverage(args[0] if args else "build/softrast", manifest, files, tmp)
        else:
            sheet(args[0], args[1] if len(args) > 1 else "build/softrast", manifest, files, tmp)


if __name__ == "__main__":
    main()
