#!/usr/bin/env bash
# fit.sh [--validate] - fits AUTO's confidence (make fit).
#
# Writes a row per patch (tests/eval/calibration.h) from every program that
# scores the default against a truth, on the TUNE halves only: the real
# models under eleven corruptions, the STL facet normals (with and without
# them as evidence), the assets' authored normals (both modes, as shipped
# and half reversed) and the generated trust families (small and large);
# then tests/eval/fit.c fits the weights and writes them into meshfix.h's
# table. --validate fits on half of the cases and prints the reliability
# on the other half instead (meshfix.h is left alone).
#
# Needs build/corpus (tests/corpus/fetch.sh) and build/assets
# (tests/corpus/fetch_assets.sh). About two minutes on two cores.
set -eu
cd "$(dirname "$0")/../.."
[ -d build/corpus ] && [ -f build/assets/manifest.tsv ] || {
    echo "fit.sh: needs build/corpus and build/assets: run tests/corpus/fetch.sh and tests/corpus/fetch_assets.sh" >&2
    exit 1
}
make -s build/models_eval build/stl_truth build/trust_eval build/assets_eval build/fit
rows=build/fitting
mkdir -p "$rows"
tune=$(bash tests/corpus/split.sh tune build/corpus)
# shellcheck disable=SC2086
build/models_eval --quiet --rows "$rows/models.rows" $tune >"$rows/models.out" &
# shellcheck disable=SC2086
build/stl_truth --rows "$rows/stl.rows" $tune >"$rows/stl.out"
# shellcheck disable=SC2086
build/stl_truth --normals --rows "$rows/stl_normals.rows" $tune >"$rows/stl_normals.out"
# the generated families and projection.stl (openscad is a tune package;
# buildings.obj, openfoam-examples, is held out)
scenes="--scene city --scene cavity_box --scene cavity_coarse --scene crossing --scene cad_part --scene spider"
# shellcheck disable=SC2086
build/trust_eval $scenes --scene projection_box --rows "$rows/trust.rows" >"$rows/trust.out"
# shellcheck disable=SC2086
build/trust_eval $scenes --size large --rows "$rows/trust_large.rows" >"$rows/trust_large.out"
build/assets_eval --split tune --rows "$rows/assets.rows" build/assets >"$rows/assets.out" 2>/dev/null
wait
if [ "${1:-}" = --validate ]; then
    build/fit --validate "$rows"/*.rows
else
    build/fit --table meshfix.h "$rows"/*.rows
fi
