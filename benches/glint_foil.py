#!/usr/bin/env python3
"""A glint-heavy request for timing the Sun-disk rules: a 1 m crumpled mirror foil (a 120x120
grid, 28,800 triangles, smooth random bumps with slopes of a few mrad, so that the faces'
mirror directions spread over about two solar radii) of the seed model at slope 1e-4, the
observer swept 1.2 degrees across the glint in 200 epochs, method `convex` (no shadow work).

    python3 benches/glint_foil.py > /tmp/foil.json
    glint simulate -q /tmp/foil.json --out /tmp/foil.csv
"""
import json
import math
import random
import sys

random.seed(7)
N = 120
bumps = [(random.uniform(-1, 1) * 2e-4, random.uniform(2, 9), random.uniform(2, 9),
          random.uniform(0, 6.28), random.uniform(0, 6.28)) for _ in range(12)]


def height(x, y):
    return sum(a * math.sin(kx * x * 6.28 + p) * math.sin(ky * y * 6.28 + q)
               for a, kx, ky, p, q in bumps)


vertices = []
for i in range(N + 1):
    for j in range(N + 1):
        x, y = i / N - 0.5, j / N - 0.5
        vertices.append((x, y, height(x, y)))
faces = []
for i in range(N):
    for j in range(N):
        a = i * (N + 1) + j
        b, c = a + 1, a + N + 1
        faces += [(a, c, c + 1), (a, c + 1, b)]
obj = "".join(f"v {x:.9f} {y:.9f} {z:.9f}\n" for x, y, z in vertices)
obj += "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in faces)

ti = math.radians(35)
sun = [math.sin(ti), 0.0, math.cos(ti)]
v0 = (-sun[0], sun[2])
epochs = []
for k in range(200):
    a = math.radians(-0.6 + 1.2 * k / 199)
    c, s = math.cos(a), math.sin(a)
    vx, vz = v0[0] * c + v0[1] * s, -v0[0] * s + v0[1] * c
    r = 3.6e7
    epochs.append({"t": float(k), "sun": sun, "observer": [vx * r, 0.002 * r, vz * r]})
request = {
    "object": {"mesh": {"obj": obj},
               "materials": [{"name": "surface", "model": "seed-microfacet", "kd": 0.1,
                              "km": 0.5, "slope_rms": 1e-4, "n": 0.18, "k": 3.6}]},
    "epochs": epochs,
    "illumination": {"earthshine": "off"},
    "method": "convex",
}
json.dump(request, sys.stdout)
