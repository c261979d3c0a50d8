"""A glTF MASK cut-out is a hole in depth and ids as in the colour image:
the draw without a colour output (ids alone), every shading and the
command line's --shade id see the same coverage as lambert."""
import base64
import json
import struct
import zlib

import numpy as np
import pytest

import softrast
from test_blend import CAMERA, CLI_CAMERA, POSE, SIDE


def write_rgba_png(path, img):
    h, w, _ = img.shape
    raw = b"".join(b"\0" + img[y].tobytes() for y in range(h))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) +
                     chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def mask_square(tmp_path):
    """A square over [-2, 2]^2 in z = 0 (the whole view), MASK on a 2x1
    texture whose left texel has alpha 0, the right 255; u runs from the
    left texel's centre (0.25) to the right's (0.75), so the bilinear alpha
    rises across the square without wrapping and the left half is cut."""
    write_rgba_png(tmp_path / "leaf.png", np.array([[[255, 0, 0, 0], [0, 255, 0, 255]]], np.uint8))
    positions = np.array([[-2, -2, 0], [2, -2, 0], [2, 2, 0], [-2, 2, 0]], np.float32).tobytes()
    uvs = np.array([[0.25, 1], [0.75, 1], [0.75, 0], [0.25, 0]], np.float32).tobytes()
    indices = np.array([0, 1, 2, 0, 2, 3], np.uint16).tobytes()
    data = base64.b64encode(positions + uvs + indices).decode()
    doc = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "buffers": [{"byteLength": 92, "uri": "data:application/octet-stream;base64," + data}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                        {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [-2, -2, 0], "max": [2, 2, 0]},
                      {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                      {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
        "images": [{"uri": "leaf.png"}], "textures": [{"source": 0}],
        "materials": [{"alphaMode": "MASK", "alphaCutoff": 0.5,
                       "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
    }
    path = tmp_path / "leaf.gltf"
    path.write_text(json.dumps(doc))
    return path


def test_mask_holes_are_holes_in_depth_and_ids_in_every_shading(cli, tmp_path):
    path = mask_square(tmp_path)
    mesh = softrast.Mesh.load(path)
    r = softrast.Renderer(SIDE, SIDE, threads=2)
    lit = r.render(mesh, **CAMERA, pose=POSE, outputs=("color", "face_ids", "depth"), shade="lambert")
    drawn = lit["face_ids"] > 0
    # the left half cut (x < 0 is columns 0..19), the right half drawn
    assert not drawn[:, :18].any() and drawn[:, 22:].all()
    bare = r.render(mesh, **CAMERA, pose=POSE, outputs=("face_ids", "depth"))  # an id draw: no colour
    assert np.array_equal(bare["face_ids"], lit["face_ids"])
    assert np.array_equal(bare["depth"].view(np.uint32), lit["depth"].view(np.uint32))
    for shade in ("id", "normal", "depth", "texture"):
        out = r.render(mesh, **CAMERA, pose=POSE, outputs=("color", "face_ids"), shade=shade)
        assert np.array_equal(out["face_ids"], lit["face_ids"]), shade
    # the command line's id draw loads the texture for its alpha too
    cli("render", path, *CLI_CAMERA, "--shade", "id", "--face-ids", tmp_path / "f.npy", "--quiet")
    assert np.array_equal(np.load(tmp_path / "f.npy"), lit["face_ids"])


@pytest.mark.parametrize("shade", ["id", "depth", "normal"])
def test_the_command_lines_coverage_is_lamberts_in_every_shading(cli, png, tmp_path, shade):
    path = mask_square(tmp_path)
    cli("render", path, *CLI_CAMERA, "--shade", "lambert", "--view-depth", tmp_path / "lit.npy", "--quiet")
    cli("render", path, *CLI_CAMERA, "--shade", shade, "--view-depth", tmp_path / "d.npy", "--quiet")
    lit, depth = np.load(tmp_path / "lit.npy"), np.load(tmp_path / "d.npy")
    assert np.array_equal(depth.view(np.uint32), lit.view(np.uint32))
    assert (lit > 0).sum() > 300 and not (lit[:, :18] > 0).any()
