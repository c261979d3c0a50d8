"""Mesh attributes from arrays: normals, uvs, colours, part ids and a
texture, validated; positions far from the origin kept to float precision
through the mesh's double origin."""
import os

import numpy as np
import pytest

import softrast
from scenes import INTRINSICS, TRIANGLE, TRIANGLE_FACES, TRIANGLE_POSE, look_pose

UVS = np.zeros((3, 2))
TEXTURE = np.zeros((2, 2, 3), np.uint8)


@pytest.mark.parametrize("kw, message", [
    (dict(normals=[[0, 0, 1], [0, np.nan, 1], [0, 0, 1]]), r"normals\[1, 1\] = nan: not a finite float32"),
    (dict(normals=np.full((3, 3), 1e39)), r"normals\[0, 0\] = 1e\+39: not a finite float32"),
    (dict(uvs=[[0, 0], [1, 0], [np.inf, 1]]), r"uvs\[2, 0\] = inf"),
    (dict(uvs=np.zeros((3, 3))), r"uvs: shape \(3, 3\) where \(N, 2\)"),
    (dict(uvs=np.zeros((2, 2))), r"uvs: shape \(2, 2\)"),
    (dict(colors=[[0, 0, 0], [0, 1.5, 0], [0, 0, 0]]), r"colors\[1, 1\] = 1.5: colours are 0..1"),
    (dict(colors=np.full((3, 3), -0.25)), r"colors\[0, 0\] = -0.25"),
    (dict(colors=np.full((3, 3), np.nan)), r"colors\[0, 0\] = nan"),
    (dict(colors=np.full((3, 3), 255)), r"colors\[0, 0\] = 255: colours are 0..1 \(or uint8\)"),
    (dict(part_ids=[0]), r"part_ids\[0\] = 0: part ids are 1 to"),
    (dict(part_ids=[2**32]), r"part_ids\[0\] = 4294967296"),
    (dict(part_ids=[1, 2]), r"part_ids: shape \(2,\) where \(M,\)"),
    (dict(part_ids=[1.5]), "part_ids: dtype float64 is not an integer type"),
    (dict(uvs=UVS, texture=np.zeros((2, 2, 3))), "texture: dtype float64 is not uint8"),
    (dict(uvs=UVS, texture=np.zeros((2, 2), np.uint8)), r"texture: shape \(2, 2\) where \(H, W, 3\)"),
    (dict(uvs=UVS, texture=np.zeros((2, 2, 2), np.uint8)), r"texture: shape \(2, 2, 2\)"),
    (dict(uvs=UVS, texture=np.zeros((0, 2, 3), np.uint8)), "texture: 2 x 0 texels; each side 1 to 16384"),
    (dict(uvs=UVS, texture=np.broadcast_to(TEXTURE[:1, :1], (1, 16385, 3))), "texture: 16385 x 1 texels"),
    (dict(uvs=UVS, texture=[[["a", "b", "c"]]]), "texture: dtype <U1 is not uint8"),
    (dict(texture=TEXTURE), r"texture: needs uvs, \(N, 2\)"),
])
def test_bad_attributes_are_refused_with_one_line(kw, message):
    with pytest.raises(ValueError, match=message):
        softrast.Mesh(TRIANGLE, TRIANGLE_FACES, **kw)


def test_attributes_in_any_layout_are_read_as_they_are():
    rng = np.random.default_rng(2)
    normals = rng.normal(size=(3, 3))
    uvs, colors = rng.uniform(0, 1, (3, 2)), rng.uniform(0, 1, (3, 3))
    texture = rng.integers(0, 256, (5, 7, 4), dtype=np.uint8)
    plain = softrast.Mesh(TRIANGLE, TRIANGLE_FACES, normals=normals, colors=colors, uvs=uvs, texture=texture)
    wide = np.zeros((3, 8))
    wide[:, ::2][:, :3] = normals  # a strided view
    ro = np.asfortranarray(colors)
    ro.flags.writeable = False
    odd = softrast.Mesh(TRIANGLE, TRIANGLE_FACES, normals=wide[:, ::2][:, :3], colors=ro, uvs=uvs.astype(">f8"),
                        texture=texture[:, ::-1][:, ::-1])
    for name in ("normals", "colors", "uvs", "texture"):
        assert np.array_equal(getattr(plain, name), getattr(odd, name)), name
    assert np.array_equal(plain.normals, normals.astype(np.float32))  # given back in the file's frame
    assert np.array_equal(plain.texture, texture[..., :3])


def two_squares(part_ids):
    """Four squares side by side at z = 4, two triangles each, seen from the origin."""
    positions, faces = [], []
    for k in range(4):
        x = -2.0 + k
        base = len(positions)
        positions += [[x, -0.5, 4], [x + 1, -0.5, 4], [x + 1, 0.5, 4], [x, 0.5, 4]]
        faces += [[base, base + 1, base + 2], [base, base + 2, base + 3]]
    return softrast.Mesh(np.array(positions), faces, part_ids=part_ids)


@pytest.mark.parametrize("ids", [[7, 7, 3, 3, 7, 7, 9, 9], [1, 1, 2, 2, 3, 3, 4, 4], [5] * 8,
                                 [4000000000, 4000000000, 1, 1, 2, 2, 1, 1]])
def test_part_ids_from_arrays_come_back_per_pixel(ids):
    mesh = two_squares(np.array(ids, np.int64))
    assert mesh.part_count == max(ids)
    out = softrast.Renderer(80, 20, threads=1).render(mesh, fx=40, outputs=("part_ids", "face_ids"))
    faces, parts = out["face_ids"], out["part_ids"]
    assert len(np.unique(faces)) == 9  # every triangle seen, and the background
    lookup = np.array([0] + ids, np.uint32)
    assert np.array_equal(parts, lookup[faces])


def test_a_mesh_without_part_ids_is_part_1():
    out = softrast.Renderer(40, 30, threads=1).render(softrast.Mesh(TRIANGLE, TRIANGLE_FACES), **INTRINSICS,
                                                      pose=TRIANGLE_POSE, outputs=("part_ids", "face_ids"))
    assert np.array_equal(out["part_ids"], out["face_ids"])


def translated(w2c, offset):
    """The pose seeing the mesh moved by offset as w2c saw it: w2c . T(-offset)."""
    moved = w2c.copy()
    moved[:3, 3] -= w2c[:3, :3] @ offset
    return moved


def test_a_mesh_far_from_the_origin_renders_the_depth_it_has_at_the_origin(root):
    mesh = softrast.Mesh.load(os.path.join(root, "assets", "torus.obj"))
    positions, faces = mesh.positions.astype(np.float64), mesh.faces
    pose = look_pose([1.3, -2.0, -2.4], [0.1, 0.05, 0.0])
    r = softrast.Renderer(96, 72, threads=2)
    kw = dict(fx=70.0, fy=65.0, cx=47.25, cy=36.5, outputs=("depth", "face_ids"))
    near = r.render(softrast.Mesh(positions, faces), pose=pose, **kw)
    drawn = near["face_ids"] > 0
    assert drawn.sum() > 1000
    for offset in ([1e7, 0, 0], [-3e6, 1e7, 2.5e6], [0, 0, -1e7]):
        offset = np.array(offset)
        far_mesh = softrast.Mesh(positions + offset, faces)
        assert far_mesh.positions.dtype == np.float64  # kept relative to a double origin
        assert np.allclose(far_mesh.positions, positions + offset, rtol=0, atol=1e-6)
        far = r.render(far_mesh, pose=translated(pose, offset), **kw)
        same = drawn & (far["face_ids"] == near["face_ids"])
        assert same.sum() > 0.99 * drawn.sum(), offset
        # positions rounded to float relative to the mesh's centre instead of
        # the world's: a float rounding of the torus (size ~3) in each
        # vertex, and of the depth
        err = np.abs(far["depth"][same] / near["depth"][same] - 1)
        assert err.max() <= 2.0**-22, (offset, err.max())
        # float32 positions at 1e7 are whole numbers: the torus is lost
        lost = r.render(softrast.Mesh((positions + offset).astype(np.float32), faces), pose=translated(pose, offset),
                        **kw)
        assert (drawn & (lost["face_ids"] == near["face_ids"])).sum() < 0.5 * drawn.sum()
