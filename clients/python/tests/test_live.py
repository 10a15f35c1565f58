"""The generated client against a live `glint serve`, started here (GLINT_BIN, default
target/debug/glint; built with cargo if missing)."""
import json
import os
import pathlib
import socket
import subprocess
import tempfile
import time
import urllib.request

import pytest

from glint_client import Client
from glint_client.api.light_curves import post_lightcurve
from glint_client.api.scenes import list_scenes
from glint_client.models import ErrorBody, LightCurve, Request

ROOT = pathlib.Path(__file__).resolve().parents[3]


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="module")
def base_url():
    binary = pathlib.Path(os.environ.get("GLINT_BIN", ROOT / "target" / "debug" / "glint"))
    if not binary.exists():
        subprocess.run(["cargo", "build", "--bin", "glint"], cwd=ROOT, check=True)
    port = free_port()
    with tempfile.TemporaryDirectory() as data:
        server = subprocess.Popen(
            [str(binary), "serve", "--addr", f"127.0.0.1:{port}", "--data-dir", data],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        url = f"http://127.0.0.1:{port}"
        try:
            for _ in range(300):
                try:
                    urllib.request.urlopen(url + "/healthz", timeout=1)
                    break
                except OSError:
                    time.sleep(0.1)
            else:
                raise RuntimeError("glint serve did not answer /healthz")
            yield url
        finally:
            server.terminate()
            server.wait(timeout=30)


def test_v_magnitudes_standard_magnitudes_and_snr(base_url):
    body = Request.from_dict(json.loads((ROOT / "scenes" / "iss-pass-v.json").read_text()))
    with Client(base_url=base_url, timeout=300) as client:
        curve = post_lightcurve.sync(client=client, body=body)
    assert isinstance(curve, LightCurve)
    lit = [e for e in curve.epochs if e.magnitude is not None]
    assert lit, "the pass has lit epochs"
    for e in lit:
        # V magnitude, and the standard magnitude reduced from it by its definition
        assert -5 < e.magnitude < 20
        assert e.magnitude_1000km == pytest.approx(
            e.magnitude - 5 * __import__("math").log10(e.range_m / 1e6), abs=1e-9
        )
        assert e.magnitude_standard is not None and e.magnitude_intrinsic is not None
        assert e.magnitude_standard - e.magnitude_intrinsic == pytest.approx(1.2425, abs=1e-3)
        assert e.observation.snr > 0
        assert e.observation.noise_e > 0
    assert "band V" in curve.summary.method


def test_a_bad_request_names_its_field(base_url):
    body = json.loads((ROOT / "scenes" / "plate.json").read_text())
    body["illumination"] = {"band": "U"}
    with Client(base_url=base_url, timeout=60) as client:
        answer = post_lightcurve.sync_detailed(client=client, body=Request.from_dict(body))
    assert answer.status_code == 422
    assert isinstance(answer.parsed, ErrorBody)
    assert answer.parsed.field == "illumination.band"


def test_the_scenes(base_url):
    with Client(base_url=base_url, timeout=60) as client:
        scenes = list_scenes.sync(client=client)
    assert any(s.name == "box-wing" for s in scenes)
