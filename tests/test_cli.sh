#!/usr/bin/env bash
# Command-line checks of build/meshfix (tools/meshfix) and the STL loader it
# shares with the tests (examples/meshio.h):
# STL corner merging stays fast on corners crafted to collide in a hash,
# inputs that are not regular files are refused at once, outputs are
# written all or nothing, NaN corners load. Run from the repository root
# after `make build/meshfix build/demo_mesh`:  bash tests/test_cli.sh
# Prints "ok   NAME" or "FAIL NAME" per check, then "N passed, N failed".
set -u
cd "$(dirname "$0")/.." || exit 1
CC=${CC:-cc}
CXX=${CXX:-c++}
MESHFIX=build/meshfix
passed=0
failed=0
tmp=$(mktemp -d "${TMPDIR:-/tmp}/meshfix_cli.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT

check_log="$tmp/last.log"
. tests/check.sh

for binary in build/meshfix build/demo_mesh; do
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
fi

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
    echo "skip 32-bit build ($CXX -m32 cannot link here)"
fi

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
