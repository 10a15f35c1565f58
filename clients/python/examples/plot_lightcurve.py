"""Posts scenes/iss-pass-v.json to a running `glint serve` and plots its V magnitudes,
standard magnitudes and SNR with matplotlib.

    pip install ./clients/python matplotlib
    glint serve &            # http://127.0.0.1:8080
    python clients/python/examples/plot_lightcurve.py --out pass.png
"""
import argparse
import json
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from glint_client import Client  # noqa: E402
from glint_client.api.light_curves import post_lightcurve  # noqa: E402
from glint_client.models import Request  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[3]


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--url", default="http://127.0.0.1:8080")
    p.add_argument("--request", default=str(ROOT / "scenes" / "iss-pass-v.json"))
    p.add_argument("--out", default="lightcurve.png")
    a = p.parse_args()
    body = Request.from_dict(json.loads(pathlib.Path(a.request).read_text()))
    with Client(base_url=a.url, timeout=600) as client:
        curve = post_lightcurve.sync(client=client, body=body)
    lit = [e for e in curve.epochs if e.magnitude is not None]
    t0 = lit[0].t
    t = [e.t - t0 for e in lit]
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(8, 6))
    top.plot(t, [e.magnitude for e in lit], label="V (apparent)")
    top.plot(t, [e.magnitude_standard for e in lit], label="standard (1000 km, 90°)")
    top.invert_yaxis()
    top.set_ylabel("magnitude")
    top.legend()
    if lit[0].observation:
        bottom.plot(t, [e.observation.snr for e in lit])
        bottom.set_yscale("log")
    bottom.set_ylabel("SNR")
    bottom.set_xlabel("seconds from the first lit epoch")
    fig.tight_layout()
    fig.savefig(a.out, dpi=100)
    print(f"{len(lit)} lit epochs; plot: {a.out}")


if __name__ == "__main__":
    main()
