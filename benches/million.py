#!/usr/bin/env python3
"""A suite class at about a million triangles and ten thousand epochs, to measure memory
(docs/performance.md, fourteenth sitting):

    glint export-objects --detail medium --dir /tmp/objs
    python3 benches/million.py /tmp/objs/rocket-body.obj scenes/rocket-body.json /tmp/big.json
    /usr/bin/time -v glint simulate /tmp/big.json --out /tmp/big.csv -q

Each triangle of the OBJ is split n x n (`--split`, default 7: 20k -> 980k triangles), the new
points nudged by 2e-6 of the object's size in a seeded random direction so that no two
triangles lie in one plane and merge into a face. The request keeps its materials and
tolerance, takes the mesh inline, turns earthshine off (the peer's lighting) and repeats its
own epochs, times shifted on, until there are `--epochs` (default 10,000).
"""
import argparse
import json
import random


def read_obj(path):
    verts, tris, mtls = [], [], []
    mtl = None
    for line in open(path):
        if line.startswith("v "):
            verts.append(tuple(map(float, line.split()[1:4])))
        elif line.startswith("usemtl"):
            mtl = line.split()[1]
        elif line.startswith("f "):
            tris.append(tuple(int(x.split("/")[0]) - 1 for x in line.split()[1:4]))
            mtls.append(mtl)
    return verts, tris, mtls


def split(verts, tris, mtls, n, seed=7):
    """Every triangle split n x n; the points on an edge shared by the two triangles beside it."""
    rng = random.Random(seed)
    size = max(max(abs(c) for c in v) for v in verts)
    jitter = 2e-6 * size
    out = list(verts)

    def new_point(p):
        out.append(tuple(c + jitter * rng.uniform(-1.0, 1.0) for c in p))
        return len(out) - 1

    on_edge = {}

    def edge_point(a, b, k):
        # the k-th of the n - 1 points from a to b, one for both triangles of the edge
        if a > b:
            a, b, k = b, a, n - k
        if (a, b, k) not in on_edge:
            pa, pb = verts[a], verts[b]
            on_edge[a, b, k] = new_point(tuple(pa[i] + (pb[i] - pa[i]) * k / n for i in range(3)))
        return on_edge[a, b, k]

    by_mtl = {}
    for (a, b, c), m in zip(tris, mtls):
        at = {}
        for i in range(n + 1):
            for j in range(n + 1 - i):
                k = n - i - j  # weights: a k, b i, c j
                if i == 0 and j == 0:
                    at[i, j] = a
                elif i == n:
                    at[i, j] = b
                elif j == n:
                    at[i, j] = c
                elif j == 0:
                    at[i, j] = edge_point(a, b, i)
                elif i == 0:
                    at[i, j] = edge_point(a, c, j)
                elif k == 0:
                    at[i, j] = edge_point(b, c, j)
                else:
                    pa, pb, pc = verts[a], verts[b], verts[c]
                    at[i, j] = new_point(tuple((pa[q] * k + pb[q] * i + pc[q] * j) / n for q in range(3)))
        faces = by_mtl.setdefault(m, [])
        for i in range(n):
            for j in range(n - i):
                faces.append((at[i, j], at[i + 1, j], at[i, j + 1]))
                if i + j < n - 1:
                    faces.append((at[i + 1, j], at[i + 1, j + 1], at[i, j + 1]))
    return out, by_mtl


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("obj", help="the class's mesh (glint export-objects --detail medium)")
    ap.add_argument("request", help="the class's request in scenes/ (materials, epochs)")
    ap.add_argument("out", help="the request to write")
    ap.add_argument("--split", type=int, default=7, help="each triangle split n x n (default 7)")
    ap.add_argument("--epochs", type=int, default=10000, help="epochs (default 10,000)")
    a = ap.parse_args()
    if a.split < 1 or a.epochs < 1:
        ap.error("--split and --epochs must be positive")
    verts, tris, mtls = read_obj(a.obj)
    points, by_mtl = split(verts, tris, mtls, a.split)
    lines = ["v %r %r %r" % v for v in points]
    count = 0
    for m, faces in by_mtl.items():
        if m is not None:
            lines.append("usemtl " + m)
        for f in faces:
            lines.append("f %d %d %d" % tuple(x + 1 for x in f))
            count += 1
    request = json.load(open(a.request))
    request["object"]["mesh"] = {"obj": "\n".join(lines) + "\n"}
    request.setdefault("illumination", {})["earthshine"] = "off"
    own = request["epochs"]
    span = own[-1]["t"] - own[0]["t"] + (own[1]["t"] - own[0]["t"] if len(own) > 1 else 1.0)
    request["epochs"] = [
        dict(own[i % len(own)], t=own[i % len(own)]["t"] + span * (i // len(own)))
        for i in range(a.epochs)
    ]
    json.dump(request, open(a.out, "w"))
    print(f"{a.out}: {count} triangles, {len(points)} vertices, {a.epochs} epochs")


if __name__ == "__main__":
    main()
