#!/usr/bin/env bash
# Docs are code: every ```c block of README.md and the QUICK START of
# meshfix.h's top comment is compiled as C99 and as C++17 with -Wall
# -Wextra -Wpedantic -Werror (C++ without -Wmissing-field-initializers:
# `= {0}` warns there, the caller's business), after an #include of
# meshfix.h unless the snippet has its own; a snippet with main() is
# linked against the implementation and run.
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
        echo "ok   docs: $name compiles as C99 and C++17$(grep -q 'int main' "$snippet" && echo ', and runs')"
    else
        echo "FAIL docs: $name"
        sed 's/^/    /' "$out/$name.c.log" "$out/$name.cpp.log" 2>/dev/null | head -20
        failed=1
    fi
done
if [ "$count" -lt 8 ]; then
    echo "FAIL docs: only $count snippets found (README.md has at least 7, the header 1)"
    failed=1
fi
exit $failed
