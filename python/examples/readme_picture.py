#!/usr/bin/python3
"""readme_picture.py [OUT.png] — the repository README's five-line Python
example, run as it is written there, and its picture: the colour image
beside the depth (near yellow to far blue, black where nothing), by default
docs/images/python-example.png. Run from the repository's root after
`make test-python` (the in-place build) or the README's install:

    /usr/bin/python3 python/examples/readme_picture.py

Debian's python3 and numpy; the PNG is written with zlib alone
(tools/pinhole_sheet.py)."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path += [os.path.dirname(HERE), os.path.join(ROOT, "tools")]  # an installed softrast first, else the in-place build
import numpy as np  # noqa: E402

import pinhole_sheet  # noqa: E402

# ---- the README's example, line for line ----
import softrast  # noqa: E402
mesh = softrast.Mesh.load("assets/torus.obj")                        # or softrast.Mesh(positions, faces, uvs=..., texture=...)
out = softrast.Renderer(640, 480).render(mesh, eye=(0, 2, 2.6), target=(0, -0.2, 0), fov=50,
                                         outputs=("color", "depth"))  # a look-at camera; or K= / fx=, pose=
color, depth = out["color"], out["depth"]                             # (480, 640, 3) uint8; (480, 640) float32, 0: nothing
# ----


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join("docs", "images", "python-example.png")
    pinhole_sheet.write_rgb_png(path, np.concatenate([color, pinhole_sheet.depth_colours(depth)], 1))
    print(f"{path}: colour and depth of {mesh}, {(depth > 0).sum()} pixels drawn")


if __name__ == "__main__":
    main()
