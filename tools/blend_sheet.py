#!/usr/bin/python3
"""blend_sheet.py OUT.png SOFTRAST — docs/images/blend-modes.png: one small
glTF scene drawn six ways by `softrast render` (docs/cli.md, "Blending"):
an opaque gray floor first in the file, then three BLEND squares of alpha
0.5 listed nearest first (red nearest, green, blue farthest), seen from the
front. Tiles, left to right, top to bottom: the file's layers (the
default: BLEND parts farthest first over the opaque ones), --blend
replace, --blend alpha, and --blend alpha, additive, premultiplied with
--depth-write off. The PNGs are read and written with pinhole_sheet.py's
zlib-only helpers."""

import base64
import json
import os
import struct
import subprocess
import sys
import tempfile

import numpy as np

from pinhole_sheet import read_rgb_png, write_rgb_png

SIZE = (200, 150)
RUNS = [[], ["--blend", "replace"], ["--blend", "alpha"],
        ["--blend", "alpha", "--depth-write", "off"], ["--blend", "additive", "--depth-write", "off"],
        ["--blend", "premultiplied", "--depth-write", "off"]]


def scene():
    """A unit square in z = 0 (front +z) placed by five nodes."""
    square = struct.pack("<12f", 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0) + struct.pack("<6H", 0, 1, 2, 0, 2, 3)
    materials = [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1]}}]
    materials += [{"alphaMode": "BLEND", "pbrMetallicRoughness": {"baseColorFactor": c + [0.5]}}
                  for c in ([1, 0, 0], [0, 1, 0], [0, 0, 1])]
    nodes = [{"mesh": 0, "translation": [-2, -1.5, 0], "scale": [4, 3, 1]},
             {"mesh": 1, "translation": [-1.1, -0.9, 1.5], "scale": [1.3, 1.3, 1]},
             {"mesh": 2, "translation": [-0.2, -0.9, 1.0], "scale": [1.3, 1.3, 1]},
             {"mesh": 3, "translation": [-0.65, -0.2, 0.5], "scale": [1.3, 1.3, 1]}]
    return {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes,
        "materials": materials,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": m}]} for m in range(4)],
        "buffers": [{"byteLength": len(square),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(square).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}]}


def main():
    out, softrast = sys.argv[1:3]
    tiles = []
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "squares.gltf")
        with open(path, "w") as f:
            json.dump(scene(), f)
        for i, options in enumerate(RUNS):
            png = os.path.join(tmp, "%d.png" % i)
            subprocess.run([softrast, "render", path, "--size", "%dx%d" % SIZE, "--eye", "0,0,-3.2", "--target",
                            "0,0,0", "--cull", "none", "--shade", "texture", "--out", png, "--quiet"] + options,
                           check=True)
            tiles.append(read_rgb_png(png))
    gap = np.full((SIZE[1], 4, 3), 255, np.uint8)
    rows = [np.concatenate([tiles[r * 3], gap, tiles[r * 3 + 1], gap, tiles[r * 3 + 2]], 1) for r in range(2)]
    sep = np.full((4, rows[0].shape[1], 3), 255, np.uint8)
    write_rgb_png(out, np.concatenate([rows[0], sep, rows[1]], 0))


if __name__ == "__main__":
    main()
