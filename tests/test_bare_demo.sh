#!/usr/bin/env bash
# `make demo` on a bare machine: a copy of the repository (without build/)
# built with nothing but make, a C and a C++ compiler. The build runs with
# an empty environment (no CPATH and the like) and a PATH of make, the
# compilers, binutils and the shell tools the Makefile's recipes use: no
# node, npm, python, cmake, pkg-config or emcc. CC and CXX are given
# --sysroot, a tree of /usr/include without tinygltf, nlohmann json,
# OpenMesh, Embree, libpng and Python's headers; the compilers' own headers
# (GCC's, libstdc++'s) lie outside it and are found as always.
# Checks that the build says once that glTF is off and what to install,
# that the demo prints its repair lines, and that the tool it built refuses
# a .glb and a .gltf with one line and exit status 1 (and links no
# tinygltf). Run from the repository root: bash tests/test_bare_demo.sh
# (CC, CXX and MAKE as for make test). Exits 1 with what went wrong.
set -u
cd "$(dirname "$0")/.." || exit 1
CC=${CC:-cc}
CXX=${CXX:-c++}
MAKE=${MAKE:-make}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/meshfix_bare.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
fail() { echo "$*"; exit 1; }
start=$(date +%s)

# the repository as it is in the work tree
src=$tmp/src
mkdir -p "$src"
tar --exclude=./build --exclude=./.git --exclude=node_modules --exclude=./js/dist --exclude=./js/build \
    -cf - . | tar -C "$src" -xf - || fail "cannot copy the repository"

# the headers: every entry of /usr/include (and of its multiarch
# directories, x86_64-linux-gnu) but the hidden ones, as symbolic links
sysroot=$tmp/sysroot
hidden() {
    case $1 in
    tiny_gltf.h | nlohmann | OpenMesh | embree* | png.h | pngconf.h | pnglibconf.h | libpng* | python*) return 0 ;;
    esac
    return 1
}
link_headers() { # from to
    local entry name
    mkdir -p "$2" || return 1
    for entry in "$1"/*; do
        name=${entry##*/}
        hidden "$name" && continue
        case $name in
        *-linux-*) [ -d "$entry" ] && [ ! -L "$entry" ] && { link_headers "$entry" "$2/$name" || return 1; continue; } ;;
        esac
        ln -s "$entry" "$2/$name" || return 1
    done
}
link_headers /usr/include "$sysroot/usr/include" || fail "cannot make the sysroot"
# the libraries and start files where the linker looks for them
for d in lib lib32 lib64 libx32 usr/lib usr/lib32 usr/lib64 usr/libx32; do
    [ -e "/$d" ] && ln -s "/$d" "$sysroot/$d"
done

# PATH: make, the compilers, what they run, what the recipes run
bin=$tmp/bin
mkdir -p "$bin"
for tool in "${MAKE%% *}" "${CC%% *}" "${CXX%% *}" cc c++ gcc g++ as ld ld.bfd ld.gold sh echo printf mkdir sed cat rm; do
    path=$(type -P "$tool") && ln -sf "$path" "$bin/${tool##*/}"
done
for tool in node npm python3 python cmake pkg-config emcc; do
    [ ! -e "$bin/$tool" ] || fail "$tool is on the bare PATH"
done

# the header probe the Makefile runs sees the same as the build
if printf '#include <tiny_gltf.h>\n' | env -i PATH="$bin" $CXX --sysroot="$sysroot" -E -x c++ - >/dev/null 2>&1; then
    fail "tiny_gltf.h is still found through the sysroot"
fi

(cd "$src" && env -i PATH="$bin" HOME="$tmp" LC_ALL=C "${MAKE%% *}" demo \
    CC="$CC --sysroot=$sysroot" CXX="$CXX --sysroot=$sysroot") >"$tmp/demo.txt" 2>&1
status=$?
echo "make demo on the bare PATH and sysroot: exit status $status, $(($(date +%s) - start)) s"
[ "$status" -eq 0 ] || { tail -n 20 "$tmp/demo.txt"; fail "make demo failed"; }

# glTF off, said once, with the packages to install
said=$(grep -c 'without glTF support' "$tmp/demo.txt")
[ "$said" -eq 1 ] || { cat "$tmp/demo.txt"; fail "the build said $said times that glTF is off, not once"; }
grep 'without glTF support' "$tmp/demo.txt"
grep 'without glTF support' "$tmp/demo.txt" | grep -q 'apt-get install libtinygltf-dev nlohmann-json3-dev' ||
    fail "the build does not say which packages bring glTF"
grep -q -- '-DMESHFIX_TOOL_NO_GLTF' "$tmp/demo.txt" || fail "the tool was not built with -DMESHFIX_TOOL_NO_GLTF"
! grep -q -- '-ltinygltf' "$tmp/demo.txt" || fail "the tool was linked with -ltinygltf"

# the demo's repair lines
for line in '^repair (policy seed): flipped [0-9]* of 8064 triangles' \
    '^fixed [0-9]* triangles in 1 patch, and left 2 of its 2 closed shells inside out: consistent now, and still wrong' \
    '^repair (policy auto): flipped 6589 of 8064 triangles' \
    '^fixed 6589 triangles in 2 patches' \
    '^  patches   2 (closed 2, inside-out 0)' \
    '^wrote build/demo_fixed.obj and build/demo_marked.ply'; do
    grep -q "$line" "$tmp/demo.txt" || { cat "$tmp/demo.txt"; fail "the demo did not print: $line"; }
done
grep -E '^(repair|fixed)' "$tmp/demo.txt"

# the tool refuses glTF with one line and exit status 1
M=$src/build/meshfix
printf 'glTF\002\000\000\000\014\000\000\000' >"$tmp/in.glb"
printf '{"asset":{"version":"2.0"}}' >"$tmp/in.gltf"
refuses() { # command...
    "$@" >"$tmp/out.txt" 2>"$tmp/err.txt"
    local st=$?
    cat "$tmp/err.txt"
    [ "$st" -eq 1 ] || fail "$*: exit status $st, not 1"
    [ "$(wc -l <"$tmp/err.txt")" -eq 1 ] || fail "$*: not one line on stderr"
    grep -q 'built without glTF support' "$tmp/err.txt" || fail "$*: not 'built without glTF support'"
}
refuses "$M" "$tmp/in.glb" "$tmp/out.glb"
[ ! -e "$tmp/out.glb" ] || fail "a refused .glb wrote its output"
refuses "$M" --inspect "$tmp/in.gltf"
"$M" --version | grep -q 'built without glTF support' || fail "--version does not say glTF is off"
if command -v ldd >/dev/null 2>&1 && ldd "$M" | grep -q tinygltf; then
    fail "the tool links tinygltf"
fi
"$M" --quiet "$src/build/demo_fixed.obj" "$tmp/again.stl" || fail "the bare tool cannot write STL"
echo "the bare build: demo repaired, glTF refused with one line"
