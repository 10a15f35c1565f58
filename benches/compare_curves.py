#!/usr/bin/env python3
"""Compares light curves written by `examples/suite --curves DIR` epoch by epoch.

    compare_curves.py REFERENCE_DIR CANDIDATE_DIR

For every CLASS-DETAIL.csv in both: the worst relative difference of the irradiance over
lit epochs (the reference above 1e-3 of its own peak), and the epoch where it occurs.
"""
import csv
import pathlib
import sys


def read(path):
    with open(path) as f:
        return [float(r["irradiance_w_m2"]) for r in csv.DictReader(f)]


def main():
    ref_dir, cand_dir = map(pathlib.Path, sys.argv[1:3])
    worst_all = 0.0
    for ref in sorted(ref_dir.glob("*.csv")):
        cand = cand_dir / ref.name
        if not cand.exists():
            continue
        a, b = read(ref), read(cand)
        peak = max(a) if a else 0.0
        worst, at = 0.0, -1
        for i, (x, y) in enumerate(zip(a, b)):
            if x > 1e-3 * peak:
                r = abs(y - x) / x
                if r > worst:
                    worst, at = r, i
        worst_all = max(worst_all, worst)
        print(f"{ref.stem:<22} epochs {len(a):>5}  worst {worst:.3e} at epoch {at}")
    print(f"worst of all: {worst_all:.3e}")


if __name__ == "__main__":
    main()
