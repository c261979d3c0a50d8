"""Point clouds: a Mesh without faces, rendered with points=True as the
command line's --points draws it (every output bit for bit), each point at
its pixel and its depth, and the refusals."""
import os
import subprocess
import sys

import numpy as np
import pytest

import softrast
from scenes import look_pose

W, H = 64, 48
K = (50.0, 50.0, 31.5, 23.5)
ALL = ("depth", "range", "face_ids", "part_ids", "normals")
EYE = (0.3, 0.2, -3.0)


def write_ply(path, positions, colours):
    header = ("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
              "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n" % len(positions))
    rows = "".join("%r %r %r %d %d %d\n" % (*map(float, p), *map(int, c)) for p, c in zip(positions, colours))
    path.write_text(header + rows)


def cloud():
    """2000 points round the origin, some outside the view, a few at the
    eye and behind it (dropped by the near plane), with colours."""
    rng = np.random.default_rng(3)
    positions = rng.uniform(-1.5, 1.5, (2000, 3)).astype(np.float32)
    positions[:5] = np.float32(EYE) + rng.uniform(-0.01, 0.01, (5, 3)).astype(np.float32)
    positions[5:10] = np.float32(EYE) + np.float32([0, 0, -1]) + rng.uniform(-1, 1, (5, 3)).astype(np.float32)
    return positions, rng.integers(0, 256, (2000, 3)).astype(np.uint8)


@pytest.mark.parametrize("threads, size", [(1, 1), (2, 1), (2, 3)])
def test_a_cloud_renders_as_the_command_lines_points(cli, png, tmp_path, threads, size):
    positions, colours = cloud()
    write_ply(tmp_path / "cloud.ply", positions, colours)
    pose = look_pose(EYE, (0, 0, 0))
    cli("render", tmp_path / "cloud.ply", "--points", "--point-size", size, "--size", f"{W}x{H}",
        "--intrinsics", ",".join(map(repr, K)), "--pose-w2c", ",".join(repr(float(v)) for v in pose.ravel()),
        "--threads", threads, "--out", tmp_path / "c.png", "--view-depth", tmp_path / "d.npy",
        "--range", tmp_path / "r.npy", "--face-ids", tmp_path / "f.npy", "--part-ids", tmp_path / "p.npy",
        "--normals", tmp_path / "n.npy", "--quiet")
    r = softrast.Renderer(W, H, threads=threads)
    for mesh in (softrast.Mesh.load(tmp_path / "cloud.ply"), softrast.Mesh(positions, colors=colours)):
        out = r.render(mesh, fx=K[0], fy=K[1], cx=K[2], cy=K[3], pose=pose, outputs=("color",) + ALL,
                       points=True, point_size=size)
        for name, file in [("depth", "d"), ("range", "r"), ("face_ids", "f"), ("part_ids", "p"), ("normals", "n")]:
            want = np.load(tmp_path / f"{file}.npy")
            assert want.dtype == out[name].dtype and want.shape == out[name].shape, name
            assert np.array_equal(want.view(np.uint32), out[name].view(np.uint32)), name
        assert np.array_equal(png.read_rgb_png(tmp_path / "c.png"), out["color"])
        assert (out["face_ids"] > 0).sum() > 500
        assert out["stats"]["points"] == 2000 and out["stats"]["rejected"] >= 5


def cli_points(cli, path, pose, tmp_path, *extra):
    """The command line's --points files of path, read back."""
    cli("render", path, "--points", "--size", f"{W}x{H}", "--intrinsics", ",".join(map(repr, K)),
        "--pose-w2c", ",".join(repr(float(v)) for v in pose.ravel()), "--out", tmp_path / "c.png",
        "--view-depth", tmp_path / "d.npy", "--range", tmp_path / "r.npy", "--face-ids", tmp_path / "f.npy",
        "--part-ids", tmp_path / "p.npy", "--normals", tmp_path / "n.npy", "--quiet", *extra)
    return {name: np.load(tmp_path / f"{file}.npy")
            for name, file in [("depth", "d"), ("range", "r"), ("face_ids", "f"), ("part_ids", "p"), ("normals", "n")]}


def assert_same(want, out, png, tmp_path):
    for name in ALL:
        assert want[name].dtype == out[name].dtype and np.array_equal(want[name].view(np.uint32),
                                                                      out[name].view(np.uint32)), name
    assert np.array_equal(png.read_rgb_png(tmp_path / "c.png"), out["color"])


@pytest.mark.parametrize("shade", ["lambert", "depth", "color"])
def test_a_clouds_asked_shading_and_its_missing_normals_are_the_command_lines(cli, png, tmp_path, shade):
    # an asked shade is kept (no colours' default), and a cloud without
    # normals gives normals of 0 whatever the shading
    positions, colours = cloud()
    write_ply(tmp_path / "cloud.ply", positions, colours)
    pose = look_pose(EYE, (0, 0, 0))
    want = cli_points(cli, tmp_path / "cloud.ply", pose, tmp_path, "--shade", shade)
    mesh = softrast.Mesh(positions, colors=colours)
    out = softrast.Renderer(W, H, threads=1).render(mesh, fx=K[0], fy=K[1], cx=K[2], cy=K[3], pose=pose,
                                                    outputs=("color",) + ALL, points=True, shade=shade)
    assert_same(want, out, png, tmp_path)
    assert not out["normals"].any() and mesh.normals is None
    if shade != "color":
        assert not np.array_equal(out["color"], colour_shaded(mesh, pose))


def colour_shaded(mesh, pose):
    return softrast.Renderer(W, H, threads=1).render(mesh, fx=K[0], fy=K[1], cx=K[2], cy=K[3], pose=pose,
                                                     outputs=("color",), points=True, shade="color")["color"]


def test_a_meshs_vertices_as_points_are_the_command_lines_parts_and_all(cli, png, root, tmp_path):
    # the room: faces, normals and 34 parts; a point has no face, so its part is 1
    path = os.path.join(root, "assets", "room.obj")
    pose = look_pose((-4.8, 2.0, -8.4), (0.0, 1.0, 0.0))
    want = cli_points(cli, path, pose, tmp_path)
    out = softrast.Renderer(W, H, threads=2).render(softrast.Mesh.load(path), fx=K[0], fy=K[1], cx=K[2], cy=K[3],
                                                    pose=pose, outputs=("color",) + ALL, points=True)
    assert_same(want, out, png, tmp_path)
    drawn = out["face_ids"] > 0
    assert drawn.sum() > 300 and np.all(out["part_ids"][drawn] == 1)


def test_a_meshs_given_part_ids_are_not_a_points(tmp_path):
    positions = np.array([[-1, -1, 4], [1, -1, 4], [0, 1, 4], [0, 0, 5]], float)
    mesh = softrast.Mesh(positions, [[0, 1, 2], [0, 1, 3]], part_ids=[7, 9])
    out = softrast.Renderer(W, H, threads=1).render(mesh, fx=K[0], points=True, outputs=("part_ids", "face_ids"))
    drawn = out["face_ids"] > 0
    assert drawn.sum() == 4 and np.all(out["part_ids"][drawn] == 1)


def test_a_point_on_a_pixels_ray_is_drawn_there_at_its_depth():
    # The camera at the origin looking along +z: point i on the ray through
    # pixel centre (u, v) at depth z shows there, its face id i + 1.
    rng = np.random.default_rng(11)
    pixels = [(int(rng.integers(0, W)), int(rng.integers(0, H))) for _ in range(40)]
    pixels = list(dict.fromkeys(pixels))
    depths = np.float32(2.0) ** rng.integers(-3, 6, len(pixels))
    positions = [((u - K[2]) / K[0] * z, (v - K[3]) / K[1] * z, z) for (u, v), z in zip(pixels, depths)]
    mesh = softrast.Mesh(np.array(positions))
    out = softrast.Renderer(W, H, threads=1).render(mesh, fx=K[0], fy=K[1], cx=K[2], cy=K[3], points=True,
                                                    near=0.01, far=100, outputs=("depth", "face_ids"))
    for i, ((u, v), z) in enumerate(zip(pixels, depths)):
        assert out["face_ids"][v, u] == i + 1, (u, v)
        assert out["depth"][v, u] == z, (u, v, out["depth"][v, u], z)
    assert (out["face_ids"] > 0).sum() == len(pixels)


def test_a_point_of_size_3_covers_its_pixel_and_the_eight_round_it():
    # on the ray through pixel centre (32, 24): x = (32 - cx) / fx * z
    mesh = softrast.Mesh(np.array([[0.02, 0.02, 2.0]]))
    out = softrast.Renderer(W, H, threads=1).render(mesh, fx=K[0], fy=K[1], cx=K[2], cy=K[3], points=True,
                                                    point_size=3, outputs=("face_ids",))
    ys, xs = np.nonzero(out["face_ids"])
    assert sorted(set(xs)) == [31, 32, 33] and sorted(set(ys)) == [23, 24, 25] and len(xs) == 9


def test_render_many_stacks_the_clouds_views():
    positions, colours = cloud()
    mesh = softrast.Mesh(positions, colors=colours)
    poses = np.stack([look_pose(EYE, (0, 0, 0)), look_pose((2.5, -1.0, -1.5), (0.2, 0, 0))])
    r = softrast.Renderer(W, H, threads=2)
    many = r.render_many(mesh, poses, fx=K[0], outputs=("color", "depth", "face_ids"), points=True, point_size=2)
    for i, pose in enumerate(poses):
        one = r.render(mesh, fx=K[0], pose=pose, outputs=("color", "depth", "face_ids"), points=True, point_size=2)
        for name in ("color", "depth", "face_ids"):
            assert np.array_equal(many[name][i], one[name]), (i, name)
        assert many["stats"][i] == one["stats"]


@pytest.mark.parametrize("kw, message", [
    (dict(), "no faces .* points=True"),
    (dict(points=True, point_size=0.5), "point_size: 0.5 is not within 1 .. 256"),
    (dict(points=True, point_size=float("nan")), "point_size: nan"),
    (dict(points=True, point_size=257), "point_size: 257"),
])
def test_bad_point_renders_are_refused(kw, message):
    mesh = softrast.Mesh(np.array([[0.0, 0.0, 2.0]]))
    with pytest.raises(ValueError, match=message):
        softrast.Renderer(W, H, threads=1).render(mesh, fx=K[0], **kw)


def test_a_file_of_points_alone_loads_as_a_cloud(tmp_path):
    # a PLY and an OBJ of the same vertices alone (the OBJ without colours)
    positions, colours = cloud()
    write_ply(tmp_path / "cloud.ply", positions, colours)
    (tmp_path / "cloud.obj").write_text("".join("v %r %r %r\n" % tuple(map(float, p)) for p in positions))
    pose = look_pose(EYE, (0, 0, 0))
    views = []
    for name in ("cloud.ply", "cloud.obj"):
        mesh = softrast.Mesh.load(tmp_path / name)
        assert mesh.faces.shape == (0, 3) and len(mesh.positions) == 2000 and "0 triangles" in repr(mesh)
        views.append(softrast.Renderer(W, H, threads=1).render(mesh, fx=K[0], pose=pose, points=True,
                                                               outputs=("depth", "face_ids")))
    assert np.array_equal(views[0]["depth"], views[1]["depth"])
    assert np.array_equal(views[0]["face_ids"], views[1]["face_ids"]) and (views[0]["face_ids"] > 0).sum() > 500


def test_the_points_picture_script_draws_the_knot_cloud(png, root, tmp_path):
    out = tmp_path / "points.png"
    subprocess.run([sys.executable, os.path.join(root, "python", "examples", "points_picture.py"), str(out)],
                   check=True, capture_output=True)
    image = png.read_rgb_png(out)
    assert image.shape == (360, 1280, 3)
    colour, depth = image[:, :640], image[:, 640:]
    assert np.array_equal(colour.any(2), depth.any(2))  # each drawn pixel has its depth, and only those
    assert 30000 < colour.any(2).sum() < 100000


def test_a_cloud_with_points_at_nan_draws_the_rest():
    # a depth sensor's organised cloud marks a pixel without a return NaN:
    # the clip planes are fitted to the finite points, the NaN ones dropped
    rng = np.random.default_rng(0)
    positions = np.c_[rng.uniform(-1, 1, (1000, 2)), rng.uniform(2, 5, 1000)]
    positions[::10] = np.nan
    s = softrast.Renderer(W, H, threads=1).render(softrast.Mesh(positions), fx=K[0], points=True)["stats"]
    assert s["points"] == 1000 and s["nonfinite"] == 100 and s["drawn"] == 900
