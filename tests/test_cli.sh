#!/usr/bin/env bash
# Command-line checks of build/meshfix (tools/meshfix) and the STL loader it
# shares with the tests (examples/meshio.h):
# STL corner merging stays fast on corners crafted to collide in a hash,
# inputs that are not regular files are refused at once, outputs are
# written all or nothing, NaN corners load, --mark FILE.png draws flipped
# faces red and back faces blue where the geometry puts them (read back
# pixel by pixel), and a build without libpng says so. Run from the repository root
# after `make build/meshfix build/demo_mesh`:  bash tests/test_cli.sh
# Prints "ok   NAME" or "FAIL NAME" per check ("SKIP NAME: why" for one that
# cannot run here), then "N passed, N failed".
set -u
cd "$(dirname "$0")/.." || exit 1
CC=${CC:-cc}
CXX=${CXX:-c++}
MESHFIX=${MESHFIX:-build/meshfix}
passed=0
failed=0
tmp=$(mktemp -d "${TMPDIR:-/tmp}/meshfix_cli.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT

check_log="$tmp/last.log"
. tests/check.sh

for binary in "$MESHFIX" build/demo_mesh; do
    if [ ! -x "$binary" ]; then
        echo "FAIL $binary is not built (make build/meshfix build/demo_mesh)"
        echo "0 passed, 1 failed"
        exit 1
    fi
done

# ---- inputs ----

# A binary STL of N triangles whose 3N corners are all different yet share
# one value of the hash the STL reader used to merge corners with
# (FNV-1a-like over the 32-bit patterns of x, y, z, each step followed by
# h ^= h >> 15): x is the corner number, y is taken from a small sequence
# and z is solved by undoing the last step, keeping only z of moderate size.
# That reader put them all in one bucket and took quadratic time.
cat >"$tmp/collide.c" <<'EOF'
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static unsigned int step(unsigned int h, unsigned int bits)
{
    h = (h ^ bits) * 16777619u;
    return h ^ (h >> 15);
}

static unsigned int bits_of(float f)
{
    unsigned int b;
    memcpy(&b, &f, 4);
    return b;
}

static void put32(unsigned char *p, unsigned int v)
{
    p[0] = (unsigned char)v;
    p[1] = (unsigned char)(v >> 8);
    p[2] = (unsigned char)(v >> 16);
    p[3] = (unsigned char)(v >> 24);
}

int main(int argc, char **argv)
{
    const unsigned int target = 0x5EEDF00Du, basis = 2166136261u;
    unsigned int inverse = 16777619u, n, c, before_last;
    unsigned char header[84], facet[50];
    FILE *f;
    int i;
    if (argc != 3 || (n = (unsigned int)strtoul(argv[1], NULL, 10)) == 0 || (f = fopen(argv[2], "wb")) == NULL)
        return 1;
    for (i = 0; i < 5; ++i)
        inverse *= 2u - 16777619u * inverse; /* the prime's inverse mod 2^32 */
    before_last = (target ^ (target >> 15) ^ (target >> 30)) * inverse; /* h ^ z before the multiplication */
    memset(header, 0, sizeof(header));
    put32(header + 80, n);
    fwrite(header, 1, sizeof(header), f);
    memset(facet, 0, sizeof(facet));
    for (c = 0; c < 3 * n; ++c) {
        unsigned int x = bits_of((float)c), y = 0, z = 0, j;
        for (j = 1; j < 1000000; ++j) {
            y = bits_of((float)j * 0.001f);
            z = before_last ^ step(step(basis, x), y);
            if (((z >> 23) & 0xFF) >= 127 - 8 && ((z >> 23) & 0xFF) <= 127 + 8)
                break; /* 2^-8 <= |z| < 2^9 */
        }
        if (step(step(step(basis, x), y), z) != target)
            return 2;
        put32(facet + 12 + 12 * (c % 3), x);
        put32(facet + 16 + 12 * (c % 3), y);
        put32(facet + 20 + 12 * (c % 3), z);
        if (c % 3 == 2)
            fwrite(facet, 1, sizeof(facet), f);
    }
    return fclose(f) != 0;
}
EOF
if ! $CC -std=c99 -O2 -o "$tmp/collide" "$tmp/collide.c"; then
    echo "FAIL cannot build the collision generator with $CC"
    echo "0 passed, 1 failed"
    exit 1
fi

build/demo_mesh "$tmp/demo.obj" >/dev/null

# ---- checks ----

crafted() { # triangles: a crafted STL loads within a generous timeout, all corners distinct
    local n=$1
    "$tmp/collide" "$n" "$tmp/crafted$n.stl" || { echo "generator failed"; return 1; }
    timeout 20 $MESHFIX --inspect "$tmp/crafted$n.stl" >"$tmp/crafted.txt" || { echo "status $?"; return 1; }
    grep -q "triangles $n " "$tmp/crafted.txt" && grep -q "vertices  $((3 * n)) used" "$tmp/crafted.txt" ||
        { cat "$tmp/crafted.txt"; return 1; }
}
check "STL with 20k triangles of hash-colliding corners loads (timeout 20 s)" crafted 20000
check "STL with 80k triangles of hash-colliding corners loads (timeout 20 s)" crafted 80000
# the quadratic reader needed about a minute here: this one tells the two apart on any machine
check "STL with 160k triangles of hash-colliding corners loads (timeout 20 s)" crafted 160000

shares_corners() { # an STL written by meshfix loads with the vertices of the mesh it came from
    $MESHFIX --quiet "$tmp/demo.obj" "$tmp/demo.stl" || return 1
    local a b
    a=$($MESHFIX --inspect "$tmp/demo.obj" | grep 'vertices ') && b=$($MESHFIX --inspect "$tmp/demo.stl" | grep 'vertices ') &&
        [ "$a" = "$b" ] && echo "$b" | grep -q 'vertices  [1-9]' || { echo "obj: $a"; echo "stl: $b"; return 1; }
}
check "STL corners merge into the OBJ's shared vertices" shares_corners

negative_zero() { # -0 and +0 are one position: two triangles share an edge
    printf 'solid z\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n'\
'facet normal 0 0 0\nouter loop\nvertex 1 -0 -0\nvertex 1 1 0\nvertex -0 1 0\nendloop\nendfacet\nendsolid z\n' >"$tmp/zero.stl"
    $MESHFIX --inspect "$tmp/zero.stl" >"$tmp/zero.txt" || return 1
    grep -q 'vertices  4 used' "$tmp/zero.txt" && grep -q ', manifold 1,' "$tmp/zero.txt" || { cat "$tmp/zero.txt"; return 1; }
}
check "STL corners at -0 and +0 merge" negative_zero

one_line_error() { # status, pattern, command...: exits with status and prints one stderr line matching pattern
    local want=$1 pattern=$2 status
    shift 2
    "$@" >/dev/null 2>"$tmp/err.txt"
    status=$?
    cat "$tmp/err.txt"
    [ "$status" -eq "$want" ] || { echo "exit status $status, expected $want"; return 1; }
    [ "$(wc -l <"$tmp/err.txt")" -eq 1 ] || { echo "expected one line on stderr"; return 1; }
    grep -qi -- "$pattern" "$tmp/err.txt"
}

mkdir "$tmp/dir.obj"
check "a directory as input: exit 1, one line saying so" one_line_error 1 "is a directory" $MESHFIX "$tmp/dir.obj" "$tmp/x.obj"
check "a directory as input of --inspect: exit 1, one line" one_line_error 1 "is a directory" $MESHFIX --inspect "$tmp/dir.obj"

mkfifo "$tmp/pipe.stl"
check "a FIFO as input: exit 1 without waiting for a writer (timeout 5 s)" \
    one_line_error 1 "not a regular file" timeout 5 $MESHFIX "$tmp/pipe.stl" "$tmp/x.obj"
check "a FIFO as output: exit 1 without waiting for a reader (timeout 5 s)" \
    one_line_error 1 "not a regular file" timeout 5 $MESHFIX "$tmp/demo.obj" "$tmp/pipe.stl"

no_temporaries() { # directory: nothing but the expected files; meshfix's temporaries are gone
    local left
    left=$(find "$1" -name '*.meshfix-*.tmp')
    [ -z "$left" ] || { echo "left behind: $left"; return 1; }
}

mark_unwritable_new() {
    mkdir -p "$tmp/w1"
    one_line_error 1 "/nonexistent-dir/x.ply" $MESHFIX --quiet "$tmp/demo.obj" "$tmp/w1/out.obj" --mark /nonexistent-dir/x.ply || return 1
    [ ! -e "$tmp/w1/out.obj" ] || { echo "out.obj was written"; return 1; }
    no_temporaries "$tmp/w1"
}
check "--mark to an unwritable path: exit 1, the output is not created" mark_unwritable_new

mark_unwritable_existing() {
    mkdir -p "$tmp/w2"
    echo "previous contents" >"$tmp/w2/out.obj"
    cp "$tmp/w2/out.obj" "$tmp/w2/expected"
    one_line_error 1 "/nonexistent-dir/x.ply" $MESHFIX --quiet "$tmp/demo.obj" "$tmp/w2/out.obj" --mark /nonexistent-dir/x.ply || return 1
    cmp "$tmp/w2/out.obj" "$tmp/w2/expected" || return 1
    no_temporaries "$tmp/w2"
}
check "--mark to an unwritable path: an existing output stays unchanged" mark_unwritable_existing

mark_directory() {
    mkdir -p "$tmp/w3/mark.ply"
    one_line_error 1 "directory" $MESHFIX --quiet "$tmp/demo.obj" "$tmp/w3/out.obj" --mark "$tmp/w3/mark.ply" || return 1
    [ ! -e "$tmp/w3/out.obj" ] || { echo "out.obj was written"; return 1; }
    no_temporaries "$tmp/w3"
}
check "--mark naming a directory: exit 1, the output is not created" mark_directory

output_unwritable() {
    mkdir -p "$tmp/w4"
    one_line_error 1 "/nonexistent-dir/out.obj" $MESHFIX --quiet "$tmp/demo.obj" /nonexistent-dir/out.obj --mark "$tmp/w4/mark.ply" || return 1
    [ ! -e "$tmp/w4/mark.ply" ] || { echo "mark.ply was written"; return 1; }
    no_temporaries "$tmp/w4"
}
check "an unwritable output: exit 1, the --mark file is not created" output_unwritable

bad_input_writes_nothing() {
    mkdir -p "$tmp/w5"
    printf 'OFF\n999999999 1 0\n' >"$tmp/w5/bad.off"
    one_line_error 1 "bad.off" $MESHFIX --quiet "$tmp/w5/bad.off" "$tmp/w5/out.obj" --mark "$tmp/w5/mark.ply" || return 1
    [ ! -e "$tmp/w5/out.obj" ] && [ ! -e "$tmp/w5/mark.ply" ] || { echo "an output was written"; return 1; }
    no_temporaries "$tmp/w5"
}
check "a bad input: exit 1, no output and no temporary left" bad_input_writes_nothing

unknown_format() {
    mkdir -p "$tmp/w6"
    one_line_error 1 "unknown output format" $MESHFIX --quiet "$tmp/demo.obj" "$tmp/w6/out.xyz" || return 1
    [ -z "$(ls -A "$tmp/w6")" ] || { ls -A "$tmp/w6"; return 1; }
}
check "an unknown output format: exit 1, nothing written" unknown_format

both_written() {
    mkdir -p "$tmp/w7"
    echo "old" >"$tmp/w7/out.ply"
    chmod 640 "$tmp/w7/out.ply"
    $MESHFIX --quiet "$tmp/demo.obj" "$tmp/w7/out.ply" --mark "$tmp/w7/mark.ply" || return 1
    $MESHFIX --inspect "$tmp/w7/out.ply" | grep -q 'inconsistent 0' || return 1
    $MESHFIX --inspect "$tmp/w7/mark.ply" | grep -q 'inconsistent 0' || return 1
    [ "$(stat -c %a "$tmp/w7/out.ply")" = 640 ] || { echo "permissions of the replaced file changed"; return 1; }
    no_temporaries "$tmp/w7"
}
check "a good run writes both outputs (a replaced one keeps its mode), no temporary left" both_written

nan_ascii() {
    printf 'solid n\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n'\
'facet normal 0 0 0\nouter loop\nvertex 1 0 0\nvertex nan 0 0\nvertex 0 1 0\nendloop\nendfacet\n'\
'facet normal 0 0 0\nouter loop\nvertex nan 0 0\nvertex 0 0 0\nvertex inf -inf 0\nendloop\nendfacet\nendsolid n\n' >"$tmp/nan.stl"
    $MESHFIX --inspect "$tmp/nan.stl" >"$tmp/nan.txt" || { echo "status $?"; cat "$tmp/nan.txt"; return 1; }
    # the finite corners merge (0 0 0 and 1 0 0 and 0 1 0), NaN/Inf corners stay apart
    grep -q 'triangles 3 ' "$tmp/nan.txt" && grep -q 'vertices  6 used (3 not finite' "$tmp/nan.txt" ||
        { cat "$tmp/nan.txt"; return 1; }
    $MESHFIX --quiet "$tmp/nan.stl" "$tmp/nan_out.obj"
    [ $? -lt 128 ] || { echo "repair crashed"; return 1; }
}
check "ASCII STL with NaN and Inf corners loads and is inspected" nan_ascii

nan_binary() {
    /usr/bin/env python3 - "$tmp/nan_bin.stl" <<'EOF' || return 1
import struct, sys
nan, inf = float("nan"), float("inf")
corners = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (nan, 0, 0), (1, 1, 0), (nan, nan, nan), (0, 0, inf), (1, 0, 0), (0, 1, 0)]
tris = [(corners[a], corners[b], corners[c]) for a, b, c in [(0, 1, 2), (1, 4, 2), (3, 1, 2), (5, 6, 0), (3, 3, 3), (7, 4, 8)] * 500]
with open(sys.argv[1], "wb") as f:
    f.write(bytes(80) + struct.pack("<I", len(tris)))
    for t in tris:
        f.write(struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *c) for c in t) + b"\0\0")
EOF
    timeout 20 $MESHFIX --inspect "$tmp/nan_bin.stl" >"$tmp/nan.txt" || { echo "status $?"; cat "$tmp/nan.txt"; return 1; }
    grep -q 'triangles 3000 ' "$tmp/nan.txt" && grep -q 'not finite' "$tmp/nan.txt" || { cat "$tmp/nan.txt"; return 1; }
    timeout 20 $MESHFIX --quiet "$tmp/nan_bin.stl" "$tmp/nan_bin.ply"
    [ $? -lt 124 ] || { echo "repair crashed or hung"; return 1; }
}
if command -v python3 >/dev/null 2>&1; then
    check "binary STL with NaN corners loads and is inspected" nan_binary
else
    echo "SKIP binary STL with NaN corners loads and is inspected: no python3 to write it (apt-get install python3)"
fi

# ---- --mark FILE.png: the picture, checked by its pixels ----

# meshes.py writes the OBJ files; png_check.py reads a PNG (zlib, the five
# filters) and checks its pixels against what the geometry says: where each
# view puts a point comes from the picture's tEXt chunk "meshfix views"
# (NAME X Y W H OX OY S RX RY RZ UX UY UZ: pixel = (OX + S p.R, OY - S p.U)),
# whose axes are checked against what front, back and top must be for z up.
cat >"$tmp/meshes.py" <<'EOF'
import sys
def box(lo, hi, inside_out=False):
    v = [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]  # outward
    f = [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]
    return v, [(a, c, b) for a, b, c in f] if inside_out else f
def sheet(nx, ny, x1, y1, down):  # [0, x1] x [0, y1] at z = 0, facing -z when down
    v = [(x1 * i / nx, y1 * j / ny, 0.0) for j in range(ny + 1) for i in range(nx + 1)]
    f = []
    for j in range(ny):
        for i in range(nx):
            a = j * (nx + 1) + i
            for t in ((a, a + 1, a + nx + 2), (a, a + nx + 2, a + nx + 1)):
                f.append((t[0], t[2], t[1]) if down else t)
    return v, f
def write(path, parts):
    with open(path, "w") as out:
        base = 0
        for v, f in parts:
            out.writelines("v %r %r %r\n" % p for p in v)
            out.writelines("f %d %d %d\n" % tuple(base + i + 1 for i in t) for t in f)
            base += len(v)
d = sys.argv[1]
write(d + "/cubes.obj", [box((0, 0, 0), (1, 1, 1), True), box((2, 0, 0), (3, 1, 1))])  # the left one inside out
write(d + "/cube.obj", [box((0, 0, 0), (1, 1, 1))])
write(d + "/sheet_down.obj", [sheet(4, 4, 2, 1, True)])
write(d + "/sheet_up.obj", [sheet(4, 4, 2, 1, False)])
EOF

cat >"$tmp/png_check.py" <<'EOF'
import struct, sys, zlib

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

path, test = sys.argv[1], sys.argv[2]
w, h, rows, text = read_png(path)
if test == "same":  # png_check.py A same B: the same pixels (whatever zlib made of them)
    w2, h2, rows2, _ = read_png(sys.argv[3])
    if (w, h) != (w2, h2):
        sys.exit("%dx%d, not %dx%d" % (w, h, w2, h2))
    differ = sum(1 for a, b in zip(rows, rows2) for x in range(0, 3 * w, 3) if a[x:x + 3] != b[x:x + 3])
    sys.exit("%d pixels differ" % differ if differ else 0)
pixel = lambda x, y: tuple(rows[y][3 * x:3 * x + 3])
views = {}
for line in text.get("meshfix views", "").splitlines():
    f = line.split()
    views[f[0]] = dict(rect=tuple(map(int, f[1:5])), o=(float(f[5]), float(f[6])), s=float(f[7]),
                       R=tuple(map(float, f[8:11])), U=tuple(map(float, f[11:14])))
if sorted(views) != ["back", "front", "oblique", "top"]:
    sys.exit("views in the tEXt chunk: %s" % sorted(views))
axes = {"front": ((1, 0, 0), (0, 0, 1)), "back": ((-1, 0, 0), (0, 0, 1)), "top": ((1, 0, 0), (0, 1, 0))}
for name, (R, U) in axes.items():
    if views[name]["R"] != R or views[name]["U"] != U:
        sys.exit("%s view: axes %s %s, expected %s %s" % (name, views[name]["R"], views[name]["U"], R, U))

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
    return [(i, j) for j in range(y, y + vh) for i in range(x, x + vw)]

def corners(lo, hi):
    return [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]

failures = []
def expect(ok, what):
    if not ok:
        failures.append(what)

legend = {"red": (12, 40, (230, 30, 30)), "amber": (12, 66, (255, 176, 0)), "blue": (330, 40, (80, 60, 220)),
          "grey": (330, 66, (190, 190, 190))}
swatch = lambda k: [(x, y) for y in range(legend[k][1], legend[k][1] + 18) for x in range(legend[k][0], legend[k][0] + 18)]

if test == "legend":  # each swatch its exact colour, its words (dark pixels) after it
    for k, (x0, y0, colour) in legend.items():
        off = [(x, y) for x, y in swatch(k) if pixel(x, y) != colour]
        expect(not off, "%s swatch at (%d, %d): %d pixels not %s" % (k, x0, y0, len(off), colour))
        ink = sum(1 for y in range(y0, y0 + 18) for x in range(x0 + 26, x0 + 146) if max(pixel(x, y)) < 100)
        expect(ink > 100, "%s swatch: no words after it (%d dark pixels)" % (k, ink))
elif test == "cubes":  # the left cube flipped: red where it projects, in every view, and nowhere else
    left, right = corners((0, 0, 0), (1, 1, 1)), corners((2, 0, 0), (3, 1, 1))
    for name, v in views.items():
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
    # front and back see the cubes from opposite sides: left and right swap
    fx = project(views["front"], (0.5, 0, 0.5))[0] - views["front"]["rect"][0]
    bx = project(views["back"], (0.5, 1, 0.5))[0] - views["back"]["rect"][0]
    expect(fx < views["front"]["rect"][2] / 2 < bx, "the flipped cube not left in front and right in back (%g, %g)" % (fx, bx))
elif test == "clean":  # nothing flipped: no red (or blue) pixel but the legend's
    for k in ("red", "blue", "amber"):
        keep = set(swatch(k))
        n = sum(1 for y in range(h) for x in range(w) if (x, y) not in keep and kind(pixel(x, y)) == k)
        expect(n == 0, "%d %s pixels outside the legend" % (n, k))
    for name, v in views.items():
        expect(count(in_view(v), "grey") > 100, "%s view: the cube is not drawn" % name)
elif test in ("sheet_down", "sheet_up"):  # an open sheet at z = 0, seen from above by top and oblique
    sheet = corners((0, 0, 0), (2, 1, 0))
    top = region(views["top"], sheet, -3)
    if test == "sheet_down":
        blue = count(top, "blue")
        expect(blue >= 0.95 * len(top), "top view: %d of %d pixels blue on a sheet facing down" % (blue, len(top)))
        expect(count(in_view(views["oblique"]), "blue") > 1000, "oblique view: the sheet's back is not blue")
    else:
        grey = count(top, "grey")
        expect(grey >= 0.95 * len(top), "top view: %d of %d pixels grey on a sheet facing up" % (grey, len(top)))
        for name, v in views.items():
            expect(count(in_view(v), "blue") == 0, "%s view: back-face pixels on a sheet facing the camera" % name)
else:
    sys.exit("unknown test " + test)
for f in failures:
    print(f)
sys.exit(1 if failures else 0)
EOF

png_supported() { $MESHFIX --version | grep -q 'PNG marks'; }

picture() { # test mesh [options]: repairs $tmp/png/MESH.obj with --mark MESH.png, checks the picture (png_check.py TEST)
    local test=$1 mesh=$2
    shift 2
    $MESHFIX --quiet "$@" "$tmp/png/$mesh.obj" "$tmp/png/$mesh.out.obj" --mark "$tmp/png/$mesh.png" || { echo "status $?"; return 1; }
    python3 "$tmp/png_check.py" "$tmp/png/$mesh.png" "$test"
}

flipped_report() { # mesh count: the report says that many triangles were flipped
    $MESHFIX --inspect "$tmp/png/$1.obj" | grep -q "would flip $2 of" || { $MESHFIX --inspect "$tmp/png/$1.obj" | tail -3; return 1; }
}

png_deterministic() {
    $MESHFIX --quiet "$tmp/demo.obj" "$tmp/png/d1.obj" --mark "$tmp/png/d1.png" &&
        $MESHFIX --quiet "$tmp/demo.obj" "$tmp/png/d2.obj" --mark "$tmp/png/d2.png" && cmp "$tmp/png/d1.png" "$tmp/png/d2.png"
}

png_docs() { # README's picture is what `make demo` draws now
    mkdir -p "$tmp/png/demo"
    cp "$tmp/demo.obj" "$tmp/png/demo/demo_input.obj"
    $MESHFIX --quiet "$tmp/png/demo/demo_input.obj" "$tmp/png/demo/fixed.obj" --mark "$tmp/png/demo/marked.png" &&
        python3 "$tmp/png_check.py" "$tmp/png/demo/marked.png" same docs/demo_marked.png ||
        { echo "(after a change to the picture: make demo && cp build/demo_marked.png docs/)"; return 1; }
}

png_batch() { # --mark DIR --mark-format png: one picture per input; without it, PLY as before
    mkdir -p "$tmp/png/marks" "$tmp/png/plys"
    $MESHFIX --quiet "$tmp/png/cube.obj" "$tmp/png/cubes.obj" -o "$tmp/png/out" --mark "$tmp/png/marks" --mark-format png &&
        $MESHFIX --quiet "$tmp/png/cube.obj" "$tmp/png/cubes.obj" -o "$tmp/png/out" --mark "$tmp/png/plys" || return 1
    [ "$(cd "$tmp/png/marks" && ls)" = "$(printf 'cube.obj.png\ncubes.obj.png')" ] || { ls "$tmp/png/marks"; return 1; }
    [ "$(cd "$tmp/png/plys" && ls)" = "$(printf 'cube.obj.ply\ncubes.obj.ply')" ] || { ls "$tmp/png/plys"; return 1; }
    python3 "$tmp/png_check.py" "$tmp/png/marks/cubes.obj.png" cubes && head -c 3 "$tmp/png/plys/cube.obj.ply" | grep -q ply
}

png_unwritable() { # all or nothing: a picture that cannot be written leaves the output unwritten
    mkdir -p "$tmp/png/w"
    one_line_error 1 "/nonexistent-dir/x.png" $MESHFIX --quiet "$tmp/demo.obj" "$tmp/png/w/out.obj" --mark /nonexistent-dir/x.png || return 1
    [ ! -e "$tmp/png/w/out.obj" ] || { echo "out.obj was written"; return 1; }
    one_line_error 1 "/nonexistent-dir/out.obj" $MESHFIX --quiet "$tmp/demo.obj" /nonexistent-dir/out.obj --mark "$tmp/png/w/m.png" || return 1
    [ ! -e "$tmp/png/w/m.png" ] || { echo "m.png was written"; return 1; }
    no_temporaries "$tmp/png/w"
}

if command -v python3 >/dev/null 2>&1 && png_supported; then
    mkdir -p "$tmp/png"
    python3 "$tmp/meshes.py" "$tmp/png"
    check "--mark FILE.png: the legend's swatches in their colours at their places, words after them" \
        picture legend cubes
    check "--mark FILE.png: the report flips the inside-out cube of two (12 triangles)" flipped_report cubes 12
    check "--mark FILE.png: red exactly where the flipped cube projects in each view, grey on the kept one" \
        picture cubes cubes
    check "--mark FILE.png: a cube with nothing flipped has no red, amber or back-face pixel" picture clean cube
    check "--mark FILE.png: an open sheet facing down is back-face blue from above (policy seed keeps it)" \
        picture sheet_down sheet_down --policy seed
    check "--mark FILE.png: the same sheet facing up has no back-face pixel" picture sheet_up sheet_up --policy seed
    check "--mark FILE.png: the same input gives the same bytes" png_deterministic
    check "docs/demo_marked.png, the README's picture, is what make demo draws" png_docs
    check "--mark DIR --mark-format png: a picture per input (PLY without it)" png_batch
    check "--mark FILE.png unwritable, or the output unwritable: nothing written" png_unwritable
elif ! png_supported; then
    echo "skip --mark FILE.png pictures ($MESHFIX was built without PNG support)"
else
    echo "skip --mark FILE.png pictures (no python3 to read them)"
fi
# ---- --mark FILE.ply in Blender ----
# Blender 3.4's PLY importer drops face colours: the mark carries vertex
# colours too, a vertex copied where faces of different colours share it.
# Debian's Blender imports it headless (tests/cli/blender_mark.py); the
# faces it shows red must be exactly the ones turned (tests/cli/turn_faces.py).

blender_mark() { # DIR IN.obj FACE...: turns the faces, repairs with --mark, imports the mark in Blender
    local d=$1 in=$2
    shift 2
    mkdir -p "$d"
    python3 tests/cli/turn_faces.py "$in" "$d/turned.obj" "$d/expected.txt" "$@" || return 1
    $MESHFIX --quiet "$d/turned.obj" "$d/fixed.obj" --mark "$d/mark.ply" || return 1
    blender -b --factory-startup --python-exit-code 1 --python tests/cli/blender_mark.py -- "$d/mark.ply" "$d/got.txt" \
        >"$d/blender.log" 2>&1 || { tail -n 20 "$d/blender.log"; return 1; }
    cat "$d/got.txt" | grep -v '^red\|^amber'
    grep -q '^colour [^ ]* CORNER\|^colour [^ ]* POINT' "$d/got.txt" || { echo "no colour attribute imported"; return 1; }
    grep -q '^mixed 0$' "$d/got.txt" || { echo "faces of more than one colour"; return 1; }
    ! grep -q '^amber' "$d/got.txt" || { echo "amber faces"; return 1; }
    grep '^red' "$d/got.txt" | sort | diff - "$d/expected.txt" || { echo "(< red in Blender, > turned)"; return 1; }
}
if ! command -v blender >/dev/null 2>&1; then
    echo "SKIP --mark FILE.ply in Blender: blender is not installed (apt-get install blender)"
elif ! command -v python3 >/dev/null 2>&1; then
    echo "SKIP --mark FILE.ply in Blender: no python3 to write the input (apt-get install python3)"
else
    mkdir -p "$tmp/bl"
    python3 "$tmp/meshes.py" "$tmp/bl"
    check "--mark FILE.ply in Blender: a cube with one triangle turned, its corners shared: exactly it red" \
        blender_mark "$tmp/bl/one" "$tmp/bl/cube.obj" 5
    check "--mark FILE.ply in Blender: two triangles of a cube's face and one of the next: exactly they red" \
        blender_mark "$tmp/bl/three" "$tmp/bl/cube.obj" 0 1 4
fi
check "--mark FILE.jpg: exit 1, one line naming .ply and .png" one_line_error 1 "give a .ply or .png file" \
    $MESHFIX --quiet "$tmp/demo.obj" "$tmp/x.obj" --mark "$tmp/x.jpg"
check "--mark-format png with --mark FILE.ply: exit 1, one line" one_line_error 1 "mark-format png" \
    $MESHFIX --quiet "$tmp/demo.obj" "$tmp/x.obj" --mark "$tmp/x.ply" --mark-format png

m32() { # the 32-bit build (without glTF and PNG: no 32-bit tinygltf or libpng) loads a 40k-triangle STL (it used to hang there)
    $CC -m32 -std=c99 -O2 -c -o "$tmp/libs32.o" tools/meshfix/libs.c &&
        $CXX -m32 -std=c++17 -O2 -DMESHFIX_TOOL_NO_GLTF -DMESHFIX_TOOL_NO_PNG -o "$tmp/meshfix32" tools/meshfix/*.cpp \
            "$tmp/libs32.o" -pthread ||
        return 1
    "$tmp/collide" 40000 "$tmp/crafted40000.stl" || return 1
    timeout 20 "$tmp/meshfix32" --inspect "$tmp/crafted40000.stl" | grep -q 'vertices  120000 used' || return 1
    timeout 20 "$tmp/meshfix32" --quiet "$tmp/demo.obj" "$tmp/demo32.stl" || return 1
    timeout 20 "$tmp/meshfix32" --inspect "$tmp/demo32.stl" | grep -q 'inconsistent 0'
}
if echo 'int main(){return 0;}' | $CXX -m32 -x c++ - -o "$tmp/m32probe" >/dev/null 2>&1; then
    check "32-bit build (-m32) loads a 40k-triangle STL within 20 s" m32
else
    echo "SKIP 32-bit build (-m32) loads a 40k-triangle STL within 20 s: $CXX -m32 cannot link here (apt-get install g++-multilib)"
fi

no_png() { # a build without libpng (MESHFIX_TOOL_NO_PNG: the 32-bit one, else one made here) refuses
             # --mark FILE.png before reading anything, in one line, and writes nothing; PLY marks still work
    local bin=$tmp/meshfix32
    if [ ! -x "$bin" ]; then
        bin=$tmp/meshfix_nopng
        $CC -std=c99 -O1 -c -o "$tmp/libs_nopng.o" tools/meshfix/libs.c &&
            $CXX -std=c++17 -O1 -DMESHFIX_TOOL_NO_GLTF -DMESHFIX_TOOL_NO_PNG -o "$bin" tools/meshfix/*.cpp \
                "$tmp/libs_nopng.o" -pthread || return 1
    fi
    mkdir -p "$tmp/nopng"
    one_line_error 1 "built without PNG support" "$bin" --quiet "$tmp/demo.obj" "$tmp/nopng/out.obj" --mark "$tmp/nopng/m.png" ||
        return 1
    [ -z "$(ls -A "$tmp/nopng")" ] || { ls -A "$tmp/nopng"; return 1; }
    "$bin" --version | grep -q 'without PNG support' || return 1
    "$bin" --quiet "$tmp/demo.obj" "$tmp/nopng/out.obj" --mark "$tmp/nopng/m.ply" && [ -s "$tmp/nopng/m.ply" ]
}
check "a build without libpng: --mark FILE.png is one line \"built without PNG support\", nothing written" no_png

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
