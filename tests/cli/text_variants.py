#!/usr/bin/env python3
"""text_variants.py DIR: writes the text-format cases of tests/test_cli_hostile.sh
(its block "text formats: byte-order marks, line ends, comments").

A unit cube of 12 triangles, facing out but for one turned triangle, in each
text format the tool reads, each written with every kind of line end: LF,
CRLF, a lone CR (old Macs) and the three mixed line by line, each with and
without a UTF-8 byte-order mark, and each with a comment line right after
the first face, so a reader that misses a line end skips the turned face,
or every face after it. Beside each input NAME.in.EXT, NAME.want.EXT is the
file a correct repair writes: the same bytes with the turned triangle's
last two corners swapped (a comment only where the format has one: the PLY
header's "comment" line, an OFF and OBJ '#', and a '#' in ASCII STL, which
the tool reads as one). Also:

  ply_binary_cr.in.ply  binary PLY whose header ends each line with a lone
      CR, the data starting with the byte 0x0A (the first x, a tiny float)
  cube_vn.obj  the same cube, quads with a normal per face (24 (v, vn)
      pairs over 8 vertices), for conversions to other formats

Standard library only.
"""
import os
import struct
import sys

VERTICES = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
TRIANGLES = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
             (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]
TURNED = 5  # written (0, 4, 5): after the comment, so a reader one face off edits another


def triangles(turned):
    out = list(TRIANGLES)
    if turned:
        a, b, c = out[TURNED]
        out[TURNED] = (a, c, b)
    return out


def obj_lines(tris):
    lines = ["v %d %d %d" % v for v in VERTICES] + ["v 0.5 0.5 0.5"]  # unused: a shift stays in range
    for i, t in enumerate(tris):
        lines.append("f %d %d %d" % tuple(k + 1 for k in t))
        if i == 0:
            lines.append("# a comment")
    return lines


def off_lines(tris):
    lines = ["OFF", "# a comment", "%d %d 0" % (len(VERTICES), len(tris))]
    lines += ["%d %d %d" % v for v in VERTICES]
    for i, t in enumerate(tris):
        lines.append("3 %d %d %d" % t)
        if i == 0:
            lines.append("# a comment")
    return lines


def stl_lines(tris):
    lines = ["solid cube"]
    for i, t in enumerate(tris):
        lines += ["facet normal 0 0 0", " outer loop"] + [" vertex %d %d %d" % VERTICES[k] for k in t]
        lines += [" endloop", "endfacet"]
        if i == 0:
            lines.append("# a comment")
    return lines + ["endsolid cube"]


def ply_lines(tris):
    lines = ["ply", "format ascii 1.0", "comment a comment", "element vertex %d" % len(VERTICES),
             "property float x", "property float y", "property float z",
             "element face %d" % len(tris), "property list uchar int vertex_indices", "end_header"]
    lines += ["%d %d %d" % v for v in VERTICES]
    return lines + ["3 %d %d %d" % t for t in tris]


ENDS = {"lf": ["\n"], "crlf": ["\r\n"], "cr": ["\r"], "mixed": ["\n", "\r\n", "\r"],
        "mixed_cr_first": ["\r", "\n", "\r\n"], "mixed_crlf_first": ["\r\n", "\r", "\n"]}


def join(lines, ends):
    return "".join(line + ends[i % len(ends)] for i, line in enumerate(lines))


def write(path, data):
    with open(path, "wb") as f:
        f.write(data)


def binary_ply(tris):
    header = ["ply", "format binary_little_endian 1.0", "element vertex %d" % len(VERTICES),
              "property float x", "property float y", "property float z",
              "element face %d" % len(tris), "property list uchar int vertex_indices", "end_header"]
    data = "".join(line + "\r" for line in header).encode()
    first_x = struct.unpack("<f", b"\x0a\x00\x00\x00")[0]  # a byte 0x0A right after the header's last CR
    for i, v in enumerate(VERTICES):
        data += struct.pack("<3f", first_x if i == 0 else v[0], v[1], v[2])
    for t in tris:
        data += struct.pack("<B3i", 3, *t)
    return data


def cube_vn():
    quads = [((0, 3, 2, 1), (0, 0, -1)), ((4, 5, 6, 7), (0, 0, 1)), ((0, 1, 5, 4), (0, -1, 0)),
             ((1, 2, 6, 5), (1, 0, 0)), ((2, 3, 7, 6), (0, 1, 0)), ((3, 0, 4, 7), (-1, 0, 0))]
    lines = ["v %d %d %d" % v for v in VERTICES] + ["vn %d %d %d" % n for _, n in quads]
    lines += ["f " + " ".join("%d//%d" % (k + 1, i + 1) for k in q) for i, (q, _) in enumerate(quads)]
    return join(lines, ["\n"])


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    formats = {"obj": obj_lines, "off": off_lines, "stl": stl_lines, "ply": ply_lines}
    for ext, lines in formats.items():
        for name, ends in ENDS.items():
            for bom in (b"", b"\xef\xbb\xbf"):
                stem = "%s_%s%s" % (ext, name, "_bom" if bom else "")
                write(os.path.join(out, stem + ".in." + ext), bom + join(lines(triangles(True)), ends).encode())
                write(os.path.join(out, stem + ".want." + ext), bom + join(lines(triangles(False)), ends).encode())
    write(os.path.join(out, "ply_binary_cr.in.ply"), binary_ply(triangles(True)))
    write(os.path.join(out, "ply_binary_cr.want.ply"), binary_ply(triangles(False)))
    write(os.path.join(out, "cube_vn.obj"), cube_vn().encode())


if __name__ == "__main__":
    main()
