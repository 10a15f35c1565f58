#!/usr/bin/env python3
"""Writes scenes/hard.json: a deliberately hard scene for `glint tradeoff`.

A concave "comb": a 4 m x 4 m base plate (2 large triangles), four 1.5 m tall fins
(two-sided, 2 triangles each) and a back wall, so the Sun throws long partial shadows
across large triangles; plus a 3 m x 1.5 m nearly mirror-smooth panel (rough conductor,
alpha 1e-4, tilted 30° from the base's normal) whose glint the observer's sweep crosses. Vectors are chosen off the axes.
"""
import json, math, os

HERE = os.path.dirname(os.path.abspath(__file__))


def norm(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


vertices, triangles, ids = [], [], []


def quad(p, m):
    """Corners counter-clockwise seen from the side the normal points to."""
    b = len(vertices)
    vertices.extend(p)
    triangles.extend([[b, b + 1, b + 2], [b, b + 2, b + 3]])
    ids.extend([m, m])


# base plate, normal +z
quad([[-2, -2, 0], [2, -2, 0], [2, 2, 0], [-2, 2, 0]], 0)
# fins in the planes x = const, normal +x (two-sided)
for x in (-1.5, -0.5, 0.5, 1.5):
    quad([[x, -2, 0], [x, 2, 0], [x, 2, 1.5], [x, -2, 1.5]], 1)
# back wall at y = -2, normal +y
quad([[-2, -2, 0], [-2, -2, 1.5], [2, -2, 1.5], [2, -2, 0]], 0)
# mirror panel beyond +y, normal (0, sin 30°, cos 30°)
n_m = [0.0, math.sin(math.radians(30)), math.cos(math.radians(30))]
up = [0.0, -n_m[2], n_m[1]]  # in the panel, towards +z
c = [0.0, 2.6, 1.0]
corners = []
for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
    corners.append([c[k] + sx * 1.5 * [1, 0, 0][k] + sy * 0.75 * up[k] for k in range(3)])
quad(corners[::-1], 2)  # reversed: counter-clockwise seen from the normal side

sun = norm([0.42, 0.15, 0.9])
mirror = [2 * dot(n_m, sun) * n_m[k] - sun[k] for k in range(3)]  # the glint direction
# observer sweeps 60° along a great circle through the glint, starting low in azimuth
a = norm(cross([0.0, 0.0, 1.0], mirror))
epochs = []
n = 241
for i in range(n):
    th = math.radians(-30 + 60 * i / (n - 1) + 0.013)  # offset: no epoch sits on the peak
    d = [math.cos(th) * mirror[k] + math.sin(th) * a[k] for k in range(3)]
    epochs.append({"t": 60.0 * i, "sun": [round(x, 9) for x in sun],
                   "observer": [round(3.6e7 * x, 3) for x in d]})

request = {
    "object": {
        "mesh": {"vertices": vertices, "triangles": triangles, "material_ids": ids},
        "materials": [
            {"name": "plate", "model": "lambert", "albedo": 0.5},
            {"name": "fin", "preset": "seed-body-wrap", "two_sided": True},
            {"name": "mirror", "model": "rough-conductor", "alpha": 1e-4, "n": 1.1, "k": 6.8},
        ],
    },
    "epochs": epochs,
    "illumination": {"earthshine": "off"},
}
with open(os.path.join(HERE, "hard.json"), "w") as f:
    json.dump(request, f, indent=1)
    f.write("\n")
print("glint direction", [round(x, 4) for x in mirror], "observer z range",
      round(min(e["observer"][2] for e in epochs) / 3.6e7, 3), round(max(e["observer"][2] for e in epochs) / 3.6e7, 3))
