"""Time glint's named peer: Mitsuba 3 (Dr.Jit LLVM backend) on the box-wing scene.

What it measures
    Per epoch of scenes/box-wing.json: point a directional emitter along -sun,
    put an orthographic camera on the observer direction framing the mesh's
    bounding sphere, render W x W px at S samples/px with the 'direct'
    integrator (one shadow ray per sample; --integrator path uses
    path/max_depth=2) and sum the image.  Scene parameters are changed through
    mi.traverse() so the JIT kernel compiled for epoch 0 is reused.  Prints
    the first-epoch time (JIT compile or kernel-cache hit), the steady-state
    ms/epoch (mean and median after --warmup epochs), epochs/s, total wall
    time (imports + scene load + all epochs) and the first image sums.

    Brightness of an epoch = sum over pixels of the mean RGB radiance; times
    the pixel area (m^2) it is the intensity in W/sr per W/m^2 of sunlight.

Install (Debian 12, Python 3.11)
    pip install -r benches/peer/requirements.txt   # mitsuba==3.9.1 drjit==1.5.0 numpy==2.4.6
    apt-get install -y libllvm19                   # /usr/lib/x86_64-linux-gnu/libLLVM-19.so
    Not libllvm15 (Debian 12's default): Dr.Jit 1.5 kernels abort in it with
    "LLVM ERROR: Cannot select: ... fmaximum".  The script sets
    DRJIT_LIBLLVM_PATH to the libLLVM-19 above when it exists and the variable
    is unset, and prints the libLLVM it loaded.

Run (from the repo root)
    python3 benches/peer/mitsuba_box_wing.py /tmp/fine_dish.obj scenes/box-wing.json \
        [--epochs N] [--spp 16] [--res 256] [--threads T] [--out sums.txt]
    The mesh: cargo build --release --example scale &&
        ./target/release/examples/scale --obj /tmp/fine_dish.obj 3 48 128 1
    Dr.Jit caches compiled kernels in ~/.drjit (a separate entry per thread
    count); remove it to time a cold compile.  Time on an idle machine: the
    LLVM backend uses every core, so any other load inflates the numbers.
"""
import time

T_START = time.perf_counter()

import argparse
import json
import os
import statistics
import tempfile

LLVM19 = "/usr/lib/x86_64-linux-gnu/libLLVM-19.so"
if os.path.exists(LLVM19):
    os.environ.setdefault("DRJIT_LIBLLVM_PATH", LLVM19)

import numpy as np
import drjit as dr
import mitsuba as mi

MATERIALS = {  # usemtl group -> BSDF (close to glint's presets; timing only)
    "body": {"type": "roughconductor", "material": "Al", "alpha": 0.1},
    "panel": {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": 0.25}}},
    "dish": {"type": "twosided", "bsdf": {"type": "roughplastic", "alpha": 0.3,
                                          "diffuse_reflectance": {"type": "rgb", "value": 0.8}}},
}


def split_obj(path, outdir):
    """Write one OBJ per usemtl group (Mitsuba's loader ignores usemtl); return files, radius."""
    verts, groups, cur = [], {}, "default"
    with open(path) as f:
        for line in f:
            p = line.split()
            if not p:
                continue
            if p[0] == "v":
                verts.append([float(x) for x in p[1:4]])
            elif p[0] == "usemtl":
                cur = p[1]
            elif p[0] == "f":
                groups.setdefault(cur, []).append([int(x.split("/")[0]) - 1 for x in p[1:4]])
    verts = np.array(verts)
    files = {}
    for name, faces in groups.items():
        faces = np.array(faces)
        used, inv = np.unique(faces, return_inverse=True)
        fn = os.path.join(outdir, f"{name}.obj")
        with open(fn, "w") as f:
            f.writelines(f"v {x:.17g} {y:.17g} {z:.17g}\n" for x, y, z in verts[used])
            f.writelines(f"f {a} {b} {c}\n" for a, b, c in inv.reshape(-1, 3) + 1)
        files[name] = (fn, len(faces))
    return files, float(np.linalg.norm(verts, axis=1).max())


def look_at(direction, dist):
    """Transform placing +z of the local frame along -direction from a point at dist*direction."""
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    up = np.eye(3)[np.argmin(np.abs(d))]  # axis least aligned with d
    return mi.ScalarTransform4f().look_at(origin=(d * dist).tolist(), target=[0, 0, 0], up=up.tolist())


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("obj")
    ap.add_argument("scene")
    ap.add_argument("--epochs", type=int, default=0, help="epochs to render (default: all)")
    ap.add_argument("--warmup", type=int, default=3)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--res", type=int, default=256)
    ap.add_argument("--threads", type=int, default=0, help="Dr.Jit worker threads (default: all cores)")
    ap.add_argument("--integrator", choices=["direct", "path"], default="direct")
    ap.add_argument("--out", help="write 'index t sum intensity ms' per epoch to this file")
    a = ap.parse_args()

    mi.set_variant("llvm_ad_rgb")
    if a.threads:
        dr.set_thread_count(a.threads)
    epochs = json.load(open(a.scene))["epochs"]
    epochs = epochs[: a.epochs] if a.epochs else epochs

    t_load = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        files, radius = split_obj(a.obj, tmp)
        radius *= 1.01
        integ = ({"type": "direct", "emitter_samples": 1, "bsdf_samples": 0} if a.integrator == "direct"
                 else {"type": "path", "max_depth": 2})
        scene_dict = {
            "type": "scene",
            "integrator": integ,
            "sun": {"type": "directional", "direction": [0, 0, -1], "irradiance": {"type": "rgb", "value": 1.0}},
            "sensor": {
                "type": "orthographic",
                "near_clip": 0.01, "far_clip": 4 * radius,
                "to_world": look_at([0, 0, 1], 2 * radius) @ mi.ScalarTransform4f().scale([radius, radius, 1]),
                "sampler": {"type": "independent", "sample_count": a.spp},
                "film": {"type": "hdrfilm", "width": a.res, "height": a.res,
                         "rfilter": {"type": "box"}, "pixel_format": "rgb"},
            },
        }
        for name, (fn, _) in files.items():
            scene_dict[name] = {"type": "obj", "filename": fn, "face_normals": True,
                                "bsdf": MATERIALS.get(name, {"type": "diffuse"})}
        scene = mi.load_dict(scene_dict)
    params = mi.traverse(scene)
    t_load = time.perf_counter() - t_load
    pixel_area = (2 * radius / a.res) ** 2

    sums, times = [], []
    for i, ep in enumerate(epochs):
        t0 = time.perf_counter()
        params["sun.to_world"] = mi.ScalarTransform4f().look_at(
            origin=[0, 0, 0], target=(-np.asarray(ep["sun"])).tolist(), up=np.eye(3)[np.argmin(np.abs(ep["sun"]))].tolist())
        params["sensor.to_world"] = look_at(ep["observer"], 2 * radius) @ mi.ScalarTransform4f().scale([radius, radius, 1])
        params.update()
        img = mi.render(scene, params, spp=a.spp, seed=i)
        sums.append(float(np.asarray(img, dtype=np.float64).mean(axis=2).sum()))  # forces evaluation
        times.append(time.perf_counter() - t0)
    t_total = time.perf_counter() - T_START

    steady = times[a.warmup:] or times
    ms_mean, ms_med = 1e3 * statistics.mean(steady), 1e3 * statistics.median(steady)
    llvm = {l.split()[-1] for l in open("/proc/self/maps") if "libLLVM" in l}
    print(f"mitsuba {mi.__version__}  drjit {dr.__version__}  variant {mi.variant()}  "
          f"threads {dr.thread_count()}  {', '.join(sorted(llvm))}")
    print(f"mesh {sum(n for _, n in files.values())} triangles {dict((k, n) for k, (_, n) in files.items())}, "
          f"bounding radius {radius:.3f} m; {a.res}x{a.res} px, {a.spp} spp, integrator {a.integrator}")
    print(f"scene load {t_load:.2f} s; first epoch {1e3 * times[0]:.0f} ms (JIT compile or cache hit); "
          f"epochs 2-{a.warmup}: {', '.join(f'{1e3 * t:.0f}' for t in times[1:a.warmup])} ms")
    print(f"steady state over {len(steady)} epochs: {ms_mean:.1f} ms/epoch mean, {ms_med:.1f} median, "
          f"min {1e3 * min(steady):.1f}, max {1e3 * max(steady):.1f}; {1e3 / ms_mean:.2f} epochs/s")
    print(f"total wall time {t_total:.2f} s for {len(epochs)} epochs (incl. imports and scene load)")
    for i, s in enumerate(sums[:5]):
        print(f"  epoch {i} t={epochs[i]['t']:g}: image sum {s:.4f}  intensity {s * pixel_area:.4f} m^2/sr")
    if a.out:
        with open(a.out, "w") as f:
            f.writelines(f"{i} {ep['t']:g} {s:.6g} {s * pixel_area:.6g} {1e3 * dt:.2f}\n"
                         for i, (ep, s, dt) in enumerate(zip(epochs, sums, times)))


if __name__ == "__main__":
    main()
