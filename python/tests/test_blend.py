"""A glTF's BLEND parts drawn as the command line draws them (blended over
the rest, farthest first; writing no depth and no ids), and the colour
space: the command line's --color-space, sRGB by default."""
import base64
import json

import numpy as np
import pytest

import softrast

SIDE = 40
# A pinhole 10 in front of the plane z = 0 of the file, looking down -z:
# 1 unit is 10 pixels there, and (0, 0) is seen between pixels 19 and 20.
POSE = np.array([[1, 0, 0, 0], [0, -1, 0, 0], [0, 0, -1, 10], [0, 0, 0, 1]], np.float64)
CAMERA = dict(fx=100.0, fy=100.0, cx=19.5, cy=19.5)
CLI_CAMERA = ("--size", f"{SIDE}x{SIDE}", "--intrinsics", "100,100,19.5,19.5",
              "--pose-w2c", ",".join(repr(v) for v in POSE.ravel()))


def squares_gltf(path, squares, colour=None):
    """A glTF of unit squares in z = 0 (front side +z), one node and
    material each: squares are ((x, y, z), scale, (r, g, b, a), alpha_mode);
    with colour, every vertex's COLOR_0 (linear, as glTF says)."""
    positions = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], np.float32).tobytes()
    indices = np.array([0, 1, 2, 0, 2, 3], np.uint16).tobytes()
    colours = np.tile(np.float32(colour if colour is not None else 0), (4, 3)).tobytes()
    data = base64.b64encode(positions + indices + colours).decode()
    attributes = {"POSITION": 0, **({"COLOR_0": 2} if colour is not None else {})}
    doc = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(len(squares)))}],
        "buffers": [{"byteLength": 108, "uri": "data:application/octet-stream;base64," + data}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 12},
                        {"buffer": 0, "byteOffset": 60, "byteLength": 48}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
                      {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC3"}],
        "nodes": [{"mesh": i, "translation": list(at), "scale": [scale, scale, 1]}
                  for i, (at, scale, _, _) in enumerate(squares)],
        "materials": [{"alphaMode": mode, "pbrMetallicRoughness": {"baseColorFactor": list(rgba)}}
                      for _, _, rgba, mode in squares],
        "meshes": [{"primitives": [{"attributes": attributes, "indices": 1, "material": i}]}
                   for i in range(len(squares))],
    }
    path.write_text(json.dumps(doc))
    return path


# Nearest the camera first, so the file's order is not back to front: a
# green BLEND square of alpha 0.5 at z = 2 (8 from the camera) over
# [-0.5, 0.5]^2, a blue one at z = 1 (9 from it) over [-1, 0] x [-0.5, 0.5],
# an opaque red one at z = 0 over [-2, 2]^2, the whole view.
SQUARES = [((-0.5, -0.5, 2), 1, (0, 1, 0, 0.5), "BLEND"), ((-1, -0.5, 1), 1, (0, 0, 1, 0.5), "BLEND"),
           ((-2, -2, 0), 4, (1, 0, 0, 1), "OPAQUE")]
# Pixels (row, column) under both translucent squares, under blue alone,
# under green alone and under neither, and their colours drawn raw, by
# hand (alpha 0.5 is 128/256; a channel is (s*128 + d*128 + 128) >> 8):
# blue blended first, then green over it.
PIXELS = [(19, 17), (19, 11), (19, 23), (2, 2)]
RAW = [(64, 128, 64), (128, 0, 128), (128, 128, 0), (255, 0, 0)]


@pytest.fixture
def squares(tmp_path):
    return squares_gltf(tmp_path / "squares.gltf", SQUARES)


@pytest.mark.parametrize("shade", ["texture", "lambert"])
@pytest.mark.parametrize("space", [None, "raw"])
def test_blend_parts_are_drawn_as_the_command_line_draws_them(cli, png, tmp_path, squares, shade, space):
    cli("render", squares, *CLI_CAMERA, "--shade", shade, *(["--color-space", space] if space else []),
        "--out", tmp_path / "c.png", "--quiet")
    want = png.read_rgb_png(tmp_path / "c.png")
    out = softrast.Renderer(SIDE, SIDE, threads=2).render(
        softrast.Mesh.load(squares), **CAMERA, pose=POSE, outputs=("color",), shade=shade,
        **({"color_space": space} if space else {}))
    assert np.array_equal(out["color"], want)
    assert out["stats"]["triangles"] == 6  # each once: the opaque draw leaves the BLEND parts' out
    if shade == "texture" and space == "raw":
        assert [tuple(out["color"][p]) for p in PIXELS] == RAW
    if shade == "texture" and space is None:  # blended in linear light: green over blue over red, decoded
        assert tuple(out["color"][PIXELS[0]]) != RAW[0] and tuple(out["color"][PIXELS[3]]) == RAW[3]


@pytest.mark.parametrize("shade", ["lambert", "texture", "id", "normal", "depth"])
def test_blend_parts_write_no_depth_and_no_ids_in_any_shading(squares, shade):
    """Depth, ids and normals are the opaque square's under the translucent
    ones, whether colour is asked for (the layers) or not (an id draw)."""
    mesh = softrast.Mesh.load(squares)
    r = softrast.Renderer(SIDE, SIDE, threads=2)
    planes = ("depth", "range", "face_ids", "part_ids", "normals")
    for outputs in (planes, ("color",) + planes):
        out = r.render(mesh, **CAMERA, pose=POSE, outputs=outputs, shade=shade)
        assert np.all(np.abs(out["depth"] - 10) <= 1e-5), outputs
        red = out["part_ids"][PIXELS[3]]
        assert np.all(out["part_ids"] == red) and red == 3  # the file's third mesh, in node order
        assert np.all((out["face_ids"] == 5) | (out["face_ids"] == 6))  # its two triangles
        assert np.allclose(out["normals"], [0, 0, -1])  # facing the camera


def test_a_mesh_without_blend_parts_draws_as_one_draw(squares, tmp_path):
    """Drawn opaque, the squares show what MASK would: green in front."""
    opaque = [(at, scale, rgba[:3] + (1,), "OPAQUE") for at, scale, rgba, _ in SQUARES]
    mesh = softrast.Mesh.load(squares_gltf(tmp_path / "opaque.gltf", opaque))
    out = softrast.Renderer(SIDE, SIDE).render(mesh, **CAMERA, pose=POSE, outputs=("color", "depth"),
                                               shade="texture", color_space="raw")
    assert [tuple(out["color"][p]) for p in PIXELS] == [(0, 255, 0), (0, 0, 255), (0, 255, 0), (255, 0, 0)]
    assert out["depth"][PIXELS[0]] == pytest.approx(8) and out["depth"][PIXELS[1]] == pytest.approx(9)


def gray_square(tmp_path, base):
    """One opaque square of a linear base colour over the whole view."""
    return softrast.Mesh.load(squares_gltf(tmp_path / "gray.gltf", [((-2, -2, 0), 4, (base,) * 3 + (1,), "OPAQUE")]))


def test_a_base_colour_is_linear_under_srgb_and_as_stored_raw(cli, png, tmp_path):
    """A glTF base colour of 0.5 is 188 by default (encoded: 187.5 rounds
    up), 128 raw: unlit, and lit head-on by lambert (0.2 + 0.8 n.l = 1)."""
    mesh = gray_square(tmp_path, 0.5)
    r = softrast.Renderer(SIDE, SIDE)
    head_on = (0, 0, 1)  # toward the light from the square: toward the camera
    for shade in ("texture", "lambert"):
        default = r.render(mesh, **CAMERA, pose=POSE, outputs=("color",), shade=shade, light=head_on)["color"]
        srgb = r.render(mesh, **CAMERA, pose=POSE, outputs=("color",), shade=shade, light=head_on,
                        color_space="srgb")["color"]
        raw = r.render(mesh, **CAMERA, pose=POSE, outputs=("color",), shade=shade, light=head_on,
                       color_space="raw")["color"]
        assert np.all(default == 188) and np.array_equal(srgb, default) and np.all(raw == 128), shade


def test_lambert_of_a_base_colour_is_the_command_lines_pixel(cli, png, tmp_path):
    """Lit by the default light, at a slant: the same pixel as `render`'s in
    either colour space, and under sRGB the raw fraction of the light
    applied in linear light (within one step of the encoding)."""
    mesh = gray_square(tmp_path, 0.5)
    r = softrast.Renderer(SIDE, SIDE)
    got = {}
    for space in ("srgb", "raw"):
        cli("render", tmp_path / "gray.gltf", *CLI_CAMERA, "--color-space", space, "--out", tmp_path / "c.png",
            "--quiet")
        want = png.read_rgb_png(tmp_path / "c.png")
        got[space] = r.render(mesh, **CAMERA, pose=POSE, outputs=("color",), color_space=space)["color"]
        assert np.array_equal(got[space], want), space
    light = got["raw"][20, 20, 0] / 127.5  # raw: 0.5 times the lambert factor, as stored
    encoded = 255 * (1.055 * (0.5 * light) ** (1 / 2.4) - 0.055)
    assert 0.25 < light < 0.99 and abs(int(got["srgb"][20, 20, 0]) - encoded) <= 1


def test_display_colours_are_decoded_under_srgb_as_the_command_line_does():
    """Colours from arrays are display values, as a PLY's: shade="color"
    gives them back under either space; lambert lights them in linear light."""
    positions = np.array([[-2, -2, 0], [2, -2, 0], [2, 2, 0], [-2, 2, 0]], np.float64)
    mesh = softrast.Mesh(positions, [[0, 1, 2], [0, 2, 3]], colors=np.full((4, 3), 128, np.uint8))
    r = softrast.Renderer(SIDE, SIDE)
    for space in ("srgb", "raw"):
        out = r.render(mesh, **CAMERA, pose=POSE, outputs=("color",), shade="color", color_space=space)["color"]
        assert np.all(out == 128), space
    assert np.array_equal(mesh.colors, np.full((4, 3), 128 / 255, np.float32))  # kept as given
    lit = {space: r.render(mesh, **CAMERA, pose=POSE, outputs=("color",), color_space=space)["color"][20, 20, 0]
           for space in ("srgb", "raw")}
    assert lit["srgb"] != lit["raw"]


def test_a_gltfs_vertex_colours_are_linear_as_on_the_command_line(cli, png, tmp_path):
    """COLOR_0 of 0.5 is linear light: 188 under sRGB (not decoded), 128 raw."""
    path = squares_gltf(tmp_path / "coloured.gltf", [((-2, -2, 0), 4, (1, 1, 1, 1), "OPAQUE")], colour=0.5)
    mesh = softrast.Mesh.load(path)
    r = softrast.Renderer(SIDE, SIDE)
    for space, value in (("srgb", 188), ("raw", 128)):
        cli("render", path, *CLI_CAMERA, "--shade", "color", "--color-space", space, "--out", tmp_path / "c.png",
            "--quiet")
        out = r.render(mesh, **CAMERA, pose=POSE, outputs=("color",), shade="color", color_space=space)["color"]
        assert np.all(out == value) and np.array_equal(out, png.read_rgb_png(tmp_path / "c.png")), space


@pytest.mark.parametrize("space, message", [("linear", "color_space: 'linear' is not 'srgb' or 'raw'"),
                                            (1, "color_space: 1 is not 'srgb' or 'raw'")])
def test_a_bad_colour_space_is_refused_with_one_line(space, message):
    mesh = softrast.Mesh([[0, 0, 1], [1, 0, 1], [0, 1, 1]], [[0, 1, 2]])
    with pytest.raises(ValueError, match=message):
        softrast.Renderer(8, 8).render(mesh, fx=4, outputs=("color",), color_space=space)
