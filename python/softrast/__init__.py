"""softrast from Python: numpy in, numpy out.

    import softrast
    mesh = softrast.Mesh.load("scan.ply")                 # or softrast.Mesh(positions, faces, uvs=..., texture=...)
    r = softrast.Renderer(640, 480)
    out = r.render(mesh, fx=525, fy=525, cx=319.5, cy=239.5, pose=pose, outputs=("color", "depth"))
    color, depth = out["color"], out["depth"]             # (480, 640, 3) uint8; (480, 640) float32, 0 where nothing

Cameras are OpenCV's pinhole (x right, y down, z forward; the centre of the
top-left pixel is (u, v) = (0, 0)); poses are 4x4 world-to-camera (pose_c2w=
for the inverse) in the mesh file's own frame, as `softrast render
--intrinsics --pose-w2c` takes them, or a look-at camera (eye=, target=,
up=, fov=) in that frame. Every returned array is new and owns its memory:
a later call never writes into it. See python/README.md.
"""
from ._softrast import MAX_SIDE, Mesh, Renderer

__all__ = ["Mesh", "Renderer", "MAX_SIDE"]
__version__ = "0.1.0"
