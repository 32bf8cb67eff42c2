#!/usr/bin/env bash
# baseline.sh [REV|worktree] [CORPUS] - score meshfix.h on the STL corpus under
# the default, seed and majority policies and print the tables of
# tests/eval/RESULTS-baseline.md as markdown on standard output.
#
# REV (default HEAD) is the commit whose meshfix.h is measured, read with
# `git show` so the work tree is never touched; `worktree` measures the
# meshfix.h in the work tree as it is. CORPUS defaults to build/corpus
# (tests/corpus/fetch.sh). CSV files and the binary go to build/eval/.
set -eu
cd "$(dirname "$0")/../.."
rev=${1:-HEAD}
corpus=${2:-build/corpus}
out=build/eval
policies="default seed majority"
mkdir -p "$out/header"

if [ "$rev" = worktree ]; then
    cp meshfix.h "$out/header/meshfix.h"
    described="the work tree's meshfix.h (uncommitted changes over $(git rev-parse --short HEAD))"
else
    git show "$rev:meshfix.h" >"$out/header/meshfix.h"
    described="meshfix.h of commit $(git rev-parse --short "$rev")"
fi
# stl_truth.c includes "meshfix.h": with no copy beside it, -I decides which.
cc -std=c99 -O2 -I"$out/header" -o "$out/stl_truth" tests/eval/stl_truth.c -lm

# Exit status 2 (a meshfix call failed on a file) is a result, not a stop:
# such files carry a FAILED note in the tables.
for policy in $policies; do
    "$out/stl_truth" --csv --policy "$policy" "$corpus" >"$out/$policy.csv" || [ $? -eq 2 ]
    { "$out/stl_truth" --policy "$policy" "$corpus" || [ $? -eq 2 ]; } | sed -n '/^total/,$p' >"$out/$policy.totals"
done

echo "Measured $(date -u '+%Y-%m-%d %H:%M UTC') on $described, corpus $corpus"
echo "($(wc -l <"$corpus/manifest.tsv") files in its manifest.tsv, sha256 $(sha256sum "$corpus/manifest.tsv" | cut -c1-16)...)."
echo
echo '```'
echo "cc -std=c99 -O2 -I$out/header -o $out/stl_truth tests/eval/stl_truth.c -lm"
for policy in $policies; do
    echo "$out/stl_truth --policy $policy $corpus"
done
echo '```'
echo
echo "## Totals"
for policy in $policies; do
    echo
    echo "Policy \`$policy\`:"
    echo
    echo '```'
    cat "$out/$policy.totals"
    echo '```'
done

# One row per file, joining the three CSVs on the path. CSV columns: 1 file,
# 2 format, 3 truth, 4 triangles, 5 clear, 6-8 unclear counts,
# 9 agree_shipped, 10 agree_best, 11 agree_repaired, 12 damaged,
# 13 agree_half, 14 orient_ms, 15 patches, 16 components, 17 edges_boundary,
# 18 edges_inconsistent, 19 note (the only field set for a refused file).
awk -F, -v corpus="$corpus/" '
function pct(part, whole) { return whole > 0 ? sprintf("%.2f", int(10000 * part / whole) / 100) : "-" }
function name(path) { sub("^" corpus, "", path); gsub("__", "/", path); return path }
FNR == 1 { policy++; next }
$5 == "" { if (policy == 1) refused[++nrefused] = $0; next }
policy == 1 {
    order[++n] = $1
    row[$1] = sprintf("| %s | %s | %s | %s | %s | %s", name($1), $3, $4, $5, pct($9, $5), pct($10, $5))
    tail[$1] = sprintf(" %.1f | %s | %s | %s | %s |", $14, $15, $16, $17, $18)
}
{ row[$1] = row[$1] sprintf(" | %s | %s | %s", pct($11, $5), $12, pct($13, $5)) }
END {
    print ""
    print "## Per file"
    print ""
    print "% of clear triangles that agree with their stored normal. ship: as shipped; best: the most that"
    print "turning whole patches can reach; fix, dmg: after repair of the shipped winding (dmg: clear"
    print "triangles that agreed before and not after); half: after reversing a random half (seed 1) and"
    print "repairing. ms, patches, parts (components), bnd (boundary edges) and inc (edges inconsistent as"
    print "shipped) are from the default run."
    print ""
    print "| file | truth | triangles | clear | ship% | best% | default fix% | dmg | half% | seed fix% | dmg | half% | majority fix% | dmg | half% | ms | patches | parts | bnd | inc |"
    print "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|"
    for (i = 1; i <= n; i++) print row[order[i]] " |" tail[order[i]]
    print ""
    print "## Not scored"
    print ""
    for (i = 1; i <= nrefused; i++) {
        split(refused[i], f, ",")
        note = refused[i]
        for (k = 1; k <= 18; k++) sub("^[^,]*,", "", note)
        gsub("\"", "", note)
        print "- " name(f[1]) ": " note
    }
}' "$out/default.csv" "$out/seed.csv" "$out/majority.csv"
