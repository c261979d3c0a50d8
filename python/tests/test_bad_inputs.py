"""Whatever is passed, an exception with one line, never a crash: wrong
dtypes and shapes, NaN, bad cameras, indices out of range, empty meshes;
non-contiguous and read-only arrays are read as they are."""
import numpy as np
import pytest

import softrast
from scenes import INTRINSICS, TRIANGLE, TRIANGLE_FACES, TRIANGLE_POSE

MESH = softrast.Mesh(TRIANGLE, TRIANGLE_FACES)


def render(mesh=MESH, **kw):
    args = dict(INTRINSICS, pose=TRIANGLE_POSE)
    args.update(kw)
    return softrast.Renderer(40, 30, threads=1).render(mesh, **args)


@pytest.mark.parametrize("positions, faces, message", [
    (TRIANGLE.astype(np.complex64), TRIANGLE_FACES, "positions: dtype complex64 is not a real number type"),
    (TRIANGLE > 0, TRIANGLE_FACES, "positions: dtype bool"),
    (np.array([["a", "b", "c"]] * 3), TRIANGLE_FACES, "positions: dtype <U1"),
    (np.array([[0, 0, 1]] * 3, dtype=object), TRIANGLE_FACES, "positions: dtype object"),
    (TRIANGLE[:, :2], TRIANGLE_FACES, r"positions: shape \(3, 2\) where \(N, 3\) is wanted"),
    (TRIANGLE.ravel(), TRIANGLE_FACES, r"positions: shape \(9,\)"),
    ([[0, 0, 1], [1, 0]], TRIANGLE_FACES, "positions: not an array"),
    ("triangle", TRIANGLE_FACES, "positions: dtype <U8"),
    (TRIANGLE, TRIANGLE_FACES.astype(np.float32), "faces: dtype float32 is not an integer type"),
    (TRIANGLE, [0, 1, 2], r"faces: shape \(3,\) where \(M, 3\)"),
    (TRIANGLE, [[0, 1, 2, 0]], r"faces: shape \(1, 4\)"),
    (TRIANGLE, [[0, -1, 2]], r"faces\[0, 1\] = -1"),
    (TRIANGLE, np.array([[0, 1, 2**40]]), r"faces\[0, 2\] = 1099511627776"),
    (np.zeros((0, 3)), np.zeros((0, 3), int), "an empty mesh"),
    (np.zeros((0, 3)), None, "an empty mesh"),
])
def test_a_bad_mesh_is_refused(positions, faces, message):
    with pytest.raises(ValueError, match=message):
        softrast.Mesh(positions, faces)


@pytest.mark.parametrize("kw, message", [
    (dict(normals=np.zeros((2, 3))), r"normals: shape \(2, 3\)"),
    (dict(colors=np.zeros((3, 4))), r"colors: shape \(3, 4\)"),
    (dict(colors=[["r", "g", "b"]] * 3), "colors: dtype"),
])
def test_bad_attributes_are_refused(kw, message):
    with pytest.raises(ValueError, match=message):
        softrast.Mesh(TRIANGLE, TRIANGLE_FACES, **kw)


def test_an_index_past_the_vertices_is_refused_by_the_draw():
    mesh = softrast.Mesh(TRIANGLE, [[0, 1, 3]])
    with pytest.raises(ValueError, match="index"):
        render(mesh)
    with pytest.raises(ValueError, match="index"):
        render(mesh, outputs=("normals",), normals="interpolated")


def test_non_contiguous_read_only_and_other_dtypes_are_read_as_they_are():
    want = render()["depth"]
    wide = np.zeros((3, 6), np.float64)
    wide[:, ::2] = TRIANGLE
    strided = wide[:, ::2]
    assert not strided.flags.c_contiguous
    frozen = TRIANGLE.copy()
    frozen.flags.writeable = False
    faces = TRIANGLE_FACES.astype(np.uint16)
    faces.flags.writeable = False
    big_endian = TRIANGLE.astype(">f8")
    for positions, f in [(strided, TRIANGLE_FACES), (frozen, faces), (big_endian, TRIANGLE_FACES[:, ::1].T.T),
                         (TRIANGLE.tolist(), TRIANGLE_FACES.tolist()), (TRIANGLE.T.copy().T, TRIANGLE_FACES)]:
        assert np.array_equal(render(softrast.Mesh(positions, f))["depth"], want)
    pose = np.asfortranarray(TRIANGLE_POSE)
    assert np.array_equal(render(pose=pose)["depth"], want)


def test_nan_positions_are_dropped_and_counted():
    positions = np.vstack([TRIANGLE, [[np.nan, 0, 4], [1, np.inf, 4], [0, 1, 4]]])
    out = render(softrast.Mesh(positions, [[0, 1, 2], [3, 4, 5]]), near=0.1, far=100)
    assert out["stats"]["nonfinite"] == 1 and out["stats"]["drawn"] == 1
    assert set(np.unique(out["depth"])) == {0.0, 4.0}


NOT_RIGID = np.diag([2.0, 2.0, 2.0, 1.0])
MIRROR = np.diag([1.0, 1.0, -1.0, 1.0])


@pytest.mark.parametrize("kw, message", [
    (dict(fx=np.nan), "intrinsics fx, fy, cx, cy must be finite"),
    (dict(fx=0.0), "fx and fy must be above 0"),
    (dict(fy=-1.0), "fx and fy must be above 0"),
    (dict(fx="wide"), "fx: 'wide' is not a number"),
    (dict(K=np.eye(3), fx=None, fy=None, cx=None, cy=None, pose=NOT_RIGID), "not a rigid pose"),
    (dict(pose=MIRROR), "not a rigid pose"),
    (dict(pose=np.full((4, 4), np.nan)), "every entry must be finite"),
    (dict(pose=np.eye(3)), r"pose: shape \(3, 3\) where \(4, 4\)"),
    (dict(pose=None, pose_c2w=NOT_RIGID), "camera-to-world pose is not a rigid pose"),
    (dict(pose_c2w=np.eye(4)), "give one of pose and pose_c2w, not both"),
    (dict(K=np.eye(3)), "give the intrinsics as K or as fx, fy, cx, cy, not both"),
    (dict(fx=None, fy=None, cx=None, cy=None), "give the intrinsics"),
    (dict(fx=None), "fy, cx and cy need fx"),
    (dict(fx=None, fy=None, cx=None, cy=None, K=[[1, 0.1, 0], [0, 1, 0], [0, 0, 1]]), "no skew"),
    (dict(fx=None, fy=None, cx=None, cy=None, K=np.eye(4)), r"K: shape \(4, 4\)"),
    (dict(near=5.0, far=1.0), "clip planes need 0 < near < far"),
    (dict(near=1.0), "clip planes need 0 < near < far"),
    (dict(far=np.inf, near=1.0), "clip planes need 0 < near < far"),
    (dict(outputs=("depth", "colour")), "outputs: 'colour' is not one of"),
    (dict(outputs=("depth", 3)), "outputs: 3 is not one of"),
    (dict(outputs="nonsense"), "outputs: 'nonsense'"),
    (dict(normals="smooth"), "normals: 'smooth' is not 'geometric' or 'interpolated'"),
])
def test_a_bad_camera_or_request_is_refused_with_one_line(kw, message):
    with pytest.raises(ValueError, match=message):
        render(**kw)


def test_render_many_names_the_bad_pose():
    poses = np.stack([TRIANGLE_POSE, NOT_RIGID])
    r = softrast.Renderer(40, 30)
    with pytest.raises(ValueError, match=r"poses\[1\]: the world-to-camera pose is not a rigid pose"):
        r.render_many(MESH, poses, **INTRINSICS)
    with pytest.raises(ValueError, match=r"poses_c2w\[1\]: the camera-to-world pose"):
        r.render_many(MESH, poses_c2w=poses, **INTRINSICS)
    with pytest.raises(ValueError, match=r"poses: shape \(4, 4\) where \(N, 4, 4\)"):
        r.render_many(MESH, TRIANGLE_POSE, **INTRINSICS)
    with pytest.raises(ValueError, match="render_many needs poses"):
        r.render_many(MESH, **INTRINSICS)


@pytest.mark.parametrize("args, message", [
    ((0, 10), "side"), ((10, -3), "side"), ((20000, 10), "side"), ((10, 10, -1), "threads: -1"),
])
def test_a_bad_renderer_is_refused(args, message):
    with pytest.raises(ValueError, match=message):
        softrast.Renderer(*args)


def test_wrong_python_types_raise_type_errors():
    r = softrast.Renderer(8, 8)
    with pytest.raises(TypeError):
        r.render(TRIANGLE, fx=1)  # a mesh must be a softrast.Mesh
    with pytest.raises(TypeError):
        softrast.Renderer("8", 8)
    with pytest.raises(TypeError):
        r.render(MESH, 5.0)  # everything but the mesh is a keyword
    with pytest.raises(TypeError, match="outputs: a sequence of names"):
        r.render(MESH, fx=1, outputs=5)


def test_an_uninitialised_mesh_or_renderer_is_refused():
    with pytest.raises(ValueError, match="empty"):
        render(softrast.Mesh.__new__(softrast.Mesh))
    with pytest.raises(RuntimeError, match="__init__"):
        softrast.Renderer.__new__(softrast.Renderer).render(MESH, fx=1)


def test_files_that_cannot_be_read_raise_os_errors(tmp_path):
    with pytest.raises(OSError, match="missing.obj"):
        softrast.Mesh.load(tmp_path / "missing.obj")
    (tmp_path / "bad.obj").write_text("v 1 2\nf 1 2 3\n")
    with pytest.raises(OSError, match="bad.obj:1"):
        softrast.Mesh.load(tmp_path / "bad.obj")
    with pytest.raises(OSError):
        softrast.Mesh.load(tmp_path)  # a directory
    (tmp_path / "empty.obj").write_text("# nothing\n")
    with pytest.raises(ValueError, match="an empty mesh"):
        softrast.Mesh.load(tmp_path / "empty.obj")
    with pytest.raises(TypeError):
        softrast.Mesh.load(3)
