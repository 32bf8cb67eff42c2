#!/usr/bin/env python3
"""winding_diff.py A B: the faces of two OBJ or STL files (the same faces in
the same order) that are wound differently, ignoring degenerate faces (a
repeated corner: no winding). Prints "N of M faces differ"; exit 0.
Used by tests/test_cli_files.sh to check that a repaired copy is the
original again. Standard library only."""
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


def canonical(face):
    """The cyclic order of a face's corners, starting at its least corner."""
    i = face.index(min(face))
    return face[i:] + face[:i]


def main():
    a, b = faces(sys.argv[1]), faces(sys.argv[2])
    if len(a) != len(b):
        print("face counts differ: %d and %d" % (len(a), len(b)))
        return 1
    differ = sum(1 for x, y in zip(a, b) if len(set(x)) == len(x) and canonical(x) != canonical(y))
    print("%d of %d faces differ" % (differ, len(a)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
