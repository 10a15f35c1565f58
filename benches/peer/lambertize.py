"""Rewrite a glint request for an accuracy comparison with the peer.

    python3 benches/peer/lambertize.py IN.json OUT.json [--albedo 0.5] [--obj MESH.obj]
        [--epochs N] [--stride K] [--tumble DEG]

Every material becomes `lambert` of albedo --albedo under its own name, keeping its
`two_sided`; earthshine is turned off (the peer has only the Sun).  --obj puts that
OBJ text inline as the mesh (so glint and the peer read one mesh); --epochs keeps the
first N epochs, --stride K every K-th (after --epochs).  --tumble DEG gives epoch i the body -> inertial attitude q_i, a turn of
i*DEG degrees about a fixed skew axis, and turns its `sun`, `observer` and `earth` into
the inertial frame (inertial = q_i * body): the light curve must not change, which
checks that glint and the peer both rotate inertial vectors back with q^-1.
"""
import argparse
import json
import math

import numpy as np


def quat_rotate(q, v):
    w, x, y, z = q
    r = np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])
    return r @ np.asarray(v, float)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    ap.add_argument("request")
    ap.add_argument("out")
    ap.add_argument("--albedo", type=float, default=0.5)
    ap.add_argument("--obj", help="use this OBJ text as the mesh")
    ap.add_argument("--epochs", type=int, default=0)
    ap.add_argument("--stride", type=int, default=1, help="keep every K-th epoch")
    ap.add_argument("--tumble", type=float, default=0.0, help="degrees per epoch (0: no attitudes)")
    a = ap.parse_args()

    req = json.load(open(a.request))
    mats = []
    for m in req["object"]["materials"]:
        m = {"name": m} if isinstance(m, str) else m
        out = {"name": m["name"], "model": "lambert", "albedo": a.albedo}
        if m.get("two_sided"):
            out["two_sided"] = True
        mats.append(out)
    req["object"]["materials"] = mats
    if a.obj:
        req["object"]["mesh"] = {"obj": open(a.obj).read()}
    req.setdefault("illumination", {})["earthshine"] = "off"
    req.pop("thumbnails", None)
    if a.epochs:
        req["epochs"] = req["epochs"][: a.epochs]
    req["epochs"] = req["epochs"][:: max(a.stride, 1)]
    if a.tumble:
        axis = np.array([0.3, -0.5, 0.81])
        axis /= np.linalg.norm(axis)
        for i, ep in enumerate(req["epochs"]):
            if ep.get("attitude") is not None:
                raise SystemExit("--tumble: the request already has attitudes")
            h = math.radians(a.tumble * i) / 2
            q = [math.cos(h), *(math.sin(h) * axis)]
            for k in ("sun", "observer", "earth"):
                if ep.get(k) is not None:
                    ep[k] = quat_rotate(q, ep[k]).tolist()
            ep["attitude"] = q
    json.dump(req, open(a.out, "w"), indent=1)


if __name__ == "__main__":
    main()
