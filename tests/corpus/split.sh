#!/usr/bin/env bash
# split.sh tune|heldout [CORPUS_DIR]: the package directories of a corpus
# (tests/corpus/fetch.sh's, default build/corpus) in one half of the split
# the project fixed before tuning anything on it: a package is held out when
# the first byte of the sha256 of its name is odd. Whole packages go one way,
# so no file of a held-out package is ever looked at while tuning. Report
# accuracy on `heldout`; tune on `tune`.
set -u
half=${1:-}
dir=${2:-build/corpus}
case $half in tune) want=0 ;; heldout) want=1 ;; *) echo "usage: split.sh tune|heldout [DIR]" >&2; exit 1 ;; esac
for d in "$dir"/*/; do
    name=$(basename "$d")
    byte=$(printf '%s' "$name" | sha256sum | cut -c1-2)
    [ $((16#$byte % 2)) -eq "$want" ] && printf '%s\n' "${d%/}"
done
exit 0
