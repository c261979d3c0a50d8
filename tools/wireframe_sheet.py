#!/usr/bin/python3
"""wireframe_sheet.py OUT.png BEFORE AFTER — docs/images/room-lines-before-after.png:
`render --lines` of the room from the viewer's first camera by two softrast
binaries (one from before hidden lines by ownership, commit 33a1003, whose
lines won the depth test by a constant bias; and one with them), before on
the left; below, the middle of each three times larger. Not a make target:
it needs a build of the old commit. The PNGs are read and written with
pinhole_sheet.py's zlib-only helpers."""

import os
import subprocess
import sys
import tempfile

import numpy as np

from pinhole_sheet import read_rgb_png, write_rgb_png

CAMERA = ["--eye", "-8,3,-8", "--target", "4,1.5,6", "--fov", "75"]  # app/view/view.c, ROOM_SPAWN
SIZE = (640, 360)
CROP = (170, 60, 214, 120)  # x, y, width, height: the box pillar in front and those behind it
ZOOM = 3


def render(binary, out):
    subprocess.run([binary, "render", "assets/room.obj", "--lines", "--size", "%dx%d" % SIZE, "--out", out, "--quiet"]
                   + CAMERA, check=True)
    return read_rgb_png(out)


def side_by_side(left, right):
    gap = np.full((left.shape[0], 8, 3), 255, np.uint8)
    return np.concatenate([left, gap, right], 1)


def main():
    out, before, after = sys.argv[1:4]
    with tempfile.TemporaryDirectory() as tmp:
        frames = [render(b, os.path.join(tmp, "%d.png" % k)) for k, b in enumerate((before, after))]
    x, y, w, h = CROP
    crops = [np.repeat(np.repeat(f[y:y + h, x:x + w], ZOOM, 0), ZOOM, 1)[:SIZE[1], :SIZE[0]] for f in frames]
    sep = np.full((8, 2 * SIZE[0] + 8, 3), 255, np.uint8)
    write_rgb_png(out, np.concatenate([side_by_side(*frames), sep, side_by_side(*crops)], 0))


if __name__ == "__main__":
    main()
