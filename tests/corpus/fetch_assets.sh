#!/usr/bin/env bash
# fetch_assets.sh [DIR] - an evaluation corpus of real assets whose authors
# stored normals, from Debian packages (default DIR: build/assets).
#
# Game data, furniture libraries, robot models and CAD/scene samples whose
# files carry the normals their exporter wrote: OBJ `vn`, PLY nx ny nz, glTF
# NORMAL, STL facet normals. tests/eval/assets_eval.cpp derives from them
# which way each triangle was meant to face and scores the repair against it.
#
# As tests/corpus/fetch.sh: each package is fetched with `apt-get download`
# (no dependencies, nothing installed) and unpacked with `dpkg-deb -x` into
# a temporary directory; a file whose content is already in the corpus is
# left out; a package already extracted is skipped (idempotent); a package
# that cannot be had is named and skipped, and the script still exits 0.
#
# What is kept, per file (any case, also .gz):
#   .obj        when a face corner names a `vn`
#   .ply        when the vertex element has nx ny nz
#   .gltf .glb  when a primitive has a NORMAL attribute ("NORMAL" in the
#               JSON); a .gltf goes into a directory of its own with the
#               buffers it names (images are not needed and not copied)
#   .stl        always (every facet stores a normal; zero ones give no truth)
#   .dae        converted to .glb with `assimp export` (assimp-utils) when
#               the source has an <input semantic="NORMAL"> and no file of
#               the same name in another kept format lies beside it (robot
#               packages ship foo.dae and foo.stl of one mesh: the STL is
#               kept, as shipped, and the model counts once). Checked with
#               assimp 5.2.5: with no post-processing flags (none are given
#               here) its Collada importer copies the stored normals
#               unchanged, and a copy of a file with its NORMAL inputs
#               renamed comes out with no normals at all, so it invents
#               none. The output must have NORMAL too.
# Not kept: .off (the tool does not read NOFF normals); .ase, .3ds and
# other formats assimp would have to convert: its 3DS and ASE importers
# compute normals from smoothing groups (for ASE the file's own
# *MESH_VERTEXNORMAL values are ignored: output identical with them
# deleted), so their normals would be assimp's, not the author's.
# Archives: the .sh3f furniture libraries (zip) are opened and their
# .obj files treated as above (original path ARCHIVE!/MEMBER).
# Duplicates: the tune packages are read first, so a file that ships in a
# tune package and in a held-out one counts for tune only (libsimbody-dev
# and dart-doc ship the same Atlas robot STL files).
#
# THE SPLIT (fixed before anything was tuned on this corpus). Every
# package goes whole to "tune" or "heldout", so no file of a held-out
# package is ever seen while tuning:
#   1. packages already in tests/corpus/fetch.sh (whose files the project
#      has scored against before) are tune;
#   2. the others, family by family in order of the sha256 of the package
#      name (printf %s NAME | sha256sum), each go to the side that has
#      fewer packages of that family so far (counting step 1), a tie to
#      heldout.
# The split depends only on the package list below, not on what was
# downloaded or on any result. Families: game (3D games' data), furniture
# (interior-design libraries: Sweet Home 3D's, Minetest's homedecor),
# robot (robot models of simulators), cad (CAD, scientific and scene
# samples, loaders' test models).
#
# DIR/manifest.tsv, one line per kept file after a '#' header:
#   sha256 bytes package version family split stored original note
# (sha256 of the content as shipped, for a .gltf of it and its buffers;
# stored relative to DIR; note: how it was converted, or -). Files left
# out are listed with the reason in DIR/<package>/.skipped. When
# tests/corpus/assets_manifest.tsv exists the two are compared.
#
# Needs: apt-get, dpkg-deb, sha256sum, gzip, unzip (for .sh3f),
# assimp (for .dae; without it they are skipped and counted); `apt-get
# update` done. sweethome3d itself is not listed: the OBJ of its default
# catalog carry no normals.
set -u

# package:family
PACKAGES="
castle-game-engine-doc:game
neverball-common:game
bouncy:game
gltron:game
brutalchess:game
performous:game
dustracing2d-data:game
spring-common:game
minetest-data:game
minetest-mod-moreblocks:game
minetest-mod-pipeworks:game
minetest-mod-mesecons:game
minetest-mod-basic-materials:game
sweethome3d-furniture:furniture
minetest-mod-homedecor:furniture
dart-doc:robot
libsimbody-dev:robot
libmujoco-samples:robot
assimp-testmodels:cad
linuxcnc-uspace:cad
cura:cad
uranium-plugins:cad
stellarium-data:cad
opencv-doc:cad
qtdatavisualization5-examples:cad
sumo-tools:cad
psychtoolbox-3-common:cad
python3-pyglet:cad
python-kivy-examples:cad
structure-synth:cad
"

CANDIDATE_REGEX='.*\.(obj|ply|stl|gltf|glb|dae|off)(\.gz)?$'

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
dir=${1:-$root/build/assets}
mkdir -p "$dir" || exit 1
dir=$(cd "$dir" && pwd)

work=$(mktemp -d) || exit 1
trap 'rm -rf "$work"' EXIT
if [ "$(id -u)" = 0 ]; then
    apt_sandbox=(-o APT::Sandbox::User=root)
else
    apt_sandbox=()
fi
have_assimp=$(command -v assimp >/dev/null 2>&1 && echo yes || echo no)
have_unzip=$(command -v unzip >/dev/null 2>&1 && echo yes || echo no)
assimp_version=$(dpkg-query -W -f '${Version}' assimp-utils 2>/dev/null || echo unknown)

name_sha() { printf %s "$1" | sha256sum | cut -c1-64; }

# ---- the split ----

# packages of tests/corpus/fetch.sh
seen=" $(sed -n '/^PACKAGES="/,/"$/p' "$here/fetch.sh" | sed 's/^PACKAGES="//; s/"$//' | tr '\n' ' ') "

declare -A family_of split_of
for entry in $PACKAGES; do
    family_of[${entry%%:*}]=${entry#*:}
done
for family in game furniture robot cad; do
    tune=0 heldout=0
    for entry in $PACKAGES; do
        package=${entry%%:*}
        if [ "${entry#*:}" = "$family" ] && [[ $seen == *" $package "* ]]; then
            split_of[$package]=tune
            tune=$((tune + 1))
        fi
    done
    for package in $(for entry in $PACKAGES; do
        package=${entry%%:*}
        if [ "${entry#*:}" = "$family" ] && [[ $seen != *" $package "* ]]; then
            echo "$(name_sha "$package") $package"
        fi
    done | LC_ALL=C sort | cut -d' ' -f2); do
        if [ "$tune" -lt "$heldout" ]; then
            split_of[$package]=tune
            tune=$((tune + 1))
        else
            split_of[$package]=heldout
            heldout=$((heldout + 1))
        fi
    done
done

# ---- files ----

downloaded_bytes=0
unavailable=""
reason=""

# Stored name: the path below the package root with usr/share/ dropped,
# '/' turned into '__', .gz removed ('!' of an archive member kept).
flat_name() {
    local path=${1#/}
    path=${path#usr/share/}
    path=${path%.gz}
    path=${path%.GZ}
    printf '%s\n' "${path//\//__}"
}

lower() { printf '%s\n' "$1" | tr '[:upper:]' '[:lower:]'; }

# Whether an OBJ has a face corner that names a normal (v/vt/vn or v//vn).
obj_has_normals() {
    grep -qE '^[[:space:]]*f[[:space:]].*[^[:space:]/]+/[^[:space:]/]*/-?[0-9]' "$1"
}

# Whether a PLY's header declares nx ny nz.
ply_has_normals() {
    head -c 65536 "$1" | tr -d '\r' | sed -n '1,/^end_header/p' | grep -qE '^property[[:space:]]+[a-z0-9]+[[:space:]]+nx$'
}

# Whether a .dae has a twin beside it: the same name in a format kept as
# shipped (.stl, .glb; .obj, .ply, .gltf with normals).
dae_twin() {
    local stem=${1%.*} twin
    stem=${stem%.[dD][aA][eE]}
    for twin in "$stem".*; do
        [ -f "$twin" ] || continue
        case $(lower "${twin##*.}") in
        stl | glb) return 0 ;;
        obj) obj_has_normals "$twin" && return 0 ;;
        ply) ply_has_normals "$twin" && return 0 ;;
        gltf) grep -aq '"NORMAL"' "$twin" && return 0 ;;
        esac
    done
    return 1
}

# The buffer files a .gltf names (not data: URIs, not images or shaders).
gltf_buffers() {
    grep -o '"uri"[[:space:]]*:[[:space:]]*"[^"]*"' "$1" | sed 's/^"uri"[[:space:]]*:[[:space:]]*"//; s/"$//' |
        grep -v '^data:' | grep -viE '\.(png|jpe?g|ktx2?|webp|dds|gif|bmp|tga|glsl|vert|frag)$' | sed 's/%20/ /g'
}

# Copies the kept files of an unpacked tree $1 into $2: writes $2/.manifest
# and $2/.skipped (reason, original path).
copy_models() {
    local from=$1 to=$2 package=$3 version=$4
    local family=${family_of[$package]} split=${split_of[$package]}
    local known="$work/known" list="$work/list" file original plain ext name sha stored note buffers b ok
    cat "$dir"/*/.manifest 2>/dev/null | cut -f1 >"$known"
    : >"$list"
    # plain files, then the .obj members of .sh3f archives
    (cd "$from" && find . -type f -regextype posix-extended -iregex "$CANDIDATE_REGEX" | LC_ALL=C sort) |
        while IFS= read -r file; do printf '%s\t%s\n' "$from/${file#./}" "/${file#./}"; done >>"$list"
    (cd "$from" && find . -type f -iname '*.sh3f' | LC_ALL=C sort) | while IFS= read -r file; do
        if [ "$have_unzip" = no ]; then
            printf 'unzip not installed\t/%s\n' "${file#./}" >>"$to/.skipped"
            continue
        fi
        local out="$work/archives/${file#./}"
        mkdir -p "$out"
        unzip -qq -o "$from/$file" '*.obj' '*.OBJ' -d "$out" 2>/dev/null
        (cd "$out" && find . -type f -iname '*.obj' | LC_ALL=C sort) | while IFS= read -r member; do
            printf '%s\t%s\n' "$out/${member#./}" "/${file#./}!/${member#./}"
        done >>"$list"
    done
    while IFS=$'\t' read -r file original; do
        plain=$file
        case $(lower "$file") in
        *.gz)
            plain="$work/plain/$(basename "${file%.*}")"
            mkdir -p "$work/plain"
            gzip -dc -- "$file" >"$plain" 2>/dev/null || { printf 'bad gzip\t%s\n' "$original" >>"$to/.skipped"; continue; }
            ;;
        esac
        ext=$(lower "${plain##*.}")
        buffers=""
        case $ext in
        obj) obj_has_normals "$plain" || { printf 'no normals\t%s\n' "$original" >>"$to/.skipped"; continue; } ;;
        ply) ply_has_normals "$plain" || { printf 'no normals\t%s\n' "$original" >>"$to/.skipped"; continue; } ;;
        gltf | glb)
            grep -aq '"NORMAL"' "$plain" || { printf 'no normals\t%s\n' "$original" >>"$to/.skipped"; continue; }
            if [ "$ext" = gltf ]; then
                buffers=$(gltf_buffers "$plain")
                ok=yes
                while IFS= read -r b; do
                    [ -n "$b" ] || continue
                    case $b in
                    /* | *..* | *:*) ok="buffer outside its directory: $b" ;;
                    *) [ -f "$(dirname "$file")/$b" ] || ok="buffer missing: $b" ;;
                    esac
                done <<<"$buffers"
                [ "$ok" = yes ] || { printf '%s\t%s\n' "$ok" "$original" >>"$to/.skipped"; continue; }
            fi
            ;;
        stl) ;;
        dae)
            grep -q 'semantic="NORMAL"' "$plain" || { printf 'no normals\t%s\n' "$original" >>"$to/.skipped"; continue; }
            dae_twin "$file" && { printf 'twin of a file beside it\t%s\n' "$original" >>"$to/.skipped"; continue; }
            [ "$have_assimp" = yes ] || { printf 'assimp not installed\t%s\n' "$original" >>"$to/.skipped"; continue; }
            ;;
        off) printf 'OFF: normals not read by the tool\t%s\n' "$original" >>"$to/.skipped"; continue ;;
        *) continue ;;
        esac
        if [ -n "$buffers" ]; then
            sha=$( { cat -- "$plain"; while IFS= read -r b; do [ -n "$b" ] && cat -- "$(dirname "$file")/$b"; done <<<"$buffers"; } |
                sha256sum | cut -c1-64)
        else
            sha=$(sha256sum -- "$plain" | cut -c1-64)
        fi
        if grep -qx "$sha" "$known"; then
            printf 'duplicate %s\t%s\n' "${sha:0:12}" "$original" >>"$to/.skipped"
            continue
        fi
        name=$(flat_name "$original")
        name=${name//!/}
        note=-
        case $ext in
        gltf)
            # a directory of its own, with the buffers at their relative paths
            stored="${name%.*}/$(basename "$plain")"
            [ -e "$to/$stored" ] && stored="${sha:0:8}-${name%.*}/$(basename "$plain")"
            mkdir -p "$to/$(dirname "$stored")"
            cp -- "$plain" "$to/$stored"
            while IFS= read -r b; do
                [ -n "$b" ] || continue
                mkdir -p "$to/$(dirname "$stored")/$(dirname "$b")"
                cp -- "$(dirname "$file")/$b" "$to/$(dirname "$stored")/$b"
            done <<<"$buffers"
            ;;
        dae)
            stored="$name.glb"
            [ -e "$to/$stored" ] && stored="${sha:0:8}-$stored"
            if ! (cd "$work" && assimp export "$plain" "$work/converted.glb" >"$work/assimp.log" 2>&1) ||
                ! grep -aq '"NORMAL"' "$work/converted.glb" 2>/dev/null; then
                printf 'assimp export failed or lost the normals\t%s\n' "$original" >>"$to/.skipped"
                rm -f "$work/converted.glb"
                continue
            fi
            mv "$work/converted.glb" "$to/$stored"
            note="assimp-$assimp_version dae->glb"
            ;;
        *)
            stored=$name
            [ -e "$to/$stored" ] && stored="${sha:0:8}-$name"
            cp -- "$plain" "$to/$stored"
            ;;
        esac
        echo "$sha" >>"$known"
        printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$sha" "$(stat -c %s "$to/$stored")" "$package" "$version" \
            "$family" "$split" "$package/$stored" "$original" "$note" >>"$to/.manifest"
    done <"$list"
    touch "$to/.manifest" "$to/.skipped"
}

fetch_package() {
    local package=$1 version deb partial="$dir/$1.partial"
    version=$(apt-cache show --no-all-versions "$package" 2>/dev/null | sed -n 's/^Version: //p')
    if [ -z "$version" ]; then
        reason="not known to apt-cache"
        return 1
    fi
    rm -rf "$work/deb" "$work/root" "$work/archives" "$work/plain" "$partial"
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
    rm -rf "${dir:?}/$package"
    mv "$partial" "$dir/$package"
}

compare_manifest() {
    local kept="$here/assets_manifest.tsv"
    [ -f "$kept" ] || return 0
    if diff <(grep -v '^#' "$kept" | cut -f1,6,7) <(grep -v '^#' "$dir/manifest.tsv" | cut -f1,6,7) >/dev/null; then
        echo "manifest: identical to tests/corpus/assets_manifest.tsv"
    else
        echo "manifest: differs from tests/corpus/assets_manifest.tsv (other package versions?):"
        diff <(grep -v '^#' "$kept" | cut -f1,6,7) <(grep -v '^#' "$dir/manifest.tsv" | cut -f1,6,7) | grep '^[<>]' |
            head -20 | sed 's/^/    /'
    fi
}

start=$(date +%s)
# tune packages first (see Duplicates above)
for package in $(for entry in $PACKAGES; do [ "${split_of[${entry%%:*}]}" = tune ] && echo "${entry%%:*}"; done) \
    $(for entry in $PACKAGES; do [ "${split_of[${entry%%:*}]}" = heldout ] && echo "${entry%%:*}"; done); do
    if [ -f "$dir/$package/.complete" ]; then
        echo "skip  $package (already extracted)"
    elif fetch_package "$package"; then
        echo "fetch $package $(cat "$dir/$package/.complete") [${family_of[$package]}, ${split_of[$package]}]:" \
            "$(wc -l <"$dir/$package/.manifest") kept, $(wc -l <"$dir/$package/.skipped") left out"
    else
        echo "MISS  $package: $reason; skipped"
        unavailable="$unavailable $package"
        rm -rf "$dir/$package.partial"
    fi
done

{
    printf '# sha256\tbytes\tpackage\tversion\tfamily\tsplit\tstored\toriginal\tnote\n'
    for entry in $PACKAGES; do
        cat "$dir/${entry%%:*}/.manifest" 2>/dev/null
    done
} >"$dir/manifest.tsv"

mb() { awk -v b="$1" 'BEGIN { printf "%.1f", b / 1048576 }'; }
body() { grep -v '^#' "$dir/manifest.tsv"; }
echo "split (package counts): $(for entry in $PACKAGES; do p=${entry%%:*}; echo "${family_of[$p]} ${split_of[$p]}"; done |
    sort | uniq -c | awk '{ printf "%s%s %s %d", sep, $2, $3, $1; sep = ", " }')"
echo "files by family and split: $(body | cut -f5,6 | sort | uniq -c | awk '{ printf "%s%s %s %d", sep, $2, $3, $1; sep = ", " }')"
echo "assets: $(body | wc -l) files from $(body | cut -f3 | sort -u | wc -l) packages," \
    "$(mb "$(body | awk -F'\t' '{ s += $2 } END { print s + 0 }')") MB in $dir," \
    "$(cat "$dir"/*/.skipped 2>/dev/null | grep -c '^duplicate') duplicates left out" \
    "(downloaded $(mb "$downloaded_bytes") MB in $(($(date +%s) - start)) s)"
[ "$have_assimp" = yes ] || echo "assimp not installed: .dae files skipped ($(cat "$dir"/*/.skipped | grep -c '^assimp not'))"
if [ -n "$unavailable" ]; then
    echo "unavailable:$unavailable"
fi
compare_manifest
exit 0
