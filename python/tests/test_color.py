"""The colour output: the command line's --shade images bit for bit, the
same triangles as the id view, the light in the poses' frame, vertex
colours and textures from arrays."""
import os

import numpy as np
import pytest

import softrast
from scenes import look_pose, write_obj

SHADES = ("lambert", "id", "color", "normal", "texture", "depth")
W, H, K = 96, 72, (70.0, 65.0, 47.25, 36.5)


def intrinsics():
    return dict(fx=K[0], fy=K[1], cx=K[2], cy=K[3])


def torus(root):
    return os.path.join(root, "assets", "torus.obj"), look_pose([1.3, -2.0, -2.4], [0.1, 0.05, 0.0])


def coloured_obj(tmp_path):
    """A random mesh whose OBJ carries vertex colours (v x y z r g b)."""
    rng = np.random.default_rng(5)
    positions = rng.uniform(-1, 1, (40, 3)).astype(np.float32)
    colors = rng.uniform(0, 1, (40, 3)).astype(np.float32)
    faces = rng.integers(0, 40, (60, 3))
    path = tmp_path / "c.obj"
    write_obj(path, positions, faces)
    lines = path.read_text().splitlines()
    for i, c in enumerate(colors):
        lines[i] += " %s %s %s" % tuple(repr(float(v)) for v in c)
    path.write_text("\n".join(lines) + "\n")
    return path, positions, faces, colors


@pytest.mark.parametrize("space", [None, "srgb", "raw"])
@pytest.mark.parametrize("shade", SHADES)
def test_color_equals_the_command_lines_image_bit_for_bit(cli, root, tmp_path, png, shade, space):
    """Each colour space as the command line's --color-space, and the
    default as its default (sRGB: the OBJ's vertex colours decoded)."""
    obj, pose = torus(root)
    if shade == "color":
        obj, *_ = coloured_obj(tmp_path)
        pose = look_pose([0.3, 0.2, -3.0], [0, 0, 0])
    cli("render", obj, "--size", f"{W}x{H}", "--intrinsics", ",".join(map(repr, K)), "--pose-w2c",
        ",".join(repr(float(v)) for v in pose.ravel()), "--shade", shade,
        *(["--color-space", space] if space else []), "--out", tmp_path / "c.png", "--quiet")
    want = png.read_rgb_png(tmp_path / "c.png")
    mesh = softrast.Mesh.load(obj)
    out = softrast.Renderer(W, H).render(mesh, **intrinsics(), pose=pose, outputs=("color", "face_ids"),
                                         shade=shade, **({"color_space": space} if space else {}))
    assert out["color"].shape == (H, W, 3) and out["color"].dtype == np.uint8 and out["color"].flags.owndata
    assert np.array_equal(out["color"], want)
    assert (out["face_ids"] > 0).sum() > 500 and len(np.unique(want.reshape(-1, 3), axis=0)) > 20


def test_a_mesh_from_its_own_arrays_gives_the_same_colour(root):
    obj, pose = torus(root)
    mesh = softrast.Mesh.load(obj)
    assert mesh.texture.shape == (256, 256, 3) and mesh.uvs.shape == (mesh.vertex_count, 2)
    arrays = softrast.Mesh(mesh.positions, mesh.faces, normals=mesh.normals, uvs=mesh.uvs, texture=mesh.texture)
    r = softrast.Renderer(W, H, threads=2)
    for shade in ("lambert", "normal", "texture"):
        kw = dict(intrinsics(), pose=pose, outputs=("color", "normals"), normals="interpolated", shade=shade)
        a, b = r.render(mesh, **kw), r.render(arrays, **kw)
        assert np.array_equal(a["color"], b["color"]), shade
        assert np.array_equal(a["normals"].view(np.uint32), b["normals"].view(np.uint32)), shade


def test_colour_and_ids_show_the_same_triangle_at_every_pixel(root):
    obj, pose = torus(root)
    mesh = softrast.Mesh.load(obj)
    r = softrast.Renderer(W, H, threads=2)
    many = r.render_many(mesh, np.stack([pose, look_pose([0.5, 2.5, 1.0], [0, 0, 0])]), **intrinsics(),
                         outputs=("color", "face_ids"), shade="id")
    rgb = many["color"].astype(np.uint32)
    assert np.array_equal(rgb[..., 0] << 16 | rgb[..., 1] << 8 | rgb[..., 2], many["face_ids"] & 0xFFFFFF)
    gray = softrast.Mesh(mesh.positions, mesh.faces)  # untextured: gray, lit at least by the ambient
    lit = r.render(gray, **intrinsics(), pose=pose, outputs=("color", "face_ids"))
    assert np.all(lit["color"][lit["face_ids"] == 0] == 0)  # nothing drawn: black
    assert np.all(lit["color"][lit["face_ids"] > 0].min(axis=1) > 0)


def square(z=1.0, **kw):
    """A square facing the camera at the origin (its normal toward it, -z), filling its view."""
    positions = np.array([[-1, -1, z], [1, -1, z], [1, 1, z], [-1, 1, z]], np.float64)
    return softrast.Mesh(positions, [[0, 2, 1], [0, 3, 2]], **kw)


def test_lambert_follows_the_light_given_in_the_poses_frame():
    r = softrast.Renderer(32, 32, threads=1)
    mesh = square()

    def gray(light):  # raw: the lit colour is the light's fraction, as stored
        c = r.render(mesh, fx=20, outputs=("color",), light=light, color_space="raw")["color"]
        assert np.all(c == c[16, 16]), "a flat square is lit evenly"
        return c[16, 16].astype(float)

    full, grazing, behind = gray((0, 0, -1)), gray((1, 0, 0)), gray((0, 0, 1))
    assert np.all(full > grazing) and np.array_equal(grazing, behind)  # ambient alone
    assert np.allclose(mesh.normals, [0, 0, -1])  # smooth normals made at the first lit render: e1 x e2
    half = gray((0, np.sin(np.pi / 3), -np.cos(np.pi / 3)))  # 60 degrees off the normal
    assert np.all(np.abs(half - (grazing + 0.5 * (full - grazing))) <= 1.0), (full, half, grazing)
    assert np.array_equal(gray((0, 0, -5)), full)  # a direction: its length does not count


def test_vertex_colours_are_read_as_floats_or_bytes():
    r = softrast.Renderer(32, 32, threads=1)
    floats = r.render(square(colors=np.tile([0.2, 0.4, 0.6], (4, 1))), fx=20, outputs=("color",), shade="color")
    c = floats["color"][16, 16]
    assert np.all(floats["color"] == c) and np.all(np.abs(c.astype(int) - [51, 102, 153]) <= 1)
    as_bytes = r.render(square(colors=np.tile(np.array([51, 102, 153], np.uint8), (4, 1))), fx=20,
                        outputs=("color",), shade="color")
    assert np.array_equal(as_bytes["color"], floats["color"])


@pytest.mark.parametrize("channels", [3, 4])
def test_a_texture_from_an_array_has_row_0_at_the_top_and_v_0_at_the_bottom(channels):
    texture = np.zeros((4, 4, channels), np.uint8)
    texture[:2, :, 0] = 255  # top half red
    texture[2:, :, 2] = 255  # bottom half blue
    if channels == 4:
        texture[..., 3] = 7  # alpha is not used
    uvs = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], np.float32)  # the square's bottom left is uv (0, 0)
    mesh = square(uvs=uvs, texture=texture)
    assert np.array_equal(mesh.texture, texture[..., :3])
    # turned half round the optical axis: the world's +y at the top of the image
    out = softrast.Renderer(64, 64, threads=1).render(mesh, fx=20, pose=np.diag([-1.0, -1.0, 1.0, 1.0]),
                                                      outputs=("color",), shade="texture")
    c = out["color"]  # the square spans rows 11.5 to 51.5: v 0.75 at row 21.5, 0.25 at 41.5 (texel row centres)
    assert np.all(c[20:24, 12:52] == [255, 0, 0]) and np.all(c[40:44, 12:52] == [0, 0, 255])


@pytest.mark.parametrize("kw, message", [
    (dict(shade="phong"), "shade: 'phong' is not one of 'lambert', 'id', 'color', 'normal', 'texture', 'depth'"),
    (dict(shade=3), "shade: 3 is not one of"),
    (dict(light=(0, 0, 0)), r"light: \(0, 0, 0\) has no direction"),
    (dict(light=(0, np.nan, 1)), "light: every entry must be finite"),
    (dict(light=(0, 1)), r"light: shape \(2,\) where \(3,\)"),
    (dict(shade="color"), "color shading needs vertex colors and the mesh has none"),
    (dict(shade="texture"), "texture shading needs texture coordinates and a texture"),
])
def test_a_bad_shading_is_refused_with_one_line(kw, message):
    with pytest.raises(ValueError, match=message):
        softrast.Renderer(16, 16).render(square(), fx=10, outputs=("color",), **kw)


def test_a_renderer_made_again_at_another_size_draws_colour_at_that_size():
    r = softrast.Renderer(48, 32, threads=1)
    mesh = square(colors=np.tile([0.2, 0.4, 0.6], (4, 1)))
    first = r.render(mesh, fx=20, outputs=("color",), shade="color")["color"]
    r.__init__(24, 16, threads=2)
    again = r.render(mesh, fx=20, cx=23.5, cy=15.5, outputs=("color",), shade="color")["color"]
    assert first.shape == (32, 48, 3) and again.shape == (16, 24, 3)
    assert np.array_equal(again, first[:16, :24])  # the same camera, its top-left corner


@pytest.mark.parametrize("shade", SHADES)
def test_colour_and_depth_come_from_one_draw(root, tmp_path, shade):
    """A render of colour (in any shading) and every other output counts
    one draw's triangles and fragments: the same counts as depth alone."""
    obj, pose = torus(root)
    if shade == "color":
        obj, *_ = coloured_obj(tmp_path)
        pose = look_pose([0.3, 0.2, -3.0], [0, 0, 0])
    mesh = softrast.Mesh.load(obj)
    r = softrast.Renderer(W, H, threads=2)
    everything = r.render(mesh, **intrinsics(), pose=pose, shade=shade,
                          outputs=("color", "depth", "range", "face_ids", "part_ids", "normals"))
    depth = r.render(mesh, **intrinsics(), pose=pose, outputs="depth")
    s = everything["stats"]
    assert s == depth["stats"] and mesh.triangle_count // 2 < s["triangles"] <= mesh.triangle_count
    assert s["fragments"] >= (everything["face_ids"] > 0).sum() > 500
    assert np.array_equal(everything["depth"], depth["depth"])


def test_every_thread_count_gives_the_same_outputs(root):
    obj, pose = torus(root)
    mesh = softrast.Mesh.load(obj)
    outputs = ("color", "depth", "range", "face_ids", "part_ids", "normals")
    one = softrast.Renderer(W, H, threads=1).render(mesh, **intrinsics(), pose=pose, outputs=outputs)
    for threads in (2, 3, 7):
        many = softrast.Renderer(W, H, threads=threads).render(mesh, **intrinsics(), pose=pose, outputs=outputs)
        for name in outputs:
            assert np.array_equal(one[name], many[name]), (threads, name)
