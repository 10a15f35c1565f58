"""Compare glint's light curve with the peer's, epoch by epoch.

    python3 benches/peer/compare.py GLINT.json PEER.csv [--request REQ.json] [--floor 1e-3] [-v]

GLINT.json is `glint simulate REQ.json --out GLINT.json`; PEER.csv is
`benches/peer/mitsuba_lightcurve.py MESH.obj REQ.json --materials lambert --out PEER.csv`,
on the same request with Lambertian materials (benches/peer/lambertize.py).

Glint's intensity from sunlight (sun_w_m2 x range_m^2, W/sr) divided by the band solar
irradiance reaching the object is the intensity per unit irradiance (m^2/sr) that the
peer's summed image gives.  The band irradiance at 1 AU is read off the response itself:
magnitude = -26.74 - 2.5 log10(E / E_sun,1AU), so E_sun,1AU = E 10^(0.4 (m + 26.74));
at the object it is that / sun_distance_au^2 (from --request, default 1 AU) x (1 -
eclipse) (the peer has no eclipses; fully eclipsed epochs are left out).  Epochs whose
signal is below --floor of the curve's maximum are left out too; the worst and median
relative difference |peer - glint| / glint over the rest are printed.
"""
import argparse
import csv
import json
import statistics
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    ap.add_argument("glint")
    ap.add_argument("peer")
    ap.add_argument("--request", help="the request, for sun_distance_au (default 1 AU)")
    ap.add_argument("--floor", type=float, default=1e-3)
    ap.add_argument("-v", "--verbose", action="store_true", help="print every epoch")
    a = ap.parse_args()

    g = json.load(open(a.glint))["epochs"]
    p = {int(r["index"]): float(r["intensity_m2_sr"]) for r in csv.DictReader(open(a.peer))}
    au = [1.0] * len(g)
    if a.request:
        au = [e.get("sun_distance_au") or 1.0 for e in json.load(open(a.request))["epochs"]]
    ref = [e["irradiance_w_m2"] * 10 ** (0.4 * (e["magnitude"] + 26.74))
           for e in g if e["magnitude"] is not None and e["irradiance_w_m2"] > 0]
    if not ref:
        sys.exit("no epoch of the glint curve has light: nothing to compare")
    e_sun_1au = statistics.median(ref)

    rows = []
    for i, e in enumerate(g):
        if i not in p or e["eclipse"] >= 1.0:
            continue
        e_sun = e_sun_1au / au[i] ** 2 * (1.0 - e["eclipse"])
        rows.append((i, e["t"], e["sun_w_m2"] * e["range_m"] ** 2 / e_sun, p[i]))
    if not rows:
        sys.exit("no epoch in common")
    top = max(max(r[2], r[3]) for r in rows)
    lit = [r for r in rows if max(r[2], r[3]) >= a.floor * top]
    diffs = [((q - s) / s if s > 0 else float("inf"), i) for i, _, s, q in lit]
    if a.verbose:
        print(f"{'epoch':>5} {'t':>10} {'glint m2/sr':>14} {'peer m2/sr':>14} {'rel diff':>10}")
        for (i, t, s, q), (d, _) in zip(lit, diffs):
            print(f"{i:5d} {t:10g} {s:14.7g} {q:14.7g} {d:10.2e}")
    worst = max(diffs, key=lambda x: abs(x[0]))
    med = statistics.median(abs(d) for d, _ in diffs)
    bias = statistics.mean(d for d, _ in diffs)
    print(f"E_sun(1 AU, band) = {e_sun_1au:.6g} W/m^2; {len(rows)} epochs in common, {len(lit)} lit "
          f"(signal >= {a.floor:g} of the maximum {top:.6g} m^2/sr)")
    print(f"relative difference peer vs glint: worst {abs(worst[0]):.3e} (epoch {worst[1]}, "
          f"signed {worst[0]:+.3e}), median {med:.3e}, mean signed {bias:+.3e}")


if __name__ == "__main__":
    main()
