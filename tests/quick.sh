#!/usr/bin/env bash
# make check (make quick): the six C suites (plain builds, already built by the
# Makefile) and the tool's own tests, with one closing line over them; a
# contributor's loop between edits. `make test` runs these and everything
# else (sanitizers, valgrind, the outputs of every build, OpenMesh, the
# real files, the bindings). A WORD runs only the C tests whose names
# contain it.
set -u
cd "$(dirname "$0")/.."
word=${1:-}
passed=0
failed=0
run() { # name, command...: adds the command's own "N passed, N failed" line
    local log line
    log=$(mktemp)
    echo "== $1"
    shift
    "$@" >"$log" 2>&1
    local status=$?
    grep -v '^ok ' "$log"
    line=$(grep -E '^[0-9]+ passed, [0-9]+ failed' "$log" | tail -n 1)
    rm -f "$log"
    if [ -z "$line" ]; then
        echo "FAIL $1: no closing line (exit status $status)"
        failed=$((failed + 1))
        return
    fi
    passed=$((passed + $(echo "$line" | cut -d' ' -f1)))
    failed=$((failed + $(echo "$line" | cut -d' ' -f3 | tr -d ',')))
}
for suite in test_meshfix test_sdf test_visibility test_hostile test_trust test_api; do
    run "$suite" build/$suite $word
done
[ -n "$word" ] || run "tests/test_cli.sh" env MESHFIX_CHECK=1 bash tests/test_cli.sh
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
