#!/usr/bin/env bash
# Docs are code: every ```c block of README.md and the QUICK START of
# meshfix.h's top comment is compiled as C99 and as C++17 with -Wall
# -Wextra -Wpedantic -Werror (C++ without -Wmissing-field-initializers:
# `= {0}` warns there, the caller's business), after an #include of
# meshfix.h unless the snippet has its own; a snippet with main() is
# linked against the implementation and run.
# Then the command-line tool's options (built with make when missing):
# every one the parser takes in --help, every one in --help in README.md.
# Usage: tests/docs.sh OUTDIR; prints "ok"/"FAIL" lines, exits 1 on a failure.
set -u
cd "$(dirname "$0")/.."
out=${1:-build/docs}
CC=${CC:-cc}
CXX=${CXX:-c++}
mkdir -p "$out"
rm -f "$out"/snippet_*.c

# README: the lines between ```c and ```, one file per block
awk -v out="$out" '
    /^```c[[:space:]]*$/ { n++; file = sprintf("%s/snippet_readme_%02d.c", out, n); inside = 1; next }
    /^```/ && inside { inside = 0; close(file); next }
    inside { print > file }
' README.md
# meshfix.h: the QUICK START block, its 7-space indent removed
awk -v out="$out" '
    /^   QUICK START/ { inside = 1; file = out "/snippet_header_quick_start.c"; next }
    /^   [A-Z][A-Z &]+$/ && inside { inside = 0 }
    inside { sub(/^       /, ""); print > file }
' meshfix.h

printf '#define MESHFIX_IMPLEMENTATION\n#include "meshfix.h"\n' >"$out/implementation.c"
$CC -std=c99 -c -I. "$out/implementation.c" -o "$out/implementation.o" || exit 1

failed=0
count=0
npass=0
nfail=0
for snippet in "$out"/snippet_*.c; do
    name=$(basename "$snippet" .c)
    count=$((count + 1))
    unit="$out/unit_$name.c"
    if grep -q '#include "meshfix.h"' "$snippet"; then
        cp "$snippet" "$unit"
    else
        { printf '#include "meshfix.h"\n'; cat "$snippet"; } >"$unit"
    fi
    ok=1
    $CC -std=c99 -Wall -Wextra -Wpedantic -Werror -I. -c "$unit" -o "$out/$name.o" 2>"$out/$name.c.log" || ok=0
    $CXX -x c++ -std=c++17 -Wall -Wextra -Wpedantic -Werror -Wno-missing-field-initializers -I. -c "$unit" \
        -o "$out/$name.cpp.o" 2>"$out/$name.cpp.log" || ok=0
    if [ "$ok" -eq 1 ] && grep -q 'int main' "$snippet"; then
        if grep -q 'MESHFIX_IMPLEMENTATION' "$snippet"; then
            $CC "$out/$name.o" -o "$out/$name" -lm && "$out/$name" >/dev/null || ok=0
        else
            $CC "$out/$name.o" "$out/implementation.o" -o "$out/$name" -lm && "$out/$name" >/dev/null || ok=0
        fi
    fi
    if [ "$ok" -eq 1 ]; then
        npass=$((npass + 1))
        echo "ok   docs: $name compiles as C99 and C++17$(grep -q 'int main' "$snippet" && echo ', and runs')"
    else
        nfail=$((nfail + 1))
        echo "FAIL docs: $name"
        sed 's/^/    /' "$out/$name.c.log" "$out/$name.cpp.log" 2>/dev/null | head -20
        failed=1
    fi
done
# The tool's options: every option its parser takes (tools/meshfix/main.cpp,
# each `a == "-..."`) is in `meshfix --help`, and every option of --help
# (the option column of its lines that start with "  -") is in README.md's
# options table (the first cell of its rows that start with "| `-").
options_documented() {
    [ -x build/meshfix ] && [ build/meshfix -nt tools/meshfix/main.cpp ] || ${MAKE:-make} -s build/meshfix >/dev/null || return 1
    build/meshfix --help >"$out/help.txt" || return 1
    sed -n 's/^  \(-.*\)/\1/p' "$out/help.txt" | sed 's/  .*//' | grep -oE '(^|[ ,])--?[a-z][a-z-]*' |
        sed 's/^[ ,]*//' | sort -u >"$out/help_options.txt"
    grep -oE 'a == "--?[a-z][a-z-]*"' tools/meshfix/main.cpp | sed 's/^a == "//; s/"$//' | sort -u >"$out/parser_options.txt"
    sed -n 's/^| \(`-[^|]*\) |.*/\1/p' README.md | grep -oE '`--?[a-z][a-z-]*' | sed 's/^`//' | sort -u \
        >"$out/readme_options.txt"
    local ok=1 n
    n=$(wc -l <"$out/help_options.txt")
    [ "$n" -ge 10 ] || { echo "only $n options found in --help"; ok=0; }
    for o in $(comm -23 "$out/parser_options.txt" "$out/help_options.txt"); do
        echo "the tool takes $o, its --help does not say it"; ok=0
    done
    for o in $(comm -23 "$out/help_options.txt" "$out/readme_options.txt"); do
        echo "--help has $o, README.md's options table does not"; ok=0
    done
    for o in $(comm -13 "$out/parser_options.txt" "$out/readme_options.txt"); do
        echo "README.md's options table has $o, the tool does not take it"; ok=0
    done
    [ "$ok" -eq 1 ] && echo "$n options: $(tr '\n' ' ' <"$out/help_options.txt")"
}
# part NAME SAYS_OK SAYS_FAIL: runs the function NAME into a log; passes
# when it returns 0, saying SAYS_OK with "%s" as the log's first line.
part() {
    if "$1" >"$out/$1.log" 2>&1; then
        npass=$((npass + 1))
        echo "ok   docs: $(printf "$2" "$(head -n 1 "$out/$1.log")")"
    else
        nfail=$((nfail + 1))
        echo "FAIL docs: $3"
        sed 's/^/    /' "$out/$1.log" | head -20
        failed=1
    fi
}
part options_documented "every option the tool takes is in --help, and every one in --help is in README.md's table (%s)" \
    "the tool's options, --help and README.md's table disagree"
# The policies the tool takes (its error for an unknown one lists them, from
# meshfix_policy_info) are README.md's --policy row, in the header's order.
policies_documented() {
    local tool readme
    tool=$(build/meshfix --policy no-such-policy in.obj out.obj 2>&1 | sed -n 's/.*(\(.*\)).*/\1/p' | tr -d ' ')
    readme=$(sed -n 's/^| `--policy P` | \(.*\) |$/\1/p' README.md | grep -oE '`[a-z]+`' | tr -d '`' | paste -sd, -)
    [ -n "$tool" ] && [ "$tool" = "$readme" ] && echo "$tool" || { echo "the tool: $tool; README.md: $readme"; return 1; }
}
part policies_documented "README.md's --policy row names the tool's policies, the header's (%s)" \
    "README.md's --policy row and the tool's policies disagree"
if [ "$count" -lt 8 ]; then
    nfail=$((nfail + 1))
    echo "FAIL docs: only $count snippets found (README.md has at least 7, the header 1)"
    failed=1
fi
echo "$npass passed, $nfail failed"
exit $failed
