#!/usr/bin/env bash
# What the suites of `make test` need on Debian; the Makefile's test target
# runs this before it builds anything.
#   - as root, with apt-get: installs the packages that are missing;
#   - otherwise: prints the apt-get line that installs them and exits 1, so
#     `make test` stops before building;
#   - then, as any user, the Khronos glTF-Validator from the npm registry
#     into build/node_modules (tests/test_cli_files.sh looks there; without
#     the network it says so, and those checks fail).
# Prints nothing when everything is there.
set -euo pipefail
cd "$(dirname "$0")/.."

need=()
has() { command -v "$1" >/dev/null 2>&1; }
has cc || need+=(gcc)
has c++ || need+=(g++)
has make || need+=(make)
has valgrind || need+=(valgrind)
has clang || need+=(clang)
[ -f /usr/include/OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh ] || need+=(libopenmesh-dev)
# real models for the suites and the command-line tool's tests
[ -f /usr/share/assimp/models/OBJ/spider.obj ] || need+=(assimp-testmodels)
[ -f /usr/share/opencascade/data/stl/motor.stl ] || need+=(occt-misc)
# the Draco engine of assimp-testmodels exported to OBJ and STL (tests/test_cli_files.sh)
has assimp || need+=(assimp-utils)
# the Blender add-on, in Debian's Blender in background mode (blender/test.sh)
has blender || need+=(blender)
# the command-line tool's glTF (the Makefile builds it without when these
# are missing, and its glTF tests would fail); they run the Khronos
# glTF-Validator under node
[ -f /usr/include/tiny_gltf.h ] || need+=(libtinygltf-dev)
[ -f /usr/include/nlohmann/json.hpp ] || need+=(nlohmann-json3-dev)
# the tool's --mark FILE.png (the Makefile builds it without when missing)
[ -f /usr/include/png.h ] || need+=(libpng-dev)
has node || need+=(nodejs)
has npm || need+=(npm)
# the npm package (js/test.sh): meshfix.h compiled to WebAssembly
has emcc || need+=(emscripten)
# the npm package's browser page (js/test/page.test.mjs): Debian's Chromium,
# headless, driven by puppeteer-core (js/package-lock.json)
has chromium || need+=(chromium)
# CMake and pkg-config consumers (tests/cmake/run.sh)
has cmake || need+=(cmake)
has pkg-config || need+=(pkg-config)
# the Python module (python/test.sh) and the tool's crafted files
# (tests/cli/hostile_gltf.py) run under Debian's python3, whatever python3
# comes first on PATH; the module's offline pip install goes into a venv
py=/usr/bin/python3
[ -x $py ] || need+=(python3)
$py -c "import numpy" >/dev/null 2>&1 || need+=(python3-numpy)
$py -c "import pytest" >/dev/null 2>&1 || need+=(python3-pytest)
$py -m pip --version >/dev/null 2>&1 || need+=(python3-pip)
$py -c "import ensurepip" >/dev/null 2>&1 || need+=(python3-venv)
$py -c "import setuptools, wheel" >/dev/null 2>&1 || need+=(python3-setuptools python3-wheel)
# 32-bit builds of the C suites (size_t of 4 bytes, x87 floats) and of the
# command-line tool (tests/test_cli.sh, C++), where the architecture has them
if [ "$(dpkg --print-architecture 2>/dev/null)" = amd64 ]; then
    dpkg -s gcc-multilib >/dev/null 2>&1 || need+=(gcc-multilib)
    dpkg -s g++-multilib >/dev/null 2>&1 || need+=(g++-multilib)
fi
if [ ${#need[@]} -gt 0 ]; then
    list=$(printf '%s\n' "${need[@]}" | awk '!seen[$0]++' | tr '\n' ' ')
    list=${list% }
    if [ "$(id -u)" -eq 0 ] && has apt-get; then
        echo "make test: installing $list"
        export DEBIAN_FRONTEND=noninteractive
        apt-get update -qq
        # shellcheck disable=SC2086
        apt-get install -y -qq $list >/dev/null
    else
        echo "make test: these packages are missing: $list"
        if has apt-get; then
            echo "As root (or with sudo), run"
            echo "    apt-get install $list"
            echo "then make test again. Nothing was built."
        else
            echo "(Debian's names: install them with your system's package manager, then make test again.)"
        fi
        exit 1
    fi
fi

if [ ! -f build/node_modules/gltf-validator/package.json ]; then
    mkdir -p build
    timeout 300 npm install --prefix build --no-audit --no-fund --silent gltf-validator >/dev/null 2>&1 ||
        echo "make test: could not install gltf-validator from the npm registry (offline?): the glTF validation checks will fail"
fi
