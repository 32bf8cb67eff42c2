#!/usr/bin/env bash
# Runs every suite and check of `make test`, then prints one closing line
# "N passed, N failed, N skipped" over all of them. Called by the Makefile
# with the binaries already built (after tests/install_deps.sh); CC and CXX
# name the compilers for the build checks. Every check that could not run
# here prints a "SKIP name: why" line, its own or a suite's, and is counted
# as skipped; the SKIP lines are said again before the closing line.
set -u
cd "$(dirname "$0")/.."
CC=${CC:-cc}
CXX=${CXX:-c++}
STRICT="-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion -Wcast-qual -Wdouble-promotion -Werror"
out=build/compile
mkdir -p "$out"
passed=0
failed=0
skipped=0
skips=()

check_log="$out/last.log"
. tests/check.sh
skip() { # "name: why": a check that cannot run here
    echo "SKIP $1"
    skipped=$((skipped + 1))
    skips+=("$1")
}
count_skips() { # log: the SKIP lines a suite printed
    local line
    while IFS= read -r line; do
        skipped=$((skipped + 1))
        skips+=("${line#SKIP }")
    done < <(grep '^SKIP ' "$1")
}

suite() { # name, command...: adds the command's own "N passed, N failed" line
    local name=$1
    local log
    log="$out/$(echo "$name" | tr -c 'A-Za-z0-9' _).log"
    shift
    echo "== $name"
    "$@" 2>&1 | tee "$log" | grep -v '^ok ' || true
    local status=${PIPESTATUS[0]}
    count_skips "$log"
    local line
    line=$(grep -E '^[0-9]+ passed, [0-9]+ failed$' "$log" | tail -n 1)
    if [ -z "$line" ]; then
        echo "FAIL $name: no closing line (exit status $status)"
        failed=$((failed + 1))
        return
    fi
    passed=$((passed + $(echo "$line" | cut -d' ' -f1)))
    failed=$((failed + $(echo "$line" | cut -d' ' -f3)))
    [ "$status" -eq 0 ] || [ "$(echo "$line" | cut -d' ' -f3)" -ne 0 ] || { echo "FAIL $name: exit status $status"; failed=$((failed + 1)); }
}

echo "== builds: header as C89, C99, C++98, C++17; static and linkage"
check "C89 -pedantic, strict warnings"   sh -c "$CC -std=c89 -pedantic $STRICT -Wstrict-prototypes -Wmissing-prototypes tests/compile/c89.c -o $out/c89 -lm && $out/c89"
check "C99 (clang if present) strict"    sh -c "$(command -v clang || echo $CC) -std=c99 $STRICT -Wstrict-prototypes -Wmissing-prototypes tests/compile/c89.c -o $out/c99 -lm && $out/c99"
CXXSTRICT="$STRICT -Wno-missing-field-initializers"
check "C++98 strict"                     sh -c "$CXX -std=c++98 $CXXSTRICT tests/compile/cpp.cpp -o $out/cpp98 && $out/cpp98"
check "C++11 strict"                     sh -c "$CXX -std=c++11 $CXXSTRICT tests/compile/cpp.cpp -o $out/cpp11 && $out/cpp11"
check "C++17 strict"                     sh -c "$CXX -std=c++17 $CXXSTRICT tests/compile/cpp.cpp -o $out/cpp17 && $out/cpp17"
if command -v clang++ >/dev/null 2>&1; then
    check "C++11 strict, clang++"        sh -c "clang++ -std=c++11 $CXXSTRICT tests/compile/cpp.cpp -o $out/cpp11clang && $out/cpp11clang"
else
    skip "C++11 strict, clang++: clang++ is not installed (apt-get install clang)"
fi
check "double include"                   sh -c "$CC -std=c99 $STRICT tests/compile/double_include.c -o $out/double -lm && $out/double"
check "MESHFIX_STATIC in two units"      sh -c "$CC -std=c99 $STRICT tests/compile/static_a.c tests/compile/static_b.c -o $out/static -lm && $out/static"
check "C implementation, C++ caller"     sh -c "$CC -std=c99 $STRICT -c tests/compile/linkage_impl.c -o $out/impl.o && $CXX $STRICT -c tests/compile/linkage_use.cpp -o $out/use.o && $CXX $out/impl.o $out/use.o -o $out/linkage -lm && $out/linkage"

# the C suites (Makefile SUITES), each also built with -O3 -ffast-math, -m32 and under valgrind
SUITES="test_meshfix test_sdf test_visibility test_hostile test_trust test_api"

suite "unit, property and real-model tests" build/test_meshfix
suite "the same under AddressSanitizer + UndefinedBehaviorSanitizer" build/test_meshfix_asan
suite "SDF policy on the six shapes" build/test_sdf
suite "the same under AddressSanitizer + UndefinedBehaviorSanitizer" build/test_sdf_asan
suite "visibility, nesting, weld, rays" build/test_visibility
suite "the same under AddressSanitizer + UndefinedBehaviorSanitizer" build/test_visibility_asan
suite "hostile input, allocation failure, adversarial sizes" build/test_hostile
MESHFIX_ADVERSARIAL_N=20000 suite "the same under AddressSanitizer + UndefinedBehaviorSanitizer" build/test_hostile_asan
suite "trust: correct meshes unchanged, open parts, assemblies and cut cavities right" build/test_trust
suite "the same under AddressSanitizer + UndefinedBehaviorSanitizer" build/test_trust_asan
suite "API 0.2: engine vertex buffers, index and position formats, check, verdict" build/test_api
suite "the same under AddressSanitizer + UndefinedBehaviorSanitizer" build/test_api_asan
suite "the generated scenes are what they claim" sh -c "$CC -std=c99 -O2 -I. -o $out/scenes_check tests/eval/scenes_check.c -lm && $out/scenes_check"
for t in $SUITES; do
    suite "$t built with -O3 -ffast-math (NaN tests on bit patterns)" build/${t}_fast
done

# 32-bit: size_t of 4 bytes, x87 floating point
if echo 'int main(void){return 0;}' | $CC -m32 -x c - -o "$out/m32probe" >/dev/null 2>&1; then
    for t in $SUITES; do
        if $MAKE -s build/${t}_m32 >"$out/m32build.log" 2>&1; then
            suite "$t built with -m32" build/${t}_m32
        else
            echo "FAIL $t: the -m32 build failed"; sed 's/^/    /' "$out/m32build.log" | head -20
            failed=$((failed + 1))
        fi
    done
    m32=1
else
    for t in $SUITES; do
        skip "$t built with -m32: no 32-bit toolchain here (apt-get install gcc-multilib)"
    done
    m32=0
fi

echo "== the same outputs from every build"
outputs() { # name, compiler and flags...: builds tests/outputs.c, prints its lines for the reference input
    local name=$1
    shift
    "$@" -std=c99 -w -Itests tests/outputs.c -o "$out/outputs_$name" -lm &&
        "$out/outputs_$name" "$out/outputs_input.bin" >"$out/outputs_$name.txt"
}
same_outputs() { # name, compiler and flags...: as the -O0 reference
    outputs "$@" && cmp "$out/outputs_O0.txt" "$out/outputs_$1.txt"
}
check "outputs: $CC -O0 (the reference, and the input meshes)" sh -c \
    "$CC -std=c99 -O0 -w -Itests tests/outputs.c -o $out/outputs_make -lm && $out/outputs_make --write $out/outputs_input.bin"
check "outputs: $CC -O0 (the reference)" outputs O0 $CC -O0
check "outputs: $CC -O2 gives the reference's" same_outputs O2 $CC -O2
check "outputs: $CC -O3 -ffast-math gives the reference's" same_outputs fast $CC -O3 -ffast-math
check "outputs: $CC -O2 -DMESHFIX_NO_SIMD (the scalar path) gives the reference's" same_outputs scalar $CC -O2 -DMESHFIX_NO_SIMD
check "outputs: $CC -O2 with Morton-cluster trees from 16 triangles gives the reference's" same_outputs morton \
    $CC -O2 -DMESHFIX__MORTON_MIN=16
if command -v clang >/dev/null 2>&1; then
    check "outputs: clang -O2 gives the reference's" same_outputs clang clang -O2
    check "outputs: clang -Ofast gives the reference's" same_outputs clangfast clang -Ofast
else
    skip "outputs: clang -O2 and -Ofast: clang is not installed (apt-get install clang)"
fi
if [ "$m32" -eq 1 ]; then
    check "outputs: $CC -m32 -O2 (x87) gives the reference's" same_outputs m32 $CC -m32 -O2
    check "outputs: $CC -m32 -O3 -ffast-math gives the reference's" same_outputs m32fast $CC -m32 -O3 -ffast-math
else
    skip "outputs: $CC -m32 -O2 and -O3 -ffast-math: no 32-bit toolchain here (apt-get install gcc-multilib)"
fi

suite "OpenMesh as oracle" build/test_openmesh
if command -v valgrind >/dev/null 2>&1; then
    # memcheck: any error or leak fails the run (exit code 99)
    VG="valgrind -q --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite,indirect"
    for t in $SUITES; do
        MESHFIX_ADVERSARIAL_N=5000 suite "valgrind memcheck: $t" $VG build/$t
    done
else
    echo "FAIL valgrind is not installed (apt-get install valgrind; make test installs it as root)"
    failed=$((failed + 1))
fi
echo "== make demo on a bare machine"
check "make demo with make, cc and c++ only (no tinygltf, nlohmann json, OpenMesh, Embree, libpng, node, python): the demo repairs, a .glb is refused in one line" \
    bash tests/test_bare_demo.sh
echo "== command-line tool"
check "meshfix CLI repairs the demo mesh" sh -c "build/demo_mesh $out/demo.obj >/dev/null && build/meshfix --quiet $out/demo.obj $out/fixed.ply && build/meshfix --inspect $out/fixed.ply | grep -q 'inconsistent 0' && build/meshfix --inspect $out/fixed.ply | grep -q 'inside-out 0'"
check "meshfix CLI: one-line error, exit 1 on a bad file" sh -c "printf 'OFF\n999999999 1 0\n' > $out/bad.off; build/meshfix $out/bad.off $out/x.obj 2>$out/err.txt; test \$? -eq 1 && test \$(wc -l < $out/err.txt) -eq 1"
check "meshfix CLI: unknown policy is a one-line error" sh -c "build/meshfix --policy sdf $out/demo.obj $out/x.obj 2>$out/err.txt; test \$? -eq 1 && test \$(wc -l < $out/err.txt) -eq 1"
check "meshfix CLI: every format round-trips" sh -c "for f in obj off stl ply; do build/meshfix --quiet $out/demo.obj $out/rt.\$f && build/meshfix --inspect $out/rt.\$f | grep -q 'triangles 8064' || exit 1; done"

suite "command-line tool: misuse, crafted and odd files" bash tests/test_cli.sh
suite "command-line tool on hostile files and runs: glTF URIs, full disks, shared bytes, deep JSON, FIFOs, collisions, interrupts" \
    bash tests/test_cli_hostile.sh
suite "command-line tool on real files: lossless round trips, scrambled copies, glTF (validator), exit statuses, --json" \
    bash tests/test_cli_files.sh
check "sdf_demo repairs its scene (exit 0: consistent, outward)" sh -c "build/sdf_demo $out/sdf.obj >/dev/null && build/meshfix --inspect $out/sdf.obj | grep -q 'inconsistent 0'"

echo "== docs are code: README.md's snippets and the header's quick start; the tool's options in --help and README.md"
docs_log="$out/docs.log"
CC="$CC" CXX="$CXX" MAKE="${MAKE:-make}" bash tests/docs.sh build/docs >"$docs_log" 2>&1
grep -v -E '^[0-9]+ passed, [0-9]+ failed$' "$docs_log"
passed=$((passed + $(grep -c '^ok ' "$docs_log")))
failed=$((failed + $(grep -c '^FAIL ' "$docs_log")))

# The packages around the header: each script prints ok / FAIL / SKIP lines
# and exits non-zero on a failure (SKIP: a tool is missing).
package_tests() { # title, log name, command...
    local title=$1 log="$out/$2.log" status
    shift 2
    echo "== $title"
    "$@" >"$log" 2>&1
    status=$?
    grep -v -E '^[0-9]+ passed, [0-9]+ failed$' "$log"
    passed=$((passed + $(grep -c '^ok ' "$log")))
    failed=$((failed + $(grep -c '^FAIL ' "$log")))
    if [ "$status" -ne 0 ] && ! grep -q '^FAIL ' "$log"; then
        echo "FAIL $*: exit status $status without a FAIL line"
        failed=$((failed + 1))
    fi
    count_skips "$log"
}
package_tests "CMake and pkg-config: a consumer through add_subdirectory, find_package and pkg-config" cmake \
    bash tests/cmake/run.sh build/cmake
package_tests "Python module: the binding against the C library on the same meshes" python \
    bash python/test.sh build/python-test
package_tests "npm package (js/): WebAssembly build, typed-array API, glTF-Transform transform" js bash js/test.sh
package_tests "Blender add-on: the operator in Debian's Blender against the command-line tool" blender \
    bash blender/test.sh build/blender-test
if [ "$skipped" -gt 0 ]; then
    echo "== not run here: $skipped skipped"
    printf 'SKIP %s\n' "${skips[@]}"
fi
echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
