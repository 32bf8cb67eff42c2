#!/usr/bin/env bash
# The command-line tool on real files (Debian's assimp-testmodels and
# occt-misc), checked by parsing what it writes (tests/cli/meshcheck.js,
# independent of the tool) and, for glTF, with the Khronos glTF-Validator:
#   - every file: a run that flips nothing writes the input back byte for
#     byte; a run that flips changes only the flipped faces' corner order
#     (STL: and the normals turned with them), as many as the --json report
#     says; a second run flips nothing; glTF outputs have no validator
#     error the input did not have; unreadable files are refused with one
#     line and nothing written;
#   - scrambled copies (30% of the faces reversed) are repaired: only those
#     faces change, and closed meshes come back as the original's repair;
#   - glTF: strips, fans and non-indexed primitives turned by --policy up,
#     shared index accessors, mirrored nodes and double-sided materials,
#     .gltf <-> .glb as documents, NORMAL fixed, Draco refused;
#   - exit statuses, --json, --check, --inspect --mark, --help, --version,
#     argument errors, several inputs and directories on threads.
# Run from the repository root after `make build/meshfix`. Needs node;
# the validator in build/node_modules (make test installs it: tests/install_deps.sh).
# Prints "ok   NAME" or "FAIL NAME" per check, then "N passed, N failed".
set -u
cd "$(dirname "$0")/.." || exit 1
M=build/meshfix
ASSIMP=/usr/share/assimp/models
OCCT=/usr/share/opencascade/data/stl
passed=0
failed=0
tmp=$(mktemp -d "${TMPDIR:-/tmp}/meshfix_files.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT

check_log="$tmp/last.log"
. tests/check.sh

for need in "$M:make build/meshfix" "$ASSIMP/OBJ/spider.obj:apt-get install assimp-testmodels" \
            "$OCCT/motor.stl:apt-get install occt-misc"; do
    if [ ! -e "${need%%:*}" ]; then
        echo "FAIL ${need%%:*} is missing (${need#*:})"
        echo "0 passed, 1 failed"
        exit 1
    fi
done
if ! command -v node >/dev/null 2>&1; then
    echo "FAIL node is not installed (apt-get install nodejs; make test installs it as root)"
    echo "0 passed, 1 failed"
    exit 1
fi
CHECK="node tests/cli/meshcheck.js"
validator=1
if [ ! -f build/node_modules/gltf-validator/package.json ]; then
    validator=0
    failed=$((failed + 1))
    echo "FAIL the Khronos glTF-Validator is not installed: npm install --prefix build gltf-validator (make test does)"
fi

# json FILE EXPRESSION: evaluates a JavaScript expression over the report `r`
json() {
    node -e 'const r = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8")); console.log(eval(process.argv[2]))' "$1" "$2"
}
# the sums over the meshes of a report's only file
FLIPPED_FACES='r.files[0].meshes.reduce((s, m) => s + m.flipped.faces, 0)'
TURNED='r.files[0].meshes.reduce((s, m) => s + m.normals.turned_with_faces, 0)'

# validator errors: the output may have no error code the input did not have
no_new_errors() { # input output
    [ "$validator" -eq 1 ] || return 0
    node tests/cli/gltf_validate.js build "$1" "$2" >"$tmp/v.txt" || { cat "$tmp/v.txt"; return 1; }
    local in out
    in=$(sed -n 1p "$tmp/v.txt") out=$(sed -n 2p "$tmp/v.txt")
    local e_in=${in%% *} e_out=${out%% *} codes_out
    codes_out=$(echo "$out" | awk '{print $4}' | tr ',' '\n')
    [ "$e_out" -le "$e_in" ] || { echo "validator: $e_out errors, the input had $e_in"; cat "$tmp/v.txt"; return 1; }
    for code in $codes_out; do
        echo "$in" | awk '{print $4}' | tr ',' '\n' | grep -qx "$code" || { echo "new error $code"; cat "$tmp/v.txt"; return 1; }
    done
}

# the files the output refers to besides itself, equal to the input's
companions_equal() { # input output
    local f
    for f in $(node -e '
        const fs = require("fs"), j = JSON.parse(fs.readFileSync(process.argv[1], "utf8"));
        for (const x of [...(j.buffers || []), ...(j.images || [])])
            if (x.uri && !x.uri.startsWith("data:")) console.log(decodeURIComponent(x.uri));' "$1"); do
        cmp "$(dirname "$1")/$f" "$(dirname "$2")/$f" || return 1
    done
}

# ---- every real file ----

counts="$tmp/counts.txt"
: >"$counts"
roundtrip() { # input: repair into a fresh directory and check what was written
    local in=$1 base out status flipped turned name
    base=$(basename "$in")
    rm -rf "$tmp/rt" && mkdir -p "$tmp/rt"
    out="$tmp/rt/$base"
    $M --json "$in" "$out" >"$tmp/rt.json" 2>"$tmp/rt.err"
    status=$?
    if [ "$status" -eq 1 ]; then
        [ "$(wc -l <"$tmp/rt.err")" -eq 1 ] || { echo "not one line:"; cat "$tmp/rt.err"; return 1; }
        [ -z "$(ls -A "$tmp/rt")" ] || { echo "something was written:"; ls -A "$tmp/rt"; return 1; }
        [ "$(json "$tmp/rt.json" 'r.files[0].exit')" = 1 ] || return 1
        echo "refused $base: $(cat "$tmp/rt.err")" >>"$counts"
        return 0
    fi
    [ "$status" -eq 0 ] || { echo "exit status $status"; cat "$tmp/rt.err"; return 1; }
    flipped=$(json "$tmp/rt.json" "$FLIPPED_FACES") && turned=$(json "$tmp/rt.json" "$TURNED") || return 1
    case "$base" in *.gltf|*.glb) no_new_errors "$in" "$out" || return 1 ;; esac
    if [ "$flipped" -eq 0 ] && [ "$turned" -eq 0 ]; then
        cmp "$in" "$out" || return 1
        case "$base" in *.gltf) companions_equal "$in" "$out" || return 1 ;; esac
        echo "equal $base" >>"$counts"
    else
        $CHECK compare "$in" "$out" --normals >"$tmp/cmp.txt" || { cat "$tmp/cmp.txt"; return 1; }
        grep -q "flipped $flipped normals $turned\$" "$tmp/cmp.txt" ||
            { echo "the report says $flipped faces flipped, $turned normals turned; the files: $(cat "$tmp/cmp.txt")"; return 1; }
        echo "flipped $base $flipped" >>"$counts"
    fi
    # a second run has nothing left to flip and writes its input back
    $M --json "$out" "$tmp/rt/again_$base" >"$tmp/again.json" 2>&1 || { cat "$tmp/again.json"; return 1; }
    [ "$(json "$tmp/again.json" "$FLIPPED_FACES")" -eq 0 ] || { echo "the second run flipped faces"; return 1; }
    cmp "$out" "$tmp/rt/again_$base"
}

files=()
while IFS= read -r f; do files+=("$f"); done < <(
    find "$ASSIMP/OBJ" "$ASSIMP/PLY" "$ASSIMP/STL" "$ASSIMP/OFF" "$ASSIMP/glTF2" "$OCCT" -maxdepth 3 -type f \
        \( -iname '*.obj' -o -iname '*.ply' -o -iname '*.stl' -o -iname '*.off' -o -iname '*.gltf' -o -iname '*.glb' \) | sort)
for f in "${files[@]}"; do
    check "round trip ${f#/usr/share/}" roundtrip "$f"
done
echo "   ${#files[@]} real files: $(grep -c '^equal' "$counts") written back byte for byte," \
     "$(grep -c '^flipped' "$counts") repaired (only the flipped faces differ), $(grep -c '^refused' "$counts") refused"
grep '^refused' "$counts" | sed 's/^/   /'

# ---- scrambled copies ----

scrambled() { # input: 30% of the faces reversed, repaired
    local in=$1 base
    base=$(basename "$in")
    rm -rf "$tmp/sc" && mkdir -p "$tmp/sc/s" "$tmp/sc/o" "$tmp/sc/r"
    $CHECK scramble "$in" "$tmp/sc/s/$base" 11 0.3 >/dev/null || return 1
    $M --json "$tmp/sc/s/$base" "$tmp/sc/o/$base" >"$tmp/sc.json" || { cat "$tmp/sc.json"; return 1; }
    local flipped turned
    flipped=$(json "$tmp/sc.json" "$FLIPPED_FACES") && turned=$(json "$tmp/sc.json" "$TURNED") || return 1
    [ "$flipped" -gt 0 ] || { echo "nothing flipped"; return 1; }
    $CHECK compare "$tmp/sc/s/$base" "$tmp/sc/o/$base" --normals >"$tmp/cmp.txt" || { cat "$tmp/cmp.txt"; return 1; }
    grep -q "flipped $flipped normals $turned\$" "$tmp/cmp.txt" ||
        { echo "report: $flipped flipped, $turned turned; files: $(cat "$tmp/cmp.txt")"; return 1; }
    case "$base" in *.gltf|*.glb) no_new_errors "$in" "$tmp/sc/o/$base" || return 1 ;; esac
    # a closed mesh comes back exactly as the original's own repair
    $M --json "$in" "$tmp/sc/r/$base" >"$tmp/orig.json" || return 1
    if [ "$(json "$tmp/orig.json" 'r.files[0].meshes.every((m) => m.before.edges_boundary === 0 && m.before.edges_non_manifold === 0)')" = true ]; then
        $CHECK compare "$tmp/sc/r/$base" "$tmp/sc/o/$base" --normals >"$tmp/cmp.txt" || { cat "$tmp/cmp.txt"; return 1; }
        grep -q "flipped 0 " "$tmp/cmp.txt" || { echo "closed, yet not as the original's repair: $(cat "$tmp/cmp.txt")"; return 1; }
    fi
}

$CHECK big-endian "$ASSIMP/PLY/cube_binary.ply" "$tmp/cube_big_endian.ply"
for f in "$ASSIMP/OBJ/spider.obj" "$ASSIMP/OBJ/WusonOBJ.obj" "$ASSIMP/OBJ/concave_polygon.obj" "$ASSIMP/OBJ/cube_usemtl.obj" \
         "$ASSIMP/OBJ/box.obj" "$ASSIMP/PLY/Wuson.ply" "$ASSIMP/PLY/cube.ply" "$ASSIMP/PLY/cube_binary.ply" \
         "$tmp/cube_big_endian.ply" "$ASSIMP/STL/Spider_binary.stl" "$ASSIMP/STL/Spider_ascii.stl" "$ASSIMP/STL/sphereWithHole.stl" \
         "$OCCT/motor.stl" "$OCCT/bearing.stl" "$OCCT/head.stl" "$ASSIMP/OFF/Wuson.off" "$ASSIMP/OFF/Cube.off" \
         "$ASSIMP/glTF2/BoxTextured-glTF/BoxTextured.gltf" "$ASSIMP/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb" \
         "$ASSIMP/glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf" \
         "$ASSIMP/glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf" \
         "$ASSIMP/glTF2/simple_skin/simple_skin.gltf" "$ASSIMP/glTF2/ClearCoat-glTF/ClearCoatTest.gltf" \
         "$ASSIMP/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"; do
    check "scrambled $(basename "$f"): only the reversed faces change back" scrambled "$f"
done

# ---- glTF specifics ----

G=$ASSIMP/glTF2
forced() { # primitive mode file, up axis that faces away: every triangle turns
    local in=$1 base out
    base=$(basename "$in")
    rm -rf "$tmp/fo" && mkdir -p "$tmp/fo"
    out="$tmp/fo/$base"
    $M --json --policy up --up -z "$in" "$out" >"$tmp/fo.json" || { cat "$tmp/fo.json"; return 1; }
    $CHECK compare "$in" "$out" >"$tmp/cmp.txt" || { cat "$tmp/cmp.txt"; return 1; }
    grep -q "^faces \([0-9]*\) flipped \1 " "$tmp/cmp.txt" || { echo "not every triangle turned: $(cat "$tmp/cmp.txt")"; return 1; }
    no_new_errors "$in" "$out" || return 1
    # facing the way it does, nothing changes, not even a strip's mode
    $M --policy up --up z "$in" "$tmp/fo/same_$base" >/dev/null && cmp "$in" "$tmp/fo/same_$base"
}
for i in 04 05 06 11 12 13 14 15; do
    check "glTF Mesh_PrimitiveMode_$i (strips, fans, lists; 8/16/32-bit and no indices) turned by --policy up" \
        forced "$G/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_$i.gltf"
done

forced_counts() {
    $M --json --policy up --up -z "$G/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_04.gltf" "$tmp/fc4.gltf" >"$tmp/fc4.json" &&
        $M --json --policy up --up -z "$G/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_06.gltf" "$tmp/fc6.gltf" >"$tmp/fc6.json" || return 1
    # mode 5 without indices: a strip written as a list; mode 4 without indices: indices added
    [ "$(json "$tmp/fc4.json" 'r.files[0].gltf.strips_fans_as_lists')" = 1 ] &&
        [ "$(json "$tmp/fc6.json" 'r.files[0].gltf.indices_added')" = 1 ]
}
check "glTF: the report counts strips written as lists and indices added" forced_counts

# one index accessor shared by two meshes: cloned before either is written
shared_accessor() {
    mkdir -p "$tmp/shared" "$tmp/sh"
    node -e '
        const fs = require("fs"), j = JSON.parse(fs.readFileSync(process.argv[1], "utf8"));
        j.meshes.push(JSON.parse(JSON.stringify(j.meshes[0])));
        j.nodes.push({ mesh: 1, translation: [3, 0, 0] });
        j.scenes[0].nodes.push(j.nodes.length - 1);
        fs.writeFileSync(process.argv[2], JSON.stringify(j));' "$G/BoxTextured-glTF/BoxTextured.gltf" "$tmp/shared/in.gltf" || return 1
    cp "$G/BoxTextured-glTF/"*.bin "$G/BoxTextured-glTF/"*.png "$tmp/shared/"
    $CHECK scramble "$tmp/shared/in.gltf" "$tmp/shared/shared.gltf" 3 0.5 >/dev/null || return 1
    $M --json "$tmp/shared/shared.gltf" "$tmp/sh/shared.gltf" >"$tmp/sh.json" || { cat "$tmp/sh.json"; return 1; }
    [ "$(json "$tmp/sh.json" 'r.files[0].gltf.index_accessors_cloned')" = 2 ] || { cat "$tmp/sh.json"; return 1; }
    $CHECK compare "$tmp/shared/shared.gltf" "$tmp/sh/shared.gltf" && no_new_errors "$tmp/shared/shared.gltf" "$tmp/sh/shared.gltf" &&
        $M --inspect "$tmp/sh/shared.gltf" | grep -q 'inconsistent 0'
}
check "glTF: an index accessor shared by two meshes is cloned, both repaired" shared_accessor

mirrored() { # the mesh is drawn by node 1, a child of node 0
    mkdir -p "$tmp/mirror" "$tmp/mi"
    node -e '
        const fs = require("fs"), j = JSON.parse(fs.readFileSync(process.argv[1], "utf8"));
        j.nodes[0].scale = [-1, 1, 1]; delete j.nodes[0].matrix;
        j.materials[0].doubleSided = true;
        fs.writeFileSync(process.argv[2], JSON.stringify(j));' "$G/BoxTextured-glTF/BoxTextured.gltf" "$tmp/mirror/mirror.gltf" || return 1
    cp "$G/BoxTextured-glTF/"*.bin "$G/BoxTextured-glTF/"*.png "$tmp/mirror/"
    $M --json "$tmp/mirror/mirror.gltf" "$tmp/mi/mirror.gltf" >"$tmp/mi.json" || return 1
    $M "$tmp/mirror/mirror.gltf" "$tmp/mi/mirror2.gltf" >"$tmp/mi.txt" || return 1
    [ "$(json "$tmp/mi.json" 'JSON.stringify(r.files[0].gltf.mirrored_nodes) + JSON.stringify(r.files[0].gltf.double_sided_materials)')" = \
      '[{"node":1,"mesh":0}][0]' ] || { cat "$tmp/mi.json"; return 1; }
    grep -q 'mirrored (negative determinant)' "$tmp/mi.txt" && grep -q 'double-sided' "$tmp/mi.txt" &&
        cmp "$tmp/mirror/mirror.gltf" "$tmp/mi/mirror.gltf"
}
check "glTF: a mirrored node and a double-sided material are reported and left as they are" mirrored

convert() { # a .gltf written as .glb and back: the same document, read by the validator as before
    local in=$1 base
    base=$(basename "$in" .gltf)
    rm -rf "$tmp/cv" && mkdir -p "$tmp/cv/b"
    $M --quiet "$in" "$tmp/cv/$base.glb" && $M --quiet "$tmp/cv/$base.glb" "$tmp/cv/b/$base.gltf" || return 1
    $CHECK compare "$in" "$tmp/cv/$base.glb" | grep -q ' flipped 0 normals 0$' &&
        $CHECK compare "$in" "$tmp/cv/b/$base.gltf" | grep -q ' flipped 0 normals 0$' &&
        no_new_errors "$in" "$tmp/cv/$base.glb" && no_new_errors "$in" "$tmp/cv/b/$base.gltf"
}
for f in "$G/BoxTextured-glTF/BoxTextured.gltf" "$G/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf" \
         "$G/simple_skin/simple_skin.gltf" "$G/textureTransform/TextureTransformTest.gltf" "$G/cameras/Cameras.gltf" \
         "$G/BoxTextured-glTF-Embedded/BoxTextured.gltf"; do
    check "glTF $(basename "$f") -> .glb -> .gltf through tinygltf: the same document, no new validator error" convert "$f"
done

fix_normals() { # normals negated at random; --fix-normals puts back the input as it was
    local in=$1 base
    base=$(basename "$in")
    rm -rf "$tmp/fn" && mkdir -p "$tmp/fn/s" "$tmp/fn/o"
    cp "$(dirname "$in")"/* "$tmp/fn/s/" 2>/dev/null
    $CHECK flip-normals "$in" "$tmp/fn/s/$base" 5 0.4 >"$tmp/fn.txt" || return 1
    local negated
    negated=$(awk '{print $2}' "$tmp/fn.txt")
    [ "$negated" -gt 0 ] || return 1
    $M --json "$tmp/fn/s/$base" "$tmp/fn/o/$base" >"$tmp/fn1.json" || return 1
    [ "$(json "$tmp/fn1.json" 'r.files[0].meshes[0].normals.disagree')" = "$negated" ] || { echo "disagree != $negated"; return 1; }
    $M --json --fix-normals "$tmp/fn/s/$base" "$tmp/fn/o/$base" >"$tmp/fn2.json" || return 1
    [ "$(json "$tmp/fn2.json" 'r.files[0].meshes[0].normals.fixed')" = "$negated" ] || return 1
    case "$base" in
        *.obj) cmp "$in" "$tmp/fn/o/$base" ;;
        *) $CHECK compare "$in" "$tmp/fn/o/$base" | grep -q ' flipped 0 normals 0$' && no_new_errors "$in" "$tmp/fn/o/$base" ;;
    esac
}
check "OBJ flat vn negated: reported, and --fix-normals writes the original back" fix_normals "$ASSIMP/OBJ/cube_usemtl.obj"
check "glTF NORMAL negated: reported, and --fix-normals writes the original back" fix_normals "$G/BoxTextured-glTF/BoxTextured.gltf"
check "glTF NORMAL negated beside TANGENT: --fix-normals puts the normals back, TANGENT.w kept" fix_normals \
    "$G/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf"

tangent_w() { # TANGENT.w against the texture coordinates: reported, fixed on request
    local in=$tmp/tw/box/box.gltf
    rm -rf "$tmp/tw" && mkdir -p "$tmp/tw/s" "$tmp/tw/o" "$tmp/tw/box"
    cp "$G/BoxTextured-glTF/"*.png "$tmp/tw/box/" && cp "$G/BoxTextured-glTF/"*.png "$tmp/tw/s/"
    $CHECK add-tangents "$G/BoxTextured-glTF/BoxTextured.gltf" "$in" | grep -q 'added to 1 ' || return 1
    $CHECK flip-normals "$in" "$tmp/tw/s/cube.gltf" 7 0.5 --tangent-w >"$tmp/tw.txt" || return 1
    local negated
    negated=$(awk '{print $2}' "$tmp/tw.txt")
    [ "$negated" -gt 0 ] || return 1
    $M --json --inspect "$in" >"$tmp/tw0.json" && [ "$(json "$tmp/tw0.json" 'r.files[0].gltf.tangents_disagree')" = 0 ] ||
        { echo "the original's TANGENT.w disagree"; return 1; }
    $M --json --inspect "$tmp/tw/s/cube.gltf" >"$tmp/tw1.json" || return 1
    [ "$(json "$tmp/tw1.json" 'r.files[0].gltf.tangents_disagree')" = "$negated" ] || { echo "not $negated reported"; return 1; }
    $M --json --fix-normals "$tmp/tw/s/cube.gltf" "$tmp/tw/o/cube.gltf" >"$tmp/tw2.json" || return 1
    [ "$(json "$tmp/tw2.json" 'r.files[0].gltf.tangents_negated')" = "$negated" ] || return 1
    $CHECK compare "$in" "$tmp/tw/o/cube.gltf" | grep -q ' flipped 0 normals 0$' && no_new_errors "$in" "$tmp/tw/o/cube.gltf"
}
check "glTF TANGENT.w negated: reported against the texture coordinates, --fix-normals puts it back" tangent_w

draco() {
    mkdir -p "$tmp/dr"
    $M "$G/draco/2CylinderEngine.gltf" "$tmp/dr/out.gltf" 2>"$tmp/dr.err"
    [ $? -eq 1 ] && [ "$(wc -l <"$tmp/dr.err")" -eq 1 ] && grep -q 'Draco' "$tmp/dr.err" && [ -z "$(ls -A "$tmp/dr")" ]
}
check "glTF with Draco compression: exit 1, one line naming it, nothing written" draco

gltf1() { # tinygltf reads glTF 1.0 as an empty 2.0 document: refused, not "clean"
    $M --inspect "$ASSIMP/glTF/BoxTextured-glTF/BoxTextured.gltf" >/dev/null 2>"$tmp/g1.err"
    [ $? -eq 1 ] && [ "$(wc -l <"$tmp/g1.err")" -eq 1 ] && grep -q 'glTF 1.0 is not supported' "$tmp/g1.err"
}
check "glTF 1.0 (assimp-testmodels glTF/): exit 1, one line, not reported clean" gltf1

# A correct CAD assembly exported to one file: the Draco engine of
# assimp-testmodels through Debian's assimp-utils, as OBJ (with vn) and
# binary STL (facet normals). Its parts touch and some are open: nothing
# may be flipped, with the file's normals or by geometry alone. Its
# inside-out and scrambled copies (the faces reversed, the normals left as
# exported) must come back as exported (scrambled: but for the faces whose
# exported normal is against their winding); inside out by geometry alone too
# (scrambled, a flat open part alone has no geometric side: only its
# normals tell).
engine_file() { # extension
    [ -f "$tmp/engine/engine.$1" ] && return 0
    mkdir -p "$tmp/engine"
    # binary STL (stlb): the corruptions below rewrite its facets
    assimp export "$G/draco/2CylinderEngine.gltf" "$tmp/engine/engine.$1" $([ "$1" = stl ] && echo -fstlb) >/dev/null 2>&1
}
engine_untouched() { # extension, options...
    local ext=$1
    shift
    engine_file "$ext" || { echo "assimp export failed"; return 1; }
    $M "$@" "$tmp/engine/engine.$ext" "$tmp/engine/out.$ext" >"$tmp/engine.txt" || return 1
    tail -n 1 "$tmp/engine.txt"
    tail -n 1 "$tmp/engine.txt" | grep -q '^clean: nothing to flip'
}
engine_recovered() { # extension, corruption (inside-out or scrambled), options...
    local ext=$1 how=$2
    shift 2
    engine_file "$ext" || return 1
    /usr/bin/python3 - "$tmp/engine/engine.$ext" "$tmp/engine/$how.$ext" "$how" <<'PY' || return 1
import random, struct, sys
src, dst, how = sys.argv[1:]
rng = random.Random(7)
data = open(src, "rb").read()
if src.endswith(".obj"):
    out = []
    for line in data.decode("latin-1").split("\n"):
        t = line.split()
        if t and t[0] == "f" and (how == "inside-out" or rng.random() < 0.5):
            line = " ".join([t[0], t[1]] + t[:1:-1])
        out.append(line)
    open(dst, "w").write("\n".join(out))
else:
    b = bytearray(data)
    n = struct.unpack_from("<I", b, 80)[0]
    for i in range(n):
        if how == "inside-out" or rng.random() < 0.5:
            at = 84 + 50 * i
            b[at + 24:at + 36], b[at + 36:at + 48] = b[at + 36:at + 48], b[at + 24:at + 36]
    open(dst, "wb").write(bytes(b))
PY
    $M --quiet "$@" "$tmp/engine/$how.$ext" "$tmp/engine/fixed.$ext" || return 1
    # scrambled, with the normals as evidence: a face whose exported normal
    # points against its exported winding follows its normal once the
    # scramble makes them agree (its neighbours' normals agree with theirs:
    # the edge between is kept apart); it is counted apart
    local skip=
    [ "$how" = scrambled ] && [ "$*" != --ignore-normals ] && skip=--skip-against-normals
    /usr/bin/python3 tests/cli/winding_diff.py $skip "$tmp/engine/engine.$ext" "$tmp/engine/fixed.$ext" | tee "$tmp/diff.txt"
    grep -q '^0 of' "$tmp/diff.txt"
}
if command -v assimp >/dev/null 2>&1; then
    check "2CylinderEngine as OBJ (a correct assembly, touching and open parts): nothing flipped" engine_untouched obj
    check "2CylinderEngine as OBJ, by geometry alone (--ignore-normals): nothing flipped" engine_untouched obj --ignore-normals
    check "2CylinderEngine as STL: nothing flipped" engine_untouched stl
    check "2CylinderEngine as STL, by geometry alone: nothing flipped" engine_untouched stl --ignore-normals
    for ext in obj stl; do
        for how in inside-out scrambled; do
            check "2CylinderEngine as $ext, $how: every face back as exported" engine_recovered $ext $how
        done
        check "2CylinderEngine as $ext, inside-out: every face back as exported by geometry alone" \
            engine_recovered $ext inside-out --ignore-normals
    done
    # a small repair: 3 neighbouring faces of 110,336 turned (tests/cli/turn_faces.py)
    engine_turned() { # writes $tmp/engine/small/turned.obj and expected.txt, prints the faces' mean corner
        mkdir -p "$tmp/engine/small"
        engine_file obj &&
            /usr/bin/python3 tests/cli/turn_faces.py "$tmp/engine/engine.obj" "$tmp/engine/small/turned.obj" \
                "$tmp/engine/small/expected.txt" 50000 50001 50002
    }
    engine_small() { # the picture: red (rings) at them in all 8 views, none elsewhere, the legend's count
        local d="$tmp/engine/small" spot
        spot=$(engine_turned) || return 1
        $M --quiet "$d/turned.obj" "$d/fixed.obj" --mark "$d/mark.png" || return 1
        # shellcheck disable=SC2086
        /usr/bin/python3 tests/cli/png_check.py "$d/mark.png" small $spot --up y &&
            /usr/bin/python3 tests/cli/png_check.py "$d/mark.png" legend "flipped: 3 triangles" "doubtful: 0 triangles" --up y &&
            /usr/bin/python3 tests/cli/png_check.py "$d/mark.png" title "up +y (OBJ)" --up y
    }
    engine_blender() { # the --mark PLY in Debian's Blender: exactly those 3 faces red
        local d="$tmp/engine/small"
        engine_turned >/dev/null || return 1
        $M --quiet "$d/turned.obj" "$d/fixed.obj" --mark "$d/mark.ply" || return 1
        blender -b --factory-startup --python-exit-code 1 --python tests/cli/blender_mark.py -- "$d/mark.ply" "$d/got.txt" \
            >"$d/blender.log" 2>&1 || { tail -n 20 "$d/blender.log"; return 1; }
        grep -v '^red\|^amber' "$d/got.txt"
        grep -q '^colour [^ ]* \(CORNER\|POINT\)' "$d/got.txt" || { echo "no colour attribute imported"; return 1; }
        grep -q '^mixed 0$' "$d/got.txt" || { echo "faces of more than one colour"; return 1; }
        ! grep -q '^amber' "$d/got.txt" || { echo "amber faces"; return 1; }
        grep '^red' "$d/got.txt" | sort | diff - "$d/expected.txt" || { echo "(< red in Blender, > turned)"; return 1; }
    }
    if $M --version | grep -q 'PNG marks'; then
        check "2CylinderEngine as OBJ, 3 faces turned: the --mark picture rings them red in all 8 views, legend 'flipped: 3'" \
            engine_small
    else
        echo "SKIP 2CylinderEngine, 3 faces turned, the --mark picture: $M was built without PNG support (apt-get install libpng-dev)"
    fi
    if command -v blender >/dev/null 2>&1; then
        check "2CylinderEngine as OBJ, 3 faces turned: its --mark PLY in Blender, exactly those 3 faces red" engine_blender
    else
        echo "SKIP 2CylinderEngine, 3 faces turned, the --mark PLY in Blender: blender is not installed (apt-get install blender)"
    fi
else
    echo "SKIP 2CylinderEngine checks: assimp (Debian assimp-utils) is not installed; bash .ci/run installs it"
fi

# ---- exit statuses, reports, arguments ----

build/demo_mesh "$tmp/demo.obj" >/dev/null
$M --quiet "$tmp/demo.obj" "$tmp/clean.obj"

check "--help and --version on stdout, exit 0" sh -c \
    "$M --help 2>/dev/null | grep -q '^usage: meshfix' && $M --version 2>/dev/null | grep -q '^meshfix 0\\.2'"
check "an unknown option is named, exit 1" sh -c "$M --bogus $tmp/demo.obj $tmp/x.obj 2>&1 >/dev/null | grep -q \"unknown option '--bogus'\"; [ \$? -eq 0 ] && ! $M --bogus $tmp/demo.obj $tmp/x.obj 2>/dev/null"
check "every argument is checked before any work (bad --up after a slow input: no output, exit 1)" sh -c \
    "! $M $OCCT/head.stl $tmp/args.stl --up w 2>$tmp/args.err && grep -q -- '--up' $tmp/args.err && [ ! -e $tmp/args.stl ]"
check "exit 0 when clean, 0 when repaired" sh -c "$M --quiet $tmp/clean.obj $tmp/c2.obj && $M --quiet $tmp/demo.obj $tmp/d2.obj"
check "--check: 0 clean, 3 when something is wrong, 1 unreadable; nothing written" sh -c \
    "$M --check --quiet $tmp/clean.obj; a=\$?; $M --check --quiet $tmp/demo.obj; b=\$?; $M --check --quiet $tmp/nothing.obj 2>/dev/null; c=\$?;
     [ \$a -eq 0 ] && [ \$b -eq 3 ] && [ \$c -eq 1 ]"
check "exit 2 when the library refuses the mesh (--weld inf), nothing written" sh -c \
    "$M --weld inf $tmp/demo.obj $tmp/refused.obj 2>/dev/null; [ \$? -eq 2 ] && [ ! -e $tmp/refused.obj ]"
check "the last line is the summary in plain words" sh -c \
    "[ \"\$($M $tmp/demo.obj $tmp/d3.obj | tail -n 1)\" = \"\$($M --json $tmp/demo.obj $tmp/d4.obj | node -e 'let s=\"\";process.stdin.on(\"data\",d=>s+=d).on(\"end\",()=>console.log(JSON.parse(s).files[0].summary))')\" ] &&
     $M $tmp/demo.obj $tmp/d3.obj | tail -n 1 | grep -q '^fixed [0-9]* triangles in 2 patches'"

inspect_mark() { # --inspect --mark: nothing but the mark, what would flip in red
    $M --inspect --json --mark "$tmp/marked.ply" "$tmp/demo.obj" >"$tmp/im.json" || return 1
    local would
    would=$(json "$tmp/im.json" 'r.files[0].meshes[0].flipped.triangles')
    [ "$would" -gt 0 ] && $CHECK colours "$tmp/marked.ply" | grep -q "^red $would amber 0 " &&
        [ "$(json "$tmp/im.json" 'r.files[0].written.length')" = 1 ]
}
check "--inspect --mark marks what a repair would flip" inspect_mark

json_schema() { # the README's schema: every member there, of its type, the counts agreeing
    $M --json "$tmp/demo.obj" "$tmp/js.obj" >"$tmp/js.json" || return 1
    node -e '
        const r = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"));
        const fail = (m) => { console.log(m); process.exit(1); };
        const want = (o, k, t) => { if (!(k in o) || (t !== "any" && typeof o[k] !== t)) fail(`${k}: ${typeof o[k]}, expected ${t}`); };
        want(r, "meshfix", "string"); want(r, "mode", "string"); want(r, "policy", "string"); want(r, "exit", "number");
        const f = r.files[0];
        for (const [k, t] of [["input", "string"], ["output", "string"], ["format", "string"], ["exit", "number"],
                              ["summary", "string"], ["wrong", "boolean"], ["written", "object"], ["meshes", "object"]]) want(f, k, t);
        if (f.error !== null) fail("error is not null");
        const m = f.meshes[0];
        for (const k of ["name", "faces", "triangles", "before", "after", "flipped", "doubtful", "evidence", "normals", "summary"]) want(m, k, "any");
        for (const k of ["verdict", "triangles", "edges_inconsistent", "patches", "patches_inside_out", "area", "signed_volume"]) { want(m.before, k, "any"); want(m.after, k, "any"); }
        for (const k of ["patches_by_volume", "patches_by_parity", "patches_by_visibility", "patches_by_normals", "patches_kept", "rays_cast"]) want(m.evidence, k, "number");
        for (const k of ["patches", "triangles", "area", "share"]) want(m.doubtful, k, "number");
        if (m.flipped.triangles !== 6589 && m.flipped.triangles <= 0) fail("flipped");
        if (m.before.edges_inconsistent === 0 || m.after.edges_inconsistent !== 0) fail("before/after");
        if (f.written.length !== 1 || r.exit !== 0 || f.exit !== 0) fail("written/exit");
        if (m.after.verdict !== "repaired") fail(`verdict ${m.after.verdict}`);' "$tmp/js.json"
}
check "--json: the documented members, before and after, evidence, what was written" json_schema

batch() { # a directory and files into -o DIR on two threads: a line each, a table, the worst status
    rm -rf "$tmp/in" "$tmp/out" && mkdir -p "$tmp/in/sub"
    cp "$tmp/demo.obj" "$tmp/in/a.obj" && cp "$tmp/clean.obj" "$tmp/in/sub/b.obj" && cp "$ASSIMP/STL/Spider_binary.stl" "$tmp/in/c.stl"
    $M -j 2 "$tmp/in" "$ASSIMP/PLY/cube.ply" -o "$tmp/out" >"$tmp/batch.txt" || { cat "$tmp/batch.txt"; return 1; }
    [ -f "$tmp/out/a.obj" ] && [ -f "$tmp/out/sub/b.obj" ] && [ -f "$tmp/out/c.stl" ] && [ -f "$tmp/out/cube.ply" ] || { ls -R "$tmp/out"; return 1; }
    grep -q "^$tmp/in/a.obj: fixed" "$tmp/batch.txt" && grep -q "^$tmp/in/sub/b.obj: clean" "$tmp/batch.txt" &&
        grep -q '^file .* triangles .* flipped' "$tmp/batch.txt" && tail -n 1 "$tmp/batch.txt" | grep -q '^4 files: ' || { cat "$tmp/batch.txt"; return 1; }
    cmp "$tmp/clean.obj" "$tmp/out/sub/b.obj" || return 1
    printf 'OFF\n9 9 0\n' >"$tmp/in/bad.off"
    $M "$tmp/in" -o "$tmp/out2" >/dev/null 2>&1
    [ $? -eq 1 ] && [ -f "$tmp/out2/a.obj" ] && [ ! -e "$tmp/out2/bad.off" ]
}
check "several inputs and a directory into -o DIR: a line per file, a table, exit 1 for a bad file" batch

progress() { # long work shows a progress line on stderr
    rm -rf "$tmp/pr" && mkdir -p "$tmp/pr"
    $M --progress -j 1 --quiet --policy visibility "$OCCT" -o "$tmp/pr" 2>"$tmp/pr.err" || return 1
    grep -q 'meshfix: [0-9]* of 10 files done; working on ' "$tmp/pr.err" ||
        { echo "no progress line (the run was too short?)"; cat "$tmp/pr.err"; return 1; }
}
check "--progress: a progress line on stderr during long work" progress

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
