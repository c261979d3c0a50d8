#!/usr/bin/python3
"""pinhole_sheet.py OUT.png BINARY — docs/images/pinhole-outputs.png: the
room through a pinhole camera, its colour, view depth, interpolated normals
and face ids from one `softrast render` call, two by two. Debian's python3
and numpy; the PNGs are read and written with zlib alone."""

import os
import struct
import subprocess
import sys
import tempfile
import zlib

import numpy as np

SIZE = (320, 240)


def c2w_looking(eye, target):
    """Camera-to-world, OpenCV's axes (x right, y down, z forward), y up."""
    f = np.subtract(target, eye, dtype=float)
    f /= np.linalg.norm(f)
    r = np.cross(f, [0.0, 1.0, 0.0])
    r /= np.linalg.norm(r)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = r, -np.cross(r, f), f, eye
    return m


def read_rgb_png(path):
    data, pos, idat, size = open(path, "rb").read(), 8, b"", None
    while pos < len(data):
        n = struct.unpack(">I", data[pos:pos + 4])[0]
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b"IHDR":
            size = struct.unpack(">II", body[:8])
        elif kind == b"IDAT":
            idat += body
    w, h = size
    raw, stride = zlib.decompress(idat), 3 * w
    out, prev = np.zeros((h, stride), np.uint8), np.zeros(stride, np.int32)
    for y in range(h):
        kind = raw[y * (stride + 1)]
        row = np.frombuffer(raw, np.uint8, stride, y * (stride + 1) + 1).astype(np.int32)
        cur = np.zeros(stride, np.int32)
        for x in range(stride):
            a = cur[x - 3] if x >= 3 else 0
            b, c = prev[x], prev[x - 3] if x >= 3 else 0
            if kind == 1:
                row[x] += a
            elif kind == 2:
                row[x] += b
            elif kind == 3:
                row[x] += (a + b) // 2
            elif kind == 4:
                p = a + b - c
                row[x] += a if abs(p - a) <= abs(p - b) and abs(p - a) <= abs(p - c) else b if abs(p - b) <= abs(p - c) else c
            cur[x] = row[x] & 255
        out[y], prev = cur, cur
    return out.reshape(h, w, 3)


def write_rgb_png(path, img):
    h, w, _ = img.shape
    raw = b"".join(b"\0" + img[y].tobytes() for y in range(h))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def depth_colours(d):
    """Near yellow to far blue over the drawn range; black where nothing."""
    drawn = d > 0
    t = np.zeros_like(d)
    t[drawn] = (d[drawn] - d[drawn].min()) / max(np.ptp(d[drawn]), 1e-30)
    stops = np.array([[250, 230, 80], [120, 220, 120], [30, 140, 200], [20, 20, 90]], float)
    i = np.clip((3 * t).astype(int), 0, 2)
    w = (3 * t - i)[..., None]
    return np.where(drawn[..., None], stops[i] * (1 - w) + stops[i + 1] * w, 0).astype(np.uint8)


def main():
    out, binary = sys.argv[1], sys.argv[2]
    pose = c2w_looking([-8.0, 3.0, 8.0], [4.0, 1.5, -6.0])  # the README's view, in the file's frame
    with tempfile.TemporaryDirectory() as tmp:
        path = lambda name: os.path.join(tmp, name)
        subprocess.run([binary, "render", "assets/room.obj", "--size", "%dx%d" % SIZE, "--fov", "75",
                        "--cull", "back", "--pose-c2w", ",".join("%.17g" % v for v in pose.flatten()),
                        "--out", path("c.png"), "--view-depth", path("d.npy"), "--normals", path("n.npy"),
                        "--normal-kind", "interpolated", "--face-ids", path("f.npy"), "--quiet"], check=True)
        colour, depth = read_rgb_png(path("c.png")), np.load(path("d.npy"))
        normals, faces = np.load(path("n.npy")), np.load(path("f.npy"))
    drawn = (faces > 0)[..., None]
    normal_colours = np.where(drawn, (0.5 + 0.5 * normals) * 255, 0).astype(np.uint8)
    palette = np.random.RandomState(3).randint(40, 256, (int(faces.max()) + 1, 3)).astype(np.uint8)
    palette[0] = 0
    sheet = np.concatenate([np.concatenate([colour, depth_colours(depth)], 1),
                            np.concatenate([normal_colours, palette[faces]], 1)], 0)
    write_rgb_png(out, sheet)


if __name__ == "__main__":
    main()
