#!/usr/bin/env python3
"""Writes the example requests in scenes/ (run from the repo root or scenes/).

Each request is a file that `glint simulate` and `POST /v1/lightcurves` take as it is.
The meshes are glint's built-in objects (scenes/objects/*.obj are their exports).
"""
import json, math, os

HERE = os.path.dirname(os.path.abspath(__file__))
GEO_RANGE = 3.6e7
GEO_RADIUS = 4.2164e7


def norm(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def sweep(sun, axis_hint, n, max_phase_deg, range_m, earth, dt=60.0):
    """Observer moving from phase 0 to max_phase in the plane of `sun` and `axis_hint`."""
    s = norm(sun)
    w = norm(cross(cross(s, axis_hint), s))
    epochs = []
    for i in range(n):
        ph = math.radians(max_phase_deg) * i / (n - 1)
        o = [range_m * (math.cos(ph) * s[k] + math.sin(ph) * w[k]) for k in range(3)]
        e = {"t": i * dt, "sun": [round(x, 9) for x in s], "observer": [round(x, 3) for x in o]}
        if earth is not None:
            e["earth"] = earth
        epochs.append(e)
    return epochs


def write(name, request):
    path = os.path.join(HERE, name)
    with open(path, "w") as f:
        json.dump(request, f, indent=1)
        f.write("\n")
    print("wrote", path, len(request["epochs"]), "epochs")


# Box-wing: the Sun high over the +y boom, so the bus shades the -y panel and the +y
# panel shades the bus; the observer sweeps from 0 to 170 degrees of phase.
write("box-wing.json", {
    "object": {
        "mesh": {"builtin": "box-wing"},
        "materials": [
            {"name": "body", "preset": "seed-body-wrap"},
            {"name": "panel", "model": "lambert", "albedo": 0.25, "two_sided": True},
            {"name": "dish", "preset": "seed-white-paint", "two_sided": True},
        ],
    },
    "epochs": sweep([0.45, 0.85, 0.28], [0.0, 0.0, 1.0], 341, 170.0, GEO_RANGE, [0.0, 0.0, -GEO_RADIUS]),
    "illumination": {"band_um": [0.4, 0.7], "sun_temperature_k": 5900, "earthshine": "seed", "earth_albedo": 0.35},
    "tolerance": 1e-3,
})

# Lambertian sphere over one geostationary day at equinox: the phase angle runs from
# 180 to 0 degrees and back, and the object passes through the Earth's shadow near 0.
epochs = []
n = 360
station = 6.371e6
for i in range(n + 1):
    a = 2 * math.pi * i / n
    pos = [GEO_RADIUS * math.cos(a), GEO_RADIUS * math.sin(a), 0.0]
    # observer on the equator below the object's longitude at t = 0 ... fixed in inertial space
    obs_pos = [station, 0.0, 0.0]
    epochs.append({
        "t": round(86164.09 * i / n, 3),
        "sun": [-1.0, 0.0, 0.0],
        "observer": [round(obs_pos[k] - pos[k], 3) for k in range(3)],
        "earth": [round(-pos[k], 3) for k in range(3)],
    })
write("sphere.json", {
    "object": {"mesh": {"builtin": "sphere"}, "materials": [{"name": "surface", "model": "lambert", "albedo": 0.3}]},
    "epochs": epochs,
    "illumination": {"earthshine": "sphere"},
})

# Flat plate facing +z: the observer sweeps across the specular direction of a glossy
# rough conductor, giving a glint on a diffuse floor.
write("plate.json", {
    "object": {
        "mesh": {"builtin": "plate"},
        "materials": [{"name": "surface", "model": "rough-conductor", "alpha": 0.1, "n": 1.5, "k": 3.0, "kd": 0.2}],
    },
    "epochs": sweep([0.5, 0.0, 0.866025404], [0.0, 1.0, 0.0], 301, 120.0, GEO_RANGE, None),
    "illumination": {"earthshine": "off"},
})
