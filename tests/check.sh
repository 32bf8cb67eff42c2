# check NAME COMMAND...: the shell test scripts' one check, sourced by
# each (tests/run_all.sh, test_cli.sh, test_cli_files.sh, cmake/run.sh,
# python/test.sh). Runs the command with its output in $check_log (the
# script sets where), prints "ok   NAME", or "FAIL NAME" and the output's
# last lines, and counts into $passed and $failed.
check() {
    local name=$1
    shift
    if "$@" >"$check_log" 2>&1; then
        passed=$((passed + 1))
        echo "ok   $name"
    else
        failed=$((failed + 1))
        echo "FAIL $name"
        sed 's/^/    /' "$check_log" | tail -n 25
    fi
}
