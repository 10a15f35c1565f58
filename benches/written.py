#!/usr/bin/env python3
"""The suite's classes as a user's exporter would hand them over: OBJ files whose coordinates
are written with N decimals or N significant digits, or stored in single precision, each with
the class's request.

    glint export-objects --detail medium --dir DIR/objects
    python3 benches/written.py DIR/objects --out DIR [--decimals N | --digits N | --f32 HOW] [--soup]

`--f32 full` writes each coordinate rounded to the nearest f32 and printed in full, as
`json.dumps(numpy.float32(x).tolist())` does (a float32 array from VTK, PyVista or a binary
STL, handed over as Python floats); `--f32 shortest` prints that f32 with the fewest digits
that read back to it, as `str(numpy.float32(x))` and most f32 writers do; `--f32 nine` with 9
significant digits (`%.9g`), as C++ streams at `max_digits10` and assimp's OBJ export do.
`--soup` gives every triangle three vertices of its own (a triangle soup, as every STL file
and many OBJ exporters store a mesh): the same triangles, about six times the vertices.

Writes DIR/CLASS.json for each class (box-wing, rocket-body, fragment, dish-sat, cubesat):
scenes/CLASS.json with the OBJ text inline, coordinates re-written from the export's (9
decimals) and sunlight alone, as the suite times it. Run them with `glint simulate`.
"""
import argparse, json, os, struct

CLASSES = ["box-wing", "rocket-body", "fragment", "dish-sat", "cubesat"]
SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes")


def to_f32(x):
    """x rounded to the nearest single-precision float, as a Python float (exact)."""
    return struct.unpack("f", struct.pack("f", x))[0]


def f32_full(x):
    return repr(to_f32(x))


def f32_nine(x):
    return "%.9g" % to_f32(x)


def f32_shortest(x):
    f = to_f32(x)
    for p in range(1, 10):
        s = "%.*g" % (p, f)
        if to_f32(float(s)) == f:
            return s
    return repr(f)


def add_writing(ap, decimals):
    """The options that say how coordinates are written (`decimals`: the default count)."""
    ap.add_argument("--decimals", type=int, default=decimals)
    ap.add_argument("--digits", type=int, help="significant digits instead of decimals")
    ap.add_argument("--f32", choices=["full", "shortest", "nine"],
                    help="single precision instead, printed in full, shortest or to 9 digits")


def writer(args):
    """A coordinate (float) as text, as `add_writing`'s options say."""
    if args.f32:
        return {"full": f32_full, "shortest": f32_shortest, "nine": f32_nine}[args.f32]
    fmt = "%%.%dg" % args.digits if args.digits else "%%.%df" % args.decimals
    return lambda x: fmt % x


def rewritten(text, write, soup=False):
    """The OBJ `text` with its coordinates written by `write`; with `soup`, each face with
    vertices of its own, written just before it."""
    out, vertices, written = [], [], 0
    for line in text.splitlines():
        if line.startswith("v "):
            line = "v " + " ".join(write(float(w)) for w in line.split()[1:4])
            if soup:
                vertices.append(line)
                continue
        elif soup and line.startswith("f "):
            corners = [int(c.split("/")[0]) for c in line.split()[1:]]
            out.extend(vertices[c - 1] for c in corners)
            line = "f " + " ".join(str(written + k + 1) for k in range(len(corners)))
            written += len(corners)
        out.append(line)
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("objects", help="directory of `glint export-objects`")
    ap.add_argument("--out", default="target/written")
    add_writing(ap, decimals=6)
    ap.add_argument("--soup", action="store_true",
                    help="every triangle three vertices of its own, as an STL file stores it")
    args = ap.parse_args()
    write = writer(args)
    os.makedirs(args.out, exist_ok=True)
    for c in CLASSES:
        with open(os.path.join(args.objects, c + ".obj")) as f:
            text = rewritten(f.read(), write, args.soup)
        with open(os.path.join(SCENES, c + ".json")) as f:
            request = json.load(f)
        request["object"]["mesh"] = {"obj": text}
        request["illumination"]["earthshine"] = "off"
        with open(os.path.join(args.out, c + ".json"), "w") as f:
            json.dump(request, f)
        print("wrote", os.path.join(args.out, c + ".json"))


if __name__ == "__main__":
    main()
