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


def qmul(a, b):
    """Hamilton product of quaternions [w, x, y, z]."""
    return [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]


def qaxis(axis, angle):
    a = norm(axis)
    h = 0.5 * angle
    return [math.cos(h)] + [math.sin(h) * x for x in a]


def tumbling(sun, axis_hint, n, min_phase_deg, max_phase_deg, range_m, earth_m, dt, spin_axis,
             momentum, nutation_deg, spin_deg, precession_deg, phase0_deg=0.0):
    """Inertial Sun and observer, the phase angle sweeping from min_phase to max_phase in the
    plane of `sun` and `axis_hint`; the Earth at distance earth_m off that plane (never
    between the object and the Sun); and a torque-free-looking tumble: the body spins about
    its `spin_axis` by spin_deg per epoch, that axis leans nutation_deg from the inertial
    angular momentum `momentum` and precesses about it by precession_deg per epoch.
    `attitude` is body -> inertial [w, x, y, z]."""
    s = norm(sun)
    w = norm(cross(cross(s, axis_hint), s))
    e = norm(cross(s, w))
    # body frame turned so that spin_axis -> z: the spin is about body z afterwards
    z = [0.0, 0.0, 1.0]
    c = sum(a * b for a, b in zip(norm(spin_axis), z))
    ax = cross(norm(spin_axis), z)
    to_z = qaxis(ax, math.acos(max(-1.0, min(1.0, c)))) if math.sqrt(sum(x * x for x in ax)) > 1e-12 \
        else ([1.0, 0.0, 0.0, 0.0] if c > 0 else [0.0, 1.0, 0.0, 0.0])
    # z -> momentum, so precession is about z before this
    m = norm(momentum)
    cm = m[2]
    axm = cross(z, m)
    z_to_m = qaxis(axm, math.acos(max(-1.0, min(1.0, cm)))) if math.sqrt(sum(x * x for x in axm)) > 1e-12 \
        else [1.0, 0.0, 0.0, 0.0]
    epochs = []
    for i in range(n):
        ph = math.radians(min_phase_deg + (max_phase_deg - min_phase_deg) * i / (n - 1))
        o = [range_m * (math.cos(ph) * s[k] + math.sin(ph) * w[k]) for k in range(3)]
        q = qmul(qaxis(z, math.radians(precession_deg * i)), qaxis([1.0, 0.0, 0.0], math.radians(nutation_deg)))
        q = qmul(q, qaxis(z, math.radians(phase0_deg + spin_deg * i)))
        q = qmul(z_to_m, qmul(q, to_z))
        qn = math.sqrt(sum(x * x for x in q))
        epochs.append({
            "t": round(i * dt, 3),
            "sun": [round(x, 9) for x in s],
            "observer": [round(x, 3) for x in o],
            "earth": [round(earth_m * x, 3) for x in e],
            "attitude": [round(x / qn, 12) for x in q],
        })
    return epochs


def write(name, request):
    path = os.path.join(HERE, name)
    with open(path, "w") as f:
        json.dump(request, f, indent=1)
        f.write("\n")
    print("wrote", path, len(request["epochs"]), "epochs")


def main():
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

    # Tumbling objects: inertial Sun and observer (the phase angle sweeps from 20 to 150
    # degrees), a body-to-inertial attitude per epoch from a spin about a body axis that
    # precesses about the angular momentum, several turns over the 261 epochs.
    LEO_RANGE = 1.2e6
    LEO_RADIUS = 7.178e6
    TUMBLE_EPOCHS = 261

    # Spent upper stage in LEO: flat spin (about an axis across the stage, as upper stages
    # end up) with the stage axis wobbling; aluminium skirt, dark nozzle.
    write("rocket-body.json", {
        "object": {
            "mesh": {"builtin": "rocket-body", "detail": "medium"},
            "materials": [
                {"name": "body", "preset": "seed-body-wrap"},
                {"name": "skirt", "model": "rough-conductor", "alpha": 0.3, "n": 1.2, "k": 7.0, "kd": 0.1},
                {"name": "nozzle", "model": "lambert", "albedo": 0.08},
            ],
        },
        "epochs": tumbling([0.6, -0.7, 0.39], [0.0, 0.0, 1.0], TUMBLE_EPOCHS, 20.0, 150.0, LEO_RANGE, LEO_RADIUS, 2.0,
                           spin_axis=[1.0, 0.1, 0.15], momentum=[0.3, 0.5, 0.81], nutation_deg=25.0,
                           spin_deg=4.0, precession_deg=1.5),
        "illumination": {"band_um": [0.4, 0.7], "sun_temperature_k": 5900, "earthshine": "seed", "earth_albedo": 0.3},
        "tolerance": 1e-3,
    })

    # Crumpled aluminium fragment in LEO, tumbling fast about an off-principal axis.
    write("fragment.json", {
        "object": {
            "mesh": {"builtin": "fragment", "detail": "medium"},
            "materials": [
                {"name": "surface", "model": "rough-conductor", "alpha": 0.25, "n": 1.4, "k": 7.5, "kd": 0.15},
            ],
        },
        "epochs": tumbling([-0.3, 0.8, 0.52], [1.0, 0.0, 0.0], TUMBLE_EPOCHS, 20.0, 150.0, LEO_RANGE, LEO_RADIUS, 1.0,
                           spin_axis=[0.4, 0.7, 0.6], momentum=[0.1, -0.4, 0.91], nutation_deg=40.0,
                           spin_deg=6.0, precession_deg=2.5),
        "illumination": {"band_um": [0.4, 0.7], "sun_temperature_k": 5900, "earthshine": "seed", "earth_albedo": 0.3},
        "tolerance": 1e-3,
    })

    # Dead communications satellite in GEO, slowly tumbling about its long axis while that
    # axis precesses: glossy cells on the wings, white dish.
    write("dish-sat.json", {
        "object": {
            "mesh": {"builtin": "dish-sat", "detail": "medium"},
            "materials": [
                {"name": "body", "preset": "seed-body-wrap"},
                {"name": "panel", "model": "ashikhmin-shirley", "rd": 0.05, "rs": 0.25, "nu": 300, "nv": 300, "two_sided": True},
                {"name": "dish", "preset": "seed-white-paint", "two_sided": True},
                {"name": "strut", "model": "lambert", "albedo": 0.5},
            ],
        },
        "epochs": tumbling([0.45, 0.85, 0.28], [0.0, 0.0, 1.0], TUMBLE_EPOCHS, 20.0, 150.0, GEO_RANGE, GEO_RADIUS, 30.0,
                           spin_axis=[0.0, 0.2, 1.0], momentum=[0.2, 0.3, 0.93], nutation_deg=20.0,
                           spin_deg=4.0, precession_deg=1.5),
        "illumination": {"band_um": [0.4, 0.7], "sun_temperature_k": 5900, "earthshine": "seed", "earth_albedo": 0.35},
        "tolerance": 1e-3,
    })

    # 6U CubeSat in LEO after deployment went wrong: anodised body, glossy panels.
    write("cubesat.json", {
        "object": {
            "mesh": {"builtin": "cubesat", "detail": "medium"},
            "materials": [
                {"name": "body", "model": "rough-conductor", "alpha": 0.2, "n": 1.5, "k": 6.0, "kd": 0.3},
                {"name": "panel", "model": "ashikhmin-shirley", "rd": 0.05, "rs": 0.25, "nu": 300, "nv": 300, "two_sided": True},
            ],
        },
        "epochs": tumbling([0.7, 0.1, -0.7], [0.0, 1.0, 0.0], TUMBLE_EPOCHS, 20.0, 150.0, 6.0e5, 6.871e6, 1.0,
                           spin_axis=[0.2, 0.3, 1.0], momentum=[-0.5, 0.2, 0.84], nutation_deg=30.0,
                           spin_deg=5.0, precession_deg=2.0),
        "illumination": {"band_um": [0.4, 0.7], "sun_temperature_k": 5900, "earthshine": "seed", "earth_albedo": 0.3},
        "tolerance": 1e-3,
    })

    # The fine-dish box-wing (detail medium, 15.5k triangles) tumbling in GEO.
    write("box-wing-tumbling.json", {
        "object": {
            "mesh": {"builtin": "box-wing", "detail": "medium"},
            "materials": [
                {"name": "body", "preset": "seed-body-wrap"},
                {"name": "panel", "model": "lambert", "albedo": 0.25, "two_sided": True},
                {"name": "dish", "preset": "seed-white-paint", "two_sided": True},
            ],
        },
        "epochs": tumbling([0.45, 0.85, 0.28], [0.0, 0.0, 1.0], TUMBLE_EPOCHS, 20.0, 150.0, GEO_RANGE, GEO_RADIUS, 30.0,
                           spin_axis=[0.1, 1.0, 0.2], momentum=[0.5, 0.1, 0.86], nutation_deg=30.0,
                           spin_deg=4.0, precession_deg=1.5),
        "illumination": {"band_um": [0.4, 0.7], "sun_temperature_k": 5900, "earthshine": "seed", "earth_albedo": 0.35},
        "tolerance": 1e-3,
    })


if __name__ == "__main__":
    main()
