"""kill -9 during jobs: submits JOBS jobs (each with its own Idempotency-Key) to
`glint serve`, killing the process with SIGKILL KILLS times while jobs run and starting it
again on the same data directory; a submission whose answer was lost in a kill is sent
again with its key. Then every acknowledged job must be there once, done, with the same
light curve as the same request computed synchronously (before any kill).

Usage: kill9.py BINARY PORT WORKDIR JOBS KILLS EPOCHS
Prints `key value` lines; exits 1 when a job is lost, duplicated or corrupted, or on a 5xx."""
import json
import os
import random
import sys
import time

sys.path.insert(0, os.path.dirname(__file__))
from common import Server, request  # noqa: E402

binary, port, work = sys.argv[1], int(sys.argv[2]), sys.argv[3]
jobs, kills, epochs = int(sys.argv[4]), int(sys.argv[5]), int(sys.argv[6])
random.seed(9)
scenes = os.path.join(os.path.dirname(__file__), "..", "..", "scenes")


def repeated(name, n):
    r = json.load(open(os.path.join(scenes, f"{name}.json")))
    r["epochs"] = [r["epochs"][i % len(r["epochs"])] for i in range(n)]
    return json.dumps(r)


bodies = [repeated("box-wing", epochs), repeated("rocket-body", epochs // 2), repeated("plate", epochs)]
data = os.path.join(work, "kill9")
server = Server(binary, port, data).start()
fivexx = 0

# The truth: each body computed synchronously, before any kill
truth = []
for b in bodies:
    st, _, body = request("POST", port, "/v1/lightcurves", b, timeout=300)
    assert st == 200, body[:300]
    truth.append(json.loads(body)["epochs"])

acknowledged = {}  # key -> (job id, body index)
kill_after = sorted(random.sample(range(1, jobs), min(kills, jobs - 1)))
done_kills = 0
lost_answers = 0
for i in range(jobs):
    key = f"kill9-{i}"
    which = i % len(bodies)
    for attempt in range(20):
        try:
            st, _, body = request("POST", port, "/v1/jobs", bodies[which],
                                  headers={"Idempotency-Key": key}, timeout=60)
        except OSError:
            lost_answers += 1
            time.sleep(0.2)
            continue
        if st >= 500:
            fivexx += 1
        if st == 202:
            acknowledged[key] = (json.loads(body)["id"], which)
            break
        time.sleep(0.2)
    else:
        raise SystemExit(f"job {key} never accepted")
    while done_kills < len(kill_after) and kill_after[done_kills] == i + 1:
        # let the queue run a little, then pull the plug mid-job
        time.sleep(random.uniform(0.2, 1.0))
        server.kill9()
        done_kills += 1
        server = Server(binary, port, data).start()

# Everything finishes after the last start
deadline = time.monotonic() + 900
while time.monotonic() < deadline:
    st, _, body = request("GET", port, "/v1/jobs?limit=1000")
    listed = json.loads(body)
    if all(j["state"] in ("done", "failed", "cancelled") for j in listed):
        break
    time.sleep(0.5)
st, _, body = request("GET", port, "/v1/jobs?limit=1000")
listed = json.loads(body)
by_id = {j["id"]: j for j in listed}
lost = [k for k, (jid, _) in acknowledged.items() if jid not in by_id]
duplicated = len(listed) - len({jid for jid, _ in acknowledged.values()})
corrupted, rerun = [], 0
for key, (jid, which) in acknowledged.items():
    j = by_id.get(jid)
    if not j:
        continue
    rerun += j["attempts"] > 1
    if j["state"] != "done":
        corrupted.append(f"{key}: {j['state']} {j.get('error')}")
        continue
    st, _, body = request("GET", port, f"/v1/jobs/{jid}/result", timeout=300)
    if st >= 500:
        fivexx += 1
    try:
        same = st == 200 and json.loads(body)["epochs"] == truth[which]
    except ValueError:
        same = False
    if not same:
        corrupted.append(f"{key}: result differs (status {st})")
server.stop()

print(f"kill9_jobs {len(acknowledged)}")
print(f"kill9_kills {done_kills}")
print(f"kill9_answers_lost_in_kills {lost_answers}")
print(f"kill9_jobs_rerun_after_a_kill {rerun}")
print(f"kill9_lost {len(lost)}")
print(f"kill9_duplicated {duplicated}")
print(f"kill9_corrupted {len(corrupted)}")
print(f"kill9_5xx {fivexx}")
for c in corrupted + [f"lost {k}" for k in lost]:
    print(f"  FAIL {c}")
sys.exit(1 if (lost or duplicated or corrupted or fivexx) else 0)
