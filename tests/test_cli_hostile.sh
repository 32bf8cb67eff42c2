#!/usr/bin/env bash
# build/meshfix on hostile files and hostile runs, as an asset pipeline meets
# them (files from anyone, in place, in batches, in CI): glTF URIs that climb
# out of their directory by any encoding, a disk that fills or fails while
# the input is replaced, index bytes shared between meshes, JSON nested to
# crash a recursive parser, FIFOs and the current directory as companions,
# batch outputs that collide, ASCII STL read two ways, OBJ line
# continuations, paths that are not UTF-8 in --json, interrupted runs;
# round 4: outputs named over the input's own files (glTF buffers, --mark),
# a glTF document tinygltf's model does not keep, normal and matrix bytes
# shared, two buffers of one file, walks through looping links, companions
# that are links out, a 255-byte name, a move into place that fails.
# The glTF files come from tests/cli/hostile_gltf.py; a disk that fails is
# tests/cli/failing_io.c (LD_PRELOAD: writes, fsync and rename that fail),
# and, as root, a small tmpfs.
# Run from the repository root after `make build/meshfix build/demo_mesh`.
# Prints "ok NAME", "FAIL NAME" or "SKIP NAME (why)", then "N passed, N failed".
set -u
cd "$(dirname "$0")/.." || exit 1
CC=${CC:-cc}
MESHFIX=${MESHFIX:-$PWD/build/meshfix}
passed=0
failed=0
tmp=$(mktemp -d "${TMPDIR:-/tmp}/meshfix_hostile.XXXXXX") || exit 1
mounted=""
cleanup() {
    [ -z "$mounted" ] || umount "$mounted" 2>/dev/null
    rm -rf "$tmp"
}
trap cleanup EXIT
check_log="$tmp/last.log"
. tests/check.sh
skip() { echo "SKIP $1"; }

for binary in build/meshfix build/demo_mesh; do
    if [ ! -x "$binary" ]; then
        echo "FAIL $binary is not built (make build/meshfix build/demo_mesh)"
        echo "0 passed, 1 failed"
        exit 1
    fi
done
build/demo_mesh "$tmp/demo.obj" >/dev/null || exit 1
/usr/bin/python3 tests/cli/hostile_gltf.py "$tmp/g" || { echo "FAIL hostile_gltf.py"; echo "0 passed, 1 failed"; exit 1; }
$CC -shared -fPIC -o "$tmp/failing_io.so" tests/cli/failing_io.c -ldl || { echo "FAIL failing_io.c"; echo "0 passed, 1 failed"; exit 1; }

# exit status `want`, one line on stderr matching `pattern`
one_line_error() { # want pattern command...
    local want=$1 pattern=$2 status
    shift 2
    "$@" >"$tmp/out.txt" 2>"$tmp/err.txt"
    status=$?
    cat "$tmp/err.txt"
    [ "$status" -eq "$want" ] || { echo "exit status $status, expected $want"; return 1; }
    [ "$(wc -l <"$tmp/err.txt")" -eq 1 ] || { echo "expected one line on stderr"; return 1; }
    grep -qi -- "$pattern" "$tmp/err.txt"
}

no_temporaries() { # directory
    local left
    left=$(find "$1" -name '*.meshfix-*.tmp')
    [ -z "$left" ] || { echo "left behind: $left"; return 1; }
}

# ---- 1. URIs that leave the glTF's directory ----

# Each case aims at traversal/NAME/secret.*: three levels above a/b/in/. The
# run must refuse (reading and writing), write nothing under out/, and leave
# no copy of the secret anywhere.
traversal() { # case
    local base="$tmp/g/traversal/$1" found
    mkdir -p "$base/out/x/y"
    touch "$base/before"
    one_line_error 1 "outside its directory" $MESHFIX "$base/a/b/in/scene.gltf" "$base/out/x/y/scene.gltf" || return 1
    one_line_error 1 "outside its directory" $MESHFIX --inspect "$base/a/b/in/scene.gltf" || return 1
    one_line_error 1 "outside its directory" $MESHFIX --json "$base/a/b/in/scene.gltf" -o "$base/out/batch" || return 1
    found=$(find "$base" -newer "$base/before" ! -type d)
    [ -z "$found" ] || { echo "written: $found"; return 1; }
    [ "$(find "$base" -name 'secret.*' | wc -l)" -eq 2 ] || { find "$base" -name 'secret.*'; return 1; }
}
for case in $(ls "$tmp/g/traversal"); do
    check "glTF URI climbing out of its directory ($case): refused, nothing read or written" traversal "$case"
done

literal_refused() {
    local d="$tmp/literal"
    mkdir -p "$d/in"
    for uri in "../secret.bin" "/etc/hostname" "file:///etc/hostname" "sub/../../secret.bin"; do
        sed "s|\"uri\": \"scene.bin\"|\"uri\": \"$uri\"|" "$tmp/g/alias/scene.gltf" >"$d/in/scene.gltf"
        cp "$tmp/g/alias/scene.bin" "$d/secret.bin"
        $MESHFIX --inspect "$d/in/scene.gltf" >/dev/null 2>&1 && { echo "'$uri' was read"; return 1; }
    done
    return 0
}
check "literal ../, absolute and file:// buffer URIs stay refused" literal_refused

# ---- 2. a disk that fills up or fails while the input is replaced ----

# In place: the input must come back byte for byte, exit 1, no temporary.
in_place_fails() { # environment assignment, file, companion...
    local setting=$1 file=$2 d="$tmp/fill" f
    shift 2
    rm -rf "$d" && mkdir -p "$d"
    for f in "$file" "$@"; do cp "$tmp/g/big/$f" "$d/"; done
    env "$setting" LD_PRELOAD="$tmp/failing_io.so" $MESHFIX "$d/$file" "$d/$file" >/dev/null 2>"$tmp/err.txt"
    [ $? -eq 1 ] || { cat "$tmp/err.txt"; echo "exit status not 1"; return 1; }
    for f in "$file" "$@"; do cmp "$d/$f" "$tmp/g/big/$f" || return 1; done
    no_temporaries "$d"
}
check "disk full after 50 KB: meshfix in.glb in.glb keeps in.glb, exit 1" in_place_fails FAILING_IO_WRITE_LIMIT=50000 in.glb
check "disk full after 50 KB: in.gltf with in.bin in place keeps both" in_place_fails FAILING_IO_WRITE_LIMIT=50000 in.gltf in.bin
check "disk full after 100 KB (the .bin written, the .gltf not): both kept" in_place_fails FAILING_IO_WRITE_LIMIT=100000 in.gltf in.bin
check "disk full at the first byte: in.gltf and in.bin kept" in_place_fails FAILING_IO_WRITE_LIMIT=0 in.gltf in.bin
check "fsync fails (EIO): in.glb kept" in_place_fails FAILING_IO_FSYNC=eio in.glb

other_formats_fail() {
    local d="$tmp/fill2" f
    rm -rf "$d" && mkdir -p "$d"
    for f in obj ply stl off; do
        $MESHFIX --quiet "$tmp/demo.obj" "$d/demo.$f" || return 1
        cp "$d/demo.$f" "$d/expected.$f"
        # scramble: a repair has to write
        FAILING_IO_WRITE_LIMIT=4096 LD_PRELOAD="$tmp/failing_io.so" $MESHFIX --policy seed "$d/demo.$f" "$d/demo.$f" \
            >/dev/null 2>&1
        cmp "$d/demo.$f" "$d/expected.$f" || { echo "$f changed"; return 1; }
    done
    no_temporaries "$d"
}
check "disk full: OBJ, PLY, STL and OFF outputs in place are kept whole" other_formats_fail

tmpfs_full() { # file companion...: on a tmpfs with about 68 KB left after the input
    local d="$tmp/tmpfs" f size=0
    mkdir -p "$d"
    for f in "$@"; do size=$((size + $(stat -c %s "$tmp/g/big/$f"))); done
    mount -t tmpfs -o size=$(((size + 68 * 1024 + 4095) / 4096 * 4096)) tmpfs "$d" || return 1
    mounted=$d
    for f in "$@"; do cp "$tmp/g/big/$f" "$d/" || return 1; done
    $MESHFIX "$d/$1" "$d/$1" >"$tmp/out.txt" 2>"$tmp/err.txt"
    local status=$?
    for f in "$@"; do cmp "$d/$f" "$tmp/g/big/$f" || { umount "$d"; mounted=""; return 1; }; done
    no_temporaries "$d" || { umount "$d"; mounted=""; return 1; }
    umount "$d"
    mounted=""
    [ "$status" -eq 1 ] || { echo "exit status $status"; return 1; }
    grep -q "No space left" "$tmp/err.txt"
}
if [ "$(id -u)" = 0 ] && mkdir -p "$tmp/probe" && mount -t tmpfs -o size=64k tmpfs "$tmp/probe" 2>/dev/null; then
    umount "$tmp/probe"
    check "a real full disk (tmpfs, 68 KB free): meshfix in.glb in.glb keeps it, exit 1" tmpfs_full in.glb
    check "a real full disk (tmpfs, 68 KB free): in.gltf + in.bin in place kept" tmpfs_full in.gltf in.bin
else
    skip "a real full disk (tmpfs, 68 KB free): meshfix in.glb in.glb keeps it, exit 1: needs root and mount (the LD_PRELOAD checks above ran)"
    skip "a real full disk (tmpfs, 68 KB free): in.gltf + in.bin in place kept: needs root and mount"
fi

# ---- 3. index bytes shared by two meshes ----

# After the repair each mesh must need nothing more, read from the bytes as
# written: a write over shared bytes would leave one of them wrong.
aliased_views() { # case
    local d="$tmp/g/$1"
    $MESHFIX --json "$d/scene.gltf" "$d/out.gltf" >"$tmp/out.json" || return 1
    grep -q '"index_accessors_cloned":[1-9]' "$tmp/out.json" || { echo "no accessor cloned"; return 1; }
    $MESHFIX --inspect "$d/out.gltf" >"$tmp/out.txt" || return 1
    [ "$(grep -c 'would flip 0 of' "$tmp/out.txt")" -eq 2 ] || { cat "$tmp/out.txt"; return 1; }
    ! grep -q 'inside-out [1-9]' "$tmp/out.txt"
}
check "two index bufferViews over the same bytes: both meshes right after the repair" aliased_views alias
check "two index bufferViews overlapping by all but one triangle: both right" aliased_views alias_offset

empty_objects() {
    local d="$tmp/g/empty"
    $MESHFIX --quiet "$d/scene.gltf" "$d/out.gltf" || return 1
    ! grep -q null "$d/out.gltf" || { grep -n -B3 null "$d/out.gltf"; return 1; }
    $MESHFIX --inspect "$d/out.gltf" | grep -q 'would flip 0 of 12'
}
check "a default material, sampler and scene ({}) written back as {} (tinygltf writes null), the output loads" empty_objects

# ---- 4. JSON nested deep ----

check "a .gltf with 20,000 nested arrays: exit 1, one line, no crash" \
    one_line_error 1 "nests deeper" timeout 20 $MESHFIX --inspect "$tmp/g/deep/scene.gltf"
check "a .glb with 20,000 nested arrays in its JSON chunk: exit 1, no crash" \
    one_line_error 1 "nests deeper" timeout 20 $MESHFIX --inspect "$tmp/g/deep/scene.glb"
deep_in_batch() {
    timeout 20 $MESHFIX --inspect "$tmp/g/deep/scene.gltf" "$tmp/demo.obj" "$tmp/g/deep/scene.glb" >"$tmp/out.txt" 2>&1
    [ $? -eq 1 ] || return 1
    grep -q "^$tmp/demo.obj: inconsistent" "$tmp/out.txt" || { cat "$tmp/out.txt"; return 1; }
}
check "deep JSON in a batch: the other files are still inspected" deep_in_batch

# ---- 5. companions that are FIFOs, or only in the current directory ----

mkfifo "$tmp/g/fifo/fifo.bin" "$tmp/g/fifo_image/fifo.png"
check "a buffer URI naming a FIFO: exit 1 at once, also under --inspect (timeout 5 s)" \
    one_line_error 1 "not a regular file" timeout 5 $MESHFIX --inspect "$tmp/g/fifo/scene.gltf"
check "an image URI naming a FIFO: exit 1 at once (timeout 5 s)" \
    one_line_error 1 "not a regular file" timeout 5 $MESHFIX "$tmp/g/fifo_image/scene.gltf" "$tmp/fifo_out.gltf"
cwd_fallback() {
    (cd "$tmp/g/cwd" && one_line_error 1 "not found" $MESHFIX --inspect in/scene.gltf)
}
check "a buffer missing beside the glTF is not taken from the current directory" cwd_fallback

# ---- 6. batch outputs that collide ----

collide_files() {
    local d="$tmp/col"
    mkdir -p "$d/a" "$d/b"
    cp "$tmp/demo.obj" "$d/a/x.obj"
    cp "$tmp/demo.obj" "$d/b/x.obj"
    one_line_error 1 "both be written" $MESHFIX "$d/a/x.obj" "$d/b/x.obj" -o "$d/out" || return 1
    [ ! -e "$d/out" ] || { ls -R "$d/out"; return 1; }
    one_line_error 1 "both be written" $MESHFIX "$d/a" "$d/b" -o "$d/out" || return 1
    [ ! -e "$d/out" ] || { ls -R "$d/out"; return 1; }
    one_line_error 1 "both be written" $MESHFIX "$d/a/x.obj" "$d/a/../a/x.obj" -o "$d/out" || return 1
    mkdir -p "$d/marks"
    one_line_error 1 "both be written" $MESHFIX --inspect "$d/a/x.obj" "$d/b/x.obj" --mark "$d/marks" || return 1
    [ -z "$(ls -A "$d/marks")" ]
}
check "two inputs named x.obj into one -o directory: refused before anything is written" collide_files

output_is_input() {
    local d="$tmp/col2"
    mkdir -p "$d/marks"
    cp "$tmp/demo.obj" "$d/x.obj"
    $MESHFIX --quiet "$tmp/demo.obj" "$d/marks/x.obj.ply" || return 1
    cp "$d/marks/x.obj.ply" "$d/expected.ply"
    # x.obj's --mark file is marks/x.obj.ply, the second input
    one_line_error 1 "is also an input" $MESHFIX --inspect "$d/x.obj" "$d/marks/x.obj.ply" --mark "$d/marks" || return 1
    cmp "$d/marks/x.obj.ply" "$d/expected.ply"
}
check "an output that is another input of the batch: refused" output_is_input

collide_companions() {
    local d="$tmp/col3"
    one_line_error 1 "scene.bin" $MESHFIX -j 1 --quiet "$tmp/g/collide/a/s.gltf" "$tmp/g/collide/b/t.gltf" -o "$d" ||
        return 1
    # the file that was written is whole: its own .gltf with its own .bin
    $MESHFIX --inspect "$d/s.gltf" | grep -q 'would flip 0 of 12' || return 1
    [ ! -e "$d/t.gltf" ]
}
check "two glTF files whose buffers are both scene.bin: the second fails, the first stays whole" collide_companions

# ---- 7. ASCII STL read two ways ----

# A cube whose facet 0 is turned, a "# endloop" comment line after it, and a
# NUL byte after the last endloop: whatever is read, the facets edited must
# be the ones the library decided on (or the file is refused).
/usr/bin/python3 - "$tmp/two_ways.stl" <<'EOF'
import sys
v = [(0,0,0),(1,0,0),(1,1,0),(0,1,0),(0,0,1),(1,0,1),(1,1,1),(0,1,1)]
f = [(0,2,1),(0,3,2),(4,5,6),(4,6,7),(0,1,5),(0,5,4),(1,2,6),(1,6,5),(2,3,7),(2,7,6),(3,0,4),(3,4,7)]
f[5] = (0, 4, 5)  # turned: after the comment, so a reader one facet off edits another
out = "solid cube\n"
for i, t in enumerate(f):
    out += "facet normal 0 0 0\n outer loop\n" + "".join(" vertex %d %d %d\n" % v[k] for k in t) + " endloop\nendfacet\n"
    if i == 0:
        out += "# endloop\n"
out = out[:out.rfind("endloop") + 7] + "\0" + out[out.rfind("endloop") + 7:] + "endsolid cube\n"
open(sys.argv[1], "w").write(out)
EOF
stl_two_ways() {
    $MESHFIX "$tmp/two_ways.stl" "$tmp/two_ways_out.stl" >/dev/null 2>"$tmp/err.txt"
    local status=$?
    if [ "$status" -eq 1 ]; then
        grep -q "read two ways" "$tmp/err.txt"
        return
    fi
    [ "$status" -eq 0 ] || return 1
    $MESHFIX --inspect "$tmp/two_ways_out.stl" >"$tmp/out.txt" || return 1
    grep -q 'inconsistent 0' "$tmp/out.txt" && grep -q 'would flip 0 of' "$tmp/out.txt" || { cat "$tmp/out.txt"; return 1; }
}
check "ASCII STL with a '# endloop' comment and a NUL after the last endloop: the right facets edited" stl_two_ways
stl_long_number() {
    # a coordinate of 300 characters: both readers must see one number
    local long
    long="0.$(printf '0%.0s' $(seq 1 297))1"
    sed "0,/vertex 1 0 0/s//vertex $long 0 0/" "$tmp/two_ways.stl" | tr -d '\000' >"$tmp/long.stl"
    $MESHFIX "$tmp/long.stl" "$tmp/long_out.stl" >/dev/null 2>&1
    local status=$?
    [ "$status" -eq 1 ] && return 0
    [ "$status" -eq 0 ] && $MESHFIX --inspect "$tmp/long_out.stl" | grep -q 'inconsistent 0'
}
check "ASCII STL with a 300-character coordinate: read one way, or refused" stl_long_number

# ---- 8. OBJ line continuations ----

printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 \\\n 4\nf 1 4 \\\r\n3\nf 2 \\\n4 \\\n3\n' >"$tmp/cont.obj"
obj_continuations() {
    $MESHFIX "$tmp/cont.obj" "$tmp/cont_out.obj" | tail -n 1 | grep -q "fixed 1 triangle" || return 1
    # only the flipped face changed, its continuation kept
    [ "$(tr '\n' '|' <"$tmp/cont_out.obj")" = "$(tr '\n' '|' <"$tmp/cont.obj" | sed 's/f 2 \\|4 \\|3/f 2 \\|3 \\|4/')" ] || {
        od -c "$tmp/cont_out.obj" | tail -4; return 1; }
    $MESHFIX "$tmp/cont_out.obj" "$tmp/cont_again.obj" | tail -n 1 | grep -q "clean" || return 1
    cmp "$tmp/cont_out.obj" "$tmp/cont_again.obj"
}
check "OBJ '\\' line continuations: read, and kept byte for byte" obj_continuations

# ---- 9. the library's refusals reach the user ----

check "--policy normals on a file without normals: exit 2, the library's message" \
    one_line_error 2 "needs options.evidence" $MESHFIX --policy normals "$tmp/demo.obj" "$tmp/normals_out.obj"

# ---- 10. paths that are not UTF-8 in --json ----

json_non_utf8() {
    local name
    name=$(printf '%s/caf\351_\377.obj' "$tmp")
    cp "$tmp/demo.obj" "$name"
    $MESHFIX --json --inspect "$name" >"$tmp/report.json" || return 1
    /usr/bin/python3 - "$tmp/report.json" "$name" <<'EOF'
import json, sys, urllib.parse
raw = open(sys.argv[1], "rb").read()
report = json.loads(raw.decode("utf-8"))  # strict: raises on a byte that is not UTF-8
entry = report["files"][0]
assert "\ufffd" in entry["input"], entry["input"]
assert urllib.parse.unquote_to_bytes(entry["input_bytes"]) == sys.argv[2].encode("utf-8", "surrogateescape")
EOF
}
check "--json with a path that is not UTF-8: valid JSON, the raw bytes percent-escaped" json_non_utf8

# ---- 11. interrupted runs ----

interrupted() { # signal, expected status
    local d="$tmp/int_$1" pid status
    mkdir -p "$d"
    cp "$tmp/g/big/in.glb" "$d/in.glb"
    FAILING_IO_FSYNC=sleep LD_PRELOAD="$tmp/failing_io.so" $MESHFIX "$d/in.glb" "$d/in.glb" >/dev/null 2>"$tmp/err.txt" &
    pid=$!
    for _ in $(seq 1 50); do
        [ -n "$(find "$d" -name '*.meshfix-*.tmp')" ] && break
        sleep 0.1
    done
    [ -n "$(find "$d" -name '*.meshfix-*.tmp')" ] || { echo "no temporary appeared"; kill $pid; return 1; }
    kill -"$1" $pid
    wait $pid
    status=$?
    [ "$status" -eq "$2" ] || { echo "exit status $status, expected $2"; return 1; }
    cmp "$d/in.glb" "$tmp/g/big/in.glb" || return 1
    no_temporaries "$d"
}
check "SIGINT while the output is being written: status 130, input kept, temporaries removed" interrupted INT 130
check "SIGTERM while the output is being written: status 143, input kept, temporaries removed" interrupted TERM 143

walk_skips_temporaries() {
    local d="$tmp/walk"
    mkdir -p "$d/in/.x.obj.meshfix-1-0.tmp" "$d/in/sub"
    head -c 1000 "$tmp/demo.obj" >"$d/in/.x.obj.meshfix-1-0.tmp/x.obj"
    cp "$tmp/demo.obj" "$d/in/sub/y.obj"
    $MESHFIX --quiet "$d/in" -o "$d/out" || return 1
    [ "$(find "$d/out" -type f | wc -l)" -eq 1 ] && [ -f "$d/out/sub/y.obj" ] || { find "$d/out"; return 1; }
}
check "a directory walk skips a temporary left by an earlier run (its name starts with a dot)" walk_skips_temporaries

# ---- 12. relative output paths make no stray directory ----

no_stray_directory() {
    local d="$tmp/stray"
    mkdir -p "$d/out/x/y"
    (cd "$d" && $MESHFIX --quiet "$tmp/demo.obj" out/x/y/o.obj) || return 1
    [ -f "$d/out/x/y/o.obj" ] || return 1
    [ "$(ls -A "$d")" = out ] || { ls -A "$d"; return 1; }
    (cd "$d" && $MESHFIX --quiet "$tmp/demo.obj" "$tmp/cont.obj" -o new/a/b) || return 1
    [ "$(ls -A "$d")" = "$(printf 'new\nout')" ] || { ls -A "$d"; return 1; }
}
check "meshfix in.obj out/x/y/o.obj makes no directory 'o' (nor any other) in the current one" no_stray_directory

# ---- 13. round 4: what the writer names, checks and commits ----

R4=$tmp/g/r4
# the files of a case directory, copied fresh into $tmp/r4/NAME
fresh() { # case
    rm -rf "$tmp/r4/$1" && mkdir -p "$tmp/r4" && cp -r "$R4/$1" "$tmp/r4/$1" && mkdir -p "$tmp/r4/$1/out" "$tmp/r4/$1/back"
}
# files of the case, byte for byte as generated
inputs_kept() { # case file...
    local c=$1 f
    shift
    for f in "$@"; do cmp "$R4/$c/$f" "$tmp/r4/$c/$f" || return 1; done
}
repaired() { # file: a second look finds nothing to flip
    $MESHFIX --inspect "$1" >"$tmp/again.txt" 2>&1 && grep -q 'clean: nothing to flip' "$tmp/again.txt" ||
        { cat "$tmp/again.txt"; return 1; }
}

new_name_beside() {
    fresh names
    $MESHFIX --quiet "$tmp/r4/names/in.gltf" "$tmp/r4/names/out.gltf" || return 1
    inputs_kept names in.gltf in.bin out.bin && repaired "$tmp/r4/names/out.gltf" && no_temporaries "$tmp/r4/names"
}
check "in.gltf -> out.gltf beside it, in.gltf's buffers in.bin and out.bin: every input kept, out.gltf repaired" new_name_beside
glb_beside() {
    fresh glb
    $MESHFIX --quiet "$tmp/r4/glb/m.gltf" "$tmp/r4/glb/m.glb" || return 1
    inputs_kept glb m.gltf m1.bin m.bin && repaired "$tmp/r4/glb/m.glb" &&
        $MESHFIX --inspect "$tmp/r4/glb/m.gltf" | grep -q 'would flip 1 triangle'
}
check "m.gltf -> m.glb beside it, buffers m1.bin and m.bin: both kept, m.gltf still loads as it was" glb_beside

mark_is_input() {
    local d="$tmp/r4/mark"
    rm -rf "$d" && mkdir -p "$d"
    $MESHFIX --quiet "$tmp/demo.obj" "$d/in.ply" && cp "$d/in.ply" "$d/kept.ply" || return 1
    one_line_error 1 "is that input" $MESHFIX --inspect --mark "$d/in.ply" "$d/in.ply" || return 1
    cmp "$d/in.ply" "$d/kept.ply" || return 1
    one_line_error 1 "both the output and the --mark" $MESHFIX "$d/in.ply" "$d/out.ply" --mark "$d/out.ply" || return 1
    [ ! -e "$d/out.ply" ] || { echo "out.ply written"; return 1; }
    ln "$d/in.ply" "$d/hard.ply"
    one_line_error 1 "is that input" $MESHFIX --inspect --mark "$d/hard.ply" "$d/in.ply" || return 1
    cmp "$d/in.ply" "$d/kept.ply"
}
check "--mark naming the input (also by a hard link) or the output: refused before anything is written" mark_is_input
mark_is_texture() {
    fresh texture
    local d="$tmp/r4/texture"
    mkdir -p "$d/out"
    one_line_error 1 "tex.png" $MESHFIX "$d/scene.gltf" "$d/out/scene.gltf" --mark "$d/tex.png" || return 1
    inputs_kept texture scene.gltf scene.bin tex.png || return 1
    [ -z "$(ls -A "$d/out")" ] || { ls -A "$d/out"; return 1; }
    one_line_error 1 "tex.png" $MESHFIX --inspect --mark "$d/tex.png" "$d/scene.gltf" || return 1
    inputs_kept texture tex.png && no_temporaries "$d"
}
if $MESHFIX --version | grep -q 'PNG marks'; then
    check "--mark tex.png, the glTF's own texture: refused, the texture kept, nothing written" mark_is_texture
else
    skip "--mark tex.png, the glTF's own texture: this meshfix has no PNG support"
fi

walk_loops() {
    local d="$tmp/r4/walk"
    rm -rf "$d" && mkdir -p "$d/in/sub"
    cp "$tmp/demo.obj" "$d/in/sub/a.obj"
    ln -s . "$d/in/loop" && ln -s .. "$d/in/sub/up" && ln -s sub "$d/in/again" && ln -s / "$d/in/root"
    timeout 20 $MESHFIX --quiet "$d/in" -o "$d/out" 2>"$tmp/err.txt" || { cat "$tmp/err.txt"; return 1; }
    [ "$(find "$d/out" -type f | wc -l)" -eq 1 ] || { find "$d/out" | head; return 1; }
    grep -q "root' is a symbolic link out of" "$tmp/err.txt"
}
check "a batch walk over links back up, to a sibling and to /: each directory once, nothing outside" walk_loops

document_equal() {
    fresh document
    local d="$tmp/r4/document"
    $MESHFIX --quiet "$d/scene.gltf" "$d/out/scene.gltf" || return 1
    repaired "$d/out/scene.gltf" || return 1
    # equal as a document but for the new indices (accessors, bufferViews,
    # the buffer's length); numbers compared as written
    /usr/bin/python3 -c '
import json, sys
num = lambda s: ("number", s)
a, b = [json.load(open(p), parse_int=num, parse_float=num, parse_constant=num) for p in sys.argv[1:]]
na, nv = len(a["accessors"]), len(a["bufferViews"])
assert len(b["accessors"]) == na + 2 and b["accessors"][:na] == a["accessors"], "accessors"
assert len(b["bufferViews"]) == nv + 2 and b["bufferViews"][:nv] == a["bufferViews"], "bufferViews"
for doc in (a, b):
    for m in doc["meshes"]:
        for p in m["primitives"]:
            p.pop("indices")
    del doc["buffers"][0]["byteLength"], doc["accessors"], doc["bufferViews"]
for k in set(a) | set(b):
    if a.get(k) != b.get(k):
        print("differs:", k, a.get(k), b.get(k))
        sys.exit(1)' "$d/scene.gltf" "$d/out/scene.gltf"
}
check "a changed glTF is its input as a document (zfar absent, nulls, [] {}, 2^53+1, -0, 1E2, names, unknown members) but the new indices" document_equal
document_glb() {
    fresh document
    local d="$tmp/r4/document"
    $MESHFIX --quiet "$d/scene.gltf" "$d/out/scene.glb" && $MESHFIX --quiet "$d/out/scene.glb" "$d/back/scene.gltf" || return 1
    repaired "$d/back/scene.gltf" || return 1
    grep -q '"big": 9007199254740993, "minus_zero": -0, "e": 1E2' "$d/back/scene.gltf" &&
        grep -q '"yfov": 0.8' "$d/back/scene.gltf" && ! grep -q zfar "$d/back/scene.gltf" &&
        grep -q '"name": "the sampler"' "$d/back/scene.gltf" && grep -q '"minVersion": "2.0"' "$d/back/scene.gltf"
}
check "the same document through .glb and back: its text kept (2^53+1, zfar absent, minVersion, the sampler's name)" document_glb

shared_normals() {
    fresh normals
    local d="$tmp/r4/normals"
    $MESHFIX --quiet --fix-normals "$d/scene.gltf" "$d/out/scene.gltf" || return 1
    # mesh B's normals are right: the bytes it shares with A stay as they are
    cmp "$d/scene.bin" "$d/out/scene.bin" || return 1
    $MESHFIX --json --inspect "$d/out/scene.gltf" >"$tmp/again.json" || return 1
    /usr/bin/python3 -c 'import json, sys; m = json.load(open(sys.argv[1]))["files"][0]["meshes"]
sys.exit(0 if m[1]["normals"]["disagree"] == 0 else 1)' "$tmp/again.json"
}
check "--fix-normals on mesh A whose NORMAL bytes mesh B reads too: B's normals stay right" shared_normals

same_file_buffers() {
    fresh same_file
    local d="$tmp/r4/same_file"
    $MESHFIX --quiet "$d/scene.gltf" "$d/scene.gltf" || return 1
    repaired "$d/scene.gltf" || return 1
    fresh same_file
    $MESHFIX --quiet "$d/scene.gltf" "$d/out/scene.gltf" && repaired "$d/out/scene.gltf"
}
check "two buffers naming one file: repaired on disk, in place and into another directory" same_file_buffers

upper_glb() {
    local d="$tmp/r4/upper" ext
    rm -rf "$d" && mkdir -p "$d"
    for ext in Glb gLB GLB; do
        $MESHFIX --quiet "$tmp/g/big/in.gltf" "$d/out.$ext" || return 1
        [ "$(head -c 4 "$d/out.$ext")" = glTF ] || { echo ".$ext is not a GLB"; head -c 40 "$d/out.$ext"; return 1; }
    done
}
check "an output named .Glb, .gLB or .GLB is a GLB" upper_glb

report_to_full() {
    $MESHFIX --json --inspect "$tmp/demo.obj" >/dev/full 2>"$tmp/err.txt"
    [ $? -eq 1 ] && grep -q "stdout" "$tmp/err.txt" || { echo "exit status not 1"; cat "$tmp/err.txt"; return 1; }
    $MESHFIX --inspect "$tmp/demo.obj" >/dev/full 2>/dev/null
    [ $? -eq 1 ]
}
if [ -w /dev/full ]; then
    check "a report that cannot be written to stdout (/dev/full): exit 1" report_to_full
else
    skip "a report that cannot be written to stdout: no /dev/full here"
fi

long_names() {
    local d="$tmp/r4/long" name
    rm -rf "$d" && mkdir -p "$d"
    name=$(printf 'n%.0s' $(seq 1 251)).obj # 255 bytes, the most a name may have
    cp "$tmp/demo.obj" "$d/$name"
    $MESHFIX --quiet "$d/$name" "$d/$name" || return 1
    repaired "$d/$name" && no_temporaries "$d"
}
check "a file whose name is 255 bytes long is repaired in place" long_names

skin_matrices() {
    fresh skin
    local d="$tmp/r4/skin"
    $MESHFIX --quiet "$d/scene.gltf" "$d/out/scene.gltf" || return 1
    repaired "$d/out/scene.gltf" || return 1
    # the inverse-bind matrix is bytes 96..160 of the buffer
    cmp <(head -c 160 "$d/scene.bin") <(head -c 160 "$d/out/scene.bin")
}
check "index bytes under a skin's MAT4 inverse-bind matrices: cloned, the matrices kept" skin_matrices

plus_uri() {
    fresh plus
    $MESHFIX --quiet "$tmp/r4/plus/scene.gltf" "$tmp/r4/plus/out/scene.gltf" || return 1
    repaired "$tmp/r4/plus/out/scene.gltf" && [ -f "$tmp/r4/plus/out/a+b.bin" ]
}
check "a buffer URI with '+' (a+b.bin) names a+b.bin, not 'a b.bin'" plus_uri

missing_texture() {
    fresh missing
    local d="$tmp/r4/missing"
    $MESHFIX --quiet "$d/scene.gltf" "$d/scene.gltf" || return 1
    repaired "$d/scene.gltf" || return 1
    fresh missing
    $MESHFIX --quiet "$d/scene.gltf" "$d/fixed.gltf" && repaired "$d/fixed.gltf" || return 1
    # elsewhere the texture would have to be copied: refused, nothing written
    one_line_error 1 "gone.png" $MESHFIX "$d/scene.gltf" "$d/out/scene.gltf" || return 1
    [ -z "$(ls -A "$d/out")" ] || { ls -R "$d/out"; return 1; }
}
check "a missing texture: the repair in place (or beside it) goes on; elsewhere refused, nothing written" missing_texture

obj_materials() {
    local d="$tmp/r4/mtl"
    rm -rf "$d" && mkdir -p "$d/in/sub"
    { echo "mtllib sub/m.mtl"; cat "$tmp/demo.obj"; } >"$d/in/a.obj"
    printf 'newmtl red\nKd 1 0 0\nmap_Kd -s 1 1 1 ../tex/red.png\n' >"$d/in/sub/m.mtl"
    mkdir -p "$d/in/tex" && echo png >"$d/in/tex/red.png"
    $MESHFIX --quiet "$d/in" -o "$d/out" || return 1
    cmp "$d/in/sub/m.mtl" "$d/out/sub/m.mtl" && cmp "$d/in/tex/red.png" "$d/out/tex/red.png" && repaired "$d/out/a.obj"
}
check "batch -o: an OBJ's mtllib, and the map it names, go beside its output" obj_materials

# a later move fails: every file the set had replaced is put back
rename_fails() { # the move that fails (a path's end), meshfix's arguments...
    local d="$tmp/r4/rename" f fail=$1
    shift
    rm -rf "$d" "$d.before" && mkdir -p "$d"
    cp "$tmp/g/big/in.gltf" "$tmp/g/big/in.bin" "$d/"
    $MESHFIX --quiet "$tmp/demo.obj" "$d/out.obj" && $MESHFIX --quiet "$tmp/demo.obj" "$d/out.ply" || return 1
    cp -r "$d" "$d.before"
    FAILING_IO_RENAME="$fail" LD_PRELOAD="$tmp/failing_io.so" $MESHFIX "$@" >/dev/null 2>"$tmp/err.txt"
    [ $? -eq 1 ] || { echo "exit status not 1"; cat "$tmp/err.txt"; return 1; }
    for f in in.gltf in.bin out.obj out.ply; do cmp "$d/$f" "$d.before/$f" || return 1; done
    [ "$(ls "$d" | wc -l)" -eq 4 ] || { ls "$d"; return 1; }
    no_temporaries "$d"
}
check "in place, the .gltf's move fails after the .bin's: in.bin put back" \
    rename_fails "/in.gltf" "$tmp/r4/rename/in.gltf" "$tmp/r4/rename/in.gltf"
check "out.obj replaced, then the --mark file's move fails: out.obj put back" \
    rename_fails "/out.ply" --policy seed "$tmp/demo.obj" "$tmp/r4/rename/out.obj" --mark "$tmp/r4/rename/out.ply"

bom_document() { # a byte-order mark, as nlohmann json (tinygltf) reads it
    fresh plus
    local d="$tmp/r4/plus"
    { printf '\357\273\277'; cat "$R4/plus/scene.gltf"; } >"$d/bom.gltf"
    $MESHFIX --quiet "$d/bom.gltf" "$d/out/bom.gltf" && $MESHFIX --quiet "$d/bom.gltf" "$d/out/bom.glb" || return 1
    repaired "$d/out/bom.gltf" && repaired "$d/out/bom.glb" && [ "$(head -c 21 "$d/out/bom.glb" | tail -c 1)" = "{" ]
}
check "a .gltf that starts with a byte-order mark is repaired (its GLB's JSON without one)" bom_document

# round 3: a companion that is a symbolic link out of the glTF's directory
link_out() { # case, how (relative, absolute, subdirectory)
    local base="$tmp/r4/links/$1" target
    rm -rf "$base" && mkdir -p "$tmp/r4/links" && cp -r "$R4/links/$1" "$base"
    case "$1" in image*) target=tex.png ;; *) target=scene.bin ;; esac
    case "$2" in
        relative) ln -s "../outside/$target" "$base/in/$target" ;;
        absolute) ln -s "$base/outside/$target" "$base/in/$target" ;;
        subdirectory) ln -s ../outside "$base/in/sub" ;;
    esac
    mkdir -p "$base/out"
    touch "$base/before"
    one_line_error 1 "symbolic link out" $MESHFIX "$base/in/scene.gltf" "$base/out/scene.gltf" || return 1
    one_line_error 1 "symbolic link out" $MESHFIX --quiet "$base/in/scene.gltf" -o "$base/batch" || return 1
    [ -z "$(ls -A "$base/out")" ] && [ -z "$(find "$base" -newer "$base/before" -name "$target")" ]
}
for how in relative absolute subdirectory; do
    check "an image that is a symbolic link out of the glTF's directory ($how): refused, not copied" link_out image_$how $how
    check "a buffer that is a symbolic link out of the glTF's directory ($how): refused, not copied" link_out buffer_$how $how
done
linked_input_directory() { # a directory given as a link is walked as itself
    local d="$tmp/r4/linked"
    rm -rf "$d" && mkdir -p "$d/real"
    cp "$tmp/demo.obj" "$d/real/a.obj" && ln -s real "$d/link"
    $MESHFIX --quiet "$d/link" -o "$d/out" && [ -f "$d/out/a.obj" ]
}
check "a directory named through a symbolic link is walked" linked_input_directory

# ---- text formats: byte-order marks, line ends, comments (formats-work) ----
# tests/cli/text_variants.py: a cube with one triangle turned in every text
# format, with every kind of line end (LF, CRLF, lone CR, mixed), with and
# without a UTF-8 byte-order mark, a comment line right after the first
# face. A correct repair writes NAME.want.EXT: the input's bytes, its mark
# and line ends kept, with only the turned triangle's corners swapped.

/usr/bin/python3 tests/cli/text_variants.py "$tmp/text" || { echo "FAIL text_variants.py"; failed=$((failed + 1)); }
text_variant() { # NAME.in.EXT: repaired to exactly NAME.want.EXT, one triangle fixed
    local in=$1 out want
    out=${in/.in./.out.} want=${in/.in./.want.}
    $MESHFIX "$in" "$out" >"$tmp/text_report.txt" || { cat "$tmp/text_report.txt"; return 1; }
    tail -n 1 "$tmp/text_report.txt" | grep -q "fixed 1 triangle" || { cat "$tmp/text_report.txt"; return 1; }
    cmp "$out" "$want"
}
for in in "$tmp"/text/*.in.*; do
    case $in in *_bom.*) what="a UTF-8 byte-order mark and " ;; *) what="" ;; esac
    name=$(basename "$in")
    check "${name%%.*}: ${what}these line ends and a comment: the turned triangle fixed, every other byte kept" \
        text_variant "$in"
done

# The audit's case: a byte-order mark hid the first v, every index named
# the next vertex, and this correct tetrahedron (its fifth vertex unused)
# came out inside out, exit 0.
printf '\357\273\277v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 0 -1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' >"$tmp/text/tetra_bom.obj"
obj_bom_kept() {
    $MESHFIX "$tmp/text/tetra_bom.obj" "$tmp/text/tetra_out.obj" >"$tmp/text_report.txt" || return 1
    tail -n 1 "$tmp/text_report.txt" | grep -q "^clean" || { cat "$tmp/text_report.txt"; return 1; }
    cmp "$tmp/text/tetra_bom.obj" "$tmp/text/tetra_out.obj"
}
check "OBJ starting with a byte-order mark: its first v read, a correct tetrahedron left as it is" obj_bom_kept

# An OBJ with normals written in another format keeps the file's 8
# vertices, shared by its faces, not one per (v, vn) pair (24: six loose
# quads), and the --mark mesh too.
obj_converted() {
    local d="$tmp/text/conv"
    mkdir -p "$d"
    $MESHFIX --quiet "$tmp/text/cube_vn.obj" "$d/cube.off" --mark "$d/mark.ply" || return 1
    $MESHFIX --quiet "$tmp/text/cube_vn.obj" "$d/cube.ply" || return 1
    [ "$(sed -n 2p "$d/cube.off")" = "8 12 0" ] || { head -n 2 "$d/cube.off"; return 1; }
    # the OFF's vertices are the OBJ's v lines, in order
    [ "$(sed -n 3,10p "$d/cube.off")" = "$(sed -n 's/^v //p' "$tmp/text/cube_vn.obj")" ] || return 1
    for ply in "$d/cube.ply" "$d/mark.ply"; do
        grep -aq '^element vertex 8$' "$ply" || { grep -a '^element' "$ply"; return 1; }
    done
    $MESHFIX --inspect "$d/cube.off" | grep -q 'boundary 0, manifold 18'
}
check "OBJ with a normal per face -> OFF, PLY and --mark PLY: the file's 8 vertices, not 24" obj_converted

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
