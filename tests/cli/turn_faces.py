"""Turns some faces of an OBJ over and says what a --mark of its repair must
show red (tests/test_cli.sh, tests/test_cli_files.sh):

    python3 tests/cli/turn_faces.py IN.obj OUT.obj EXPECTED.txt F...

F: face numbers, from 0, counting the f lines. OUT.obj is IN.obj with
those faces' corners after the first reversed (every other byte kept).
Prints the mean of the turned faces' corners, "X Y Z".
EXPECTED.txt has a line "red X Y Z X Y Z X Y Z" per turned face, its
corners as float32 values (repr) sorted, the lines sorted, as
tests/cli/blender_mark.py prints the red faces Blender imports."""
import struct
import sys

src, dst, expected = sys.argv[1:4]
turn = set(int(f) for f in sys.argv[4:])
f32 = lambda x: struct.unpack("<f", struct.pack("<f", float(x)))[0]
positions, out, red, face, mean = [], [], [], 0, [0.0, 0.0, 0.0]
for line in open(src, encoding="latin-1").read().split("\n"):
    t = line.split()
    if t and t[0] == "v":
        positions.append(tuple(f32(x) for x in t[1:4]))
    elif t and t[0] == "f":
        if face in turn:
            line = " ".join([t[0], t[1]] + t[:1:-1])
            corners = [int(c.split("/")[0]) for c in t[1:]]
            corners = sorted(positions[c - 1 if c > 0 else len(positions) + c] for c in corners)
            for p in corners:
                mean = [m + x / len(corners) / len(turn) for m, x in zip(mean, p)]
            red.append("red " + " ".join(repr(x) for p in corners for x in p))
        face += 1
    out.append(line)
open(dst, "w", encoding="latin-1").write("\n".join(out))
open(expected, "w").write("".join(r + "\n" for r in sorted(red)))
print("%r %r %r" % tuple(mean))
if len(red) != len(turn):
    sys.exit("turn_faces.py: %d of the faces %s are in %s" % (len(red), sorted(turn), src))
