"""Compare glint's light curve with the peer's, epoch by epoch.

    python3 benches/peer/compare.py GLINT.json PEER.csv [--peer2 PEER2.csv] [--request REQ.json]
        [--floor 1e-3] [-v] [--summary OUT.csv --label NAME]

GLINT.json is `glint simulate REQ.json --out GLINT.json`; PEER.csv is
`benches/peer/mitsuba_lightcurve.py MESH.obj REQ.json --materials lambert --out PEER.csv`,
on the same request with Lambertian materials (benches/peer/lambertize.py). PEER.csv may
also be another glint response (a .json: another method, another tolerance) on the same
request.

Glint's intensity from sunlight (sun_w_m2 x range_m^2, W/sr) divided by the band solar
irradiance reaching the object is the intensity per unit irradiance (m^2/sr) that the
peer's summed image gives.  The band irradiance at 1 AU is read off the response itself:
magnitude = -26.74 - 2.5 log10(E / E_sun,1AU), so E_sun,1AU = E 10^(0.4 (m + 26.74));
at the object it is that / sun_distance_au^2 (from --request, default 1 AU) x (1 -
eclipse) (the peer has no eclipses; fully eclipsed epochs are left out).  Epochs whose
signal is below --floor of the curve's maximum are left out too; the worst and median
relative difference |peer - glint| / glint over the rest are printed.

--peer2: the peer on the same request at another --scale.  The light its shadow rays
leak grows with their offset relative to the mesh's size (the CSVs' ray_offset column;
see mitsuba_lightcurve.py), so each epoch is extrapolated linearly in that offset to
none, p0 = (x2 p1 - x1 p2) / (x2 - x1), and compared as well.
"""
import argparse
import csv
import json
import os
import statistics
import sys


def sun_intensities(epochs, au, e_sun_1au):
    """index -> intensity from sunlight per unit band irradiance at the object (m^2/sr)."""
    out = {}
    for i, e in enumerate(epochs):
        if e["eclipse"] >= 1.0:
            continue
        e_sun = e_sun_1au / au[i] ** 2 * (1.0 - e["eclipse"])
        out[i] = e["sun_w_m2"] * e["range_m"] ** 2 / e_sun
    return out


def read_peer(path, au, e_sun_1au):
    """index -> (intensity m^2/sr, relative ray offset or None), from the peer's CSV or a
    glint response."""
    if path.endswith(".json"):
        other = sun_intensities(json.load(open(path))["epochs"], au, e_sun_1au)
        return {i: (v, None) for i, v in other.items()}
    rows = csv.DictReader(open(path))
    return {int(r["index"]): (float(r["intensity_m2_sr"]),
                              float(r["ray_offset"]) if r.get("ray_offset") else None)
            for r in rows}


def stats(pairs):
    """(worst signed, its epoch, median |d|, mean signed) of [(d, epoch)]."""
    worst = max(pairs, key=lambda x: abs(x[0]))
    return worst[0], worst[1], statistics.median(abs(d) for d, _ in pairs), \
        statistics.mean(d for d, _ in pairs)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    ap.add_argument("glint")
    ap.add_argument("peer")
    ap.add_argument("--peer2", help="the peer at another --scale: extrapolate to no ray offset")
    ap.add_argument("--request", help="the request, for sun_distance_au (default 1 AU)")
    ap.add_argument("--floor", type=float, default=1e-3)
    ap.add_argument("-v", "--verbose", action="store_true", help="print every epoch")
    ap.add_argument("--summary", help="append 'label,lit,worst,median,mean' (and the "
                    "extrapolated three) to this CSV")
    ap.add_argument("--label", default="")
    a = ap.parse_args()

    g = json.load(open(a.glint))["epochs"]
    au = [1.0] * len(g)
    if a.request:
        au = [e.get("sun_distance_au") or 1.0 for e in json.load(open(a.request))["epochs"]]
    ref = [e["irradiance_w_m2"] * 10 ** (0.4 * (e["magnitude"] + 26.74))
           for e in g if e["magnitude"] is not None and e["irradiance_w_m2"] > 0]
    if not ref:
        sys.exit("no epoch of the glint curve has light: nothing to compare")
    e_sun_1au = statistics.median(ref)
    mine = sun_intensities(g, au, e_sun_1au)
    p = read_peer(a.peer, au, e_sun_1au)
    p2 = read_peer(a.peer2, au, e_sun_1au) if a.peer2 else None

    rows = []
    for i, s in mine.items():
        if i not in p or (p2 is not None and i not in p2):
            continue
        q, x1 = p[i]
        q0 = None
        if p2 is not None:
            q2, x2 = p2[i]
            if x1 is None or x2 is None or x1 == x2:
                sys.exit("--peer2 needs two peer CSVs with different ray_offset columns")
            q0 = (x2 * q - x1 * q2) / (x2 - x1)
        rows.append((i, g[i]["t"], s, q, q0))
    if not rows:
        sys.exit("no epoch in common")
    top = max(max(r[2], r[3]) for r in rows)
    lit = [r for r in rows if max(r[2], r[3]) >= a.floor * top and r[2] > 0]
    if not lit:
        sys.exit("no lit epoch in common")
    raw = [((q - s) / s, i) for i, _, s, q, _ in lit]
    ext = [((q0 - s) / s, i) for i, _, s, _, q0 in lit] if p2 is not None else None
    if a.verbose:
        print(f"{'epoch':>5} {'t':>10} {'glint m2/sr':>14} {'peer m2/sr':>14} {'rel diff':>10}"
              + (f" {'no offset':>14} {'rel diff':>10}" if ext else ""))
        for k, (i, t, s, q, q0) in enumerate(lit):
            line = f"{i:5d} {t:10g} {s:14.7g} {q:14.7g} {raw[k][0]:10.2e}"
            if ext:
                line += f" {q0:14.7g} {ext[k][0]:10.2e}"
            print(line)
    print(f"E_sun(1 AU, band) = {e_sun_1au:.6g} W/m^2; {len(rows)} epochs in common, {len(lit)} lit "
          f"(signal >= {a.floor:g} of the maximum {top:.6g} m^2/sr)")
    w, wi, med, bias = stats(raw)
    print(f"relative difference peer vs glint: worst {abs(w):.3e} (epoch {wi}, "
          f"signed {w:+.3e}), median {med:.3e}, mean signed {bias:+.3e}")
    row = [a.label, len(lit), f"{w:+.3e}", f"{med:.3e}", f"{bias:+.3e}"]
    if ext:
        w, wi, med, bias = stats(ext)
        print(f"extrapolated to no ray offset: worst {abs(w):.3e} (epoch {wi}, "
              f"signed {w:+.3e}), median {med:.3e}, mean signed {bias:+.3e}")
        row += [f"{w:+.3e}", f"{med:.3e}", f"{bias:+.3e}"]
    else:
        row += ["", "", ""]
    if a.summary:
        new = not os.path.exists(a.summary) or os.path.getsize(a.summary) == 0
        with open(a.summary, "a") as f:
            if new:
                f.write("label,lit,worst,median,mean,worst_no_offset,median_no_offset,"
                        "mean_no_offset\n")
            f.write(",".join(str(x) for x in row) + "\n")


if __name__ == "__main__":
    main()
