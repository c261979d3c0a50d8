"""Scenes the tests share: the C suite's triangle and its camera."""
import numpy as np

# tests/test_cli_pinhole.c: a triangle in the plane z = 0 of the file and a
# camera 4 in front of it, looking along +z: every pixel it shows is at view
# depth 4 exactly.
TRIANGLE = np.array([[-1, 0.2, 0], [1, 0.2, 0], [0, 1, 0]], np.float32)
TRIANGLE_FACES = np.array([[0, 1, 2]], np.int32)
TRIANGLE_POSE = np.array([[1, 0, 0, 0], [0, 1, 0, -0.5], [0, 0, 1, 4], [0, 0, 0, 1]], np.float64)
W, H = 40, 30
INTRINSICS = dict(fx=30.0, fy=25.0, cx=19.5, cy=14.5)


def write_obj(path, positions, faces):
    """An OBJ of these arrays, each float32 coordinate written exactly."""
    with open(path, "w") as f:
        for p in np.asarray(positions, np.float32):
            f.write("v %s %s %s\n" % tuple(repr(float(c)) for c in p))
        for t in np.asarray(faces):
            f.write("f %d %d %d\n" % tuple(int(i) + 1 for i in t))


def rotation(axis, angle):
    """A rotation matrix about a unit axis (Rodrigues)."""
    x, y, z = np.asarray(axis, np.float64) / np.linalg.norm(axis)
    k = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * (k @ k)


def look_pose(eye, target, up=(0, -1, 0)):
    """World-to-camera of a camera at eye looking at target (OpenCV axes)."""
    eye, target = np.asarray(eye, np.float64), np.asarray(target, np.float64)
    z = target - eye
    z /= np.linalg.norm(z)
    x = np.cross(up, z)
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    w2c = np.eye(4)
    w2c[:3, :3] = np.stack([x, y, z])
    w2c[:3, 3] = -w2c[:3, :3] @ eye
    return w2c
