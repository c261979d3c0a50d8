"""How many vertices clusters of consecutive triangles of an OBJ would map:
for each cluster size, the distinct vertices per cluster, and their sum over
the mesh's vertices (the vertex work clusters would repeat, as a cluster
maps its boundary vertices again). docs/performance.md, "The limits".
Python standard library; faces as the OBJ loader triangulates them (a
polygon's fan), vertices by position index.

    python3 tools/cluster_reuse.py MESH.obj [SIZE ...]   (default sizes 32 64 128 256)
"""
import sys


def triangles(path):
    """The OBJ's vertex count and its triangles' position indices, 0-based."""
    vertices, tris = 0, []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                vertices += 1
            elif line.startswith("f "):
                idx = [int(t.split("/")[0]) for t in line.split()[1:]]
                idx = [i - 1 if i > 0 else vertices + i for i in idx]
                tris.extend((idx[0], idx[k], idx[k + 1]) for k in range(1, len(idx) - 1))
    return vertices, tris


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__.strip().splitlines()[-1].strip())
    vertices, tris = triangles(sys.argv[1])
    sizes = [int(s) for s in sys.argv[2:]] or [32, 64, 128, 256]
    print(f"{vertices} vertices, {len(tris)} triangles")
    for size in sizes:
        clusters = [tris[i:i + size] for i in range(0, len(tris), size)]
        mapped = sum(len({v for t in c for v in t}) for c in clusters)
        print(f"clusters of {size} triangles: {mapped / len(clusters):.1f} vertices each, "
              f"{mapped / vertices:.2f} times the mesh's vertices")


if __name__ == "__main__":
    main()
