#!/usr/bin/python3
"""materials_sheet.py OUT.png BEFORE AFTER — docs/images/materials-before-after.png:
multi-material files of Debian's assimp-testmodels rendered by two softrast
binaries (a build before materials per part, and one with them), lambert
shading, one row per file, before on the left. Both draw from AFTER's
default camera (the three-quarter view of sr_camera_frame_bounds, worked
out here from `AFTER info --json`'s bounds and given to both, since
BEFORE's default was a front view); each in its own default colour
arithmetic (BEFORE had only raw colours; AFTER's is sRGB). Needs the
package's files (not the repository's), hence not a make target; the PNGs
are read and written with pinhole_sheet.py's zlib-only helpers."""

import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

from pinhole_sheet import read_rgb_png, write_rgb_png

MODELS = "/usr/share/assimp/models/"
FILES = [  # docs/scene-files.md, "Materials", names what each row shows
    "glTF/CesiumMilkTruck/CesiumMilkTruck.gltf",
    "OBJ/spider.obj",
    "Collada/teapots.DAE",
    "glTF2/ClearCoat-glTF/ClearCoatTest.gltf",
    "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
]
SIZE = (240, 180)


FOV_DEG, MARGIN, AZIMUTH_DEG, ELEVATION_DEG = 60.0, 1.05, 30.0, 20.0  # src/scene/camera.c


def framed_camera(binary, model):
    """The default camera's --eye, --target, --near and --far for a file
    whose upright turn is none (every file here is +y up)."""
    info = json.loads(subprocess.run([binary, "info", "--json", MODELS + model], check=True,
                                     capture_output=True, text=True).stdout)
    assert info["upright_turn"] == [[1, 0, 0], [0, 1, 0], [0, 0, 1]], model
    lo, hi = info["bounds_world"]["min"], info["bounds_world"]["max"]
    centre = [0.5 * (a + b) for a, b in zip(lo, hi)]
    radius = 0.5 * math.dist(lo, hi)
    half = math.radians(FOV_DEG) / 2
    narrow = min(half, math.atan(math.tan(half) * SIZE[0] / SIZE[1]))
    distance = MARGIN * radius / math.sin(narrow)
    az, el = math.radians(AZIMUTH_DEG), math.radians(ELEVATION_DEG)
    toward = (math.sin(az) * math.cos(el), math.sin(el), -math.cos(az) * math.cos(el))
    eye = [c + distance * t for c, t in zip(centre, toward)]
    point = lambda v: ",".join("%.9g" % x for x in v)
    return ["--eye", point(eye), "--target", point(centre), "--near", "%.9g" % (0.99 * (distance - radius)),
            "--far", "%.9g" % (1.01 * (distance + radius))]


def render(binary, model, out, camera):
    subprocess.run([binary, "render", MODELS + model, "--size", "%dx%d" % SIZE, "--out", out, "--quiet", *camera],
                   check=True)
    return read_rgb_png(out)


def main():
    out, before, after = sys.argv[1:4]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for i, model in enumerate(FILES):
            camera = framed_camera(after, model)
            pair = [render(b, model, os.path.join(tmp, "%d%s.png" % (i, k)), camera)
                    for k, b in (("b", before), ("a", after))]
            gap = np.full((SIZE[1], 4, 3), 255, np.uint8)
            rows.append(np.concatenate([pair[0], gap, pair[1]], 1))
    sep = np.full((4, rows[0].shape[1], 3), 255, np.uint8)
    write_rgb_png(out, np.concatenate([r if k == 0 else np.concatenate([sep, r], 0) for k, r in enumerate(rows)], 0))


if __name__ == "__main__":
    main()
