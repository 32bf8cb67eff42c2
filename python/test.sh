#!/usr/bin/env bash
# The Python module: builds it (python/build.sh), checks that
# `python3 -c "import meshfix"` orients a NumPy mesh as the C library does,
# runs the pytest suite (python/tests: the binding against a C program on
# the real models of assimp-testmodels and occt-misc), and installs it with
# pip into a virtual environment, offline. Prints "ok   name" / "FAIL name" /
# "SKIP name: reason" lines (pytest: one line per test function, its cases
# counted; one FAIL line per failing case); exits 1 when something failed.
# Usage: python/test.sh [WORKDIR]   (default build/python-test, emptied first)
# PYTHON: the interpreter (default /usr/bin/python3, Debian's, where
# python3-numpy and python3-pytest live; a pyenv python3 first on PATH
# usually has neither). CC: the C compiler.
set -u
cd "$(dirname "$0")/.."
root=$(pwd)
work=${1:-build/python-test}
case "$work" in /*) ;; *) work="$root/$work" ;; esac
rm -rf "$work"
mkdir -p "$work"
CC=${CC:-cc}
export CC
if [ -z "${PYTHON:-}" ]; then
    if [ -x /usr/bin/python3 ]; then PYTHON=/usr/bin/python3; else PYTHON=python3; fi
fi
export PYTHONDONTWRITEBYTECODE=1
passed=0
failed=0
log="$work/last.log"

check_log="$log"
. tests/check.sh

if ! command -v "$PYTHON" >/dev/null 2>&1; then
    echo "SKIP python: no $PYTHON (apt-get install python3 python3-numpy python3-pytest)"
    exit 0
fi
if ! "$PYTHON" -c "import numpy" >/dev/null 2>&1; then
    echo "SKIP python: $PYTHON has no NumPy (apt-get install python3-numpy; or set PYTHON)"
    exit 0
fi

check "python: python/build.sh builds the module with $CC (shared library + __init__.py)" \
    sh python/build.sh "$work/module"

# `python3 -c "import meshfix"` from the built module, outside the source
# tree, on the README's tetrahedron; the same arrays through the C program
smoke() {
    $CC -std=c99 -O2 -I. python/tests/cref.c -o "$work/cref" -lm || return 1
    (cd "$work" && PYTHONPATH="$work/module" "$PYTHON" -c '
import numpy as np, meshfix
positions = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32)
indices = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 3, 2]], np.uint32)
fixed, report = meshfix.orient(indices, positions)
print(meshfix.__file__)
print(report.summary)
indices.tofile("tetra_indices.bin"); positions.tofile("tetra_positions.bin"); fixed.tofile("tetra_python.bin")
assert report.triangles_flipped == 1 and fixed[3].tolist() == [1, 2, 3]
') >"$work/smoke.txt" || return 1
    cat "$work/smoke.txt"
    grep -q "^$work/module/meshfix/__init__.py$" "$work/smoke.txt" || { echo "imported the wrong meshfix"; return 1; }
    "$work/cref" orient indices="$work/tetra_indices.bin" index_size=4 positions="$work/tetra_positions.bin" \
        position_size=4 out="$work/tetra_c.bin" >"$work/smoke_c.txt" || return 1
    cat "$work/smoke_c.txt"
    head -c 48 "$work/tetra_c.bin" | cmp - "$work/tetra_python.bin" || return 1
    grep -q "^summary=$(sed -n 2p "$work/smoke.txt")$" "$work/smoke_c.txt" &&
        grep -q "^triangles_flipped=1$" "$work/smoke_c.txt"
}
check "python: python3 -c \"import meshfix\" orients a NumPy tetrahedron as C does (1 flip, same indices and summary)" smoke

# pytest, its results mapped to lines
if "$PYTHON" -c "import pytest" >/dev/null 2>&1; then
    (cd python/tests && PYTHONPATH="$work/module" "$PYTHON" -m pytest -q -p no:cacheprovider \
        --basetemp="$work/pytest" --junitxml="$work/pytest.xml" >"$work/pytest.txt" 2>&1)
    status=$?
    if [ -f "$work/pytest.xml" ]; then
        "$PYTHON" - "$work/pytest.xml" >"$work/pytest_lines.txt" <<'EOF'
import collections
import sys
import xml.etree.ElementTree as ET

tests = collections.OrderedDict()
for case in ET.parse(sys.argv[1]).iter("testcase"):
    name = case.get("name")
    function = name.split("[")[0]
    outcome, message = "passed", ""
    for child in case:
        if child.tag in ("failure", "error"):
            outcome, message = "failed", (child.get("message") or child.tag).splitlines()[0]
        elif child.tag == "skipped":
            outcome, message = "skipped", (child.get("message") or "").splitlines()[0]
    tests.setdefault(function, []).append((name, outcome, message))
for function, cases in tests.items():
    failed = [c for c in cases if c[1] == "failed"]
    skipped = [c for c in cases if c[1] == "skipped"]
    ran = len(cases) - len(skipped)
    for name, _, message in failed:
        print("FAIL python: %s: %s" % (name, message[:200]))
    if not failed and ran:
        print("ok   python: %s (%d case%s)" % (function, ran, "" if ran == 1 else "s"))
    reasons = collections.Counter(c[2] for c in skipped)
    for reason, n in reasons.items():
        print("SKIP python: %s (%d case%s): %s" % (function, n, "" if n == 1 else "s", reason))
EOF
        cat "$work/pytest_lines.txt"
        grep -q '^FAIL' "$work/pytest_lines.txt" && failed=1
        if [ "$status" -ne 0 ] && ! grep -q '^FAIL' "$work/pytest_lines.txt"; then
            echo "FAIL python: pytest exited with $status"
            tail -20 "$work/pytest.txt" | sed 's/^/    /'
            failed=1
        fi
    else
        echo "FAIL python: pytest wrote no results (exit status $status)"
        tail -20 "$work/pytest.txt" | sed 's/^/    /'
        failed=1
    fi
else
    echo "SKIP python: pytest suite: $PYTHON has no pytest (apt-get install python3-pytest)"
fi

# pip, offline: the pyproject.toml/setup.py build into a virtual environment
missing=""
"$PYTHON" -m pip --version >/dev/null 2>&1 || missing="$missing python3-pip"
"$PYTHON" -c "import ensurepip" >/dev/null 2>&1 || missing="$missing python3-venv"
"$PYTHON" -c "import setuptools, wheel" >/dev/null 2>&1 || missing="$missing python3-setuptools python3-wheel"
if [ -z "$missing" ]; then
    pip_install() {
        mkdir -p "$work/pip/src/python" &&
            cp meshfix.h "$work/pip/src/" &&
            cp -r python/pyproject.toml python/setup.py python/README.md python/meshfix "$work/pip/src/python/" &&
            "$PYTHON" -m venv --system-site-packages --without-pip "$work/pip/venv" &&
            "$work/pip/venv/bin/python" -m pip install --no-build-isolation --no-index \
                --disable-pip-version-check "$work/pip/src/python" &&
            (cd "$work" && "$work/pip/venv/bin/python" -c '
import numpy as np, meshfix, sys
assert meshfix.__file__.startswith(sys.prefix), meshfix.__file__
positions = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32)
indices = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 3, 2]], np.uint16)
fixed, report = meshfix.orient(indices, positions.astype(np.float64))
print(meshfix.__file__, meshfix.__version__, report.summary)
assert report.triangles_flipped == 1 and fixed.dtype == np.uint16 and fixed[3].tolist() == [1, 2, 3]
')
    }
    check "python: pip install --no-build-isolation --no-index ./python into a venv, then import meshfix there" pip_install
else
    echo "SKIP python: pip install ./python: missing$missing"
fi

[ "$failed" -eq 0 ]
