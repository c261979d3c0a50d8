"""What render returns: the C suite's exact cases, the command line's files
bit for bit, the pinhole formula, and the shapes, types and ids."""
import os

import numpy as np
import pytest

import softrast
from scenes import (H, INTRINSICS, TRIANGLE, TRIANGLE_FACES, TRIANGLE_POSE, W, look_pose, rotation,
                    write_obj)

ALL = ("depth", "range", "face_ids", "part_ids", "normals")


def triangle_render(**kw):
    r = softrast.Renderer(W, H, threads=1)
    return r.render(softrast.Mesh(TRIANGLE, TRIANGLE_FACES), **INTRINSICS, pose=TRIANGLE_POSE, **kw)


def test_the_triangle_at_depth_4_is_exactly_4_and_its_range_the_ray_length():
    out = triangle_render(outputs=("depth", "range"))
    depth, rng = out["depth"], out["range"]
    assert set(np.unique(depth)) == {0.0, 4.0}
    drawn = depth == 4.0
    assert 30 < drawn.sum() < 45  # 0.8 square units, 7.5 by 6.25 px a unit
    y, x = np.nonzero(drawn)
    u, v = (x - 19.5) / 30.0, (y - 14.5) / 25.0
    assert np.array_equal(rng[drawn], (4.0 * np.sqrt(u * u + v * v + 1.0)).astype(np.float32))
    assert np.all(rng[~drawn] == 0.0)


def test_outputs_have_the_documented_shapes_and_types_and_own_their_memory():
    out = triangle_render(outputs=ALL)
    assert set(out) == set(ALL) | {"stats"}
    for name, dtype in [("depth", np.float32), ("range", np.float32), ("face_ids", np.uint32),
                        ("part_ids", np.uint32)]:
        assert out[name].shape == (H, W) and out[name].dtype == dtype
        assert out[name].flags.owndata and out[name].flags.c_contiguous and out[name].flags.writeable
    assert out["normals"].shape == (H, W, 3) and out["normals"].dtype == np.float32
    on = out["depth"] > 0
    assert np.array_equal(out["face_ids"], on.astype(np.uint32))
    assert np.array_equal(out["part_ids"], on.astype(np.uint32))
    # e1 x e2 of the given order is +z in the file frame, and the pose turns nothing
    assert np.all(out["normals"][on] == [0, 0, 1]) and np.all(out["normals"][~on] == 0)
    s = out["stats"]
    assert s["triangles"] == 1 and s["drawn"] == 1 and s["fragments"] == on.sum() and s["nonfinite"] == 0


def test_a_second_render_leaves_the_first_results_alone():
    r = softrast.Renderer(W, H, threads=1)
    mesh = softrast.Mesh(TRIANGLE, TRIANGLE_FACES)
    first = r.render(mesh, **INTRINSICS, pose=TRIANGLE_POSE)["depth"]
    kept = first.copy()
    moved = TRIANGLE_POSE.copy()
    moved[2, 3] = 8
    r.render(mesh, **INTRINSICS, pose=moved)
    assert np.array_equal(first, kept)


def test_invalid_nan_marks_where_nothing_is_drawn():
    out = triangle_render(outputs=("depth", "range", "face_ids"), invalid=float("nan"))
    assert np.array_equal(np.isnan(out["depth"]), out["face_ids"] == 0)
    assert set(np.unique(out["depth"][~np.isnan(out["depth"])])) == {4.0}
    assert np.isnan(out["range"]).sum() == np.isnan(out["depth"]).sum() > 0


def test_K_c2w_and_the_default_fy_cx_cy_give_the_same_images():
    mesh = softrast.Mesh(TRIANGLE, TRIANGLE_FACES)
    r = softrast.Renderer(W, H, threads=1)
    want = r.render(mesh, **INTRINSICS, pose=TRIANGLE_POSE, outputs=ALL)
    K = np.array([[30, 0, 19.5], [0, 25, 14.5], [0, 0, 1]])
    for got in (r.render(mesh, K=K, pose=TRIANGLE_POSE, outputs=ALL),
                r.render(mesh, K=K, pose_c2w=np.linalg.inv(TRIANGLE_POSE), outputs=ALL)):
        for name in ALL:
            assert np.array_equal(got[name], want[name]), name
    centred = r.render(mesh, fx=30, pose=TRIANGLE_POSE)["depth"]
    assert np.array_equal(centred, r.render(mesh, fx=30, fy=30, cx=19.5, cy=14.5, pose=TRIANGLE_POSE)["depth"])


def torus_scene(root):
    mesh = softrast.Mesh.load(os.path.join(root, "assets", "torus.obj"))
    pose = look_pose([1.3, -2.0, -2.4], [0.1, 0.05, 0.0])
    return mesh, pose


@pytest.mark.parametrize("threads", [1, 2])
def test_outputs_equal_the_command_lines_files_bit_for_bit(cli, root, tmp_path, threads):
    obj = os.path.join(root, "assets", "torus.obj")
    mesh, pose = torus_scene(root)
    w, h, k = 96, 72, (70.0, 65.0, 47.25, 36.5)
    cli("render", obj, "--size", f"{w}x{h}", "--intrinsics", ",".join(map(repr, k)),
        "--pose-w2c", ",".join(repr(float(v)) for v in pose.ravel()), "--threads", threads,
        "--view-depth", tmp_path / "d.npy", "--range", tmp_path / "r.npy", "--face-ids", tmp_path / "f.npy",
        "--part-ids", tmp_path / "p.npy", "--normals", tmp_path / "n.npy", "--quiet")
    r = softrast.Renderer(w, h, threads=threads)
    arrays = softrast.Mesh(mesh.positions, mesh.faces)  # the same mesh from numpy, in the file's frame
    for m in (mesh, arrays):
        out = r.render(m, fx=k[0], fy=k[1], cx=k[2], cy=k[3], pose=pose, outputs=ALL)
        for name, file in [("depth", "d"), ("range", "r"), ("face_ids", "f"), ("part_ids", "p"), ("normals", "n")]:
            want = np.load(tmp_path / f"{file}.npy")
            assert want.dtype == out[name].dtype and want.shape == out[name].shape, name
            assert np.array_equal(want.view(np.uint32), out[name].view(np.uint32)), name
        assert (out["depth"] > 0).sum() > 1000


def test_a_mesh_from_arrays_and_its_obj_file_render_alike(cli, tmp_path):
    rng = np.random.default_rng(7)
    positions = rng.uniform(-1, 1, (60, 3)).astype(np.float32)
    faces = rng.integers(0, 60, (80, 3))
    write_obj(tmp_path / "m.obj", positions, faces)
    pose = look_pose([0.3, 0.2, -3.0], [0, 0, 0])
    cli("render", tmp_path / "m.obj", "--size", "64x48", "--intrinsics", "50,50,31.5,23.5",
        "--pose-w2c", ",".join(repr(float(v)) for v in pose.ravel()), "--view-depth", tmp_path / "d.npy",
        "--face-ids", tmp_path / "f.npy", "--quiet")
    out = softrast.Renderer(64, 48).render(softrast.Mesh(positions, faces), fx=50, pose=pose,
                                           outputs=("depth", "face_ids"))
    assert np.array_equal(np.load(tmp_path / "d.npy").view(np.uint32), out["depth"].view(np.uint32))
    assert np.array_equal(np.load(tmp_path / "f.npy"), out["face_ids"])
    loaded = softrast.Mesh.load(tmp_path / "m.obj")
    # the loader numbers vertices in order of first use: the corners are the same
    assert np.array_equal(loaded.positions[loaded.faces], positions[faces])


def test_depth_follows_the_pinhole_formula_on_a_tilted_plane():
    # A square in the plane n . X = d of the camera frame, posed anywhere:
    # the depth at pixel (x, y) is d / (n . ((x - cx)/fx, (y - cy)/fy, 1)).
    rng = np.random.default_rng(11)
    for trial in range(20):
        w, h = 80, 60
        fx, fy, cx, cy = rng.uniform(40, 120), rng.uniform(40, 120), rng.uniform(20, 60), rng.uniform(15, 45)
        n = np.array([rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), 1.0])
        n /= np.linalg.norm(n)
        d = rng.uniform(0.5, 50)
        a = np.cross(n, [1.0, 0, 0])
        a /= np.linalg.norm(a)
        b = np.cross(n, a)
        centre = n * d  # the plane's point nearest the camera
        s = 4 * d
        cam_points = np.array([centre + s * (i * a + j * b) for i, j in [(-1, -1), (1, -1), (1, 1), (-1, 1)]])
        c2w = np.eye(4)
        c2w[:3, :3] = rotation(rng.normal(size=3), rng.uniform(0, np.pi))
        c2w[:3, 3] = rng.uniform(-10, 10, 3)
        world = cam_points @ c2w[:3, :3].T + c2w[:3, 3]
        mesh = softrast.Mesh(world, [[0, 1, 2], [0, 2, 3]])
        out = softrast.Renderer(w, h, threads=1).render(mesh, fx=fx, fy=fy, cx=cx, cy=cy, pose_c2w=c2w,
                                                         outputs=("depth", "range"))
        y, x = np.mgrid[0:h, 0:w]
        rays = np.stack([(x - cx) / fx, (y - cy) / fy, np.ones_like(x, dtype=np.float64)], -1)
        want = d / (rays @ n)
        assert np.all(out["depth"] > 0), trial  # the square fills the view
        # float32 world positions round the plane itself: a few ulps of the distance
        assert np.allclose(out["depth"], want, rtol=2e-6, atol=0), (trial, np.max(np.abs(out["depth"] / want - 1)))
        assert np.allclose(out["range"], want * np.linalg.norm(rays, axis=-1), rtol=2e-6, atol=0)


def test_face_ids_and_normals_follow_the_given_faces():
    # Two triangles side by side facing opposite ways: ids 1 and 2, normals
    # e1 x e2 of each (the second's order reversed), in the camera frame.
    positions = np.array([[-2, -1, 5], [0, -1, 5], [-1, 1, 5], [0, -1, 5], [2, -1, 5], [1, 1, 5]], np.float64)
    faces = np.array([[0, 1, 2], [3, 5, 4]])
    out = softrast.Renderer(64, 32, threads=1).render(softrast.Mesh(positions, faces), fx=20, pose=np.eye(4),
                                                      outputs=("face_ids", "normals"))
    ids, normals = out["face_ids"], out["normals"]
    assert set(np.unique(ids)) == {0, 1, 2}
    e = positions[faces[:, 1]] - positions[faces[:, 0]], positions[faces[:, 2]] - positions[faces[:, 0]]
    cross = np.cross(e[0], e[1])
    cross /= np.linalg.norm(cross, axis=1, keepdims=True)
    for k in (1, 2):
        assert np.array_equal(normals[ids == k], np.broadcast_to(cross[k - 1].astype(np.float32),
                                                                 normals[ids == k].shape))


def test_interpolated_normals_are_the_vertex_normals_or_smooth_ones():
    positions = np.array([[-1, -1, 3], [1, -1, 3], [0, 1, 3]], np.float64)
    mesh = softrast.Mesh(positions, [[0, 1, 2]], normals=np.tile([0, 0.6, 0.8], (3, 1)))
    r = softrast.Renderer(32, 32, threads=1)
    out = r.render(mesh, fx=20, outputs=("normals", "face_ids"), normals="interpolated")
    on = out["face_ids"] > 0
    assert np.allclose(out["normals"][on], [0, 0.6, 0.8], atol=1e-6)
    bare = softrast.Mesh(positions, [[0, 1, 2]])  # smooth normals made from the faces: e1 x e2
    out = r.render(bare, fx=20, outputs=("normals",), normals="interpolated")
    assert np.allclose(out["normals"][on], [0, 0, 1], atol=1e-6)


def test_render_many_stacks_what_render_returns():
    mesh = softrast.Mesh(TRIANGLE, TRIANGLE_FACES)
    r = softrast.Renderer(W, H, threads=1)
    poses = np.stack([TRIANGLE_POSE] * 3)
    poses[1, 2, 3] = 6
    poses[2, :3, :3] = rotation([0, 0, 1], 0.3)
    many = r.render_many(mesh, poses, **INTRINSICS, outputs=ALL)
    assert many["depth"].shape == (3, H, W) and many["normals"].shape == (3, H, W, 3)
    assert len(many["stats"]) == 3
    for i, pose in enumerate(poses):
        one = r.render(mesh, **INTRINSICS, pose=pose, outputs=ALL)
        for name in ALL:
            assert np.array_equal(many[name][i], one[name]), (i, name)
        assert many["stats"][i] == one["stats"]
    c2w = r.render_many(mesh, poses_c2w=np.linalg.inv(poses), **INTRINSICS)
    assert np.array_equal(c2w["depth"], many["depth"])
    assert r.render_many(mesh, np.zeros((0, 4, 4)), **INTRINSICS)["depth"].shape == (0, H, W)


def test_loaded_meshes_keep_their_parts(root):
    glb = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"
    if not os.path.exists(glb):
        pytest.skip("assimp-testmodels not installed")
    mesh = softrast.Mesh.load(glb)
    assert mesh.part_count > 1 and mesh.triangle_count > 100000
    out = softrast.Renderer(160, 120).render(mesh, fx=150, pose=look_pose([300, 250, -500], [0, 0, 0]),
                                             outputs=("part_ids", "face_ids"))
    assert len(np.unique(out["part_ids"])) > 5
    assert out["face_ids"].max() <= mesh.triangle_count


def test_file_faces_map_face_ids_to_the_obj_faces_as_the_command_line_does(tmp_path, cli):
    # a quad, a triangle and a pentagon: fanned into 2, 1 and 3 triangles
    (tmp_path / "poly.obj").write_text(
        "v -1 -1 0\nv 0 -1 0\nv 0 0 0\nv -1 0 0\nv 0.2 -1 0\nv 1 -1 0\nv 0.6 0 0\n"
        "v -1 0.2 0\nv 0 0.2 0\nv 0.3 0.6 0\nv 0 1 0\nv -1 1 0\n"
        "f 1 2 3 4\nf 5 6 7\nf 8 9 10 11 12\n")
    mesh = softrast.Mesh.load(tmp_path / "poly.obj")
    assert mesh.file_faces.dtype == np.int64
    assert mesh.file_faces.tolist() == [0, 0, 1, 2, 2, 2]
    pose = look_pose([0.1, 0.05, 3.0], [0, 0, 0])
    cli("render", tmp_path / "poly.obj", "--size", "64x48", "--intrinsics", "40,40,31.5,23.5",
        "--pose-w2c", ",".join(repr(float(v)) for v in pose.ravel()), "--face-ids", tmp_path / "f.npy",
        "--face-ids-of", "file", "--quiet")
    ids = softrast.Renderer(64, 48).render(mesh, fx=40, pose=pose, outputs=("face_ids",))["face_ids"]
    assert set(np.unique(ids)) == {0, 1, 2, 3, 4, 5, 6}
    as_file = np.where(ids > 0, mesh.file_faces[np.maximum(ids, 1) - 1] + 1, 0)
    assert np.array_equal(np.load(tmp_path / "f.npy"), as_file.astype(np.uint32))
    # a mesh from arrays is its own faces
    assert softrast.Mesh(TRIANGLE, TRIANGLE_FACES).file_faces.tolist() == [0]
