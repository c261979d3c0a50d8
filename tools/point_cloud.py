"""Writes a colored point cloud as an ASCII PLY of vertices alone, the kind
a depth sensor or a photogrammetry tool gives: points on a torus knot tube,
colored by their normal (make docs-images draws it with render --points).

    python3 tools/point_cloud.py OUT.ply [POINTS]
"""
import math
import sys


def knot(t):
    """The (2, 3) torus knot, and its derivative."""
    r = 2.0 + math.cos(3.0 * t)
    p = (r * math.cos(2.0 * t), r * math.sin(2.0 * t), math.sin(3.0 * t))
    dr = -3.0 * math.sin(3.0 * t)
    d = (dr * math.cos(2.0 * t) - 2.0 * r * math.sin(2.0 * t), dr * math.sin(2.0 * t) + 2.0 * r * math.cos(2.0 * t),
         3.0 * math.cos(3.0 * t))
    return p, d


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def main():
    out, count = sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 40000
    golden = (math.sqrt(5.0) - 1.0) / 2.0
    rows = []
    for i in range(count):
        t = 2.0 * math.pi * i / count
        a = 2.0 * math.pi * ((i * golden) % 1.0)
        p, d = knot(t)
        tangent = normalize(d)
        side = normalize(cross(tangent, (0.0, 0.0, 1.0)))
        up = cross(side, tangent)
        n = tuple(math.cos(a) * side[k] + math.sin(a) * up[k] for k in range(3))
        q = tuple(p[k] + 0.45 * n[k] for k in range(3))
        rgb = tuple(int(round(255 * (0.5 + 0.5 * c))) for c in n)
        rows.append("%.5f %.5f %.5f %d %d %d" % (q + rgb))
    with open(out, "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex %d\n" % count)
        f.write("property float x\nproperty float y\nproperty float z\n")
        f.write("property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n")
        f.write("\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
