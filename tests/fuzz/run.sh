#!/usr/bin/env bash
# make fuzz: builds the libFuzzer targets with ASan + UBSan and runs each
# for FUZZ_SECONDS (default 60) from its seed corpus in
# tests/fuzz/corpus/<target>, then prints the executions per target.
#   meshfix  every entry point on small meshes (64 vertices, integer grid)
#   loaders  the example OBJ / OFF / STL / PLY loaders, then a repair
#   stress   large real-valued meshes, every option field, scratch,
#            parallel_for, SDF and weld, with an oracle for each call
#   gltf     the command-line tool's glTF path (load, repair, write,
#            commit, load again) on mutated .gltf/.glb files with their
#            companions in a scratch directory; seeds: the glTF files of
#            assimp-testmodels and tests/cli/hostile_gltf.py, packed by
#            tests/fuzz/gltf_seeds.py
#   text     the command-line tool's OBJ, OFF, STL and PLY readers and
#            writers (load, repair, write, commit, load again); seeds: the
#            files of tests/cli/text_variants.py and assimp-testmodels'
#            files of those formats, a format byte before each
#   stress-msan  the same with MemorySanitizer instead (reads of memory
#            never written); not in the default list: FUZZ_TARGETS adds it
# A crash does not stop the other targets: its input is saved in
# build/fuzz/crashes_<target>/ and the script exits 1 after the summary.
# FUZZ_TARGETS="stress" runs a subset; FUZZ_CFLAGS adds compiler flags,
# e.g. -DSTRESS_TOLERATE_KNOWN (see tests/fuzz/crashes/README.md);
# FUZZ_FLAGS adds libFuzzer flags, e.g. "-fork=1 -ignore_crashes=1" to go
# on past crashes (each is still saved, and the target counts as failed).
# Installs clang and its fuzzer runtime when missing (Debian; as root).
set -uo pipefail
cd "$(dirname "$0")/../.."
if ! printf 'int LLVMFuzzerTestOneInput(const char*d,unsigned long n){return 0;}' |
        clang -x c -fsanitize=fuzzer - -o /tmp/meshfix_fuzz_probe 2>/dev/null; then
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq && apt-get install -y -qq clang libclang-rt-14-dev >/dev/null || exit 1
fi
seconds=${FUZZ_SECONDS:-60}
targets=${FUZZ_TARGETS:-meshfix loaders stress gltf text}
mkdir -p build/fuzz
failed=0
summary=""
for target in $targets; do
    # the stress target's inputs expand into thousands of triangles: longer
    # inputs and a longer per-input limit (an input costs well under a second)
    source=$target sanitizers="address,undefined -fno-sanitize-recover=all" max_len=4096 timeout=10 knobs=""
    # stress meshes stay under 4096 triangles: the Morton-cluster trees and
    # their parallel build start lower there, so that it reaches them
    case $target in
    stress) max_len=200000 timeout=30 knobs="-DMESHFIX__MORTON_MIN=64 -DMESHFIX__PARALLEL_UNIT=512" ;;
    stress-msan) source=stress sanitizers="memory -fsanitize-memory-track-origins=2" max_len=200000 timeout=60
        knobs="-DMESHFIX__MORTON_MIN=64 -DMESHFIX__PARALLEL_UNIT=512" ;;
    esac
    if [ "$target" = gltf ] || [ "$target" = text ]; then
        # C++ against the tool's sources (all but main.cpp) and tinygltf; the
        # --mark picture is not fuzzed here (no libpng: MESHFIX_TOOL_NO_PNG)
        mkdir -p build/fuzz/seeds_$target
        if [ "$target" = gltf ]; then
            max_len=262144
            /usr/bin/python3 tests/cli/hostile_gltf.py build/fuzz/hostile_gltf &&
                /usr/bin/python3 tests/fuzz/gltf_seeds.py build/fuzz/seeds_gltf \
                    $(find /usr/share/assimp/models/glTF2 build/fuzz/hostile_gltf -name '*.gltf' -o -name '*.glb' | sort)
        else
            max_len=65536
            /usr/bin/python3 tests/cli/text_variants.py build/fuzz/text_variants
            k=0
            for f in $(find build/fuzz/text_variants /usr/share/assimp/models/OBJ /usr/share/assimp/models/OFF \
                    /usr/share/assimp/models/STL /usr/share/assimp/models/PLY -type f -size -64k 2>/dev/null | sort); do
                case ${f,,} in *.obj) b=0 ;; *.off) b=1 ;; *.stl) b=2 ;; *.ply) b=3 ;; *) continue ;; esac
                { printf "\\$(printf '%03o' $((b + 4 * (k % 4))))"; cat "$f"; } >build/fuzz/seeds_text/$k
                k=$((k + 1))
            done
        fi
        # shellcheck disable=SC2086
        build() {
            clang -g -O1 -fsanitize=fuzzer-no-link,$sanitizers -std=c99 -c -o build/fuzz/${target}_libs.o tools/meshfix/libs.c &&
                clang++ -g -O1 -std=c++17 -fsanitize=fuzzer,$sanitizers -DMESHFIX_TOOL_NO_PNG ${FUZZ_CFLAGS:-} -o build/fuzz/fuzz_$target \
                    tests/fuzz/fuzz_$target.cpp $(ls tools/meshfix/*.cpp | grep -v main.cpp) build/fuzz/${target}_libs.o \
                    -ltinygltf -pthread
        }
    else
        # shellcheck disable=SC2086
        build() {
            clang -g -O1 -fsanitize=fuzzer,$sanitizers $knobs ${FUZZ_CFLAGS:-} \
                -o build/fuzz/fuzz_$target tests/fuzz/fuzz_$source.c -lm
        }
    fi
    if ! build; then
        summary+=$(printf '%-10s %12s  %s' "$target" "-" "does not build")$'\n'
        failed=1
        continue
    fi
    mkdir -p build/fuzz/corpus_$target build/fuzz/crashes_$target
    log=build/fuzz/fuzz_$target.log
    touch build/fuzz/.start_$target # crashes of this run: the files newer than this
    echo "== fuzz_$target for $seconds s (log: $log)"
    # slow units are reported (and saved as failures) from the per-input limit on
    # shellcheck disable=SC2086
    build/fuzz/fuzz_$target -max_total_time="$seconds" -timeout=$timeout -report_slow_units=$timeout \
        -print_final_stats=1 -max_len=$max_len \
        -artifact_prefix=build/fuzz/crashes_$target/ ${FUZZ_FLAGS:-} \
        build/fuzz/corpus_$target $(if [ -d build/fuzz/seeds_$target ]; then echo build/fuzz/seeds_$target; else echo tests/fuzz/corpus/$source; fi) \
        >"$log" 2>&1
    status=$?
    grep -E 'stat::number_of_executed_units|stat::peak_rss|invariant violated|assertion failed|ERROR|WARNING: Memory|SUMMARY|Test unit written|Done' "$log" |
        awk '!seen[$0]++'
    grep -E '^#[0-9]+: cov:' "$log" | tail -n 1 # fork mode: the last progress line
    # executions: the final stats, libFuzzer's "Done N runs", or in fork
    # mode the last "#N: cov: ..." line
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
    [ -n "$runs" ] || runs=$(sed -n 's/^Done \([0-9]*\) runs.*/\1/p' "$log" | tail -n 1)
    [ -n "$runs" ] || runs=$(sed -n 's/^#\([0-9]*\): cov:.*/\1/p' "$log" | tail -n 1)
    [ -n "$runs" ] || runs="?"
    crashes=$(find build/fuzz/crashes_$target -type f -newer build/fuzz/.start_$target | wc -l)
    if [ "$status" -eq 0 ] && [ "$crashes" -eq 0 ]; then
        outcome="ok"
    else
        outcome="FAILED (exit $status, $crashes inputs in build/fuzz/crashes_$target/)"
        failed=1
    fi
    summary+=$(printf '%-10s %12s  %s' "$target" "$runs" "$outcome")$'\n'
done
echo
echo "== executions per target ($seconds s each)"
printf '%-10s %12s  %s\n' target executions outcome
printf '%s' "$summary"
exit $failed
