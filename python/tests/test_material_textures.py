"""A loaded file's parts each drawn with their own material's texture, as
the command line draws them (src/io/material_textures.c, one rule)."""
import numpy as np
import pytest

import softrast
from scenes import look_pose

W, H, K = 80, 40, (60.0, 60.0, 39.5, 19.5)
POSE = look_pose([0.0, 0.0, -3.0], [0.0, 0.0, 0.0])
BLUE = (0, 0, 255)


def two_textured_quads(tmp_path, png, right_texture="right.png"):
    """Two quads side by side in z = 0 (x < 0 and x > 0), each with a
    material of its own map_Kd: a random 4x4 texture on the left, plain
    blue on the right."""
    rng = np.random.default_rng(11)
    png.write_rgb_png(tmp_path / "left.png", rng.integers(0, 256, (4, 4, 3), dtype=np.uint8))
    png.write_rgb_png(tmp_path / "right.png", np.tile(np.array(BLUE, np.uint8), (4, 4, 1)))
    (tmp_path / "two.mtl").write_text("newmtl left\nmap_Kd left.png\nnewmtl right\nmap_Kd %s\n" % right_texture)
    lines = ["mtllib two.mtl"]
    for x0 in (-1.2, 0.0):
        lines += ["v %r -0.6 0" % x0, "v %r -0.6 0" % (x0 + 1.2), "v %r 0.6 0" % (x0 + 1.2), "v %r 0.6 0" % x0]
    lines += ["vt 0 0", "vt 1 0", "vt 1 1", "vt 0 1"]
    lines += ["usemtl left", "f 1/1 2/2 3/3 4/4", "usemtl right", "f 5/1 6/2 7/3 8/4"]
    (tmp_path / "two.obj").write_text("\n".join(lines) + "\n")
    return tmp_path / "two.obj"


def cli_color(cli, png, tmp_path, obj, shade):
    cli("render", obj, "--size", f"{W}x{H}", "--intrinsics", ",".join(map(repr, K)), "--pose-w2c",
        ",".join(repr(float(v)) for v in POSE.ravel()), "--shade", shade, "--out", tmp_path / "c.png", "--quiet")
    return png.read_rgb_png(tmp_path / "c.png")


def python_render(mesh, shade):
    return softrast.Renderer(W, H, threads=2).render(mesh, fx=K[0], fy=K[1], cx=K[2], cy=K[3], pose=POSE,
                                                     outputs=("color", "part_ids"), shade=shade)


@pytest.mark.parametrize("shade", ["texture", "lambert"])
def test_each_part_draws_its_own_texture_as_the_command_line_does(cli, png, tmp_path, shade):
    obj = two_textured_quads(tmp_path, png)
    want = cli_color(cli, png, tmp_path, obj, shade)
    mesh = softrast.Mesh.load(obj)
    out = python_render(mesh, shade)
    assert np.array_equal(out["color"], want)
    right = out["part_ids"] == 2
    assert right.sum() > 500 and (out["part_ids"] == 1).sum() > 500
    if shade == "texture":  # the right quad blue, not the left's (first) texture
        assert np.all(out["color"][right] == BLUE)
        assert len(np.unique(out["color"][out["part_ids"] == 1], axis=0)) > 8
    # `texture` gives the first material's
    assert mesh.texture.shape == (4, 4, 3) and np.array_equal(mesh.texture, png.read_rgb_png(tmp_path / "left.png"))


def test_a_missing_texture_warns_and_its_part_draws_its_base_colour_as_the_command_line_does(cli, png, tmp_path):
    obj = two_textured_quads(tmp_path, png, right_texture="gone.png")
    want = cli_color(cli, png, tmp_path, obj, "texture")
    with pytest.warns(UserWarning, match=r"gone\.png.*its materials are drawn untextured") as caught:
        mesh = softrast.Mesh.load(obj)
    assert len(caught) == 1
    out = python_render(mesh, "texture")
    assert np.array_equal(out["color"], want)
    right = out["part_ids"] == 2
    assert right.sum() > 500 and np.all(out["color"][right] == (255, 255, 255))  # the map_Kd's white base
