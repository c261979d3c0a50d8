"""What a render costs from Python beyond the library's own work (a
benchmark, not a test): 640 x 480, the 121k-triangle glTF engine of Debian's
assimp-testmodels, depth and face ids (and colour with depth), one thread.

    make build/pinhole_time test-python && /usr/bin/python3 python/benchmarks/overhead.py [ROUNDS]

1. Instructions (callgrind, exact and deaf to the machine's other work):
   Python is run under valgrind twice, rendering 1 and then 3 frames, and a
   function's instructions a frame are the difference over 2 (the first
   frame, which sets up the workspace, drops out). render() is the
   binding's render_call, all of it; the library's part of it is what it
   calls in the library's sources (sr_draw_layered, sr_pinhole_resolve,
   sr_pinhole_fit_clip, ...), and the rest (argument checks, arrays, the
   dict, the GIL released and taken back) is Python's overhead, given as a
   share of the draw's. A render of colour (lambert) and depth is counted
   the same way, whole.
2. Time (ms, medians of N, the best of ROUNDS rounds that alternate the two
   so a busy spell on a shared machine hits both): build/pinhole_time (the
   public C API: the id draw, then sr_pinhole_resolve of depth and face
   ids) against render(); render() of nothing in view, what a call costs
   with next to no drawing (arguments, two new 640 x 480 arrays written
   whole, the dict); and render() with colour too (the same one draw,
   lambert shaded).
"""
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.append(os.path.dirname(HERE))  # an installed softrast first, else the in-place build
import numpy as np  # noqa: E402

import softrast  # noqa: E402

ENGINE = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"
W, H, N = 640, 480, 30
FX, FY, CX, CY = 500.0, 500.0, 319.5, 239.5


def look_pose(eye, target, up=(0, -1, 0)):
    eye, target = np.asarray(eye, float), np.asarray(target, float)
    z = (target - eye) / np.linalg.norm(target - eye)
    x = np.cross(up, z)
    x /= np.linalg.norm(x)
    w2c = np.eye(4)
    w2c[:3, :3] = np.stack([x, np.cross(z, x), z])
    w2c[:3, 3] = -w2c[:3, :3] @ eye
    return w2c


POSE = look_pose([300, 250, -500], [0, 0, 0])
IDS, COLOUR = ("depth", "face_ids"), ("color", "depth")


def render_frames(frames, outputs):
    """What the instruction count runs: frames renders after the load."""
    mesh = softrast.Mesh.load(ENGINE)
    r = softrast.Renderer(W, H, threads=1)
    for _ in range(frames):
        r.render(mesh, fx=FX, fy=FY, cx=CX, cy=CY, pose=POSE, outputs=outputs)


def instructions(frames, outputs, tmp):
    """render()'s inclusive instructions (the binding's render_call), and
    those of its callees in the library's sources, by name."""
    out = os.path.join(tmp, f"callgrind.{frames}.{len(outputs)}")
    subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", sys.executable, __file__,
                    "--frames", str(frames), *outputs], check=True, capture_output=True)
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--tree=calling", "--threshold=100", out],
                          check=True, capture_output=True, text=True).stdout
    block = re.search(r"^\s*([\d,]+) \([^)]*\)\s+\*\s+\S+:render_call \[.*?\n\n", text, re.M | re.S)
    library = {}
    for count, path, name in re.findall(r"^\s*([\d,]+) \([^)]*\)\s+>\s+(\S+):(\w+)", block.group(0), re.M):
        if os.path.abspath(path).startswith(os.path.join(ROOT, "src") + os.sep):
            library[name] = library.get(name, 0) + int(count.replace(",", ""))
    return int(block.group(1).replace(",", "")), library


def median_ms(f):
    f()
    times = []
    for _ in range(N):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return 1e3 * statistics.median(times)


def library_ms(timer):
    out = subprocess.run([timer, ENGINE, str(W), str(H), f"{FX},{FY},{CX},{CY}", ",".join(map(repr, POSE.ravel())),
                          "1", str(N)], capture_output=True, text=True, check=True).stdout
    t = json.loads(out)
    return t["draw_ms"], t["resolve_ms"]


def main():
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    timer = os.path.join(ROOT, "build", "pinhole_time")
    for path, make in ((ENGINE, "apt-get install assimp-testmodels"), (timer, "make build/pinhole_time")):
        if not os.path.exists(path):
            sys.exit(f"overhead.py: {path} is missing: {make}")
    mesh = softrast.Mesh.load(ENGINE)
    print(f"{mesh.triangle_count} triangles, {W}x{H}, depth and face ids, 1 thread", flush=True)

    with tempfile.TemporaryDirectory() as tmp:
        (call1, lib1), (call3, lib3) = instructions(1, IDS, tmp), instructions(3, IDS, tmp)
        (colour1, _), (colour3, _) = instructions(1, COLOUR, tmp), instructions(3, COLOUR, tmp)
    each = {name: (lib3[name] - lib1.get(name, 0)) / 2 for name in lib3}
    call, library, draw = (call3 - call1) / 2, sum(each.values()), each["sr_draw_layered"]
    overhead = call - library
    print(f"  instructions a frame (callgrind): render() {call / 1e6:.3f} M; the library {library / 1e6:.3f} M "
          f"({', '.join(f'{name} {n / 1e6:.3f} M' for name, n in sorted(each.items(), key=lambda x: -x[1]) if n)})")
    print(f"  Python's overhead: {overhead / 1e3:.1f} k instructions, {100 * overhead / draw:.3f} % of the draw's")
    print(f"  render() of colour and depth: {(colour3 - colour1) / 2e6:.3f} M instructions a frame")

    r = softrast.Renderer(W, H, threads=1)
    camera = dict(fx=FX, fy=FY, cx=CX, cy=CY, pose=POSE)
    behind = softrast.Mesh([[0, 0, -1], [1, 0, -1], [0, 1, -1]], [[0, 1, 2]])
    rows = []
    for _ in range(rounds):
        lib_draw, lib_resolve = library_ms(timer)
        render = median_ms(lambda: r.render(mesh, **camera, outputs=("depth", "face_ids")))
        nothing = median_ms(lambda: r.render(behind, fx=FX, fy=FY, cx=CX, cy=CY, outputs=("depth", "face_ids")))
        color = median_ms(lambda: r.render(mesh, **camera, outputs=("color", "depth", "face_ids")))
        rows.append((lib_draw + lib_resolve, lib_draw, render, nothing, color))
    lib, lib_draw, render, nothing, color = min(rows, key=lambda row: row[2])
    print(f"  time (ms), median of {N}, best of {rounds} rounds (load {os.getloadavg()[0]:.1f}):")
    print(f"    library (pinhole_time): draw {lib_draw:.2f} + resolve {lib - lib_draw:.2f} = {lib:.2f}")
    print(f"    render():               {render:.2f}")
    print(f"    render() of nothing:    {nothing:.2f} ({100 * nothing / lib_draw:.1f} % of the draw)")
    print(f"    render() with colour:   {color:.2f}")


if __name__ == "__main__":
    if len(sys.argv) >= 4 and sys.argv[1] == "--frames":
        render_frames(int(sys.argv[2]), tuple(sys.argv[3:]))
    else:
        main()
