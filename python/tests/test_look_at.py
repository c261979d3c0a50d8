"""The look-at camera: eye, target, up and a vertical field of view in the
poses' frame, the command line's --eye, --target, --up and --fov."""
import os

import numpy as np
import pytest

import softrast
from scenes import look_pose


def markers(eye, target, up):
    """A wall through target facing the eye (part 1), and two small
    triangles in front of it, one toward up (part 2), one toward the image's
    right, forward x up (part 3)."""
    eye, target, up = (np.asarray(v, np.float64) for v in (eye, target, up))
    f = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(f, up)
    right /= np.linalg.norm(right)
    top = np.cross(right, f)
    d = np.linalg.norm(target - eye)
    s = 0.1 * d

    def quad(centre, a, b):
        return [centre - a - b, centre + a - b, centre + a + b, centre - a + b]

    corners = quad(target, 2 * d * right, 2 * d * top)
    corners += quad(target - 0.1 * d * f + 0.5 * d * top, s * right, s * top)
    corners += quad(target - 0.1 * d * f + 0.5 * d * right, s * right, s * top)
    faces = [[4 * k, 4 * k + 1, 4 * k + 2] for k in range(3)] + [[4 * k, 4 * k + 2, 4 * k + 3] for k in range(3)]
    return softrast.Mesh(np.array(corners), faces, part_ids=[1, 2, 3, 1, 2, 3]), d


def test_the_target_is_at_the_centre_up_at_the_top_and_forward_x_up_on_the_right():
    rng = np.random.default_rng(4)
    w, h = 81, 61
    r = softrast.Renderer(w, h, threads=1)
    for trial in range(20):
        eye, target = rng.uniform(-10, 10, 3), rng.uniform(-10, 10, 3)
        up = rng.normal(size=3)
        mesh, d = markers(eye, target, up)
        out = r.render(mesh, eye=eye, target=target, up=up, fov=50, outputs=("depth", "part_ids"))
        assert np.isclose(out["depth"][30, 40], d, rtol=1e-6), trial  # the centre pixel looks at target
        parts = out["part_ids"]
        y, x = np.nonzero(parts == 2)
        assert len(y) and y.max() < 30 and np.all(np.abs(x - 40) <= 8), trial
        y, x = np.nonzero(parts == 3)
        assert len(x) and x.min() > 40 and np.all(np.abs(y - 30) <= 8), trial


def test_fov_is_the_vertical_field_of_view_of_a_centred_camera():
    mesh, d = markers([0, 0, 5], [0, 0, 0], [0, 1, 0])
    r = softrast.Renderer(64, 48, threads=1)
    kw = dict(outputs=("depth", "face_ids", "normals"))
    looking = look_pose([0, 0, 5], [0, 0, 0], up=(0, -1, 0))  # tests/scenes.py's own construction
    for fov in (30.0, 60.0, 100.0):
        fy = 24 / np.tan(np.radians(fov) / 2)
        a = r.render(mesh, eye=(0, 0, 5), target=(0, 0, 0), fov=fov, **kw)
        b = r.render(mesh, fx=fy, fy=fy, cx=31.5, cy=23.5, pose=looking, **kw)
        c = r.render(mesh, fov=fov, pose=looking, **kw)
        for name in ("depth", "face_ids", "normals"):
            assert np.array_equal(a[name], b[name]) and np.array_equal(a[name], c[name]), (fov, name)
    default = r.render(mesh, eye=(0, 0, 5), target=(0, 0, 0), **kw)  # 60 degrees, as on the command line
    assert np.array_equal(default["depth"], r.render(mesh, eye=(0, 0, 5), target=(0, 0, 0), fov=60, **kw)["depth"])


def test_the_command_lines_eye_and_target_are_the_same_view(cli, root, tmp_path, png):
    # The command line's look-at camera lives in softrast's world, the file's
    # with z negated (docs/conventions.md): its --eye X,Y,Z is eye (X, Y, -Z).
    obj = os.path.join(root, "assets", "torus.obj")
    cli("render", obj, "--size", "96x72", "--eye", "1.3,2.0,-2.4", "--target", "0.1,0.05,0.2", "--fov", "50",
        "--shade", "id", "--cull", "none", "--out", tmp_path / "ids.png", "--quiet")
    want = png.read_rgb_png(tmp_path / "ids.png")
    out = softrast.Renderer(96, 72).render(softrast.Mesh.load(obj), eye=(1.3, 2.0, 2.4), target=(0.1, 0.05, -0.2),
                                           fov=50, outputs=("color", "face_ids"), shade="id")
    drawn = out["face_ids"] > 0
    assert drawn.sum() > 1000
    # another projection matrix (the command line's is float, near 0.1 and
    # far 100): the same triangle but at a few edge pixels
    same = np.all(out["color"] == want, axis=2)
    assert same.mean() > 0.99 and same[drawn].mean() > 0.98, (same.mean(), same[drawn].mean())


@pytest.mark.parametrize("kw, message", [
    (dict(eye=(0, 0, 5)), "the look-at camera needs eye and target"),
    (dict(target=(0, 0, 5)), "the look-at camera needs eye and target"),
    (dict(up=(0, 1, 0)), "the look-at camera needs eye and target"),
    (dict(eye=(1, 2, 3), target=(1, 2, 3)), "eye and target: the same point"),
    (dict(eye=(0, 0, 5), target=(0, 0, 0), up=(0, 0, 2)), "up: zero or along the view direction"),
    (dict(eye=(0, 0, 5), target=(0, 0, 0), up=(0, 0, 0)), "up: zero or along the view direction"),
    (dict(eye=(0, 0, np.nan), target=(0, 0, 0)), "eye: every entry must be finite"),
    (dict(eye=(0, 0), target=(0, 0, 0)), r"eye: shape \(2,\) where \(3,\)"),
    (dict(eye=(0, 0, 5), target=(0, 0, 0), pose=np.eye(4)), "a pose and the look-at camera"),
    (dict(eye=(0, 0, 5), target=(0, 0, 0), fov=60, fx=30), "as K, as fx, fy, cx, cy or as fov, not two"),
    (dict(eye=(0, 0, 5), target=(0, 0, 0), fov=0), "fov: 0 degrees"),
    (dict(eye=(0, 0, 5), target=(0, 0, 0), fov=180), "fov: 180 degrees"),
    (dict(eye=(0, 0, 5), target=(0, 0, 0), fov=np.nan), "fov: nan degrees"),
    (dict(eye=(0, 0, 5), target=(0, 0, 0), fov="wide"), "fov: 'wide' is not a number"),
])
def test_a_bad_look_at_camera_is_refused_with_one_line(kw, message):
    mesh, _ = markers([0, 0, 5], [0, 0, 0], [0, 1, 0])
    with pytest.raises(ValueError, match=message):
        softrast.Renderer(16, 16).render(mesh, **kw)


def test_render_many_of_look_at_cameras_is_render_of_each(root):
    mesh = softrast.Mesh.load(os.path.join(root, "assets", "torus.obj"))
    eyes = np.array([[1.3, 2.0, 2.4], [0.5, -2.5, 2.0], [-2.0, 0.3, 1.5]])
    targets = np.array([[0.1, 0.05, -0.2], [0.0, 0.0, 0.0], [0.2, -0.1, 0.1]])
    ups = np.array([[0, 1, 0], [1, 0, 0], [0, 0.6, 0.8]])
    kw = dict(fov=50, outputs=("color", "depth", "face_ids", "normals"))
    r = softrast.Renderer(48, 36)
    for target, up in ((targets[0], None), (targets, None), (targets[1], ups), (targets, ups)):
        many = r.render_many(mesh, eye=eyes, target=target, up=up, **kw)
        assert many["depth"].shape == (3, 36, 48)
        for i, eye in enumerate(eyes):
            one = r.render(mesh, eye=eye, target=target if target.ndim == 1 else target[i],
                           up=None if up is None else up[i], **kw)
            for name in kw["outputs"]:
                assert np.array_equal(many[name][i], one[name]), (i, name)
            assert many["stats"][i] == one["stats"] and (one["face_ids"] > 0).sum() > 200
        assert not np.array_equal(many["depth"][0], many["depth"][1])


@pytest.mark.parametrize("kw, message", [
    (dict(eye=np.ones((3, 3)), target=np.zeros((2, 3))), "target: 2 rows where another of eye, target and up has 3"),
    (dict(eye=[[0, 0, 5], [1, 2, 3]], target=(1, 2, 3)), "frame 1: eye and target: the same point"),
    (dict(eye=[[0, 0, 5], [0, 0, -5]], target=(0, 0, 0), up=[[0, 1, 0], [0, 0, 1]]),
     "frame 1: up: zero or along the view direction"),
    (dict(eye=np.ones((3, 2)), target=(0, 0, 0)), r"eye: shape \(3, 2\) where \(N, 3\) or \(3,\)"),
    (dict(eye=[[0, 0, 5], [0, np.inf, 5]], target=(0, 0, 0)), "eye: every entry must be finite"),
    (dict(eye=[[0, 0, 5]], target=(0, 0, 0), poses=np.eye(4)[None]), "a pose and the look-at camera"),
    (dict(target=(0, 0, 0)), "the look-at camera needs eye and target"),
])
def test_render_many_refuses_a_bad_look_at_camera_with_one_line(kw, message):
    mesh, _ = markers([0, 0, 5], [0, 0, 0], [0, 1, 0])
    with pytest.raises(ValueError, match=message):
        softrast.Renderer(16, 16).render_many(mesh, **kw)
