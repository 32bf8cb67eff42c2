#!/usr/bin/env bash
# The Blender add-on in Debian's Blender: builds the zip (blender/build.sh),
# then runs blender/tests/test_addon.py in `blender -b --factory-startup`,
# which installs the zip as an add-on into a user scripts directory under
# WORKDIR (BLENDER_USER_SCRIPTS, BLENDER_USER_CONFIG: the user's own setup
# is not read or touched) and checks it on real models against the
# command-line tool (build/meshfix, built with make when missing), and
# scores Blender's own Recalculate Outside beside it. Prints "ok   name" /
# "FAIL name: why" / "SKIP name (why)" lines and "N passed, N failed";
# exits 1 when something failed.
# Usage: blender/test.sh [WORKDIR] [--readme]
#   WORKDIR  default build/blender-test, emptied first
#   --readme write the measured table into blender/README.md
# BLENDER: the blender binary (default blender); MAKE, CC: for build/meshfix.
set -u
cd "$(dirname "$0")/.."
root=$(pwd)
work=build/blender-test
readme=0
for a in "$@"; do
    case "$a" in
    --readme) readme=1 ;;
    *) work=$a ;;
    esac
done
case "$work" in /*) ;; *) work="$root/$work" ;; esac
BLENDER=${BLENDER:-blender}
passed=0
failed=0
log="$work/last.log"

finish() {
    echo "$passed passed, $failed failed"
    [ "$failed" -eq 0 ]
    exit
}

if ! command -v "$BLENDER" >/dev/null 2>&1; then
    echo "SKIP blender: no $BLENDER (apt-get install blender)"
    finish
fi
if [ ! -d /usr/share/assimp/models ] && [ ! -d /usr/share/opencascade/data/stl ]; then
    echo "SKIP blender: no models (apt-get install assimp-testmodels occt-misc)"
    finish
fi
rm -rf "$work"
mkdir -p "$work/scripts" "$work/config" "$work/models"
check_log="$log"
. tests/check.sh

zip_has_module() {
    sh blender/build.sh "$work/meshfix_blender.zip" || return 1
    "${PYTHON:-python3}" - "$work/meshfix_blender.zip" <<'PY'
import sys, zipfile
names = zipfile.ZipFile(sys.argv[1]).namelist()
print("\n".join(names))
for need in ("meshfix_blender/__init__.py", "meshfix_blender/repair.py", "meshfix_blender/meshfix/__init__.py"):
    assert need in names, need
assert any(n.startswith("meshfix_blender/meshfix/_libmeshfix") for n in names), "no shared library"
PY
}
check "blender: blender/build.sh builds the add-on zip (add-on, meshfix module, shared library from meshfix.h)" \
    zip_has_module
[ "$failed" -eq 0 ] || finish

cli=$root/build/meshfix
if [ ! -x "$cli" ]; then
    check "blender: make build/meshfix (the tool the add-on is compared with)" ${MAKE:-make} build/meshfix
    [ "$failed" -eq 0 ] || finish
fi

results="$work/results.txt"
: >"$results"
BLENDER_USER_SCRIPTS="$work/scripts" BLENDER_USER_CONFIG="$work/config" \
    "$BLENDER" -b --factory-startup --python-exit-code 1 --python blender/tests/test_addon.py -- \
    --zip "$work/meshfix_blender.zip" --cli "$cli" --work "$work/models" --table "$work/table.md" \
    --results "$results" >"$work/blender.log" 2>&1
status=$?
grep -E '^(ok|FAIL|SKIP|    )' "$results"
passed=$((passed + $(grep -c '^ok ' "$results")))
failed=$((failed + $(grep -c '^FAIL ' "$results")))
if [ "$status" -ne 0 ] && ! grep -q '^FAIL ' "$results"; then
    echo "FAIL blender: $BLENDER exited with $status"
    tail -25 "$work/blender.log" | sed 's/^/    /'
    failed=$((failed + 1))
fi
if [ -s "$work/table.md" ]; then
    echo "the measurements (written to $work/table.md):"
    sed 's/^/    /' "$work/table.md"
    if [ "$readme" -eq 1 ]; then
        "${PYTHON:-python3}" - blender/README.md "$work/table.md" <<'PY'
import sys
readme, table = sys.argv[1], open(sys.argv[2]).read()
text = open(readme).read()
start, end = "<!-- table: blender/test.sh --readme -->\n", "<!-- end of table -->\n"
a, b = text.index(start) + len(start), text.index(end)
open(readme, "w").write(text[:a] + table + text[b:])
print("wrote the table into " + readme)
PY
    fi
fi
finish
