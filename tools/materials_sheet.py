#!/usr/bin/python3
"""materials_sheet.py OUT.png BEFORE AFTER — docs/images/materials-before-after.png:
multi-material files of Debian's assimp-testmodels rendered by two softrast
binaries (a build before materials per part, and one with them), default
camera and lambert shading, one row per file, before on the left. Needs the
package's files (not the repository's), hence not a make target; the PNGs
are read and written with pinhole_sheet.py's zlib-only helpers."""

import os
import subprocess
import sys
import tempfile

import numpy as np

from pinhole_sheet import read_rgb_png, write_rgb_png

MODELS = "/usr/share/assimp/models/"
FILES = [  # docs/conventions.md, "Materials", names what each row shows
    "glTF/CesiumMilkTruck/CesiumMilkTruck.gltf",
    "OBJ/spider.obj",
    "Collada/teapots.DAE",
    "glTF2/ClearCoat-glTF/ClearCoatTest.gltf",
    "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
]
SIZE = (240, 180)


def render(binary, model, out):
    subprocess.run([binary, "render", MODELS + model, "--size", "%dx%d" % SIZE, "--out", out, "--quiet"],
                   check=True)
    return read_rgb_png(out)


def main():
    out, before, after = sys.argv[1:4]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for i, model in enumerate(FILES):
            pair = [render(b, model, os.path.join(tmp, "%d%s.png" % (i, k))) for k, b in (("b", before), ("a", after))]
            gap = np.full((SIZE[1], 4, 3), 255, np.uint8)
            rows.append(np.concatenate([pair[0], gap, pair[1]], 1))
    sep = np.full((4, rows[0].shape[1], 3), 255, np.uint8)
    write_rgb_png(out, np.concatenate([r if k == 0 else np.concatenate([sep, r], 0) for k, r in enumerate(rows)], 0))


if __name__ == "__main__":
    main()
