#!/usr/bin/env python3
"""Objects held out from the suite: shapes no code in glint was tuned to, written as OBJ
files and tumbling requests, to check that speed holds beyond the suite's classes.

    python3 benches/heldout.py [--out DIR] [--decimals N | --digits N | --f32 full|shortest|nine]
    python3 benches/heldout.py --fixture tests/fixtures/heldout-cluster.json

Writes DIR/NAME.obj and DIR/NAME.json (the OBJ text inline, sunlight alone) for
- torus: a smooth ring that shades itself (R 1 m, r 0.38 m), 20,000 triangles;
- truss: a 2 m cube frame of 16 closed ten-sided struts, each through its neighbours
  at the nodes, 20,160 triangles;
- station: four cylindrical modules crossing each other and two panels through the
  ends of one, 19,680 triangles;
- cluster: 28 boxes of random size and attitude through one another (seeded), each
  side a grid of 8 x 8 squares, 21,504 triangles.
Coordinates are written with N decimals (default 9; 6 is what most exporters write), or
with N significant digits (`%g`, as C++ streams and assimp write them), or stored in single
precision and printed in full, shortest or to 9 digits (as benches/written.py's `--f32`).
The epochs tumble as the suite's do (`tumbling` in scenes/generate.py), in LEO.
benches/heldout.sh runs glint and the peer on them.
"""
import argparse, json, math, os, random, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes"))
from generate import tumbling  # noqa: E402
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from written import add_writing, writer  # noqa: E402

MATERIAL = {"name": "surface", "model": "rough-conductor", "alpha": 0.3, "n": 1.4, "k": 7.5, "kd": 0.1}


def torus(R=1.0, r=0.38, nu=100, nv=100):
    V, T = [], []
    for i in range(nu):
        a = 2 * math.pi * i / nu
        for j in range(nv):
            b = 2 * math.pi * j / nv
            V.append([(R + r * math.cos(b)) * math.cos(a), (R + r * math.cos(b)) * math.sin(a), r * math.sin(b)])
    at = lambda i, j: (i % nu) * nv + (j % nv)
    for i in range(nu):
        for j in range(nv):
            a, b, c, d = at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)
            T += [[a, b, c], [a, c, d]]
    return V, T


def prism(p, q, rad, sides, segs, V, T):
    """A closed prism from p to q: `sides` flat sides in `segs` rings, capped by fans."""
    ax = [q[k] - p[k] for k in range(3)]
    length = math.sqrt(sum(x * x for x in ax))
    ax = [x / length for x in ax]
    h = [1, 0, 0] if abs(ax[0]) < 0.9 else [0, 1, 0]
    u = [ax[1] * h[2] - ax[2] * h[1], ax[2] * h[0] - ax[0] * h[2], ax[0] * h[1] - ax[1] * h[0]]
    n = math.sqrt(sum(x * x for x in u))
    u = [x / n for x in u]
    w = [ax[1] * u[2] - ax[2] * u[1], ax[2] * u[0] - ax[0] * u[2], ax[0] * u[1] - ax[1] * u[0]]
    base = len(V)
    for s in range(segs + 1):
        c = [p[k] + (q[k] - p[k]) * s / segs for k in range(3)]
        for j in range(sides):
            a = 2 * math.pi * j / sides
            V.append([c[k] + rad * (math.cos(a) * u[k] + math.sin(a) * w[k]) for k in range(3)])
    ring = lambda s, j: base + s * sides + j % sides
    for s in range(segs):
        for j in range(sides):
            a, b, c, d = ring(s, j), ring(s, j + 1), ring(s + 1, j + 1), ring(s + 1, j)
            T += [[a, b, c], [a, c, d]]
    cp = len(V)
    V.append(list(p))
    cq = len(V)
    V.append(list(q))
    for j in range(sides):
        T.append([cp, ring(0, j + 1), ring(0, j)])
        T.append([cq, ring(segs, j), ring(segs, j + 1)])


def truss():
    V, T = [], []
    corners = [[x, y, z] for x in (-1.0, 1.0) for y in (-1.0, 1.0) for z in (-1.0, 1.0)]
    edges = [(i, j) for i in range(8) for j in range(i + 1, 8)
             if abs(sum(abs(corners[i][k] - corners[j][k]) for k in range(3)) - 2.0) < 1e-9]
    edges += [(0, 3), (4, 7), (0, 5), (2, 7)]  # diagonals across four sides
    for i, j in edges:
        p, q = corners[i], corners[j]
        d = [q[k] - p[k] for k in range(3)]
        length = math.sqrt(sum(x * x for x in d))
        d = [x / length for x in d]
        # each strut runs 6 cm past its nodes, through the struts that meet there
        prism([p[k] - 0.06 * d[k] for k in range(3)], [q[k] + 0.06 * d[k] for k in range(3)], 0.035, 10, 62, V, T)
    return V, T


def box(V, T, c, half, k, rot=None):
    """A closed box (centre c, half-sizes `half`, turned by the matrix `rot`), each side a
    k x k grid of squares."""
    def place(p):
        if rot:
            p = [sum(rot[i][j] * p[j] for j in range(3)) for i in range(3)]
        return [c[i] + p[i] for i in range(3)]
    for axis in range(3):
        for sign in (-1, 1):
            a1, a2 = (axis + 1) % 3, (axis + 2) % 3
            base = len(V)
            for i in range(k + 1):
                for j in range(k + 1):
                    p = [0.0, 0.0, 0.0]
                    p[axis] = sign * half[axis]
                    p[a1] = (-1 + 2 * i / k) * half[a1]
                    p[a2] = (-1 + 2 * j / k) * half[a2]
                    V.append(place(p))
            at = lambda i, j: base + i * (k + 1) + j
            for i in range(k):
                for j in range(k):
                    a, b, cc, d = at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)
                    T += [[a, b, cc], [a, cc, d]] if sign > 0 else [[a, cc, b], [a, d, cc]]


def station():
    V, T = [], []
    prism([-2.5, 0, 0], [2.5, 0, 0], 0.55, 96, 40, V, T)
    prism([0, -1.8, 0], [0, 1.8, 0], 0.45, 80, 30, V, T)
    prism([0, 0, -1.5], [0, 0, 2.2], 0.4, 64, 30, V, T)
    prism([1.2, -1.5, 0.0], [1.2, 1.5, 0.0], 0.3, 48, 20, V, T)
    for x in (-2.0, 2.0):
        box(V, T, [x, 0, 0], [0.12, 3.0, 0.02], 6)
    return V, T


def turn(rng):
    q = [rng.gauss(0, 1) for _ in range(4)]
    n = math.sqrt(sum(x * x for x in q))
    w, x, y, z = [v / n for v in q]
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def cluster_boxes():
    """The cluster's 28 boxes (seeded): (centre, half-sizes, turning matrix) each."""
    rng = random.Random(7)
    boxes = []
    for _ in range(28):
        c = [rng.uniform(-0.9, 0.9) for _ in range(3)]
        half = [rng.uniform(0.1, 0.5) for _ in range(3)]
        boxes.append((c, half, turn(rng)))
    return boxes


def cluster():
    V, T = [], []
    for c, half, rot in cluster_boxes():
        box(V, T, c, half, 8, rot)
    return V, T


def epochs():
    """The tumbling epochs every held-out request asks for."""
    return tumbling([0.2, -0.6, 0.77], [1.0, 0.0, 0.0], 261, 20.0, 150.0, 1.2e6, 7.178e6, 1.0,
                    spin_axis=[0.3, 0.8, 0.5], momentum=[-0.2, 0.4, 0.89], nutation_deg=35.0,
                    spin_deg=5.0, precession_deg=2.0)


def write_fixture(path):
    """The cluster as tests/silhouette.rs builds it: its boxes and its epochs, not its
    triangles (the test lays each side out as an 8 x 8 grid, as `box` does)."""
    fixture = {
        "made_by": "benches/heldout.py --fixture (the held-out cluster: seed 7, 28 boxes)",
        "boxes": [{"centre": c, "half": half, "turn": rot} for c, half, rot in cluster_boxes()],
        "epochs": epochs(),
    }
    with open(path, "w") as f:
        json.dump(fixture, f, indent=None, separators=(",", ":"))
        f.write("\n")


def obj_text(V, T, write):
    """The OBJ text of vertices V and triangles T, each coordinate written by `write`."""
    vertices = "".join("v %s %s %s\n" % tuple(write(x) for x in v) for v in V)
    return vertices + "usemtl surface\n" + "".join(
        "f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1) for t in T)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="target/heldout")
    ap.add_argument("--fixture", metavar="PATH",
                    help="write only the cluster's boxes and epochs, as tests/silhouette.rs reads them")
    add_writing(ap, decimals=9)
    args = ap.parse_args()
    if args.fixture:
        write_fixture(args.fixture)
        print("wrote", args.fixture)
        return
    write = writer(args)
    os.makedirs(args.out, exist_ok=True)
    for name, build in [("torus", torus), ("truss", truss), ("station", station), ("cluster", cluster)]:
        V, T = build()
        text = obj_text(V, T, write)
        with open(os.path.join(args.out, name + ".obj"), "w") as f:
            f.write(text)
        request = {
            "object": {"mesh": {"obj": text}, "materials": [MATERIAL]},
            "epochs": epochs(),
            "illumination": {"band_um": [0.4, 0.7], "sun_temperature_k": 5900, "earthshine": "off"},
            "tolerance": 1e-3,
        }
        with open(os.path.join(args.out, name + ".json"), "w") as f:
            json.dump(request, f)
        print("wrote", os.path.join(args.out, name), len(T), "triangles")


if __name__ == "__main__":
    main()
