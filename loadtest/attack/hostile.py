"""Hostile inputs against `glint serve` (started here on 127.0.0.1:PORT): malformed and
extreme JSON, hostile values, path traversal, bad queries and methods, oversized URIs and
heads, bad headers. Every answer must be a 4xx (or the 2xx a valid request earns) with the
JSON error shape `{"error": ..., "field": ...}`, never a 5xx, and come back quickly.

Usage: hostile.py BINARY PORT WORKDIR [MAX_SECONDS]  (the slowest answer allowed, default 1)
Prints `key value` lines; exits 1 on any failure."""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
from common import Server, raw  # noqa: E402

binary, port, work = sys.argv[1], int(sys.argv[2]), sys.argv[3]
max_seconds = float(sys.argv[4]) if len(sys.argv) > 4 else 1.0

PLATE = {"mesh": {"builtin": "plate"},
         "materials": [{"name": "surface", "model": "lambert", "albedo": 0.5}]}
EPOCH = {"t": 0, "sun": [0, 0, 1], "observer": [0, 0, 1e6]}


def req(**over):
    r = {"object": PLATE, "epochs": [EPOCH]}
    r.update(over)
    return json.dumps(r)


def http(method, path, body=b"", headers=(), content_type="application/json"):
    if isinstance(body, str):
        body = body.encode("utf-8", "surrogatepass")
    head = f"{method} {path} HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n"
    if content_type:
        head += f"Content-Type: {content_type}\r\n"
    for h in headers:
        head += h + "\r\n"
    if body or method in ("POST", "PUT", "PATCH"):
        head += f"Content-Length: {len(body)}\r\n"
    return head.encode("latin-1") + b"\r\n" + body


# (name, raw request bytes, the statuses allowed)
CASES = []


def case(name, data, ok=range(400, 500)):
    CASES.append((name, data, ok))


LC = "/v1/lightcurves"
for path in (LC, "/v1/jobs"):
    p = path.rsplit("/", 1)[1]
    # malformed JSON and bodies
    for name, body in [
        ("empty", ""), ("spaces", "   \n"), ("null", "null"), ("true", "true"), ("number", "1"),
        ("string", '"x"'), ("array", "[]"), ("object", "{}"), ("truncated", req()[:-5]),
        ("trailing-data", req() + " {}"), ("two-documents", req() + req()),
        ("nan-literal", req().replace("0.5", "NaN")), ("infinity-literal", req().replace("0.5", "Infinity")),
        ("1e400", req().replace("0.5", "1e400")), ("-1e400", req().replace("0.5", "-1e400")),
        ("deep-nesting-arrays", "[" * 100000 + "]" * 100000),
        ("deep-nesting-objects", '{"a":' * 50000 + "1" + "}" * 50000),
        ("deep-in-field", req(extra=None).replace("null", "[" * 5000 + "]" * 5000)),
        ("lone-surrogate", req().replace("surface", "\\ud800")),
        ("nul-in-string", req().replace("surface", "sur\\u0000face")),
        ("bom", "\ufeff" + req()), ("latin1-bytes", req().replace("surface", "s\xe9")),
        ("duplicate-key", req()[:-1] + ', "epochs": []}'),
        ("comment", "// x\n" + req()), ("single-quotes", req().replace('"', "'")),
        ("huge-string", req(object={**PLATE, "name": "x" * 2_000_000})),
        ("huge-array", req(epochs=[EPOCH] * 200_000)),
        ("many-keys", json.dumps({f"k{i}": i for i in range(100_000)})),
    ]:
        # 200,000 epochs are within a job's limits (not a light curve's)
        ok = range(200, 500) if (p, name) == ("jobs", "huge-array") else range(400, 500)
        case(f"{p}:json:{name}", http("POST", path, body), ok)
    # hostile values where a number, vector or name goes
    for name, over in [
        ("epochs-empty", {"epochs": []}), ("epochs-null", {"epochs": None}),
        ("epochs-object", {"epochs": {"t": 0}}),
        ("sun-zero", {"epochs": [{**EPOCH, "sun": [0, 0, 0]}]}),
        ("sun-4", {"epochs": [{**EPOCH, "sun": [0, 0, 1, 0]}]}),
        ("sun-2", {"epochs": [{**EPOCH, "sun": [0, 1]}]}),
        ("sun-strings", {"epochs": [{**EPOCH, "sun": ["0", "0", "1"]}]}),
        ("observer-at-object", {"epochs": [{**EPOCH, "observer": [0, 0, 0]}]}),
        ("observer-huge", {"epochs": [{**EPOCH, "observer": [0, 0, 1.7e308]}]}),
        ("t-huge", {"epochs": [{**EPOCH, "t": 1.7e308}]}),
        ("t-string", {"epochs": [{**EPOCH, "t": "yesterday"}]}),
        ("t-iso-bad", {"epochs": [{**EPOCH, "t": "2026-13-45T99:99:99Z"}]}),
        ("albedo-negative", {"object": {**PLATE, "materials": [{"name": "surface", "model": "lambert", "albedo": -1}]}}),
        ("albedo-huge", {"object": {**PLATE, "materials": [{"name": "surface", "model": "lambert", "albedo": 1e300}]}}),
        ("model-unknown", {"object": {**PLATE, "materials": [{"name": "surface", "model": "../../etc/passwd"}]}}),
        ("builtin-traversal", {"object": {**PLATE, "mesh": {"builtin": "../../../../etc/passwd"}}}),
        ("builtin-absolute", {"object": {**PLATE, "mesh": {"builtin": "/etc/passwd"}}}),
        ("obj-nan", {"object": {**PLATE, "mesh": {"obj": "v nan 0 0\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 2 3 4\nf 1 3 4\n"}}}),
        ("obj-inf", {"object": {**PLATE, "mesh": {"obj": "v inf 0 0\nv 0 0 0\nv 1 0 0\nf 1 2 3\n"}}}),
        ("obj-mtllib-traversal", {"object": {**PLATE, "mesh": {"obj": "mtllib ../../../../etc/passwd\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"}}}),
        ("obj-bad-index", {"object": {**PLATE, "mesh": {"obj": "v 0 0 0\nf 1 2 99999999999\n"}}}),
        ("obj-negative-index", {"object": {**PLATE, "mesh": {"obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -9\n"}}}),
        ("obj-empty", {"object": {**PLATE, "mesh": {"obj": ""}}}),
        ("mesh-two-forms", {"object": {**PLATE, "mesh": {"builtin": "plate", "obj": "v 0 0 0\n"}}}),
        ("vertices-nan-string", {"object": {**PLATE, "mesh": {"vertices": [["nan", 0, 0]], "triangles": [[0, 0, 0]]}}}),
        ("triangles-out-of-range", {"object": {**PLATE, "mesh": {"vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "triangles": [[0, 1, 3]]}}}),
        ("triangles-negative", {"object": {**PLATE, "mesh": {"vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "triangles": [[0, 1, -1]]}}}),
        ("method-unknown", {"method": "rm -rf /"}),
        ("image-size-huge", {"method": "image", "image_size": 1 << 30}),
        ("image-samples-huge", {"method": "image", "image_size": 4096, "image_samples": 1 << 20}),
        ("thumbnails-huge", {"thumbnails": {"size": 1 << 20, "samples": 1 << 10, "epochs": [0]}}),
        ("thumbnails-epoch-out", {"thumbnails": {"size": 16, "samples": 1, "epochs": [99]}}),
        ("unknown-field", {"evil": True}),
        ("geometry-and-epochs", {"geometry": {"orbit": {"tle": ["x", "y"]}}}),
        ("tle-garbage", {"epochs": None, "geometry": {"orbit": {"tle": ["1 " + "9" * 67, "2 " + "9" * 67]},
                                                      "site": {"lat_deg": 0, "lon_deg": 0, "alt_m": 0},
                                                      "times": {"start": "2026-01-01T00:00:00Z", "stop": "2026-01-01T00:01:00Z", "step_s": 1},
                                                      "attitude": {"law": "nadir"}}}),
        ("times-step-zero", {"epochs": None, "geometry": {"orbit": {"tle": ["a", "b"]}, "times": {"start": "2026-01-01T00:00:00Z", "stop": "2027-01-01T00:00:00Z", "step_s": 0}}}),
        ("times-billions", {"epochs": None, "geometry": {"orbit": {"tle": [
            "1 25544U 98067A   26336.50000000  .00016717  00000-0  30306-3 0  9992",
            "2 25544  51.6400 200.0000 0005000  90.0000 270.0000 15.50000000 49995"]},
            "site": {"lat_deg": 0, "lon_deg": 0, "alt_m": 0},
            "times": {"start": "2026-01-01T00:00:00Z", "stop": "2126-01-01T00:00:00Z", "step_s": 0.001},
            "attitude": {"law": "nadir"}}}),
    ]:
        r = {"object": PLATE, "epochs": [EPOCH]}
        r.update(over)
        r = {k: v for k, v in r.items() if v is not None}
        # valid after all: a time near f64's end is a time, and `mtllib` is ignored (the
        # request's materials are the only ones; no file is opened)
        ok = range(200, 500) if name in ("t-huge", "obj-mtllib-traversal") else range(400, 500)
        case(f"{p}:value:{name}", http("POST", path, json.dumps(r)), ok)
    # headers
    case(f"{p}:no-content-type", http("POST", path, req(), content_type=None))
    case(f"{p}:text-plain", http("POST", path, req(), content_type="text/plain"))
    case(f"{p}:form", http("POST", path, "a=b", content_type="application/x-www-form-urlencoded"))
    case(f"{p}:content-type-junk", http("POST", path, req(), content_type="\x01\x02"))
    case(f"{p}:body-over-limit-declared", (f"POST {path} HTTP/1.1\r\nHost: x\r\nConnection: close\r\n"
                                           f"Content-Type: application/json\r\nContent-Length: {1 << 40}\r\n\r\n{{").encode())
    case(f"{p}:content-length-junk", (f"POST {path} HTTP/1.1\r\nHost: x\r\nConnection: close\r\n"
                                      "Content-Type: application/json\r\nContent-Length: -5\r\n\r\n").encode())
    case(f"{p}:chunked-bad", (f"POST {path} HTTP/1.1\r\nHost: x\r\nConnection: close\r\nContent-Type: application/json\r\n"
                              "Transfer-Encoding: chunked\r\n\r\nzz\r\n{}\r\n0\r\n\r\n").encode())
    case(f"{p}:te-and-cl", (f"POST {path} HTTP/1.1\r\nHost: x\r\nConnection: close\r\nContent-Type: application/json\r\n"
                            "Transfer-Encoding: chunked\r\nContent-Length: 3\r\n\r\n0\r\n\r\n").encode())

for key in ("", " ", "\x7f" * 3, "k" * 300, "ü"):
    case(f"jobs:idempotency-key:{key[:8]!r}", http("POST", "/v1/jobs", req(), headers=[f"Idempotency-Key: {key}"]))
case("fits:json:empty-object", http("POST", "/v1/fits/brdf", "{}"))
case("fits:json:trailing", http("POST", "/v1/fits/brdf", '{"model":"lambert"} x'))
case("fits:value:huge-csv", http("POST", "/v1/fits/brdf", json.dumps({"model": "seed", "samples_csv": "a,b\n" * 500_000})))
case("fits:value:nan", http("POST", "/v1/fits/brdf", json.dumps({"model": "seed", "samples_csv": "theta_i,phi_i,theta_r,phi_r,brdf\nnan,0,0,0,1\n"})))

# paths, queries, methods
for path in [
    "/v1/scenes/../../etc/passwd", "/v1/scenes/..%2f..%2fetc%2fpasswd", "/v1/scenes/%2e%2e/%2e%2e/etc/passwd",
    "/v1/scenes/nope", "/v1/scenes/%00", "/v1/jobs/../../etc/passwd", "/v1/jobs/%00", "/v1/jobs/nope",
    "/v1/jobs/nope/result", "/v1/jobs/nope/thumbnails/0.png", "/v1/jobs/nope/thumbnails/..%2f..%2fx.png",
    "/v1/jobs?limit=0", "/v1/jobs?limit=-1", "/v1/jobs?limit=1e999", "/v1/jobs?limit=99999999999999999999999",
    "/v1/jobs?limit=1001", "/v1/jobs?state=evil", "/v1/jobs?limit=1&limit=2", "/v1/jobs?limit=%ff",
    "/nope", "/" + "%" * 50, "/v1/jobs/" + "a" * 9000, "/v1/jobs/" + "a" * 70000,
]:
    case(f"get:{path[:48]}", http("GET", path, content_type=None))
for method in ("PUT", "PATCH", "TRACE", "OPTIONS", "CONNECT", "FOO"):
    case(f"method:{method}", http(method, LC, req() if method in ("PUT", "PATCH") else ""))
case("delete:lightcurves", http("DELETE", LC, content_type=None))
case("head:huge-field", http("GET", "/healthz", headers=["X-Big: " + "b" * 300_000], content_type=None))
case("head:many-fields", http("GET", "/healthz", headers=[f"X-F{i}: {i}" for i in range(200)], content_type=None))
case("head:bad-version", b"GET /healthz HTTP/9.9\r\nHost: x\r\nConnection: close\r\n\r\n")
case("head:garbage", b"\x16\x03\x01\x02\x00\x01\x00\x01\xfc\x03\x03" + b"\x00" * 64, ok=[0] + list(range(400, 500)))
case("head:lf-only", b"GET /healthz HTTP/1.1\nHost: x\nConnection: close\n\n", ok=[200])
case("auth:junk-when-none-set", http("GET", "/v1/scenes", headers=["Authorization: Bearer \x01"], content_type=None), ok=[200, 400])
case("accept:csv-on-json-only", http("GET", "/v1/scenes", headers=["Accept: text/csv"], content_type=None), ok=[200])

failures, slowest, statuses = [], (0.0, ""), {}
server = Server(binary, port, os.path.join(work, "hostile")).start()
answers = []
try:
    for name, data, ok in CASES:
        answers.append((name, ok, *raw(port, data)))
        if server.proc.poll() is not None:
            failures.append(f"{name}: the service died")
            break
finally:
    server.stop()
for name, ok, status, headers, body, secs in answers:
    statuses[status] = statuses.get(status, 0) + 1
    if secs > slowest[0]:
        slowest = (secs, name)
    problems = []
    if status not in ok:
        problems.append(f"status {status}")
    if status >= 400:
        try:
            e = json.loads(body)
            if not isinstance(e.get("error"), str) or not e["error"]:
                problems.append("no `error` text")
            if "field" in e and not isinstance(e["field"], str):
                problems.append("`field` not a string")
        except ValueError:
            problems.append(f"not a JSON body: {body[:80]!r}")
    if secs > max_seconds:
        problems.append(f"{secs:.2f} s")
    if problems:
        failures.append(f"{name}: {', '.join(problems)}")

print(f"hostile_cases {len(CASES)}")
print(f"hostile_statuses {json.dumps(dict(sorted(statuses.items())))}")
print(f"hostile_5xx {sum(n for s, n in statuses.items() if s >= 500)}")
print(f"hostile_slowest_s {slowest[0]:.3f} ({slowest[1]})")
print(f"hostile_failures {len(failures)}")
for f in failures:
    print(f"  FAIL {f}")
sys.exit(1 if failures else 0)
