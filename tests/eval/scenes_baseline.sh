#!/usr/bin/env bash
# scenes_baseline.sh [REV|worktree] [SIZES] - score meshfix.h on the generated
# scenes of tests/scenes.h (tests/eval/scenes_eval.c) and print the tables of
# tests/eval/RESULTS-scenes-baseline.md as markdown on standard output.
#
# REV (default HEAD) is the commit whose meshfix.h is measured, read with
# `git show` so the work tree is never touched; `worktree` measures the
# meshfix.h in the work tree as it is. SIZES is "small large" by default.
# CSV files and the binary go to build/eval/scenes/. About 4 minutes for both
# sizes on the 2-core machine.
set -eu
cd "$(dirname "$0")/../.."
rev=${1:-HEAD}
sizes=${2:-small large}
out=build/eval/scenes
policies="default seed majority outward visibility up"
mkdir -p "$out/header"

if [ "$rev" = worktree ]; then
    cp meshfix.h "$out/header/meshfix.h"
    described="the work tree's meshfix.h (uncommitted changes over $(git rev-parse --short HEAD))"
else
    git show "$rev:meshfix.h" >"$out/header/meshfix.h"
    described="meshfix.h of commit $(git rev-parse --short "$rev")"
fi
# scenes_eval.c includes "meshfix.h" first: the copy in $out/header wins, and
# the include guards make examples/meshio.h's "../meshfix.h" a no-op.
cc -std=c99 -O2 -I"$out/header" -I. -o "$out/scenes_eval" tests/eval/scenes_eval.c -lm

echo "Measured $(date -u '+%Y-%m-%d %H:%M UTC') on $described, $(nproc) cores."
echo
echo '```'
echo "cc -std=c99 -O2 -I$out/header -I. -o $out/scenes_eval tests/eval/scenes_eval.c -lm"
for size in $sizes; do
    echo "$out/scenes_eval --size $size --parts                  # default policy (options NULL)"
    echo "$out/scenes_eval --size $size --policy NAME --csv      # NAME: $policies"
done
echo '```'

for size in $sizes; do
    for policy in $policies; do
        "$out/scenes_eval" --size "$size" --policy "$policy" --csv >"$out/$size-$policy.csv" 2>"$out/$size-$policy.err" ||
            [ $? -eq 2 ]
    done
    "$out/scenes_eval" --size "$size" --parts >"$out/$size-default-parts.txt" 2>&1 || [ $? -eq 2 ]

    echo
    echo "## Default policy, $size scenes"
    echo
    echo '```'
    grep -v '^    part' "$out/$size-default-parts.txt"
    echo '```'
    echo
    echo "Parts not all right after the repair (\`--parts\`):"
    echo
    echo '```'
    awk '/^    part/ { sub(/^    /, ""); printf "%-28s %s\n", key, $0; next } { key = $1 " " $2 }' "$out/$size-default-parts.txt"
    echo '```'

    # One row per (scene, corruption): after% by count for each policy, and
    # damaged in brackets where not 0. CSV columns: 1 scene, 2 size,
    # 3 corruption, 4 policy, 5 triangles, 6 scored, 7 right_before,
    # 8 right_after, 9 area_scored, 10 area_right_after, 11 damaged, 12 flips,
    # 13 changed_otherwise, 14 undecided, 15 undecided_up_after, 16 ms.
    echo
    echo "## All policies, $size scenes: % of scored triangles right after (damaged)"
    echo
    files=""
    for policy in $policies; do files="$files $out/$size-$policy.csv"; done
    # shellcheck disable=SC2086
    awk -F, -v policies="$policies" '
    BEGIN { np = split(policies, name, " ") }
    FNR == 1 { p++; next }
    {
        key = $1 " | " $3
        if (!(key in seen)) { seen[key] = 1; order[++n] = key; before[key] = $6 > 0 ? sprintf("%.2f", 100 * $7 / $6) : "-" }
        cell = $6 > 0 ? sprintf("%.2f", 100 * $8 / $6) : "-"
        if ($11 > 0) cell = cell " (" $11 ")"
        value[key, p] = cell
        time[key, p] = $16
    }
    END {
        header = "| scene | corruption | before%"
        rule = "|---|---|--:"
        for (i = 1; i <= np; i++) { header = header " | " name[i]; rule = rule "|--:" }
        print header " |"
        print rule "|"
        for (k = 1; k <= n; k++) {
            line = "| " order[k] " | " before[order[k]]
            for (i = 1; i <= np; i++) line = line " | " value[order[k], i]
            print line " |"
        }
    }' $files
    echo
    echo "Totals per policy ($size): counts over all rows; unchanged = correct and shuffled inputs returned with no flip."
    echo
    echo "| policy | triangles | scored | before% | after% | damaged | flips | undecided | up% | unchanged | ms | ms/100k |"
    echo "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|"
    # shellcheck disable=SC2086
    awk -F, '
    function pct(a, b) { return b > 0 ? sprintf("%.2f", 100 * a / b) : "-" }
    FNR == 1 { if (policy != "") emit(); policy = ""; for (k = 5; k <= 16; k++) sum[k] = 0; inputs = 0; kept = 0; next }
    {
        policy = $4
        for (k = 5; k <= 16; k++) sum[k] += $k
        if ($3 == "correct" || $3 == "shuffled") { inputs++; kept += $12 == 0 }
    }
    function emit() {
        printf "| %s | %d | %d | %s | %s | %d | %d | %d | %s | %d of %d | %.0f | %.1f |\n", policy, sum[5], sum[6],
            pct(sum[7], sum[6]), pct(sum[8], sum[6]), sum[11], sum[12], sum[14], pct(sum[15], sum[14]), kept, inputs,
            sum[16], (sum[5] > 0 ? sum[16] * 1e5 / sum[5] : 0)
    }
    END { if (policy != "") emit() }' $files
done
