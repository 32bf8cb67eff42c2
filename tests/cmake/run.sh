#!/usr/bin/env bash
# CMake and pkg-config: builds tests/cmake/consumer (repairs a tetrahedron
# with a turned face and asserts one flip) three ways: add_subdirectory,
# find_package after `"$CMAKE" --install` into a temporary prefix, and
# pkg-config; checks the installed files, the version file, a relocated
# prefix, the CLI and test options. Prints "ok   name" / "FAIL name" /
# "SKIP name: reason" lines; exits 1 when a check failed.
# Usage: tests/cmake/run.sh [WORKDIR]   (default build/cmake, emptied first)
set -u
cd "$(dirname "$0")/../.."
root=$(pwd)
work=${1:-build/cmake}
case "$work" in /*) ;; *) work="$root/$work" ;; esac
rm -rf "$work"
mkdir -p "$work"
log="$work/last.log"
passed=0
failed=0
CC=${CC:-cc}
CMAKE=${CMAKE:-cmake}
CTEST=${CTEST:-ctest}
PKG_CONFIG=${PKG_CONFIG:-pkg-config}
JOBS=${JOBS:-2}

check_log="$log"
. tests/check.sh

if ! command -v "$CMAKE" >/dev/null 2>&1; then
    for name in "cmake: configure, build and install meshfix" "cmake: consumer through add_subdirectory" \
        "cmake: consumer through find_package" "pkg-config: consumer"; do
        echo "SKIP $name: cmake is not installed (apt-get install cmake)"
    done
    exit 0
fi

version=$(sed -n 's/^#define MESHFIX_VERSION_\(MAJOR\|MINOR\|PATCH\) \+\([0-9]\+\).*/\2/p' meshfix.h | paste -sd.)
major_minor=${version%.*}
next_minor="${version%%.*}.$((${major_minor#*.} + 1))"
prefix="$work/prefix"

# Whether `make build/meshfix` would build here: the CLI option is checked
# only where the Makefile's own rule can build the tool.
cli=OFF
if make -s -n build/meshfix >/dev/null 2>&1 && make -s build/meshfix >"$work/make_cli.log" 2>&1; then
    cli=ON
fi

configure_meshfix() {
    "$CMAKE" -S "$root" -B "$work/meshfix" -DCMAKE_BUILD_TYPE=Release -DMESHFIX_BUILD_CLI=$cli &&
        "$CMAKE" --build "$work/meshfix" -j "$JOBS" &&
        "$CMAKE" --install "$work/meshfix" --prefix "$prefix"
}
check "cmake: configure, build (CLI $cli) and install meshfix $version into a temporary prefix" configure_meshfix

installed() {
    local f
    for f in include/meshfix.h share/cmake/meshfix/meshfixConfig.cmake \
        share/cmake/meshfix/meshfixConfigVersion.cmake share/cmake/meshfix/meshfixTargets.cmake \
        share/pkgconfig/meshfix.pc; do
        [ -f "$prefix/$f" ] || { echo "missing $prefix/$f"; return 1; }
    done
    cmp meshfix.h "$prefix/include/meshfix.h" || return 1
    if [ "$cli" = ON ]; then
        [ -x "$prefix/bin/meshfix" ] || { echo "missing $prefix/bin/meshfix"; return 1; }
    fi
    echo "installed:" && (cd "$prefix" && find . -type f | sort)
}
check "cmake: the prefix holds the header, meshfixConfig.cmake, its version file, meshfix.pc$([ "$cli" = ON ] && echo ', bin/meshfix')" installed

consumer() { # build directory, cmake arguments...
    local dir=$1
    shift
    "$CMAKE" -S tests/cmake/consumer -B "$dir" "$@" &&
        "$CMAKE" --build "$dir" -j "$JOBS" &&
        "$dir/consumer" | tee "$dir/out.txt" &&
        grep -q "^meshfix $version: fixed 1 triangle in 1 patch$" "$dir/out.txt"
}
check "cmake: consumer through add_subdirectory repairs the tetrahedron (1 flip)" \
    consumer "$work/sub" -DMESHFIX_VIA=add_subdirectory -DMESHFIX_SOURCE_DIR="$root"
check "cmake: consumer through find_package($major_minor) after cmake --install repairs the tetrahedron (1 flip)" \
    consumer "$work/found" -DMESHFIX_VIA=find_package -DMESHFIX_WANT="$major_minor" -DCMAKE_PREFIX_PATH="$prefix"

# nothing of the source tree leaks into the installed package
not_from_source() {
    ! grep -rl "$root" "$prefix" --include='*.cmake' --include='*.pc'
}
check "cmake: the installed package files do not name the source or build tree" not_from_source

refuses() {
    local want=$1
    ! "$CMAKE" -S tests/cmake/consumer -B "$work/refused_$want" -DMESHFIX_VIA=find_package \
        -DMESHFIX_WANT="$want" -DCMAKE_PREFIX_PATH="$prefix" >"$work/refused_$want.log" 2>&1 || return 1
    cat "$work/refused_$want.log"
    grep -q "compatible with requested version \"$want\"" "$work/refused_$want.log"
}
check "cmake: find_package($next_minor) refuses $version (a 0.x minor version may break the API)" refuses "$next_minor"
check "cmake: find_package($version) accepts it" \
    "$CMAKE" -S tests/cmake/consumer -B "$work/exact" -DMESHFIX_VIA=find_package -DMESHFIX_WANT="$version" \
    -DCMAKE_PREFIX_PATH="$prefix"

if command -v "$PKG_CONFIG" >/dev/null 2>&1; then
    pc() { # prefix: builds the consumer with pkg-config's flags, runs it
        local p=$1 out="$work/pc_$(basename "$1")"
        mkdir -p "$out"
        local modversion cflags libs
        modversion=$(PKG_CONFIG_PATH="$p/share/pkgconfig" "$PKG_CONFIG" --modversion meshfix) || return 1
        cflags=$(PKG_CONFIG_PATH="$p/share/pkgconfig" "$PKG_CONFIG" --cflags meshfix) || return 1
        libs=$(PKG_CONFIG_PATH="$p/share/pkgconfig" "$PKG_CONFIG" --libs meshfix) || return 1
        echo "modversion $modversion; cflags $cflags; libs $libs"
        [ "$modversion" = "$version" ] || { echo "expected version $version"; return 1; }
        case " $libs " in *" -lm "*) ;; *) echo "no -lm in Libs"; return 1 ;; esac
        # shellcheck disable=SC2086
        $CC -std=c99 -Wall -Wextra -Werror $cflags -c tests/cmake/consumer/main.c -o "$out/main.o" &&
            $CC -std=c99 -Wall -Wextra -Werror $cflags -c tests/cmake/consumer/implementation.c -o "$out/impl.o" &&
            ${CXX:-c++} -std=c++11 -Wall -Wextra -Werror $cflags -c tests/cmake/consumer/check.cpp -o "$out/check.o" &&
            ${CXX:-c++} "$out/main.o" "$out/impl.o" "$out/check.o" -o "$out/consumer" $libs &&
            "$out/consumer" | tee "$out/out.txt" &&
            grep -q "^meshfix $version: fixed 1 triangle in 1 patch$" "$out/out.txt"
    }
    check "pkg-config: consumer built with pkg-config --cflags/--libs meshfix ($version, -lm) repairs the tetrahedron (1 flip)" pc "$prefix"
    relocated() {
        rm -rf "$work/moved" && cp -a "$prefix" "$work/moved" && rm -rf "$prefix.hidden" && mv "$prefix" "$prefix.hidden" &&
            pc "$work/moved" &&
            consumer "$work/found_moved" -DMESHFIX_VIA=find_package -DCMAKE_PREFIX_PATH="$work/moved"
        local status=$?
        mv "$prefix.hidden" "$prefix"
        return $status
    }
    check "pkg-config and find_package: a copied prefix works (the original moved away)" relocated
else
    echo "SKIP pkg-config: consumer: pkg-config is not installed (apt-get install pkg-config)"
fi

if [ "$cli" = ON ]; then
    cli_runs() {
        printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 4 3\n' >"$work/tetra.obj" &&
            "$prefix/bin/meshfix" "$work/tetra.obj" "$work/tetra_fixed.obj" | tee "$work/cli.txt" &&
            "$prefix/bin/meshfix" --inspect "$work/tetra_fixed.obj" | grep -q 'inconsistent 0'
    }
    check "cmake: the installed CLI (MESHFIX_BUILD_CLI=ON) repairs a tetrahedron OBJ" cli_runs
else
    echo "SKIP cmake: MESHFIX_BUILD_CLI: \`make build/meshfix\` does not build here (see $work/make_cli.log)"
fi

tests_option() {
    "$CMAKE" -S "$root" -B "$work/tests" -DMESHFIX_BUILD_TESTS=ON -DMESHFIX_INSTALL=OFF &&
        "$CMAKE" --build "$work/tests" -j "$JOBS" --target test_meshfix test_sdf test_api &&
        (cd "$work/tests" && "$CTEST" --output-on-failure -R '^test_(meshfix|sdf|api)$')
}
check "cmake: MESHFIX_BUILD_TESTS=ON: test_meshfix, test_sdf, test_api built and passed under ctest" tests_option

[ "$failed" -eq 0 ]
