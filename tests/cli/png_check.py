"""Checks a --mark picture (tests/test_cli.sh, tests/test_cli_files.sh)
against what the geometry says, pixel by pixel:

    python3 tests/cli/png_check.py PICTURE.png TEST [ARGS] [--up y|z]

It reads the PNG itself (zlib, the five filters); where each view puts a
point comes from the picture's tEXt chunk "meshfix views" (NAME X Y W H OX
OY S RX RY RZ UX UY UZ: pixel = (OX + S p.R, OY - S p.U)), whose axes are
checked against what front, back and top must be for the up axis (--up,
default z), before and after. Text is read back from the pixels with the
tool's own font (the table in tools/meshfix/render.cpp). TEST:
    same B.png          the same pixels as B.png
    same_views B.png    the same pixels in every view (titles may differ)
    legend LINE...      each swatch its colour at its place, the words after
                        it these (red, amber, grey; blue, ring), read back
    title TEXT          the first line contains TEXT
    cubes               the left of two unit cubes flipped (cubes.off)
    clean               nothing flipped: no red, amber or blue
    sheet_down, sheet_up  an open sheet at z = 0 seen from above
    slab                the L-shaped slab of meshes.py, seen from above
    small X Y Z         a few flipped faces around (X, Y, Z): red (a ring)
                        there in every view, before and after, none away
Exits 1 after printing what failed."""
import os
import re
import struct
import sys
import zlib


def read_png(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit("not a PNG")
    at, idat, text = 8, b"", {}
    while at < len(data):
        n, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + n]
        at += 12 + n
        if kind == b"IHDR":
            w, h, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if (depth, colour, interlace) != (8, 2, 0):
                sys.exit("expected 8-bit RGB, not interlaced")
        elif kind == b"IDAT":
            idat += body
        elif kind == b"tEXt":
            key, value = body.split(b"\0", 1)
            text[key.decode("latin-1")] = value.decode("latin-1")
    raw, stride, rows = zlib.decompress(idat), 3 * w, []
    prev = bytearray(stride)
    for y in range(h):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - 3] if x >= 3 else 0
            b, c = prev[x], prev[x - 3] if x >= 3 else 0
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return w, h, rows, text


def kind(px):
    r, g, b = px
    if r >= 60 and r > 2.5 * g and r > 2.5 * b:
        return "red"
    if r >= 60 and 0.45 * r <= g <= 0.85 * r and b <= 0.3 * r:
        return "amber"
    if b >= 40 and b > 2 * r and b > 2 * g:
        return "blue"
    if 30 <= max(px) <= 225 and max(px) - min(px) <= 0.35 * max(px):
        return "grey"  # kept faces (and text, which no region checked here holds)
    return None


args = sys.argv[1:]
up = "z"
if "--up" in args:
    up = args[args.index("--up") + 1]
    del args[args.index("--up"):args.index("--up") + 2]
path, test, rest = args[0], args[1], args[2:]
w, h, rows, text = read_png(path)
pixel = lambda x, y: tuple(rows[y][3 * x:3 * x + 3])

# the font: 95 glyphs of 5 x 9 cells, drawn at twice the size, 12 pixels apart
source = open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../tools/meshfix/render.cpp")).read()
glyphs = ["".join(re.findall(r'"([.#]{5})"', line)) for line in source.split("\n") if re.match(r'\s*"[.#]{5}"\s+"', line)]
if len(glyphs) != 95:
    sys.exit("read %d glyphs from render.cpp, not 95" % len(glyphs))


def read_text(x, y, n):
    """The n characters drawn with their cells' top left at (x, y) ('?' for
    a cell that is no glyph), trailing spaces cut."""
    out = ""
    for k in range(min(n, (w - x) // 12)):
        cell = "".join("#" if max(pixel(x + 12 * k + 2 * i, y + 2 * j)) < 100 else "." for j in range(9) for i in range(5))
        out += chr(32 + glyphs.index(cell)) if cell in glyphs else "?"
    return out.rstrip()


views = {}
for line in text.get("meshfix views", "").splitlines():
    f = line.split()
    views[f[0]] = dict(rect=tuple(map(int, f[1:5])), o=(float(f[5]), float(f[6])), s=float(f[7]),
                       R=tuple(map(float, f[8:11])), U=tuple(map(float, f[11:14])))
names = ["back", "front", "oblique", "top"]
if sorted(views) != sorted(names + ["before_" + n for n in names]):
    sys.exit("views in the tEXt chunk: %s" % sorted(views))
axes = {"z": {"front": ((1, 0, 0), (0, 0, 1)), "back": ((-1, 0, 0), (0, 0, 1)), "top": ((1, 0, 0), (0, 1, 0))},
        "y": {"front": ((1, 0, 0), (0, 1, 0)), "back": ((-1, 0, 0), (0, 1, 0)), "top": ((1, 0, 0), (0, 0, -1))}}[up]
for name, (R, U) in axes.items():
    for v in (name, "before_" + name):
        if views[v]["R"] != R or views[v]["U"] != U:
            sys.exit("%s view: axes %s %s, expected %s %s (up %s)" % (v, views[v]["R"], views[v]["U"], R, U, up))
after = {n: views[n] for n in names}
before = {n: views["before_" + n] for n in names}


def project(v, p):
    dot = lambda a: sum(x * y for x, y in zip(p, a))
    return v["o"][0] + v["s"] * dot(v["R"]), v["o"][1] - v["s"] * dot(v["U"])


def region(v, points, grow):
    """The pixels whose centres are inside the convex hull of the points'
    projections grown by `grow` pixels (shrunk when negative)."""
    xy = sorted(set(project(v, p) for p in points))
    cross = lambda o, a, b: (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    hull = []
    for seq in (xy, xy[::-1]):  # Andrew's monotone chain: lower, then upper
        part = []
        for q in seq:
            while len(part) >= 2 and cross(part[-2], part[-1], q) <= 0:
                part.pop()
            part.append(q)
        hull += part[:-1]
    edges = []
    for a, b in zip(hull, hull[1:] + hull[:1]):  # counter-clockwise (y down): inside is where cross > 0
        n = ((b[0] - a[0]) ** 2 + (b[1] - a[1]) ** 2) ** 0.5
        edges.append((a, b, n))
    x0, x1 = min(x for x, _ in xy) - abs(grow) - 1, max(x for x, _ in xy) + abs(grow) + 1
    y0, y1 = min(y for _, y in xy) - abs(grow) - 1, max(y for _, y in xy) + abs(grow) + 1
    out = []
    for y in range(max(0, int(y0)), min(h, int(y1) + 1)):
        for x in range(max(0, int(x0)), min(w, int(x1) + 1)):
            c = (x + 0.5, y + 0.5)
            if all(cross(a, b, c) / n >= -grow for a, b, n in edges):
                out.append((x, y))
    return out


def count(pixels, k):
    return sum(1 for x, y in pixels if kind(pixel(x, y)) == k)


def in_view(v):
    x, y, vw, vh = v["rect"]
    return [(i, j) for j in range(y + 28, y + vh) for i in range(x, x + vw)]  # below the view's label


def corners(lo, hi):
    return [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]


failures = []


def expect(ok, what):
    if not ok:
        failures.append(what)


legend = {"red": (12, 40, (230, 30, 30)), "amber": (12, 66, (255, 176, 0)), "grey": (12, 92, (190, 190, 190)),
          "blue": (560, 40, (80, 60, 220)), "ring": (560, 66, None)}
swatch = lambda k: [(x, y) for y in range(legend[k][1], legend[k][1] + 18) for x in range(legend[k][0], legend[k][0] + 18)]
legend_pixels = set(p for k in legend for p in swatch(k))

if test == "same":  # the same pixels (whatever zlib made of them)
    w2, h2, rows2, _ = read_png(rest[0])
    if (w, h) != (w2, h2):
        sys.exit("%dx%d, not %dx%d" % (w, h, w2, h2))
    differ = sum(1 for a, b in zip(rows, rows2) for x in range(0, 3 * w, 3) if a[x:x + 3] != b[x:x + 3])
    sys.exit("%d pixels differ" % differ if differ else 0)
elif test == "same_views":  # the views' pixels the same: the same drawing of the model
    w2, h2, rows2, text2 = read_png(rest[0])
    expect([l.split()[:5] for l in text2.get("meshfix views", "").splitlines()] == [l.split()[:5] for l in text["meshfix views"].splitlines()],
           "the views are not in the same places")
    for name, v in views.items():
        differ = sum(1 for x, y in in_view(v) if rows[y][3 * x:3 * x + 3] != rows2[y][3 * x:3 * x + 3])
        expect(differ == 0, "%s view: %d pixels differ" % (name, differ))
elif test == "legend":  # each swatch its exact colour, its words after it
    for (k, (x0, y0, colour)), words in zip(legend.items(), rest):
        if colour is not None:
            off = [(x, y) for x, y in swatch(k) if pixel(x, y) != colour]
            expect(not off, "%s swatch at (%d, %d): %d pixels not %s" % (k, x0, y0, len(off), colour))
        else:
            expect(count(swatch(k), "red") > 20, "the ring swatch has no red ring")
        got = read_text(x0 + 26, y0, 40)
        expect(got == words, "%s swatch: the words after it are %r, not %r" % (k, got, words))
elif test == "title":
    got = read_text(12, 10, (w - 24) // 12)
    expect(rest[0] in got, "the title is %r, without %r" % (got, rest[0]))
elif test == "cubes":  # the left cube flipped: red where it projects, in every view, and nowhere else
    left, right = corners((0, 0, 0), (1, 1, 1)), corners((2, 0, 0), (3, 1, 1))
    for name, v in after.items():
        inner, outer = region(v, left, -3), set(region(v, left, 2))
        other = region(v, right, -3)
        red = count(inner, "red")
        expect(red >= 0.95 * len(inner), "%s view: %d of %d pixels red where the flipped cube is" % (name, red, len(inner)))
        stray = [p for p in in_view(v) if p not in outer and kind(pixel(*p)) == "red"]
        expect(not stray, "%s view: %d red pixels away from the flipped cube, e.g. %s" % (name, len(stray), stray[:3]))
        grey = count(other, "grey")
        expect(grey >= 0.95 * len(other), "%s view: %d of %d pixels grey where the kept cube is" % (name, grey, len(other)))
        blue = count(in_view(v), "blue")
        expect(blue == 0, "%s view: %d back-face pixels on closed cubes facing out" % (name, blue))
    for name, v in before.items():  # as read: both cubes grey (the inside-out one's far walls face the camera)
        for cube in (left, right):
            inner = region(v, cube, -3)
            grey = count(inner, "grey")
            expect(grey >= 0.95 * len(inner), "before %s: %d of %d pixels grey on a cube" % (name, grey, len(inner)))
        for k in ("red", "amber", "blue"):
            expect(count(in_view(v), k) == 0, "before %s: %s pixels" % (name, k))
    # front and back see the cubes from opposite sides: left and right swap
    fx = project(views["front"], (0.5, 0, 0.5))[0] - views["front"]["rect"][0]
    bx = project(views["back"], (0.5, 1, 0.5))[0] - views["back"]["rect"][0]
    expect(fx < views["front"]["rect"][2] / 2 < bx, "the flipped cube not left in front and right in back (%g, %g)" % (fx, bx))
elif test == "clean":  # nothing flipped: no red (or blue) pixel but the legend's
    for k in ("red", "blue", "amber"):
        n = sum(1 for y in range(h) for x in range(w) if (x, y) not in legend_pixels and kind(pixel(x, y)) == k)
        expect(n == 0, "%d %s pixels outside the legend" % (n, k))
    for name, v in views.items():
        expect(count(in_view(v), "grey") > 100, "%s view: the cube is not drawn" % name)
elif test in ("sheet_down", "sheet_up"):  # an open sheet at z = 0, seen from above by top and oblique
    sheet = corners((0, 0, 0), (2, 1, 0))
    top, top_before = region(views["top"], sheet, -3), region(views["before_top"], sheet, -3)
    if test == "sheet_down":
        blue = count(top, "blue")
        expect(blue >= 0.95 * len(top), "top view: %d of %d pixels blue on a sheet facing down" % (blue, len(top)))
        expect(count(in_view(views["oblique"]), "blue") > 1000, "oblique view: the sheet's back is not blue")
        shown = count(top_before, "grey") + count(top_before, "blue")
        expect(shown == 0, "before, top view: %d of %d pixels drawn on a sheet facing away (culled)" % (shown, len(top)))
    else:
        for t, name in ((top, "top"), (top_before, "before_top")):
            grey = count(t, "grey")
            expect(grey >= 0.95 * len(t), "%s view: %d of %d pixels grey on a sheet facing up" % (name, grey, len(t)))
        for name, v in views.items():
            expect(count(in_view(v), "blue") == 0, "%s view: back-face pixels on a sheet facing the camera" % name)
elif test == "slab":  # meshes.py's L, [-1.5, 1.5] x [-1.5, -0.5] and [-1.5, -0.5] x [-0.5, 1.5], from above
    def point(a, b):  # (along x, along the ground's other axis: the front at -1.5) in the file's axes
        return (a, 0.0, -b) if up == "y" else (a, b, 0.0)
    box = lambda x0, x1, y0, y1: [point(x, y) for x in (x0, x1) for y in (y0, y1)]
    for name in ("top", "before_top"):
        v = views[name]
        arms = region(v, box(-1.5, 1.5, -1.5, -0.5), -3) + region(v, box(-1.5, -0.5, -0.5, 1.5), -3)
        notch = region(v, box(-0.5, 1.5, -0.5, 1.5), -3)
        grey = count(arms, "grey")
        expect(grey >= 0.95 * len(arms), "%s view: %d of %d pixels grey on the L's arms" % (name, grey, len(arms)))
        drawn = sum(1 for x, y in notch if pixel(x, y) != (238, 240, 243))
        expect(drawn == 0, "%s view: %d of %d pixels drawn in the L's notch" % (name, drawn, len(notch)))
        # the arm along x is the front: at the bottom of the top view, the other arm on the left
        (fx, fy), (bx, by) = project(v, point(0.5, -1.0)), project(v, point(-1.0, 1.0))
        expect(fy > by and bx < fx, "%s view: the L is not the way round it is (%g %g, %g %g)" % (name, fx, fy, bx, by))
elif test == "small":  # a few flipped faces at one point: red there (a ring) in every view, before and after
    spot = tuple(map(float, rest[:3]))
    for name, v in views.items():
        near = region(v, [spot], 40)
        red = count(near, "red")
        expect(red >= 150, "%s view: %d red pixels within 40 of the flipped faces" % (name, red))
        far = set(near)
        stray = [p for p in in_view(v) if p not in far and kind(pixel(*p)) == "red"]
        expect(not stray, "%s view: %d red pixels away from the flipped faces, e.g. %s" % (name, len(stray), stray[:3]))
else:
    sys.exit("unknown test " + test)
for f in failures:
    print(f)
sys.exit(1 if failures else 0)
