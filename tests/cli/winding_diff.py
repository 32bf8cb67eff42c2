#!/usr/bin/env python3
"""winding_diff.py A B: the faces of two OBJ or STL files (the same faces in
the same order) that are wound differently, ignoring degenerate faces (a
repeated corner: no winding). Prints "N of M faces differ"; exit 0.
Used by tests/test_cli_files.sh to check that a repaired copy is the
original again. With --skip-against-normals, faces of A whose stored
normal (OBJ vn of its corners, summed; an STL facet normal) points against
its own winding are left out and counted apart: the exporter's word
against itself, where the library follows the normal once a corruption
makes the two agree. Standard library only."""
import struct
import sys


def faces(path):
    data = open(path, "rb").read()
    if path.lower().endswith(".obj"):
        out = []
        for line in data.decode("latin-1").splitlines():
            t = line.split()
            if t and t[0] == "f":
                out.append(tuple(int(c.split("/")[0]) for c in t[1:]))
        return out
    if len(data) >= 84 and len(data) == 84 + 50 * struct.unpack_from("<I", data, 80)[0]:
        n = struct.unpack_from("<I", data, 80)[0]
        return [tuple(struct.unpack_from("<9f", data, 84 + 50 * i + 12)[k:k + 3] for k in (0, 3, 6)) for i in range(n)]
    out, corners = [], []
    for line in data.decode("latin-1").splitlines():
        t = line.split()
        if t and t[0] == "vertex":
            corners.append(tuple(float(x) for x in t[1:4]))
        elif t and t[0] == "endloop":
            out.append(tuple(corners))
            corners = []
    return out


def against_normals(path):
    """Per face of an OBJ or binary STL: 1 when its stored normal points
    against its winding (cosine below -0.3), else 0."""
    data = open(path, "rb").read()
    out = []
    if path.lower().endswith(".obj"):
        v, vn = [], []
        for line in data.decode("latin-1").splitlines():
            t = line.split()
            if not t:
                continue
            if t[0] == "v":
                v.append(tuple(float(x) for x in t[1:4]))
            elif t[0] == "vn":
                vn.append(tuple(float(x) for x in t[1:4]))
            elif t[0] == "f":
                corners = [c.split("/") for c in t[1:]]
                p = [v[int(c[0]) - 1] for c in corners]
                n = [0.0, 0.0, 0.0]
                for c in corners:
                    if len(c) > 2 and c[2]:
                        n = [n[k] + vn[int(c[2]) - 1][k] for k in range(3)]
                out.append(points_against(p[:3], n))
        return out
    count = struct.unpack_from("<I", data, 80)[0]
    for i in range(count):
        f = struct.unpack_from("<12f", data, 84 + 50 * i)
        out.append(points_against([f[3:6], f[6:9], f[9:12]], f[0:3]))
    return out


def points_against(p, n):
    u = [p[1][k] - p[0][k] for k in range(3)]
    w = [p[2][k] - p[0][k] for k in range(3)]
    g = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
    dot = sum(g[k] * n[k] for k in range(3))
    lengths = (sum(x * x for x in g) * sum(x * x for x in n)) ** 0.5
    return 1 if lengths > 0 and dot < -0.3 * lengths else 0


def canonical(face):
    """The cyclic order of a face's corners, starting at its least corner."""
    i = face.index(min(face))
    return face[i:] + face[:i]


def main():
    skip = "--skip-against-normals" in sys.argv[1:]
    paths = [x for x in sys.argv[1:] if x != "--skip-against-normals"]
    a, b = faces(paths[0]), faces(paths[1])
    if len(a) != len(b):
        print("face counts differ: %d and %d" % (len(a), len(b)))
        return 1
    against = against_normals(paths[0]) if skip else [0] * len(a)
    differ = left_out = 0
    for x, y, k in zip(a, b, against):
        if len(set(x)) == len(x) and canonical(x) != canonical(y):
            differ += not k
            left_out += k
    print("%d of %d faces differ" % (differ, len(a)))
    if skip:
        print("(%d faces whose stored normal points against their winding as exported: %d of them differ)"
              % (sum(against), left_out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
