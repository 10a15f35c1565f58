"""Glint's named peer: Mitsuba 3 (Dr.Jit LLVM backend) renders a light curve of a glint request.

What it does
    Reads an OBJ (faces grouped by `usemtl`, one group per material of the
    request) and a glint request JSON.  Per epoch: when the epoch has an
    `attitude` [w, x, y, z] (body -> inertial, as glint takes it), `sun` and
    `observer` are inertial and are rotated into the body frame,
    body = q^-1 * inertial; otherwise they already are body-frame vectors.
    A directional emitter of unit irradiance shines along -sun; an
    orthographic camera on the observer direction frames the mesh's bounding
    sphere; the `direct` integrator (one shadow ray per sample; --integrator
    path uses path/max_depth=2) renders --res x --res px at --spp samples/px,
    and the image is summed.  The scene is built once: the emitter and camera
    transforms change through mi.traverse(), so the JIT kernel compiled for
    the first epoch is reused.

    Intensity per unit solar irradiance (m^2/sr) = sum over pixels of the mean
    RGB radiance x pixel area: glint's intensity_w_sr from sunlight divided by
    the band solar irradiance at the object (benches/peer/compare.py).

Materials (--materials)
    lambert  every group is a Lambertian (Mitsuba `diffuse`) of the request
             material's `albedo` (f = albedo/pi, as glint's `lambert`): for
             accuracy comparisons with glint run on the same request
             (benches/peer/lambertize.py rewrites a request to that).
    timing   stand-in BSDFs close to the request's materials (a rough
             aluminium conductor, Lambertian panels, a rough-plastic dish),
             for timing only (the default).
    Either way a material with `two_sided: true` is wrapped in `twosided`;
    the others are lit and seen from the front only.

Install: benches/peer/setup.sh (idempotent), that is
    apt-get install -y libllvm19                   # /usr/lib/x86_64-linux-gnu/libLLVM-19.so
    pip install -r benches/peer/requirements.txt   # mitsuba==3.9.1 drjit==1.5.0 numpy==2.4.6
    Not libllvm15 (Debian 12's default): Dr.Jit 1.5 kernels abort in it with
    "LLVM ERROR: Cannot select: ... fmaximum".  The script sets
    DRJIT_LIBLLVM_PATH to the libLLVM-19 above when it exists and the variable
    is unset, and prints the libLLVM it loaded.

Run (from the repo root)
    python3 benches/peer/mitsuba_lightcurve.py MESH.obj REQUEST.json \
        [--epochs N] [--spp 16] [--res 256] [--threads T] [--materials lambert|timing] \
        [--scale S] [--out curve.csv] [--summary suite-peer.csv --label NAME]
    --out writes per epoch: index, t, intensity (m^2/sr), ms, ray_offset.
    --summary appends one row (label, triangles, ms_per_epoch, ...) for the
    suite chart.
    Meshes: `glint export-objects --dir DIR` (built-in objects) or
    `./target/release/examples/scale --obj /tmp/fine_dish.obj 3 48 128 1`
    (the box-wing with a 48 x 128 fine dish).  Dr.Jit caches compiled kernels
    in ~/.drjit (a separate entry per thread count); remove it to time a cold
    compile.  Time on an idle machine: the LLVM backend uses every core.

Light that leaks through the shadow rays' offset (--scale)
    Mitsuba starts a shadow ray off the surface, along its normal, by
    (1 + max|p|) * RayEpsilon (RayEpsilon = 1500 * 2^-24 ~ 8.9e-5, f32;
    mitsuba/render/interaction.h, offset_p).  Where a surface is shadowed by a
    neighbour meeting it at a concave crease, a band along the crease about
    that offset wide is lit when it should be dark, so the peer reads high in
    proportion to the offset relative to the object's size (a crumpled
    fragment at 1.8 m and 20k triangles: +2e-4 to +5e-3 of each epoch,
    growing with phase).
    --scale S renders the mesh scaled by S (intensities are still written at
    scale 1, divided by S^2) and the CSV's ray_offset column gives the offset
    relative to the mesh's size, (1 + S m) * RayEpsilon / (S m) with m its
    largest coordinate (where the leak is, |p| is smaller: the offset's part
    that scales with the mesh, 1500 * 2^-24 * |p|, no scaling separates from
    the light itself, so the extrapolation rests on this choice of m; with
    the surface's mean largest coordinate instead, the fragment's dimmest
    epochs move by up to 2e-3): two runs at different scales (1 and 10; at 0.1 the
    offset is an eighth of a side of the 200k-triangle fragment's triangles
    and the leak no longer grows in proportion) let
    benches/peer/compare.py --peer2 extrapolate each epoch to no offset.
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

# --materials timing: stand-ins close to glint's presets, by group name
STAND_INS = {
    "body": {"type": "roughconductor", "material": "Al", "alpha": 0.1},
    "panel": {"type": "diffuse", "reflectance": {"type": "rgb", "value": 0.25}},
    "dish": {"type": "roughplastic", "alpha": 0.3, "diffuse_reflectance": {"type": "rgb", "value": 0.8}},
}


def request_materials(req):
    """name -> material object of the request (a bare preset name is a one-sided material)."""
    out = {}
    for m in req["object"]["materials"]:
        m = {"name": m, "preset": m} if isinstance(m, str) else m
        out[m["name"]] = m
    return out


def bsdf_for(name, mat, mode):
    if mode == "lambert":
        if mat is None or mat.get("model") != "lambert" or "albedo" not in mat:
            raise SystemExit(f"--materials lambert: material `{name}` of the request is not "
                             f"`lambert` with an `albedo` (rewrite it with benches/peer/lambertize.py)")
        bsdf = {"type": "diffuse", "reflectance": {"type": "rgb", "value": float(mat["albedo"])}}
    elif name in STAND_INS:
        bsdf = STAND_INS[name]
    elif mat is not None and mat.get("model") == "lambert":
        bsdf = {"type": "diffuse", "reflectance": {"type": "rgb", "value": float(mat.get("albedo", 0.5))}}
    else:  # a specular + diffuse stand-in for the microfacet models and presets
        bsdf = {"type": "roughplastic", "alpha": 0.2, "diffuse_reflectance": {"type": "rgb", "value": 0.5}}
    if mat is not None and mat.get("two_sided"):
        bsdf = {"type": "twosided", "bsdf": bsdf}
    return bsdf


# Mitsuba's RayEpsilon<float> (mitsuba/core/math.h: dr::Epsilon<float32> * 1500)
RAY_EPSILON = 1500 * 2.0**-24


def split_obj(path, outdir, scale=1.0):
    """Write one OBJ per usemtl group (Mitsuba's loader ignores usemtl), its vertices
    scaled by `scale`; return files, bounding radius and largest |coordinate| (scaled)."""
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
                idx = [int(x.split("/")[0]) for x in p[1:]]
                idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
                for k in range(1, len(idx) - 1):  # fan-triangulate polygons
                    groups.setdefault(cur, []).append([idx[0], idx[k], idx[k + 1]])
    verts = np.array(verts) * scale
    files = {}
    for name, faces in groups.items():
        faces = np.array(faces)
        used, inv = np.unique(faces, return_inverse=True)
        fn = os.path.join(outdir, f"{name}.obj")
        with open(fn, "w") as f:
            f.writelines(f"v {x:.17g} {y:.17g} {z:.17g}\n" for x, y, z in verts[used])
            f.writelines(f"f {a} {b} {c}\n" for a, b, c in inv.reshape(-1, 3) + 1)
        files[name] = (fn, len(faces))
    return files, float(np.linalg.norm(verts, axis=1).max()), float(np.abs(verts).max())


def to_body(q, v):
    """Rotate inertial v into the body frame: q^-1 * v, q = [w, x, y, z] body -> inertial."""
    w, x, y, z = np.asarray(q, float) / np.linalg.norm(q)
    r = np.array([  # rotation matrix of q (body -> inertial); its transpose is q^-1
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])
    return r.T @ np.asarray(v, float)


def body_vectors(ep):
    sun, obs = np.asarray(ep["sun"], float), np.asarray(ep["observer"], float)
    if ep.get("attitude") is not None:
        sun, obs = to_body(ep["attitude"], sun), to_body(ep["attitude"], obs)
    return sun / np.linalg.norm(sun), obs / np.linalg.norm(obs)


def up_for(d):
    return np.eye(3)[np.argmin(np.abs(d))].tolist()  # the axis least aligned with d


def camera(direction, radius):
    """Orthographic view from `direction` (unit, body frame) framing the bounding sphere."""
    look = mi.ScalarTransform4f().look_at(origin=(direction * 2 * radius).tolist(), target=[0, 0, 0],
                                          up=up_for(direction))
    return look @ mi.ScalarTransform4f().scale([radius, radius, 1])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("obj", help="mesh, faces grouped by usemtl (material names of the request)")
    ap.add_argument("request", help="glint request JSON (its epochs and materials are used)")
    ap.add_argument("--epochs", type=int, default=0, help="only the first N epochs (default: all)")
    ap.add_argument("--warmup", type=int, default=3, help="epochs left out of the steady-state time")
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--res", type=int, default=256)
    ap.add_argument("--threads", type=int, default=0, help="Dr.Jit worker threads (default: all cores)")
    ap.add_argument("--materials", choices=["lambert", "timing"], default="timing")
    ap.add_argument("--integrator", choices=["direct", "path"], default="direct")
    ap.add_argument("--scale", type=float, default=1.0,
                    help="render the mesh scaled by this (intensities written at scale 1; see above)")
    ap.add_argument("--out", help="write 'index,t,intensity_m2_sr,ms,ray_offset' per epoch (CSV)")
    ap.add_argument("--summary", help="append 'label,triangles,ms_per_epoch,...' to this CSV")
    ap.add_argument("--label", default="", help="first column of the --summary row (e.g. the class)")
    a = ap.parse_args()
    if not a.scale > 0:
        ap.error(f"--scale must be positive, got {a.scale}")

    mi.set_variant("llvm_ad_rgb")
    if a.threads:
        dr.set_thread_count(a.threads)
    req = json.load(open(a.request))
    epochs = req["epochs"][: a.epochs] if a.epochs else req["epochs"]
    mats = request_materials(req)

    t_load = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        files, radius, largest = split_obj(a.obj, tmp, a.scale)
        radius *= 1.01
        unknown = sorted(set(files) - set(mats))
        if unknown and a.materials == "lambert":
            raise SystemExit(f"OBJ groups {unknown} name no material of the request")
        integ = ({"type": "direct", "emitter_samples": 1, "bsdf_samples": 0} if a.integrator == "direct"
                 else {"type": "path", "max_depth": 2})
        scene_dict = {
            "type": "scene",
            "integrator": integ,
            "sun": {"type": "directional", "direction": [0, 0, -1], "irradiance": {"type": "rgb", "value": 1.0}},
            "sensor": {
                "type": "orthographic",
                "near_clip": 0.01 * radius, "far_clip": 4 * radius,
                "to_world": camera(np.array([0.0, 0.0, 1.0]), radius),
                "sampler": {"type": "independent", "sample_count": a.spp},
                "film": {"type": "hdrfilm", "width": a.res, "height": a.res,
                         "rfilter": {"type": "box"}, "pixel_format": "rgb"},
            },
        }
        for name, (fn, _) in files.items():
            scene_dict["mesh_" + name] = {"type": "obj", "filename": fn, "face_normals": True,
                                          "bsdf": bsdf_for(name, mats.get(name), a.materials)}
        scene = mi.load_dict(scene_dict)
    params = mi.traverse(scene)
    t_load = time.perf_counter() - t_load
    # per unit of the unscaled mesh's area: intensities as at scale 1
    pixel_area = (2 * radius / a.res) ** 2 / a.scale**2
    # the shadow rays' offset relative to the mesh's size
    ray_offset = (1 + largest) * RAY_EPSILON / largest

    sums, times = [], []
    for i, ep in enumerate(epochs):
        t0 = time.perf_counter()
        sun, obs = body_vectors(ep)
        params["sun.to_world"] = mi.ScalarTransform4f().look_at(
            origin=[0, 0, 0], target=(-sun).tolist(), up=up_for(sun))
        params["sensor.to_world"] = camera(obs, radius)
        params.update()
        img = mi.render(scene, params, spp=a.spp, seed=i)
        sums.append(float(np.asarray(img, dtype=np.float64).mean(axis=2).sum()))  # forces evaluation
        times.append(time.perf_counter() - t0)
    t_total = time.perf_counter() - T_START

    steady = times[a.warmup:] or times
    ms_mean, ms_med = 1e3 * statistics.mean(steady), 1e3 * statistics.median(steady)
    triangles = sum(n for _, n in files.values())
    llvm = {l.split()[-1] for l in open("/proc/self/maps") if "libLLVM" in l}
    print(f"mitsuba {mi.__version__}  drjit {dr.__version__}  variant {mi.variant()}  "
          f"threads {dr.thread_count()}  {', '.join(sorted(llvm))}")
    print(f"mesh {triangles} triangles {dict((k, n) for k, (_, n) in files.items())}, "
          f"bounding radius {radius:.3f} m; {a.res}x{a.res} px, {a.spp} spp, integrator {a.integrator}, "
          f"materials {a.materials}, scale {a.scale:g} (shadow-ray offset {ray_offset:.3g} of the size); {sum(1 for e in epochs if e.get('attitude') is not None)} of "
          f"{len(epochs)} epochs with an attitude")
    print(f"scene load {t_load:.2f} s; first epoch {1e3 * times[0]:.0f} ms (JIT compile or cache hit); "
          f"epochs 2-{a.warmup}: {', '.join(f'{1e3 * t:.0f}' for t in times[1:a.warmup])} ms")
    print(f"steady state over {len(steady)} epochs: {ms_mean:.1f} ms/epoch mean, {ms_med:.1f} median, "
          f"min {1e3 * min(steady):.1f}, max {1e3 * max(steady):.1f}; {1e3 / ms_mean:.2f} epochs/s")
    print(f"total wall time {t_total:.2f} s for {len(epochs)} epochs (incl. imports and scene load)")
    for i, s in enumerate(sums[:5]):
        print(f"  epoch {i} t={epochs[i]['t']}: image sum {s:.4f}  intensity {s * pixel_area:.6g} m^2/sr")
    if a.out:
        with open(a.out, "w") as f:
            f.write("index,t,intensity_m2_sr,ms,ray_offset\n")
            f.writelines(f"{i},{ep['t']},{s * pixel_area:.9g},{1e3 * dt:.3f},{ray_offset:.6g}\n"
                         for i, (ep, s, dt) in enumerate(zip(epochs, sums, times)))
    if a.summary:
        new = not os.path.exists(a.summary) or os.path.getsize(a.summary) == 0
        with open(a.summary, "a") as f:
            if new:
                f.write("class,triangles,ms_per_epoch,ms_median,epochs,res,spp,threads,total_s\n")
            f.write(f"{a.label},{triangles},{ms_mean:.3f},{ms_med:.3f},{len(epochs)},{a.res},{a.spp},"
                    f"{dr.thread_count()},{t_total:.2f}\n")


if __name__ == "__main__":
    main()
