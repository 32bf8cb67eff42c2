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

# meshes.py writes the test meshes, OFF (z up by the format's convention)
# and OBJ; tests/cli/png_check.py reads a PNG (zlib, the five filters) and
# checks its pixels against what the geometry says: where each view puts a
# point comes from the picture's tEXt chunk "meshfix views" (NAME X Y W H
# OX OY S RX RY RZ UX UY UZ: pixel = (OX + S p.R, OY - S p.U)), whose axes
# are checked against what front, back and top must be for the up axis;
# words are read back from the pixels in the tool's font.
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
def fine_cube(n, turned):  # [0, 1]^3, n x n squares a side, facing out; the triangles `turned` of its -y side reversed
    v, f, at = [], [], {}
    def vertex(p):
        if p not in at:
            at[p] = len(v)
            v.append(p)
        return at[p]
    sides = [((0, 0, 0), (1, 0, 0), (0, 0, 1)), ((0, 1, 0), (0, 0, 1), (1, 0, 0)), ((0, 0, 0), (0, 0, 1), (0, 1, 0)),
             ((1, 0, 0), (0, 1, 0), (0, 0, 1)), ((0, 0, 0), (0, 1, 0), (1, 0, 0)), ((0, 0, 1), (1, 0, 0), (0, 1, 0))]
    for o, u, w in sides:  # u x w points out
        p = lambda i, j: vertex(tuple(o[k] + u[k] * i / n + w[k] * j / n for k in range(3)))
        for j in range(n):
            for i in range(n):
                for t in ((p(i, j), p(i + 1, j), p(i + 1, j + 1)), (p(i, j), p(i + 1, j + 1), p(i, j + 1))):
                    f.append((t[0], t[2], t[1]) if len(f) in turned else t)
    return v, f
def slab(lift, y_up):  # an L, [-1.5, 1.5] x [-1.5, -0.5] and [-1.5, -0.5] x [-0.5, 1.5], 0.25 high from z = lift
    ring = [(-1.5, -1.5), (1.5, -1.5), (1.5, -0.5), (-0.5, -0.5), (-0.5, 1.5), (-1.5, 1.5)]  # counter-clockwise
    v = [(x, y, lift + h) for h in (0.0, 0.25) for x, y in ring]
    f = [tuple(range(5, -1, -1)), tuple(range(6, 12))] + [(k, (k + 1) % 6, (k + 1) % 6 + 6, k + 6) for k in range(6)]
    return [(x, z, -y) for x, y, z in v] if y_up else v, f  # y up: the same solid turned, z to y
def write(path, parts):
    off = path.endswith(".off")
    with open(path, "w") as out:
        if off:
            out.write("OFF\n%d %d 0\n" % (sum(len(v) for v, _ in parts), sum(len(f) for _, f in parts)))
        for v, f in parts:
            out.writelines(("%r %r %r\n" if off else "v %r %r %r\n") % p for p in v)
        base = 0
        for v, f in parts:
            if off:
                out.writelines("%d %s\n" % (len(t), " ".join(str(base + i) for i in t)) for t in f)
            else:
                out.writelines("f %s\n" % " ".join(str(base + i + 1) for i in t) for t in f)
            base += len(v)
d = sys.argv[1]
for ext in ("off", "obj"):
    write(d + "/cubes." + ext, [box((0, 0, 0), (1, 1, 1), True), box((2, 0, 0), (3, 1, 1))])  # the left one inside out
    write(d + "/cube." + ext, [box((0, 0, 0), (1, 1, 1))])
write(d + "/sheet_down.off", [sheet(4, 4, 2, 1, True)])
write(d + "/sheet_up.off", [sheet(4, 4, 2, 1, False)])
n = 80  # three triangles turned at the middle of the -y side, around (0.5, 0, 0.5)
middle = 2 * (n * (n // 2) + n // 2)
write(d + "/fine_cube.off", [fine_cube(n, {middle, middle + 1, middle + 2})])
write(d + "/slab_y.obj", [slab(0.0, True)])       # y up, standing on y = 0
write(d + "/slab_z.obj", [slab(0.0, False)])      # z up, standing on z = 0
write(d + "/slab_zc.obj", [slab(-0.125, False)])  # z up, centred: only its flat base says so
EOF

png_supported() { $MESHFIX --version | grep -q 'PNG marks'; }
PNG_CHECK="python3 tests/cli/png_check.py"

picture() { # test mesh.ext [options]: repairs $tmp/png/MESH.EXT with --mark MESH.EXT.png, checks the picture (png_check.py TEST)
    local test=$1 mesh=$2 args=()
    shift 2
    while [ $# -gt 0 ] && [ "$1" != -- ]; do args+=("$1"); shift; done
    [ $# -gt 0 ] && shift # the png_check.py arguments follow --
    local out=("$tmp/png/out.$mesh")
    case " ${args[*]-} " in *" --inspect "*) out=() ;; esac # --inspect writes nothing but the mark
    $MESHFIX --quiet "${args[@]}" "$tmp/png/$mesh" "${out[@]}" --mark "$tmp/png/$mesh.png" || { echo "status $?"; return 1; }
    $PNG_CHECK "$tmp/png/$mesh.png" "$test" "$@"
}

flipped_report() { # mesh count: the report says that many triangles were flipped
    $MESHFIX --inspect "$tmp/png/$1" | grep -q "would flip $2 of" || { $MESHFIX --inspect "$tmp/png/$1" | tail -3; return 1; }
}

png_deterministic() {
    $MESHFIX --quiet "$tmp/demo.obj" "$tmp/png/d1.obj" --mark "$tmp/png/d1.png" &&
        $MESHFIX --quiet "$tmp/demo.obj" "$tmp/png/d2.obj" --mark "$tmp/png/d2.png" && cmp "$tmp/png/d1.png" "$tmp/png/d2.png"
}

png_docs() { # README's picture is what `make demo` draws now
    mkdir -p "$tmp/png/demo"
    cp "$tmp/demo.obj" "$tmp/png/demo/demo_input.obj"
    $MESHFIX --quiet "$tmp/png/demo/demo_input.obj" "$tmp/png/demo/fixed.obj" --mark "$tmp/png/demo/marked.png" &&
        $PNG_CHECK "$tmp/png/demo/marked.png" same docs/demo_marked.png --up y ||
        { echo "(after a change to the picture: make demo && cp build/demo_marked.png docs/)"; return 1; }
}

png_batch() { # --mark DIR --mark-format png: one picture per input; without it, PLY as before
    mkdir -p "$tmp/png/marks" "$tmp/png/plys"
    $MESHFIX --quiet "$tmp/png/cube.off" "$tmp/png/cubes.off" -o "$tmp/png/out" --mark "$tmp/png/marks" --mark-format png &&
        $MESHFIX --quiet "$tmp/png/cube.off" "$tmp/png/cubes.off" -o "$tmp/png/out" --mark "$tmp/png/plys" || return 1
    [ "$(cd "$tmp/png/marks" && ls)" = "$(printf 'cube.off.png\ncubes.off.png')" ] || { ls "$tmp/png/marks"; return 1; }
    [ "$(cd "$tmp/png/plys" && ls)" = "$(printf 'cube.off.ply\ncubes.off.ply')" ] || { ls "$tmp/png/plys"; return 1; }
    $PNG_CHECK "$tmp/png/marks/cubes.off.png" cubes && head -c 3 "$tmp/png/plys/cube.off.ply" | grep -q ply
}

png_unwritable() { # all or nothing: a picture that cannot be written leaves the output unwritten
    mkdir -p "$tmp/png/w"
    one_line_error 1 "/nonexistent-dir/x.png" $MESHFIX --quiet "$tmp/demo.obj" "$tmp/png/w/out.obj" --mark /nonexistent-dir/x.png || return 1
    [ ! -e "$tmp/png/w/out.obj" ] || { echo "out.obj was written"; return 1; }
    one_line_error 1 "/nonexistent-dir/out.obj" $MESHFIX --quiet "$tmp/demo.obj" /nonexistent-dir/out.obj --mark "$tmp/png/w/m.png" || return 1
    [ ! -e "$tmp/png/w/m.png" ] || { echo "m.png was written"; return 1; }
    no_temporaries "$tmp/png/w"
}

slab_same() { # A B: the L slab of A and of B drawn alike, B's up (picture_up) found from the mesh
    picture slab "$2" -- --up "$3" && $PNG_CHECK "$tmp/png/$1.png" same_views "$tmp/png/$2.png" --up y
}

png_formats() { # the cubes, repaired, written as PLY and STL: z up by convention, as the OFF
    local ext
    for ext in ply stl; do
        $MESHFIX --quiet "$tmp/png/cubes.off" "$tmp/png/cubes.$ext" || return 1
        picture clean "cubes.$ext" && $PNG_CHECK "$tmp/png/cubes.$ext.png" title "up +z (${ext^^})" || { echo "($ext)"; return 1; }
    done
}

png_gltf() { # glTF: y up by convention
    local glb=/usr/share/assimp/models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb
    $MESHFIX --quiet --inspect "$glb" --mark "$tmp/png/box.glb.png" &&
        $PNG_CHECK "$tmp/png/box.glb.png" title "up +y (glTF)" --up y
}

if command -v python3 >/dev/null 2>&1 && png_supported; then
    mkdir -p "$tmp/png"
    python3 "$tmp/meshes.py" "$tmp/png"
    check "--mark FILE.png: the legend's swatches in their colours at their places, their counts read back from the pixels" \
        picture legend cubes.off -- "flipped: 12 triangles" "doubtful: 0 triangles" "kept: 12 triangles in 1 patch" \
        "seen from behind (inside-out)" "ringed: too small to see"
    check "--mark FILE.png --inspect: the legend says \"would flip\"" \
        picture legend cubes.off --inspect -- "would flip: 12 triangles" "doubtful: 0 triangles" \
        "kept: 12 triangles in 1 patch" "seen from behind (inside-out)" "ringed: too small to see"
    check "--mark FILE.png: the report flips the inside-out cube of two (12 triangles)" flipped_report cubes.off 12
    check "--mark FILE.png: red exactly where the flipped cube projects in each view, grey on the kept one; before: both grey" \
        picture cubes cubes.off
    check "--mark FILE.png: a cube with nothing flipped has no red, amber or back-face pixel" picture clean cube.off
    check "--mark FILE.png: an open sheet facing down is back-face blue from above, culled before (policy seed keeps it)" \
        picture sheet_down sheet_down.off --policy seed
    check "--mark FILE.png: the same sheet facing up has no back-face pixel, grey before too" \
        picture sheet_up sheet_up.off --policy seed
    check "--mark FILE.png: 3 triangles flipped of 76,800 (each a few pixels): red rings there in all 8 views, no red elsewhere" \
        picture small fine_cube.off -- 0.51 0 0.51
    check "--mark FILE.png: the legend of those 3 flipped triangles" \
        picture legend fine_cube.off -- "flipped: 3 triangles" "doubtful: 0 triangles" \
        "kept: 76797 triangles in 1 patch" "seen from behind (inside-out)" "ringed: too small to see"
    check "--mark FILE.png: up by convention: OFF z (its title says so)" picture title cubes.off -- "up +z (OFF)"
    check "--mark FILE.png: up by convention: PLY and STL z" png_formats
    if [ -f /usr/share/assimp/models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb ] && $MESHFIX --version | grep -q glTF; then
        check "--mark FILE.png: up by convention: glTF y" png_gltf
    else
        echo "SKIP --mark FILE.png: up by convention: glTF y: no glTF support or no assimp-testmodels (apt-get install assimp-testmodels)"
    fi
    check "--mark FILE.png: a y-up OBJ (an L standing on y = 0) drawn y up, its top view the L as it lies" \
        picture slab slab_y.obj -- --up y
    check "--mark FILE.png: the y-up OBJ's title says why" picture title slab_y.obj -- "up +y (OBJ)" --up y
    check "--mark FILE.png: the same L turned z up, standing on z = 0: z up, the same pixels in every view" \
        slab_same slab_y.obj slab_z.obj z
    check "--mark FILE.png: the same L z up, centred (only its flat base says so): z up, the same pixels" \
        slab_same slab_y.obj slab_zc.obj z
    check "--mark FILE.png: their titles say why" sh -c "$PNG_CHECK $tmp/png/slab_z.obj.png title 'up +z (OBJ standing on z = 0)' &&
        $PNG_CHECK $tmp/png/slab_zc.obj.png title 'up +z (OBJ with a flat base at its lowest z)'"
    check "--mark FILE.png: --up overrides the convention (the y-up OBJ drawn z up)" \
        picture title slab_y.obj --up z -- "up +z (--up)"
    check "--mark FILE.png: the same input gives the same bytes" png_deterministic
    check "docs/demo_marked.png, the README's picture, is what make demo draws" png_docs
    check "--mark DIR --mark-format png: a picture per input (PLY without it)" png_batch
    check "--mark FILE.png unwritable, or the output unwritable: nothing written" png_unwritable
elif ! png_supported; then
    echo "SKIP --mark FILE.png pictures: $MESHFIX was built without PNG support (apt-get install libpng-dev)"
else
    echo "SKIP --mark FILE.png pictures: no python3 to read them (apt-get install python3)"
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
    python3 tests/cli/turn_faces.py "$in" "$d/turned.obj" "$d/expected.txt" "$@" >/dev/null || return 1
    $MESHFIX --quiet "$d/turned.obj" "$d/fixed.obj" --mark "$d/mark.ply" || return 1
    blender -b --factory-startup --python-exit-code 1 --python tests/cli/blender_mark.py -- "$d/mark.ply" "$d/got.txt" \
        >"$d/blender.log" 2>&1 || { tail -n 20 "$d/blender.log"; return 1; }
    cat "$d/got.txt" | grep -v '^red\|^amber'
    grep -q '^colour [^ ]* \(CORNER\|POINT\)' "$d/got.txt" || { echo "no colour attribute imported"; return 1; }
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
if [ -n "${MESHFIX_CHECK:-}" ]; then
    # make check: plain builds only (the tool built -m32 again is a third of this script's time)
    echo "SKIP 32-bit build (-m32) loads a 40k-triangle STL within 20 s: make check builds plainly; make test runs it"
elif echo 'int main(){return 0;}' | $CXX -m32 -x c++ - -o "$tmp/m32probe" >/dev/null 2>&1; then
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
