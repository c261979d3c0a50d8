"""What a render costs from Python against the draw alone (a benchmark, not a
test): 640 x 480, the 110k-triangle glTF engine of Debian's
assimp-testmodels, one thread.

    make build/softrast test-python && /usr/bin/python3 python/benchmarks/overhead.py

- draw: `softrast render --shade id --frames N --stats`, ms_median (the
  timed frame: clear and draw, as in the command line's own timing);
- render(): softrast.Renderer.render(..., outputs=("depth",)), the median of
  N calls: the same draw, sr_pinhole_resolve of the depth, and Python's part
  (arguments, checks, a new 640 x 480 array, the result dict);
- call: render() of one triangle outside the view: what a call costs with
  next to no drawing (a 640 x 480 array allocated, cleared and resolved).
"""
import json
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(HERE))
import numpy as np  # noqa: E402

import softrast  # noqa: E402

ENGINE = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"
W, H, N = 640, 480, 40
K = (500.0, 500.0, 319.5, 239.5)


def look_pose(eye, target, up=(0, -1, 0)):
    eye, target = np.asarray(eye, float), np.asarray(target, float)
    z = (target - eye) / np.linalg.norm(target - eye)
    x = np.cross(up, z)
    x /= np.linalg.norm(x)
    w2c = np.eye(4)
    w2c[:3, :3] = np.stack([x, np.cross(z, x), z])
    w2c[:3, 3] = -w2c[:3, :3] @ eye
    return w2c


def median_ms(f):
    f()
    times = []
    for _ in range(N):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return 1e3 * statistics.median(times)


def main():
    pose = look_pose([300, 250, -500], [0, 0, 0])
    cli = subprocess.run([os.path.join(ROOT, "build", "softrast"), "render", ENGINE, "--size", f"{W}x{H}",
                          "--intrinsics", ",".join(map(str, K)), "--pose-w2c", ",".join(map(repr, pose.ravel())),
                          "--shade", "id", "--frames", str(N), "--threads", "1", "--stats", "--quiet"],
                         capture_output=True, text=True, check=True)
    draw = json.loads(cli.stdout.splitlines()[0])["ms_median"]
    mesh = softrast.Mesh.load(ENGINE)
    r = softrast.Renderer(W, H, threads=1)
    fx, fy, cx, cy = K
    render = median_ms(lambda: r.render(mesh, fx=fx, fy=fy, cx=cx, cy=cy, pose=pose))
    behind = softrast.Mesh([[0, 0, -1], [1, 0, -1], [0, 1, -1]], [[0, 1, 2]])
    call = median_ms(lambda: r.render(behind, fx=fx, fy=fy, cx=cx, cy=cy, pose=np.eye(4)))
    print(f"{mesh.triangle_count} triangles, {W}x{H}, 1 thread, median of {N}:")
    print(f"  draw (command line, --shade id):    {draw:7.3f} ms")
    print(f"  render() from Python, depth:        {render:7.3f} ms  (+{render - draw:.3f} ms, "
          f"{100 * (render - draw) / draw:.1f} % of the draw: the resolve and Python)")
    print(f"  render() of nothing in view:        {call:7.3f} ms  ({100 * call / draw:.1f} % of the draw)")


if __name__ == "__main__":
    main()
