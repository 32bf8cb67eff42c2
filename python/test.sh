#!/usr/bin/env bash
# The Python module: builds it (python/build.sh), checks that
# `python3 -c "import meshfix"` orients a NumPy mesh as the C library does,
# runs the pytest suite (python/tests: the binding against a C program on
# the real models of assimp-testmodels and occt-misc), runs the READMEs'
# install block as written (a wheel, a plain venv, offline) and their
# python blocks in that venv. Prints "ok   name" / "FAIL name" / "SKIP name:
# reason" lines (pytest: one line per test function, its cases counted; one
# FAIL line per failing case), then "N passed, N failed"; exits 1 when
# something failed.
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
    echo "$passed passed, $failed failed"; exit 0
fi
if ! "$PYTHON" -c "import numpy" >/dev/null 2>&1; then
    echo "SKIP python: $PYTHON has no NumPy (apt-get install python3-numpy; or set PYTHON)"
    echo "$passed passed, $failed failed"; exit 0
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
        passed=$((passed + $(grep -c '^ok' "$work/pytest_lines.txt")))
        failed=$((failed + $(grep -c '^FAIL' "$work/pytest_lines.txt")))
        if [ "$status" -ne 0 ] && ! grep -q '^FAIL' "$work/pytest_lines.txt"; then
            echo "FAIL python: pytest exited with $status"
            tail -20 "$work/pytest.txt" | sed 's/^/    /'
            failed=$((failed + 1))
        fi
    else
        echo "FAIL python: pytest wrote no results (exit status $status)"
        tail -20 "$work/pytest.txt" | sed 's/^/    /'
        failed=$((failed + 1))
    fi
else
    echo "SKIP python: pytest suite: $PYTHON has no pytest (apt-get install python3-pytest)"
fi

# The READMEs' install block (README.md and python/README.md, the same
# block), run line by line as written in a copy of the checkout (meshfix.h
# and python/), offline, with none of this machine's pip configuration: a
# wheel built by Debian's python3, a plain venv (no system site packages),
# the wheel installed from the file. `venv/bin/pip install numpy` needs
# PyPI, which this machine does not reach: in its place Debian's NumPy is
# linked into the venv's site-packages (the package and its metadata, and
# nothing else), as the user's own NumPy would be there.
missing=""
[ -x /usr/bin/python3 ] || missing="$missing python3"
/usr/bin/python3 -m pip --version >/dev/null 2>&1 || missing="$missing python3-pip"
/usr/bin/python3 -c "import ensurepip" >/dev/null 2>&1 || missing="$missing python3-venv"
/usr/bin/python3 -c "import setuptools, wheel" >/dev/null 2>&1 || missing="$missing python3-setuptools python3-wheel"
/usr/bin/python3 -c "import numpy" >/dev/null 2>&1 || missing="$missing python3-numpy"
if [ -z "$missing" ]; then
    copy="$work/checkout"
    mkdir -p "$copy/python"
    cp meshfix.h README.md "$copy/"
    cp -r python/pyproject.toml python/setup.py python/README.md python/meshfix "$copy/python/"
    # a fresh machine's pip: no configuration file, no PIP_* settings
    for v in $(env | sed -n 's/^\(PIP_[A-Z_]*\)=.*/\1/p'); do unset "$v"; done
    export PIP_CONFIG_FILE=/dev/null PIP_DISABLE_PIP_VERSION_CHECK=1
    numpy_into_venv() { # VENV: Debian's numpy linked into its site-packages
        local site
        site=$("$1/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])') &&
            /usr/bin/python3 -c '
import glob, os, sys, numpy
where = os.path.dirname(numpy.__path__[0])
meta = glob.glob(os.path.join(where, "numpy-*.egg-info")) + glob.glob(os.path.join(where, "numpy-*.dist-info"))
assert meta, "no metadata of Debian numpy in %s" % where
for path in [numpy.__path__[0]] + meta:
    os.symlink(path, os.path.join(sys.argv[1], os.path.basename(path)))
    print("linked", path)' "$site"
    }
    readme_install() {
        /usr/bin/python3 python/tests/readme.py install README.md python/README.md >"$work/install.sh" || return 1
        local line
        while IFS= read -r line; do
            case "$line" in '' | '#'*) continue ;; esac
            echo "\$ $line"
            if [ "$line" = "venv/bin/pip install numpy" ]; then
                (cd "$copy" && numpy_into_venv venv) || return 1
            else
                (cd "$copy" && bash -euc "$line") || return 1
            fi
        done <"$work/install.sh"
        grep -qx 'include-system-site-packages = false' "$copy/venv/pyvenv.cfg" || {
            echo "not a plain venv:"; cat "$copy/venv/pyvenv.cfg"; return 1; }
        "$copy/venv/bin/pip" list | tee "$work/pip_list.txt"
        grep -q '^meshfix  *0\.' "$work/pip_list.txt" && grep -q '^numpy ' "$work/pip_list.txt"
    }
    check "python: the READMEs' install block, run as written: a wheel by Debian's python3, a plain venv, pip install --no-index of the wheel" \
        readme_install
    installed_snippets() { # the READMEs' python blocks in that venv, on the meshfix it installed
        (cd "$work" && "$copy/venv/bin/python" -c '
import meshfix, sys
assert meshfix.__file__.startswith(sys.prefix + "/lib/"), meshfix.__file__
print(meshfix.__file__)' && "$copy/venv/bin/python" "$root/python/tests/readme.py" run "$root/README.md" "$root/python/README.md")
    }
    check "python: README.md's and python/README.md's python blocks run in that venv and print what they say" \
        installed_snippets
    without_numpy() { # the wheel's --no-index install stops at the missing NumPy, installs nothing
        /usr/bin/python3 -m venv "$work/bare" || return 1
        (cd "$copy" && "$work/bare/bin/pip" install --no-index build/wheels/meshfix-*.whl) >"$work/bare.txt" 2>&1
        local status=$?
        cat "$work/bare.txt"
        [ "$status" -ne 0 ] && grep -q numpy "$work/bare.txt" && ! "$work/bare/bin/python" -c "import meshfix" 2>/dev/null
    }
    check "python: without NumPy in the venv, pip install --no-index of the wheel refuses, naming numpy" without_numpy
    system_site() { # the READMEs' other venv: Debian's NumPy seen through --system-site-packages
        /usr/bin/python3 -m venv --system-site-packages "$work/system" &&
            (cd "$copy" && "$work/system/bin/pip" install --no-index build/wheels/meshfix-*.whl) &&
            (cd "$work" && "$work/system/bin/python" -c '
import meshfix, numpy, sys
assert meshfix.__file__.startswith(sys.prefix + "/lib/"), meshfix.__file__
assert not numpy.__file__.startswith(sys.prefix), numpy.__file__
print(meshfix.__file__, numpy.__file__)')
    }
    check "python: a venv with --system-site-packages takes the same wheel, with Debian's NumPy" system_site
else
    echo "SKIP python: the READMEs' install into a venv: missing$missing"
fi

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
