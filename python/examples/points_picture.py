#!/usr/bin/python3
"""points_picture.py [OUT.png] — a point cloud from Python: the torus knot
cloud of tools/point_cloud.py (40,000 coloured points, vertices alone, as
a depth sensor gives them) loaded, and seen by a pinhole camera as 2-pixel
points: its colours beside its view depth (near yellow to far blue, black
where nothing). By default docs/images/python-points.png. Run from the
repository's root after `make test-python` (the in-place build) or the
README's install:

    /usr/bin/python3 python/examples/points_picture.py

Debian's python3 and numpy; the PNG is written with zlib alone
(tools/pinhole_sheet.py)."""
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path += [os.path.dirname(HERE), os.path.join(ROOT, "tools")]  # an installed softrast first, else the in-place build
import numpy as np  # noqa: E402

import pinhole_sheet  # noqa: E402
import softrast  # noqa: E402


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join("docs", "images", "python-points.png")
    with tempfile.TemporaryDirectory() as tmp:
        ply = os.path.join(tmp, "knot-cloud.ply")
        subprocess.run([sys.executable, os.path.join(ROOT, "tools", "point_cloud.py"), ply], check=True,
                       stdout=subprocess.DEVNULL)
        cloud = softrast.Mesh.load(ply)
    out = softrast.Renderer(640, 360).render(cloud, eye=(0, 4, 9), target=(0, 0, 0), fov=45, points=True,
                                             point_size=2, outputs=("color", "depth"))
    depth = out["depth"]
    pinhole_sheet.write_rgb_png(path, np.concatenate([out["color"], pinhole_sheet.depth_colours(depth)], 1))
    print(f"{path}: colour and view depth of {cloud} as points, {(depth > 0).sum()} pixels drawn")


if __name__ == "__main__":
    main()
