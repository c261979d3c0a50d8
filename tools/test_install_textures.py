#!/usr/bin/env python3
"""make test-install's check that the installed render_mesh gives each
material its own texture.

Usage: test_install_textures.py RENDER_MESH DIR

Writes into DIR an OBJ of two quads side by side, one eight times the
other's area, each with a material of its own whose map_Kd is a 2x2 PNG of
one colour, runs RENDER_MESH on it and reads back the PNG it writes. Every
vertex normal points at the default light (SR_DEFAULT_LIGHT, with OBJ's z
flipped), so lambert lights each texel at full intensity and a pixel of a
part is exactly its texture's colour (a texture of one colour filters to
that colour). The check: every pixel is the background or one of the two
colours, both colours are there, the big part's colour covers more than
twice the pixels of the small one's (8 to 1 in area, which the camera's
oblique view foreshortens), and in every row they lie apart, the big one
on the same side. A render_mesh that drew every material with one texture,
or swapped them, fails it.
"""
import subprocess
import sys
from pathlib import Path

import numpy as np

from pinhole_sheet import read_rgb_png, write_rgb_png

BACKGROUND = (0x20, 0x20, 0x20)  # render_mesh's clear colour
BIG = (200, 30, 60)              # the texture of the big quad's material
SMALL = (20, 180, 90)            # the texture of the small quad's material


def write_model(folder):
    for name, colour in (("big", BIG), ("small", SMALL)):
        write_rgb_png(folder / f"{name}.png", np.full((2, 2, 3), colour, np.uint8))
    (folder / "parts.mtl").write_text("newmtl big\nKd 1 1 1\nmap_Kd big.png\n"
                                      "newmtl small\nKd 1 1 1\nmap_Kd small.png\n")
    # OBJ's z is negated on loading: this normal is SR_DEFAULT_LIGHT's direction.
    (folder / "parts.obj").write_text(
        "mtllib parts.mtl\n"
        "v -2 -0.5 0\nv 0 -0.5 0\nv 0 0.5 0\nv -2 0.5 0\n"
        "v 0.1 -0.5 0\nv 0.35 -0.5 0\nv 0.35 0.5 0\nv 0.1 0.5 0\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
        "vn -0.35 0.8 0.5\n"
        "usemtl big\nf 1/1/1 2/2/1 3/3/1 4/4/1\n"
        "usemtl small\nf 5/1/1 6/2/1 7/3/1 8/4/1\n")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.split("\n\n")[1])
    render_mesh, folder = sys.argv[1], Path(sys.argv[2])
    folder.mkdir(parents=True, exist_ok=True)
    write_model(folder)
    out = folder / "parts.png"
    run = subprocess.run([render_mesh, str(folder / "parts.obj"), str(out)], capture_output=True, text=True)
    print(f"render_mesh {folder / 'parts.obj'}: {run.stdout.strip()}{run.stderr.strip()}")
    if run.returncode != 0 or run.stderr:
        sys.exit("render_mesh failed or warned on the two-texture model")
    img = read_rgb_png(out)
    is_big, is_small = (np.all(img == colour, axis=2) for colour in (BIG, SMALL))
    other = ~(is_big | is_small | np.all(img == BACKGROUND, axis=2))
    if other.any():
        y, x = np.argwhere(other)[0]
        sys.exit(f"{out}: pixel {tuple(img[y, x])} at ({x}, {y}) is neither texture's colour nor the background")
    big, small = int(is_big.sum()), int(is_small.sum())
    if not big or not small:
        sys.exit(f"{out}: {big} pixels of the big part's texture and {small} of the small part's:"
                 " each material must draw its own")
    if big <= 2 * small:
        sys.exit(f"{out}: the big part's texture covers {big} pixels, the small part's {small}:"
                 " the materials' textures are swapped")
    columns = np.arange(img.shape[1])
    sides = set()  # per row holding both: whether the big part's pixels all lie left of the small one's
    for y in np.flatnonzero(is_big.any(axis=1) & is_small.any(axis=1)):
        b, s = columns[is_big[y]], columns[is_small[y]]
        if b.min() < s.max() and s.min() < b.max():
            sys.exit(f"{out}: row {y} mixes the two textures' pixels")
        sides.add(bool(b.max() < s.min()))
    if len(sides) != 1:
        sys.exit(f"{out}: the two textures' pixels change sides between rows")
    print(f"two materials, two textures: {big} and {small} pixels of exactly their own colour,"
          f" of {img.size // 3}")


if __name__ == "__main__":
    main()
