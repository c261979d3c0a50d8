"""softrast's render() against Open3D's RaycastingScene.cast_rays, both from
Python, on the same mesh arrays, camera and threads (a benchmark, not a
test): time per view of depth and face ids, and where the two disagree.

Needs Debian's python3-open3d, which this script does not install:

    sudo apt-get install python3-open3d

and Debian's Open3D 0.16 misses every ray without the ray-mask preload
(tools/open3d_ray_mask.c, docs/open3d-compare.md):

    make build/open3d_ray_mask.so test-python
    LD_PRELOAD=$PWD/build/open3d_ray_mask.so /usr/bin/python3 python/benchmarks/against_open3d.py [MESH ...]

The meshes default to the 121k-triangle glTF engine of assimp-testmodels
and, when `make scans` has fetched it, the 202k-triangle dragon. Both get
softrast.Mesh.load's arrays (Open3D's vertices as float32), so Open3D's
primitive id is face_ids - 1. Cameras are tools/compare_open3d.py's: a
three-quarter view, 40 degrees vertical, OpenCV's convention for both (Open3D's
rays go through the pixel centres). Times are medians of FRAMES views, the
best of ROUNDS rounds that alternate the two; softrast's includes Python's
call and its two new arrays, Open3D's the cast of premade rays.
"""
import argparse
import os
import statistics
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path += [os.path.dirname(HERE), os.path.join(ROOT, "tools")]  # an installed softrast first, else the in-place build
import numpy as np  # noqa: E402

import softrast  # noqa: E402

try:
    import compare_open3d as o3d_side  # noqa: E402  (tools/compare_open3d.py: Open3D's scene, rays and cast)
    import open3d  # noqa: F401,E402
except ImportError as e:
    sys.exit(f"against_open3d.py: {e}: it needs Debian's python3-open3d (sudo apt-get install python3-open3d)")

MESHES = ["/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
          os.path.join(ROOT, "build", "scans", "dragon.obj")]
SIZES = ((640, 480), (1920, 1080))


def softrast_ms(r, mesh, k, w2c, frames):
    render = lambda: r.render(mesh, K=k, pose=w2c, outputs=("depth", "face_ids"))  # noqa: E731
    out = render()
    ms = []
    for _ in range(frames):
        t0 = time.perf_counter()
        render()
        ms.append(1e3 * (time.perf_counter() - t0))
    return statistics.median(ms), out["depth"], out["face_ids"].astype(np.int64) - 1


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("meshes", nargs="*")
    ap.add_argument("--frames", type=int, default=9)
    ap.add_argument("--rounds", type=int, default=3)
    args = ap.parse_args()
    meshes = args.meshes or [m for m in MESHES if os.path.exists(m)]
    print(f"load {os.getloadavg()[0]:.1f}; medians of {args.frames} views, best of {args.rounds} rounds\n")
    print("| mesh | triangles | size | threads | softrast render() ms | Open3D cast_rays ms | Open3D / softrast "
          "| coverage differs | other triangle | depth, same triangle: max relative difference |")
    print("| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for path in meshes:
        mesh = softrast.Mesh.load(path)
        v, t = mesh.positions.astype(np.float64), mesh.faces
        scene = o3d_side.open3d_scene(v, t)
        for width, height in SIZES:
            k, w2c = o3d_side.camera(v, width, height)
            rays = o3d_side.open3d_rays(k, w2c, width, height)
            for threads in (1, 2):
                r = softrast.Renderer(width, height, threads=threads)
                s_ms, o_ms = [], []
                for _ in range(args.rounds):
                    ms, depth, ids = softrast_ms(r, mesh, k, w2c, args.frames)
                    s_ms.append(ms)
                    ms, _, t_hit, o_ids = o3d_side.run_open3d(scene, rays, threads, args.frames)
                    o_ms.append(ms)
                s, o = min(s_ms), min(o_ms)
                hit, o_hit = ids >= 0, o_ids >= 0
                same = hit & o_hit & (ids == o_ids)
                rel = np.abs(depth[same].astype(np.float64) / t_hit[same] - 1)
                print(f"| {os.path.basename(path)} | {len(t)} | {width}x{height} | {threads} | {s:.2f} | {o:.2f} | "
                      f"{o / s:.2f} | {(hit != o_hit).sum()} | {(hit & o_hit & (ids != o_ids)).sum()} | "
                      f"{rel.max():.1e} |", flush=True)


if __name__ == "__main__":
    main()
