#!/usr/bin/python3
"""compare_open3d.py — softrast's pinhole camera against Open3D's
RaycastingScene on the same meshes, cameras and threads, both held to an
exact double-precision ray cast (docs/open3d-compare.md).

    compare_open3d.py dense IN.obj OUT.obj LEVELS
        IN subdivided LEVELS times (Open3D's Loop subdivision), as OBJ.
    compare_open3d.py run [--softrast B] [--timer B] [--frames K]
                          [--rounds R] [--out TABLE.md] MESH.obj ...
        The table: time per view at 640x480 and 1920x1080 on 1 and 2
        threads, depth errors, coverage and visibility disagreements.

Needs Debian's python3-numpy and python3-open3d, and Open3D's rays need
the ray-mask preload (tools/open3d_ray_mask.c): run it as
    LD_PRELOAD=build/open3d_ray_mask.so /usr/bin/python3 tools/compare_open3d.py run ...
`make compare-open3d` does all of it.

Cameras: OpenCV's (x right, y down, z forward; the centre of the top-left
pixel is (u, v) = (0, 0)), a pose in the mesh file's own frame, the same
4x4 for both. Open3D gets the file's vertices and triangles as they are,
in file order, so its primitive id is softrast's face id - 1.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

SIZES = ((640, 480), (1920, 1080))
THREADS = (1, 2)
VFOV_DEG = 40.0           # vertical field of view of every camera
TIE = 1e-9                # two exact depths within this (relative) are the same surface point


# ---- meshes -----------------------------------------------------------------

def read_obj(path):
    """Vertices (float64, the file's decimals) and triangles (int64, a
    polygon fanned as (c0, ck, ck+1) in file order, as softrast counts)."""
    verts, tris = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                verts.append(line.split()[1:4])
            elif line.startswith("f "):
                c = [int(w.split("/")[0]) for w in line.split()[1:]]
                c = [i - 1 if i > 0 else len(verts) + i for i in c]
                tris.extend((c[0], c[k], c[k + 1]) for k in range(1, len(c) - 1))
    return np.array(verts, dtype=np.float64), np.array(tris, dtype=np.int64)


def write_obj(path, v, t, comment):
    with open(path + ".tmp", "w") as f:
        f.write(f"# {comment}\n")
        np.savetxt(f, v, fmt="v %.9g %.9g %.9g")
        np.savetxt(f, t + 1, fmt="f %d %d %d")
    os.replace(path + ".tmp", path)


def dense(src, dst, levels):
    import open3d as o3d
    v, t = read_obj(src)
    m = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(v), o3d.utility.Vector3iVector(t.astype(np.int32)))
    m = m.subdivide_loop(number_of_iterations=levels)
    tv, tt = np.asarray(m.vertices), np.asarray(m.triangles).astype(np.int64)
    write_obj(dst, tv.astype(np.float32).astype(np.float64), tt,
              f"{os.path.basename(src)} after {levels} Loop subdivisions (Open3D): "
              f"{len(tv)} vertices, {len(tt)} triangles")
    print(f"{dst}: {len(tt)} triangles")


# ---- cameras ----------------------------------------------------------------

def camera(v, width, height):
    """A three-quarter view from the front, a little above (y is up in
    every mesh here): the bounding box's half diagonal over 0.8 of the frame's height.
    Returns K (3x3) and the world-to-camera pose (4x4), OpenCV's axes."""
    lo, hi = v.min(0), v.max(0)
    centre, radius = 0.5 * (lo + hi), 0.5 * np.linalg.norm(hi - lo)
    az, el = np.radians(30.0), np.radians(20.0)
    dist = 0.8 * radius / np.sin(np.radians(VFOV_DEG) / 2)
    eye = centre + dist * np.array([np.sin(az) * np.cos(el), np.sin(el), np.cos(az) * np.cos(el)])
    z = centre - eye
    z /= np.linalg.norm(z)
    x = np.cross(z, [0.0, 1.0, 0.0])
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    w2c = np.eye(4)
    w2c[:3, :3] = np.stack([x, y, z])
    w2c[:3, 3] = -w2c[:3, :3] @ eye
    f = 0.5 * height / np.tan(np.radians(VFOV_DEG) / 2)
    k = np.array([[f, 0, (width - 1) / 2], [0, f, (height - 1) / 2], [0, 0, 1]])
    return k, w2c


def numbers(a):
    return ",".join(repr(float(x)) for x in np.ravel(a))


# ---- the exact ray cast -----------------------------------------------------

def ray_triangle(cv, tri, px, py, k):
    """The ray through pixel centre (px, py) met with triangle tri, in
    double in the camera frame (Möller–Trumbore): z depth (the ray's
    direction has z = 1) and the smallest barycentric (>= 0: inside)."""
    d = np.stack([(px - k[0, 2]) / k[0, 0], (py - k[1, 2]) / k[1, 1], np.ones(len(px))], axis=1)
    a, b, c = cv[tri[:, 0]], cv[tri[:, 1]], cv[tri[:, 2]]
    e1, e2 = b - a, c - a
    p = np.cross(d, e2)
    det = np.einsum("ij,ij->i", e1, p)
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / det
        s = -a
        u = np.einsum("ij,ij->i", s, p) * inv
        q = np.cross(s, e1)
        w = np.einsum("ij,ij->i", d, q) * inv
        t = np.einsum("ij,ij->i", e2, q) * inv
    bary = np.minimum(np.minimum(u, w), 1.0 - u - w)
    bary[~np.isfinite(bary) | (det == 0)] = -np.inf
    return t, bary


def exact_cast(cv, tris, k, width, height):
    """Every pixel's nearest hit, exactly: the triangles whose projected
    bounding box holds a pixel centre are its candidates, each tested in
    double. Returns z depth (inf: nothing) and triangle id (-1)."""
    assert (cv[:, 2] > 0).all(), "the exact cast wants every vertex in front of the camera"
    u = k[0, 0] * cv[:, 0] / cv[:, 2] + k[0, 2]
    v = k[1, 1] * cv[:, 1] / cv[:, 2] + k[1, 2]
    tu, tv = u[tris], v[tris]
    x0 = np.clip(np.ceil(tu.min(1)), 0, width).astype(np.int64)
    x1 = np.clip(np.floor(tu.max(1)), -1, width - 1).astype(np.int64)
    y0 = np.clip(np.ceil(tv.min(1)), 0, height).astype(np.int64)
    y1 = np.clip(np.floor(tv.max(1)), -1, height - 1).astype(np.int64)
    bw, bh = np.maximum(x1 - x0 + 1, 0), np.maximum(y1 - y0 + 1, 0)
    count = bw * bh
    keep = np.nonzero(count)[0]
    depth = np.full(width * height, np.inf)
    ids = np.full(width * height, -1, dtype=np.int64)
    hits_pix, hits_t, hits_tri = [], [], []
    cum = np.cumsum(count[keep])
    start = 0
    while start < len(keep):
        end = int(np.searchsorted(cum, (cum[start - 1] if start else 0) + 4_000_000, side="right"))
        end = max(end, start + 1)
        sel = keep[start:end]
        n = count[sel]
        tri = np.repeat(sel, n)
        first = np.repeat(np.cumsum(n) - n, n)
        j = np.arange(len(tri)) - first
        w = np.repeat(bw[sel], n)
        px, py = np.repeat(x0[sel], n) + j % w, np.repeat(y0[sel], n) + j // w
        t, bary = ray_triangle(cv, tris[tri], px.astype(np.float64), py.astype(np.float64), k)
        hit = (bary >= 0) & (t > 0)
        hits_pix.append(py[hit] * width + px[hit])
        hits_t.append(t[hit])
        hits_tri.append(tri[hit])
        start = end
    pix, t, tri = (np.concatenate(a) for a in (hits_pix, hits_t, hits_tri))
    order = np.lexsort((tri, t, pix))
    pix, t, tri = pix[order], t[order], tri[order]
    first = np.ones(len(pix), dtype=bool)
    first[1:] = pix[1:] != pix[:-1]
    depth[pix[first]], ids[pix[first]] = t[first], tri[first]
    return depth.reshape(height, width), ids.reshape(height, width)


# ---- the two renderers ------------------------------------------------------

def run_softrast(binary, mesh, k, w2c, width, height, threads, frames, tmp):
    d, f = os.path.join(tmp, "depth.npy"), os.path.join(tmp, "ids.npy")
    out = subprocess.run([binary, "render", mesh, "--size", f"{width}x{height}",
                          "--intrinsics", numbers([k[0, 0], k[1, 1], k[0, 2], k[1, 2]]),
                          "--pose-w2c", numbers(w2c), "--shade", "id", "--view-depth", d, "--face-ids", f,
                          "--threads", str(threads), "--frames", str(frames), "--stats", "--quiet"],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)["ms_median"], np.load(d), np.load(f).astype(np.int64) - 1


def run_timer(binary, mesh, k, w2c, width, height, threads, frames):
    out = subprocess.run([binary, mesh, str(width), str(height),
                          numbers([k[0, 0], k[1, 1], k[0, 2], k[1, 2]]), numbers(w2c), str(threads), str(frames)],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)["resolve_ms"]


def open3d_scene(v, t):
    import open3d as o3d
    scene = o3d.t.geometry.RaycastingScene()
    scene.add_triangles(o3d.core.Tensor(v.astype(np.float32)), o3d.core.Tensor(t.astype(np.uint32)))
    return scene


def open3d_rays(k, w2c, width, height):
    """Open3D's own rays. Its create_rays_pinhole puts pixel x's centre at
    x + 0.5 (the corner convention), so OpenCV's cx, cy go in + 0.5; the
    direction is R^T K^-1 (u, v, 1), so t_hit is the z depth."""
    import open3d as o3d
    k2 = k.copy()
    k2[0, 2] += 0.5
    k2[1, 2] += 0.5
    return o3d.t.geometry.RaycastingScene.create_rays_pinhole(o3d.core.Tensor(k2), o3d.core.Tensor(w2c),
                                                              width, height)


def run_open3d(scene, rays, threads, frames):
    scene.cast_rays(rays, nthreads=threads)  # warm-up (the first call also builds the BVH)
    ms, cpu0 = [], time.process_time()
    for _ in range(frames):
        t0 = time.perf_counter()
        ans = scene.cast_rays(rays, nthreads=threads)
        ms.append(1e3 * (time.perf_counter() - t0))
    cpu = 1e3 * (time.process_time() - cpu0) / sum(ms)
    t_hit = ans["t_hit"].numpy()
    if not np.isfinite(t_hit).any():
        sys.exit("compare_open3d: Open3D's rays hit nothing: Debian's Embree wants the ray-mask preload, "
                 "LD_PRELOAD=build/open3d_ray_mask.so (tools/open3d_ray_mask.c)")
    ids = ans["primitive_ids"].numpy().astype(np.int64)
    ids[~np.isfinite(t_hit)] = -1
    return float(np.median(ms)), cpu, t_hit, ids


# ---- the comparison ---------------------------------------------------------

def depth_at(cv, tris, k, ids, mask):
    """Exact z depth where each pixel of mask meets the plane of the
    triangle ids names, and the smallest barycentric (>= 0: the ray is
    inside that triangle)."""
    py, px = np.nonzero(mask)
    return ray_triangle(cv, tris[ids[mask]], px.astype(np.float64), py.astype(np.float64), k)


def edge_distance(cv, tris, k, ids, mask):
    """For each pixel of mask, the distance in pixels from its centre to
    the nearest edge of its triangle as projected (in double)."""
    py, px = np.nonzero(mask)
    p = np.stack([px, py], axis=1).astype(np.float64)
    c = cv[tris[ids[mask]]]                                      # n x 3 corners x xyz
    uv = np.stack([k[0, 0] * c[..., 0] / c[..., 2] + k[0, 2], k[1, 1] * c[..., 1] / c[..., 2] + k[1, 2]], axis=-1)
    best = np.full(len(p), np.inf)
    for i in range(3):
        a, b = uv[:, i], uv[:, (i + 1) % 3]
        ab = b - a
        with np.errstate(divide="ignore", invalid="ignore"):
            s = np.clip(np.einsum("ij,ij->i", p - a, ab) / np.einsum("ij,ij->i", ab, ab), 0.0, 1.0)
        s = np.nan_to_num(s)
        best = np.minimum(best, np.linalg.norm(a + s[:, None] * ab - p, axis=1))
    return best


def accuracy(depth, ids, exact, exact_ids, cv, cv32, tris, k):
    """One renderer against the exact cast (of the file's decimals, cv),
    and its depth against its own triangle's plane met exactly with the
    float32 vertices it drew (cv32): the error of its arithmetic alone."""
    hit, ehit = ids >= 0, exact_ids >= 0
    both = hit & ehit
    with np.errstate(invalid="ignore"):
        rel = np.abs(depth.astype(np.float64) - exact) / exact
    same = both & (ids == exact_ids)
    other = both & (ids != exact_ids)
    t, bary = depth_at(cv, tris, k, ids, other)
    gap = (t - exact[other]) / exact[other]
    inside = bary >= 0
    outside = np.zeros_like(other)
    outside[other] = ~inside
    behind = inside & (gap > TIE)
    extra, missed = hit & ~ehit, ~hit & ehit
    own, _ = depth_at(cv32, tris, k, ids, hit)
    own = np.abs(depth[hit].astype(np.float64) - own) / own
    return {"own_max": float(own.max()), "own_p999": float(np.quantile(own, 0.999)),"max": float(rel[both].max()), "p999": float(np.quantile(rel[both], 0.999)),
            "max_same": float(rel[same].max()),
            "extra": int(extra.sum()), "missed": int(missed.sum()),
            "edge": int(outside.sum()),
            "edge_px": float(max(edge_distance(cv, tris, k, ids, outside | extra).max(initial=0.0),
                                 edge_distance(cv, tris, k, exact_ids, missed).max(initial=0.0))),
            "behind": int(behind.sum()), "behind_max": float(gap[behind].max(initial=0.0))}


def between(s_ids, o_ids, exact_ids):
    """The two renderers against each other, and who the exact cast agrees with."""
    sh, oh = s_ids >= 0, o_ids >= 0
    cover = sh != oh
    vis = sh & oh & (s_ids != o_ids)
    return {"cover": int(cover.sum()), "cover_s": int((cover & (s_ids == exact_ids)).sum()),
            "cover_o": int((cover & (o_ids == exact_ids)).sum()),
            "vis": int(vis.sum()), "vis_s": int((vis & (s_ids == exact_ids)).sum()),
            "vis_o": int((vis & (o_ids == exact_ids)).sum())}


def fmt_err(x):
    return f"{x:.1e}"


def run(args):
    rows, acc_rows = [], []
    args.load = os.getloadavg()
    tmp = tempfile.mkdtemp(prefix="compare-open3d-")
    for mesh in args.meshes:
        v, tris = read_obj(mesh)
        name = os.path.splitext(os.path.basename(mesh))[0]
        scene = open3d_scene(v, tris)
        for width, height in SIZES:
            k, w2c = camera(v, width, height)
            cv = v @ w2c[:3, :3].T + w2c[:3, 3]
            t0 = time.perf_counter()
            exact, exact_ids = exact_cast(cv, tris, k, width, height)
            exact_s = time.perf_counter() - t0
            rays = open3d_rays(k, w2c, width, height)
            outputs = {}
            for threads in THREADS:
                s_ms, s_res, o_ms, o_cpu = [], [], [], []
                for _ in range(args.rounds):  # interleaved: a busy spell hits both
                    ms, sd, si = run_softrast(args.softrast, mesh, k, w2c, width, height, threads, args.frames, tmp)
                    s_ms.append(ms)
                    s_res.append(run_timer(args.timer, mesh, k, w2c, width, height, threads, args.frames))
                    ms, cpu, od, oi = run_open3d(scene, rays, threads, args.frames)
                    o_ms.append(ms)
                    o_cpu.append(cpu)
                    for key, value in (("sd", sd), ("si", si), ("od", od), ("oi", oi)):
                        if key in outputs and not np.array_equal(outputs[key], value, equal_nan=True):
                            print(f"warning: {name} {width}x{height}: {key} differs between runs", file=sys.stderr)
                        outputs.setdefault(key, value)
                # each round's median; the best round, as the least disturbed by the machine's other work
                draw, res, o = (float(np.min(a)) for a in (s_ms, s_res, o_ms))
                rows.append((name, len(tris), f"{width}x{height}", threads, draw, res, draw + res, o,
                             (draw + res) / o, float(o_cpu[int(np.argmin(o_ms))])))
                print("  ".join(str(c) for c in rows[-1]), file=sys.stderr)
            s_depth = np.where(outputs["si"] >= 0, outputs["sd"], np.inf)
            cv32 = v.astype(np.float32).astype(np.float64) @ w2c[:3, :3].T + w2c[:3, 3]
            sa = accuracy(s_depth, outputs["si"], exact, exact_ids, cv, cv32, tris, k)
            oa = accuracy(outputs["od"], outputs["oi"], exact, exact_ids, cv, cv32, tris, k)
            bt = between(outputs["si"], outputs["oi"], exact_ids)
            acc_rows.append((name, f"{width}x{height}", int((exact_ids >= 0).sum()), sa, oa, bt, exact_s))
            print(name, width, height, sa, oa, bt, f"exact cast {exact_s:.1f} s", file=sys.stderr)
    table = format_tables(rows, acc_rows, args)
    print(table)
    if args.out:
        with open(args.out, "w") as f:
            f.write(table)


def format_tables(rows, acc_rows, args):
    out = [f"Time per view, ms: the median of {args.frames} views, the best of {args.rounds} rounds that "
           f"alternate the two (load average {args.load[0]:.2f} before, {os.getloadavg()[0]:.2f} after):",
           "",
           "| mesh | triangles | size | threads | softrast draw | + resolve | softrast view | Open3D cast_rays "
           "| softrast / Open3D | Open3D CPU / wall |",
           "| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for name, n, size, threads, draw, res, view, o, ratio, cpu in rows:
        out.append(f"| {name} | {n:,} | {size} | {threads} | {draw:.2f} | {res:.2f} | {view:.2f} | {o:.2f} "
                   f"| {ratio:.2f}× | {cpu:.2f} |")
    out += ["",
            "Against the exact cast (double precision, every pixel centre, the file's decimals): relative "
            "depth error where both hit (all pixels; on the exact triangle only; and against the renderer's "
            "own triangle with the float32 vertices both draw, its arithmetic alone); pixels hit that the exact cast misses (extra) and "
            "missed; pixels showing another triangle than the exact nearest, whose plane the exact ray "
            "misses (edge) or meets behind the nearest (behind, with the largest gap); and the farthest a "
            "wrong pixel centre lies from the triangle edge that decided it, in pixels:",
            "",
            "| mesh | size | pixels hit | renderer | depth max | depth p99.9 | max, exact triangle "
            "| own triangle, float32: max / p99.9 | extra / missed | edge | behind (max gap) | edge distance, px |",
            "| --- | --- | ---: | --- | ---: | ---: | ---: | --- | --- | ---: | --- | ---: |"]
    for name, size, nhit, sa, oa, bt, _ in acc_rows:
        for who, a in (("softrast", sa), ("Open3D", oa)):
            out.append(f"| {name} | {size} | {nhit:,} | {who} | {fmt_err(a['max'])} | {fmt_err(a['p999'])} "
                       f"| {fmt_err(a['max_same'])} | {fmt_err(a['own_max'])} / {fmt_err(a['own_p999'])} "
                       f"| {a['extra']} / {a['missed']} | {a['edge']} "
                       f"| {a['behind']} ({fmt_err(a['behind_max'])}) | {a['edge_px']:.4f} |")
    out += ["",
            "softrast against Open3D: pixels where one hits and the other does not, and where both hit but "
            "different triangles; of each, how many the exact cast agrees with:",
            "",
            "| mesh | size | coverage differs | exact agrees: softrast / Open3D "
            "| triangle differs | exact agrees: softrast / Open3D / neither |",
            "| --- | --- | ---: | --- | ---: | --- |"]
    for name, size, nhit, sa, oa, bt, _ in acc_rows:
        out.append(f"| {name} | {size} | {bt['cover']} | {bt['cover_s']} / {bt['cover_o']} | {bt['vis']} "
                   f"| {bt['vis_s']} / {bt['vis_o']} / {bt['vis'] - bt['vis_s'] - bt['vis_o']} |")
    return "\n".join(out) + "\n"


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    d = sub.add_parser("dense")
    d.add_argument("src")
    d.add_argument("dst")
    d.add_argument("levels", type=int)
    r = sub.add_parser("run")
    r.add_argument("--softrast", default="build/softrast")
    r.add_argument("--timer", default="build/pinhole_time")
    r.add_argument("--frames", type=int, default=11)
    r.add_argument("--rounds", type=int, default=5)
    r.add_argument("--out")
    r.add_argument("meshes", nargs="+")
    args = p.parse_args()
    if args.command == "dense":
        dense(args.src, args.dst, args.levels)
    else:
        run(args)


if __name__ == "__main__":
    main()
