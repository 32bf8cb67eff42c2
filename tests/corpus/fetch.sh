#!/usr/bin/env bash
# fetch.sh [DIR] - build a corpus of real triangle meshes from Debian packages.
#
# Nobody on the project wrote these files: they come from CAD tools, slicers,
# CFD and DEM tutorials, test suites of other mesh libraries. STL files carry
# the facet normals their exporter wrote, an independent truth of which way
# each triangle was meant to face (tests/eval/stl_truth.c scores against it).
#
# Each package is fetched with `apt-get download` (no dependencies, nothing
# installed) and unpacked with `dpkg-deb -x` into a temporary directory; every
# .stl .obj .ply .off file (any case, also gzip-compressed, as Debian ships
# documentation) is copied to DIR/<package>/<flattened path>. A file whose
# content is already in the corpus is left out, so no model counts twice.
#
# Idempotent: a package already extracted is skipped. A package that cannot
# be had is named with the reason and skipped; the script still exits 0.
# DIR/manifest.tsv lists every model with its sha256, package version and
# original path; when tests/corpus/manifest.tsv exists the two are compared,
# so a corpus built later can be checked against the one results came from.
#
# Needs: apt-get, dpkg-deb, sha256sum, gzip; `apt-get update` done.
set -u

PACKAGES="occt-misc assimp-testmodels openfoam-examples liggghts-doc
linuxcnc-uspace libsimbody-dev openscad-testing-data openscad cura
prusa-slicer netgen-doc libplb-doc lib3mf-doc ippsample-data admesh yade
lammps-examples invesalius freecad-common"

# Extensions kept; a trailing .gz is allowed and removed on copy.
MODEL_REGEX='.*\.(stl|obj|ply|off)(\.gz)?$'

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
dir=${1:-$root/build/corpus}
mkdir -p "$dir" || exit 1
dir=$(cd "$dir" && pwd)

work=$(mktemp -d) || exit 1
trap 'rm -rf "$work"' EXIT
# As root, apt downloads as its sandbox user _apt, which cannot write into
# a private temporary directory: download as root instead.
if [ "$(id -u)" = 0 ]; then
    apt_sandbox=(-o APT::Sandbox::User=root)
else
    apt_sandbox=()
fi

downloaded_bytes=0
unavailable=""
reason="" # why fetch_package failed

# Stored name of an extracted file: path below the package root with the
# common usr/share/ prefix dropped, '/' turned into '__', .gz removed.
flat_name() {
    local path=${1#./}
    path=${path#usr/share/}
    path=${path%.gz}
    printf '%s\n' "${path//\//__}"
}

# sha256 of a file's content after gunzip when it is compressed.
content_sha() {
    case $1 in
    *.gz) gzip -dc -- "$1" | sha256sum | cut -d' ' -f1 ;;
    *) sha256sum -- "$1" | cut -d' ' -f1 ;;
    esac
}

# Hashes of every model already in the corpus, one a line.
known_hashes() {
    cat "$dir"/*/.manifest 2>/dev/null | cut -f1
}

# Copies the models of an unpacked package from $1 into $2 and writes
# $2/.manifest: sha256, bytes, package, version, stored path, original path;
# copies of models already in the corpus are listed in $2/.duplicates.
copy_models() {
    local from=$1 to=$2 package=$3 version=$4
    local known="$work/known" file name sha
    known_hashes >"$known"
    (cd "$from" && find . -type f -regextype posix-extended -iregex "$MODEL_REGEX" | LC_ALL=C sort) |
        while IFS= read -r file; do
            sha=$(content_sha "$from/$file")
            if grep -qx "$sha" "$known"; then # a copy of a model already kept
                printf '%s\t/%s\n' "$sha" "${file#./}" >>"$to/.duplicates"
                continue
            fi
            echo "$sha" >>"$known"
            name=$(flat_name "$file")
            if [ -e "$to/$name" ]; then # foo.stl and foo.stl.gz, both different
                name="${sha:0:8}-$name"
            fi
            case $file in
            *.gz) gzip -dc -- "$from/$file" >"$to/$name" ;;
            *) cp -- "$from/$file" "$to/$name" ;;
            esac
            printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$sha" "$(stat -c %s "$to/$name")" \
                "$package" "$version" "$package/$name" "/${file#./}" >>"$to/.manifest"
        done
    touch "$to/.manifest"
}

# Downloads and unpacks one package into DIR/<package>; on failure returns
# non-zero with the cause in $reason.
fetch_package() {
    local package=$1 version deb partial="$dir/$1.partial"
    version=$(apt-cache show --no-all-versions "$package" 2>/dev/null | sed -n 's/^Version: //p')
    if [ -z "$version" ]; then
        reason="not known to apt-cache"
        return 1
    fi
    rm -rf "$work/deb" "$work/root" "$partial"
    mkdir -p "$work/deb" "$work/root" "$partial"
    if ! (cd "$work/deb" && apt-get download -q "${apt_sandbox[@]}" "$package" >/dev/null 2>"$work/apt.err"); then
        reason="apt-get download failed: $(tail -n 1 "$work/apt.err")"
        return 1
    fi
    deb=$(ls "$work"/deb/*.deb)
    downloaded_bytes=$((downloaded_bytes + $(stat -c %s "$deb")))
    if ! dpkg-deb -x "$deb" "$work/root"; then
        reason="dpkg-deb could not unpack $(basename "$deb")"
        return 1
    fi
    copy_models "$work/root" "$partial" "$package" "$version"
    echo "$version" >"$partial/.complete"
    # The rename is the commit: a directory named after its package is whole.
    rm -rf "${dir:?}/$package"
    mv "$partial" "$dir/$package"
}

# Compares the manifest built here with the one kept in the repository.
compare_manifest() {
    local kept="$here/manifest.tsv"
    [ -f "$kept" ] || return 0
    if diff <(cut -f1,5 "$kept") <(cut -f1,5 "$dir/manifest.tsv") >/dev/null; then
        echo "manifest: identical to tests/corpus/manifest.tsv"
    else
        echo "manifest: differs from tests/corpus/manifest.tsv (other package versions?):"
        diff <(cut -f1,5 "$kept") <(cut -f1,5 "$dir/manifest.tsv") | grep '^[<>]' | head -20 | sed 's/^/    /'
    fi
}

start=$(date +%s)
for package in $PACKAGES; do
    if [ -f "$dir/$package/.complete" ]; then
        echo "skip  $package (already extracted)"
    elif fetch_package "$package"; then
        echo "fetch $package $(cat "$dir/$package/.complete"): $(wc -l <"$dir/$package/.manifest") models"
    else
        echo "MISS  $package: $reason; skipped"
        unavailable="$unavailable $package"
        rm -rf "$dir/$package.partial"
    fi
done

for package in $PACKAGES; do
    cat "$dir/$package/.manifest" 2>/dev/null
done >"$dir/manifest.tsv"

files=$(wc -l <"$dir/manifest.tsv")
stl_files=$(cut -f5 "$dir/manifest.tsv" | grep -ci '\.stl$')
packages=$(cut -f3 "$dir/manifest.tsv" | sort -u | wc -l)
corpus_bytes=$(awk -F'\t' '{ s += $2 } END { print s + 0 }' "$dir/manifest.tsv")
mb() { awk -v b="$1" 'BEGIN { printf "%.1f", b / 1048576 }'; }
duplicates=$(cat "$dir"/*/.duplicates 2>/dev/null | wc -l)
echo "corpus: $files files ($stl_files STL) from $packages packages, $(mb "$corpus_bytes") MB in $dir," \
    "$duplicates duplicates left out" \
    "(downloaded $(mb "$downloaded_bytes") MB in $(($(date +%s) - start)) s)"
if [ -n "$unavailable" ]; then
    echo "unavailable:$unavailable"
fi
compare_manifest
exit 0
