"""The add-on inside Debian's Blender, run by blender/test.sh:

    blender -b --factory-startup --python-exit-code 1 --python blender/tests/test_addon.py -- \
        --zip build/meshfix_blender.zip --cli build/meshfix --work DIR [--table FILE]

Installs the zip into the user scripts directory the environment names
(test.sh points BLENDER_USER_SCRIPTS and BLENDER_USER_CONFIG at DIR), imports
real models (assimp-testmodels, occt-misc), reverses a seeded half of their
faces and checks that the operator flips exactly the faces the command-line
tool flips on the same mesh (written to OBJ as Blender holds it), that UVs
and custom normals stay on their corners, that one undo step restores the
input, that edit mode changes only the selected faces, that the doubtful
faces are the tool's, that select flipped selects the faces the library
flipped, and that Inside is Outside reversed (closed meshes: every closed
patch inside out); then scores Blender's own Recalculate Outside and the
add-on against the winding the models shipped with. Prints "ok NAME",
"FAIL NAME: why", "SKIP NAME (why)" and "N passed, N failed"."""

import argparse
import os
import struct
import subprocess
import sys
import time
import traceback
import zlib

import bmesh
import bpy
import numpy as np

# Debian 12's Blender 3.4 glTF importer (io_scene_gltf2) asks for np.bool, which NumPy 1.24 removed:
# without this every glTF import fails in Debian's Blender, add-on or not
if "bool" not in np.__dict__:
    np.bool = bool

ASSIMP = os.environ.get("MESHFIX_MODELS", "/usr/share/assimp/models")
OCCT = "/usr/share/opencascade/data/stl"

# name, path, what it is
MODELS = [
    ("sh2.stl", OCCT + "/sh2.stl", "closed CAD part"),
    ("shape.stl", OCCT + "/shape.stl", "closed CAD part"),
    ("TR12J_OCC.stl", OCCT + "/TR12J_OCC.stl", "closed CAD part, genus 22"),
    ("box.obj", ASSIMP + "/OBJ/box.obj", "closed, quads"),
    ("BoxTextured.gltf", ASSIMP + "/glTF2/BoxTextured-glTF/BoxTextured.gltf",
     "closed, UVs, custom normals, corners split at seams"),
    ("WusonOBJ.obj", ASSIMP + "/OBJ/WusonOBJ.obj", "open character, custom normals"),
    ("spider.obj", ASSIMP + "/OBJ/spider.obj", "18 parts, UVs, custom normals"),
    ("motor.stl", OCCT + "/motor.stl", "13 CAD parts touching, non-manifold"),
    ("2CylinderEngine.glb", ASSIMP + "/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
     "CAD assembly: many objects, custom normals"),
    ("concave_polygon.obj", ASSIMP + "/OBJ/concave_polygon.obj", "one concave 66-gon"),
    # closed models cut into pieces whose seams are not welded (each piece's corners its own, at the
    # same positions: an export that writes parts, smoothing groups or UV islands apart), half the
    # pieces reversed whole and 2% of the faces on their own
    ("sh2.stl cut16", OCCT + "/sh2.stl", "closed CAD part in 16 unwelded pieces"),
    ("shape.stl cut16", OCCT + "/shape.stl", "closed CAD part in 16 unwelded pieces"),
    ("TR12J_OCC.stl cut64", OCCT + "/TR12J_OCC.stl", "closed CAD part in 64 unwelded pieces"),
]

OP = "meshfix_recalculate_outside"
# models whose meshes are closed: Inside must leave every closed patch of them inside out
CLOSED = {"sh2.stl", "shape.stl", "TR12J_OCC.stl", "box.obj", "sh2.stl cut16", "shape.stl cut16",
          "TR12J_OCC.stl cut64"}

passed = failed = 0


class Skip(Exception):
    pass


RESULTS = None  # the file the ok / FAIL / SKIP lines also go to (Blender's reports share stdout)


def say(line):
    print("\n" + line, flush=True)
    if RESULTS is not None:
        with open(RESULTS, "a") as f:
            f.write(line + "\n")


def check(name, function, *args):
    global passed, failed
    try:
        function(*args)
    except Skip as e:
        say("SKIP %s (%s)" % (name, e))
        return False
    except Exception as e:  # a failure is one line and the traceback indented
        failed += 1
        say("FAIL %s: %s" % (name, (str(e) or type(e).__name__).splitlines()[0][:300]))
        for line in traceback.format_exc().splitlines()[-6:]:
            say("    " + line)
        return False
    passed += 1
    say("ok   %s" % name)
    return True


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser()
    p.add_argument("--zip", required=True)
    p.add_argument("--cli", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--table")
    p.add_argument("--results")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--only", help="comma-separated model names")
    return p.parse_args(argv)


# ---- the add-on ----

def install(zip_path):
    scripts = os.environ.get("BLENDER_USER_SCRIPTS", "")
    assert scripts and os.path.isdir(scripts), "BLENDER_USER_SCRIPTS is not a directory: %r" % scripts
    bpy.ops.preferences.addon_install(filepath=os.path.abspath(zip_path), overwrite=True)
    bpy.ops.preferences.addon_enable(module="meshfix_blender")
    import meshfix_blender
    where = os.path.realpath(meshfix_blender.__file__)
    assert where.startswith(os.path.realpath(scripts) + os.sep), "enabled from %s, not %s" % (where, scripts)
    assert hasattr(bpy.types, "MESH_OT_meshfix_recalculate_outside"), "operator not registered"
    for menu in (bpy.types.VIEW3D_MT_edit_mesh_normals, bpy.types.VIEW3D_MT_object):
        assert meshfix_blender._menu in getattr(menu.draw, "_draw_funcs", []), "not in %s" % menu.__name__


def policies_are_the_librarys():
    import meshfix_blender
    enum_items = bpy.ops.mesh.meshfix_recalculate_outside.get_rna_type().properties["policy"].enum_items
    items = enum_items.keys()
    names = [p.name.lower() for p in meshfix_blender.meshfix.Policy if p.name != "SDF"]
    assert items == names, "%s != %s" % (items, names)
    assert "sdf" not in items and "auto" in items
    for name in items:  # the tooltips are the header's lines (meshfix_policy_info)
        text = meshfix_blender.meshfix.policy_info(name).description
        assert enum_items[name].description.lower() == text.lower(), (name, enum_items[name].description, text)
    op = bpy.types.MESH_OT_meshfix_recalculate_outside
    assert op.bl_options == {'REGISTER', 'UNDO'}, op.bl_options


# ---- meshes ----

def clear_scene():
    if bpy.context.object is not None and bpy.context.object.mode != 'OBJECT':
        bpy.ops.object.mode_set(mode='OBJECT')
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)
    for m in list(bpy.data.meshes):
        bpy.data.meshes.remove(m)


def import_model(path):
    before = set(bpy.data.objects)
    ext = os.path.splitext(path)[1].lower()
    if ext == ".obj":
        bpy.ops.wm.obj_import(filepath=path)
    elif ext == ".stl":
        bpy.ops.import_mesh.stl(filepath=path)
    elif ext in (".gltf", ".glb"):
        bpy.ops.import_scene.gltf(filepath=path)
    else:
        raise ValueError(path)
    objects, seen = [], set()
    for o in bpy.data.objects:
        if o not in before and o.type == 'MESH' and len(o.data.polygons) and o.data not in seen:
            seen.add(o.data)
            objects.append(o)
    objects.sort(key=lambda o: o.name)
    return objects


def select_only(objects):
    for o in bpy.context.view_layer.objects:
        o.select_set(False)
    for o in objects:
        o.select_set(True)
    bpy.context.view_layer.objects.active = objects[0]


def layout(me):
    starts = np.empty(len(me.polygons), np.int64)
    totals = np.empty(len(me.polygons), np.int64)
    me.polygons.foreach_get("loop_start", starts)
    me.polygons.foreach_get("loop_total", totals)
    return starts, totals


def loop_vertices(me):
    v = np.empty(len(me.loops), np.int64)
    me.loops.foreach_get("vertex_index", v)
    return v


def winding(me):
    """Each polygon's first vertex, second and last: enough to tell it from its reversal."""
    starts, totals = layout(me)
    v = loop_vertices(me)
    return v[starts], v[starts + 1], v[starts + totals - 1]


def reversed_from(me, reference):
    """Per polygon, whether it is wound against `reference` (winding() of the same mesh)."""
    first, second, last = winding(me)
    same = (first == reference[0]) & (second == reference[1])
    turned = (first == reference[0]) & (second == reference[2])
    assert np.all(same | turned), "%d polygons are neither as before nor reversed" % np.count_nonzero(~(same | turned))
    return turned & ~same


def corner_keys(me):
    """A sort order of the loops by (polygon, vertex), to compare what corners hold across a flip."""
    starts, totals = layout(me)
    polygon = np.repeat(np.arange(len(me.polygons)), totals)
    return np.lexsort((loop_vertices(me), polygon))


def corner_values(me, attribute):
    if attribute == "normal":
        me.calc_normals_split()
        a = np.empty(3 * len(me.loops), np.float32)
        me.loops.foreach_get("normal", a)
        a = a.reshape(-1, 3)
    else:
        layer = me.uv_layers[attribute].data
        a = np.empty(2 * len(layer), np.float32)
        layer.foreach_get("uv", a)
        a = a.reshape(-1, 2)
    return a[corner_keys(me)]


def cut(me, rng, pieces):
    """Cuts the mesh into pieces (each face to the nearest of `pieces` seeded face centres) and
    unwelds the seams (bmesh.ops.split_edges): the faces, their order and winding stay; returns
    the piece of each face."""
    centres = np.empty(3 * len(me.polygons), np.float32)
    me.polygons.foreach_get("center", centres)
    centres = centres.reshape(-1, 3).astype(np.float64)
    seeds = centres[rng.choice(len(centres), min(pieces, len(centres)), replace=False)]
    piece = np.empty(len(centres), np.int64)
    for lo in range(0, len(centres), 4096):
        d = ((centres[lo:lo + 4096, None, :] - seeds[None, :, :]) ** 2).sum(axis=2)
        piece[lo:lo + 4096] = d.argmin(axis=1)
    bm = bmesh.new()
    bm.from_mesh(me)
    bm.faces.ensure_lookup_table()
    seams = [e for e in bm.edges if len({piece[f.index] for f in e.link_faces}) > 1]
    bmesh.ops.split_edges(bm, edges=seams)
    bm.to_mesh(me)
    bm.free()
    me.update()
    return piece


def scramble(me, rng, flip=None):
    """Reverses a seeded random half of the faces (at least one), or those of `flip`, with bmesh,
    the custom normals kept on their corners (a file whose winding is broken and whose normals
    are not)."""
    from meshfix_blender import repair
    count = len(me.polygons)
    if flip is None:
        flip = np.zeros(count, bool)
        flip[rng.permutation(count)[:max(1, count // 2)]] = True
    before = repair.loop_vertices(me)
    normals = repair.corner_normals(me)
    bm = bmesh.new()
    bm.from_mesh(me)
    repair.flip_bmesh(bm, flip)
    bm.to_mesh(me)
    bm.free()
    if normals is not None:
        repair.restore_corner_normals(me, normals, before)
    me.update()
    return flip


def truth_known(me):
    """Closed, consistent and outward as shipped (models_eval's rule): every edge between two
    faces run opposite ways, every part closed with a positive volume. The facts are the
    library's inspect, which decides nothing."""
    from meshfix_blender import meshfix, repair
    indices, positions, _, _ = repair.mesh_arrays(me, None, use_normals=False)
    report, out = meshfix.inspect(indices, positions, outputs=("components",))
    m = report.mesh
    return (m.edges_boundary == 0 and m.edges_non_manifold == 0 and m.edges_inconsistent == 0 and
            bool(np.all(out.components["closed"] != 0)) and bool(np.all(out.components["signed_volume"] > 0)))


# ---- the command-line tool on the same mesh ----

def write_obj(me, path, scope=None, normals=True):
    """The mesh as Blender holds it: positions exactly (float32 written as its double), each
    custom corner normal exactly, the faces in scope in polygon order with their corners in
    loop order."""
    co = np.empty(3 * len(me.vertices), np.float32)
    me.vertices.foreach_get("co", co)
    starts, totals = layout(me)
    v = loop_vertices(me)
    lines = ["v %r %r %r" % tuple(float(x) for x in p) for p in co.reshape(-1, 3)]
    loop_vn = None
    if normals and me.has_custom_normals:
        me.calc_normals_split()
        ln = np.empty(3 * len(me.loops), np.float32)
        me.loops.foreach_get("normal", ln)
        ln = ln.reshape(-1, 3)
        unique, loop_vn = np.unique(ln.view(np.dtype((np.void, 12))).reshape(-1), return_inverse=True)
        lines += ["vn %r %r %r" % tuple(float(x) for x in n) for n in unique.view(np.float32).reshape(-1, 3)]
    polygons = range(len(me.polygons)) if scope is None else np.flatnonzero(scope)
    for p in polygons:
        s, n = int(starts[p]), int(totals[p])
        if loop_vn is None:
            lines.append("f " + " ".join(str(v[k] + 1) for k in range(s, s + n)))
        else:
            lines.append("f " + " ".join("%d//%d" % (v[k] + 1, loop_vn[k] + 1) for k in range(s, s + n)))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return polygons


def read_mark(path):
    """The --mark PLY: per triangle, whether it is doubtful (amber)."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode()
    vertices = int(header.split("element vertex ")[1].split()[0])
    faces = int(header.split("element face ")[1].split()[0])
    # a vertex is its float x, y, z and, where the header says so, its uchar colour
    vertex_bytes = sum(4 if kind == "float" else 1 for kind in
                       (line.split()[1] for line in header.split("element vertex ")[1].split("element face")[0].splitlines()
                        if line.startswith("property ")))
    rows = np.frombuffer(data, np.dtype([("n", "u1"), ("i", "<u4", 3), ("rgb", "u1", 3)]), faces,
                         end + vertex_bytes * vertices)
    assert np.all(rows["n"] == 3)
    return np.all(rows["rgb"] == (255, 176, 0), axis=1)


def cli_decide(cli, me, work, name, scope=None, normals=True, options=()):
    """The tool on the mesh written as OBJ: (faces it flipped, faces it marks doubtful), per
    polygon of the mesh (False outside scope)."""
    source, target, mark = (os.path.join(work, name + suffix) for suffix in (".obj", ".out.obj", ".mark.ply"))
    polygons = write_obj(me, source, scope, normals)
    run = subprocess.run([cli, "--quiet"] + list(options) + [source, target, "--mark", mark], stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, universal_newlines=True)
    assert run.returncode == 0, "%s exited %d: %s" % (cli, run.returncode, run.stdout.strip()[-300:])

    def faces(path):
        with open(path) as f:
            return [line for line in f if line.startswith("f ")]
    before, after = faces(source), faces(target)
    assert len(before) == len(after) == len(polygons)
    flipped = np.zeros(len(me.polygons), bool)
    flipped[polygons] = [a != b for a, b in zip(before, after)]
    doubtful_triangle = read_mark(mark)
    starts, totals = layout(me)
    per_face = totals[polygons] - 2  # the tool's triangles of a polygon: n - 2, in face order
    assert per_face.sum() == len(doubtful_triangle), "%d triangles marked, %d expected" % (
        len(doubtful_triangle), per_face.sum())
    face_of = np.repeat(np.arange(len(polygons)), per_face)
    doubtful = np.zeros(len(me.polygons), bool)
    doubtful[np.asarray(polygons)[np.unique(face_of[doubtful_triangle])]] = True
    return flipped, doubtful


# ---- the operators ----

def run_addon(objects, **options):
    select_only(objects)
    result = bpy.ops.mesh.meshfix_recalculate_outside('EXEC_DEFAULT', **options)
    assert result == {'FINISHED'}, result


def run_blender(objects):
    """Blender's own Recalculate Outside on every face of the objects (multi-object edit mode)."""
    select_only(objects)
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_mode(type='FACE')
    bpy.ops.mesh.select_all(action='SELECT')
    bpy.ops.mesh.normals_make_consistent(inside=False)
    bpy.ops.object.mode_set(mode='OBJECT')


def copies(objects):
    return [o.data.copy() for o in objects]


def put(objects, meshes):
    """Each object gets a fresh copy of its saved mesh."""
    for o, m in zip(objects, meshes):
        old = o.data
        o.data = m.copy()
        if old.users == 0:
            bpy.data.meshes.remove(old)


# ---- per model ----

class Model:
    def __init__(self, name, path, what):
        self.name, self.path, self.what = name, path, what
        self.pieces = int(name.split(" cut")[1]) if " cut" in name else 0
        self.objects = []
        self.faces = 0
        self.truth = None
        self.scores = {}


def model_checks(m, args, rng):
    clear_scene()
    m.objects = import_model(m.path)
    assert m.objects, "no mesh imported"
    objects = m.objects
    m.faces = sum(len(o.data.polygons) for o in objects)
    m.ngons = sum(int(np.count_nonzero(layout(o.data)[1] > 3)) for o in objects)
    m.truth = all(truth_known(o.data) for o in objects)
    m.has_uv = any(len(o.data.uv_layers) for o in objects)
    m.has_normals = any(o.data.has_custom_normals for o in objects)
    pieces = [cut(o.data, rng, m.pieces) if m.pieces else None for o in objects]
    shipped = copies(objects)
    truth = [winding(o.data) for o in objects]
    for o, piece in zip(objects, pieces):
        if piece is None:
            scramble(o.data, rng)
        else:
            turned = rng.permutation(m.pieces)[:m.pieces // 2]
            scramble(o.data, rng, np.isin(piece, turned) ^ (rng.random(len(piece)) < 0.02))
    scrambled = copies(objects)
    start = [winding(o.data) for o in objects]
    work = os.path.join(args.work, m.name.replace(" ", "-"))
    os.makedirs(work, exist_ok=True)
    cli = [cli_decide(args.cli, o.data, work, "%03d" % i) for i, o in enumerate(objects)]
    uv_before = [corner_values(o.data, o.data.uv_layers[0].name) if len(o.data.uv_layers) else None
                 for o in objects]
    normals_before = [corner_values(o.data, "normal") if o.data.has_custom_normals else None for o in objects]

    t = time.time()
    run_addon(objects, select_doubtful=True)
    m.seconds = time.time() - t
    flips = [reversed_from(o.data, s) for o, s in zip(objects, start)]
    m.flipped = sum(int(f.sum()) for f in flips)

    def same_as_cli():
        differ = sum(int(np.count_nonzero(f != c[0])) for f, c in zip(flips, cli))
        assert differ == 0, "%d of %d faces differ from the tool's (add-on flipped %d, tool %d)" % (
            differ, m.faces, m.flipped, sum(int(c[0].sum()) for c in cli))
    check("%s: the add-on flips exactly the faces build/meshfix flips (%d faces, %d flipped, %d n-gons)" % (
        m.name, m.faces, m.flipped, m.ngons), same_as_cli)

    def doubtful_as_cli():
        selected = [np.empty(len(o.data.polygons), bool) for o in objects]
        for o, s in zip(objects, selected):
            o.data.polygons.foreach_get("select", s)
        differ = sum(int(np.count_nonzero(s != c[1])) for s, c in zip(selected, cli))
        assert differ == 0, "%d faces differ: selected %d, the tool's --mark doubtful %d" % (
            differ, sum(int(s.sum()) for s in selected), sum(int(c[1].sum()) for c in cli))
        m.doubtful = sum(int(s.sum()) for s in selected)
    check("%s: select doubtful faces selects the faces build/meshfix --mark marks doubtful" % m.name,
          doubtful_as_cli)

    if m.has_uv:
        def uvs_follow():
            for o, before in zip(objects, uv_before):
                if before is not None:
                    after = corner_values(o.data, o.data.uv_layers[0].name)
                    assert np.array_equal(before, after), "a UV moved off its corner"
        check("%s: UVs stay on their corners (a flipped face's UV loop order reverses with it)" % m.name,
              uvs_follow)
    if m.has_normals:
        def normals_follow():
            # Blender stores a custom normal as two 16-bit angles in its corner's normal space, which
            # the flip changes: set again, a normal moves by a fraction of a degree
            worst = 0.0
            for o, before in zip(objects, normals_before):
                if before is not None:
                    after = corner_values(o.data, "normal")
                    a, b = (x / np.maximum(np.linalg.norm(x, axis=1), 1e-12)[:, None] for x in (before, after))
                    cos = np.clip(np.sum(a * b, axis=1), -1.0, 1.0)
                    worst = max(worst, float(np.degrees(np.arccos(cos.min()))))
            assert worst < 1.0, "a corner's custom normal turned by %.3f degrees" % worst
            m.normal_degrees = worst
        check("%s: custom split normals stay on their corners" % m.name, normals_follow)

    check("%s: select flipped faces selects the faces the library flipped (the module's decision, the tool's)" %
          m.name, flipped_selected, m, objects, scrambled, start, cli)
    check("%s: select flipped and doubtful faces together select both" % m.name,
          both_selected, objects, scrambled, start, cli)
    check("%s: Inside turns every face the other way from Outside%s" % (
        m.name, ", custom normals too" if m.has_normals else ""), inside_check, m, objects, scrambled, start, cli)

    # the scores: % of faces facing as shipped after the repair of the scrambled copy, and faces
    # turned on the shipped (correct) input
    def score(run):
        put(objects, scrambled)
        run()
        right = sum(int(np.count_nonzero(~reversed_from(o.data, t))) for o, t in zip(objects, truth))
        put(objects, shipped)
        run()
        damaged = sum(int(np.count_nonzero(reversed_from(o.data, t))) for o, t in zip(objects, truth))
        return 100.0 * right / m.faces, damaged
    m.scores["blender"] = score(lambda: run_blender(objects))
    m.scores["meshfix"] = score(lambda: run_addon(objects))
    m.scores["meshfix-no-normals"] = score(lambda: run_addon(objects, use_custom_normals=False))
    say("#    %s: Blender %.2f%% right, %d damaged; meshfix %.2f%%, %d; without custom normals %.2f%%, %d" % (
        (m.name,) + m.scores["blender"] + m.scores["meshfix"] + m.scores["meshfix-no-normals"]))
    put(objects, scrambled)
    m.object_names = [o.name for o in objects]
    m.scrambled_names = [c.name for c in scrambled]
    return True


def selected_faces(me):
    s = np.empty(len(me.polygons), bool)
    me.polygons.foreach_get("select", s)
    return s


def closed_facts(me):
    """The library's facts on the mesh as it is (meshfix.inspect): (patches, closed, inside out)."""
    from meshfix_blender import meshfix, repair
    indices, positions, _, _ = repair.mesh_arrays(me, None, False)
    facts = meshfix.inspect(indices, positions).mesh
    return facts.patches, facts.patches_closed, facts.patches_inside_out


def flipped_selected(m, objects, scrambled, start, cli):
    """select_flipped alone: the selection is exactly the faces reversed, which are the faces the
    library flipped: repair.decide (the module, as the operator calls it) and the tool alike."""
    from meshfix_blender import repair
    put(objects, scrambled)
    decided = [repair.decide(o.data, None, threads=2) for o in objects]
    run_addon(objects, select_flipped=True)
    total = 0
    for o, s, c, d in zip(objects, start, cli, decided):
        sel, turned = selected_faces(o.data), reversed_from(o.data, s)
        assert np.array_equal(sel, turned), "%d faces selected, %d reversed, %d differ" % (
            sel.sum(), turned.sum(), np.count_nonzero(sel != turned))
        assert np.array_equal(sel, d.flip), "selected %d, the library flipped %d" % (sel.sum(), d.flip.sum())
        assert np.array_equal(sel, c[0]), "selected %d, the tool flipped %d" % (sel.sum(), c[0].sum())
        total += int(sel.sum())
    assert total > 0, "nothing flipped, nothing selected"
    say("#    %s: %d flipped faces selected" % (m.name, total))


def both_selected(objects, scrambled, start, cli):
    put(objects, scrambled)
    run_addon(objects, select_flipped=True, select_doubtful=True)
    for o, s, c in zip(objects, start, cli):
        sel = selected_faces(o.data)
        want = reversed_from(o.data, s) | c[1]
        assert np.array_equal(sel, want), "selected %d, flipped or doubtful %d" % (sel.sum(), want.sum())


def inside_check(m, objects, scrambled, start, cli):
    """Inside on the scrambled mesh: every face wound against Outside's result (and, with custom
    normals, each corner's normal the negation of Outside's, but around zero-area faces); the faces reversed are the ones the
    library did not flip, and select flipped selects them; on a closed mesh the library then finds
    every closed patch inside out (Outside: none)."""
    put(objects, scrambled)
    run_addon(objects)
    outside = [winding(o.data) for o in objects]
    outside_normals = [corner_values(o.data, "normal") if o.data.has_custom_normals else None for o in objects]
    outside_facts = [closed_facts(o.data) for o in objects]
    put(objects, scrambled)
    run_addon(objects, inside=True, select_flipped=True)
    closed = 0
    for o, w, s, c, n, before in zip(objects, outside, start, cli, outside_normals, outside_facts):
        against = reversed_from(o.data, w)
        assert against.all(), "%d of %d faces face as Outside left them" % (np.count_nonzero(~against), len(against))
        turned = reversed_from(o.data, s)
        assert np.array_equal(turned, ~c[0]), "%d faces reversed, %d not flipped by the tool" % (
            turned.sum(), np.count_nonzero(~c[0]))
        assert np.array_equal(selected_faces(o.data), turned), "the selection is not the faces reversed"
        if n is not None:
            # but at the vertices of zero-area faces: Blender builds the normal space of a corner
            # from its fan of faces, and with a face of no area in it, it cannot always hold the
            # negated normal (2CylinderEngine, scrambled with seed 1: 18 of 195,951 corners)
            a = corner_values(o.data, "normal")
            a, b = (x / np.maximum(np.linalg.norm(x, axis=1), 1e-12)[:, None] for x in (a, -n))
            area = np.empty(len(o.data.polygons), np.float32)
            o.data.polygons.foreach_get("area", area)
            starts, totals = layout(o.data)
            vertex = loop_vertices(o.data)
            degenerate = np.zeros(len(o.data.vertices), bool)
            degenerate[vertex[np.repeat(area == 0, totals)]] = True
            kept = ~degenerate[vertex[corner_keys(o.data)]]
            cos = np.clip(np.sum(a * b, axis=1), -1.0, 1.0)[kept]
            worst = float(np.degrees(np.arccos(cos.min()))) if cos.size else 0.0
            assert worst < 1.0, "a corner normal is %.3f degrees from the negation of Outside's" % worst
        patches, closed_patches, inside_out = closed_facts(o.data)
        if patches and closed_patches == patches:
            assert before[2] == 0, "Outside left %d closed patches inside out" % before[2]
            assert inside_out == closed_patches, "Inside: %d of %d closed patches inside out" % (
                inside_out, closed_patches)
            closed += closed_patches
    say("#    %s: Inside is Outside reversed; %d closed patches, all inside out after Inside" % (m.name, closed))
    if m.name in CLOSED:
        assert closed > 0, "a closed model, and no closed mesh found"


def live(m):
    """The model's objects and scrambled meshes, looked up again (an undo rebuilds every ID)."""
    return [bpy.data.objects[n] for n in m.object_names], [bpy.data.meshes[n] for n in m.scrambled_names]


def undo_checks(m):
    """One undo step: the operator's call is undone whole by one ed.undo (object and edit mode)."""
    objects, scrambled = live(m)
    put(objects, scrambled)
    select_only(objects)
    reference = [winding(o.data) for o in objects]
    bpy.ops.ed.undo_push(message="before meshfix")
    result = bpy.ops.mesh.meshfix_recalculate_outside('EXEC_DEFAULT', True)  # True: push an undo step, as the UI does
    assert result == {'FINISHED'}
    changed = sum(int(reversed_from(o.data, r).sum()) for o, r in zip(objects, reference))
    assert changed > 0, "nothing flipped: nothing to undo"
    bpy.ops.ed.undo()
    objects, _ = live(m)
    after = sum(int(reversed_from(o.data, r).sum()) for o, r in zip(objects, reference))
    assert after == 0, "one undo left %d of %d flipped faces flipped" % (after, changed)


def edit_undo_check(m):
    objects, scrambled = live(m)
    put(objects, scrambled)
    select_only(objects)
    reference = [winding(o.data) for o in objects]
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_all(action='SELECT')
    bpy.ops.ed.undo_push(message="before meshfix")
    assert bpy.ops.mesh.meshfix_recalculate_outside('EXEC_DEFAULT', True) == {'FINISHED'}
    bpy.ops.ed.undo()
    bpy.ops.object.mode_set(mode='OBJECT')
    objects, _ = live(m)
    after = sum(int(reversed_from(o.data, r).sum()) for o, r in zip(objects, reference))
    assert after == 0, "one undo in edit mode left %d faces flipped" % after


def edit_selection_check(m, args, hide=False, inside=False):
    """Edit mode on a selection: the faces on one side of the middle, the others untouched; the
    selected ones flip as the tool flips a file of only them. hide: those faces hidden instead, none
    selected: the visible ones are repaired. inside: with Inside and Select Flipped Faces, the
    selected faces the tool does not flip are the ones reversed, and the selection becomes them."""
    objects, scrambled = live(m)
    put(objects, scrambled)
    total = chosen = flipped_inside = 0
    cli = []
    reference = []
    masks = []
    normals = []
    for i, o in enumerate(objects):
        me = o.data
        centres = np.empty(3 * len(me.polygons), np.float32)
        me.polygons.foreach_get("center", centres)
        x = centres.reshape(-1, 3)[:, 0]
        mask = x < np.median(x)
        if not mask.any():
            mask[:] = True
        if hide:
            me.polygons.foreach_set("select", np.zeros(len(mask), bool))
            me.polygons.foreach_set("hide", ~mask)
        else:
            me.polygons.foreach_set("select", mask)
        masks.append(mask)
        reference.append(winding(me))
        normals.append(corner_values(me, "normal") if me.has_custom_normals else None)
        cli.append(cli_decide(args.cli, me, os.path.join(args.work, m.name.replace(" ", "-")), "selection%03d" % i,
                              mask)[0])
    select_only(objects)
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_mode(type='FACE')
    options = dict(inside=True, select_flipped=True) if inside else {}
    assert bpy.ops.mesh.meshfix_recalculate_outside('EXEC_DEFAULT', **options) == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')
    for o, r, mask, c, before in zip(objects, reference, masks, cli, normals):
        flips = reversed_from(o.data, r)
        if inside:
            c = mask & ~c
            assert np.array_equal(selected_faces(o.data), flips), "the selection is not the faces reversed"
        elif before is not None:  # edit mode sets them on the mesh and reads the edit mesh back
            after = corner_values(o.data, "normal")
            a, b = (x / np.maximum(np.linalg.norm(x, axis=1), 1e-12)[:, None] for x in (before, after))
            turned = float(np.degrees(np.arccos(np.clip(np.sum(a * b, axis=1), -1.0, 1.0).min())))
            assert turned < 1.0, "a corner's custom normal turned by %.3f degrees in edit mode" % turned
        outside = int(np.count_nonzero(flips & ~mask))
        assert outside == 0, "%d %s faces flipped" % (outside, "hidden" if hide else "unselected")
        differ = int(np.count_nonzero(flips != c))
        assert differ == 0, "%d selected faces differ from the tool's on them (add-on %d, tool %d)" % (
            differ, int(flips.sum()), int(c.sum()))
        total += len(mask)
        chosen += int(mask.sum())
        flipped_inside += int(flips.sum())
    assert flipped_inside > 0, "nothing flipped in the selection"


def options_check(m, args, policy, weld):
    """Policy and weld tolerance from the redo panel: the tool's --policy and --weld on the same mesh."""
    objects, scrambled = live(m)
    put(objects, scrambled)
    reference = [winding(o.data) for o in objects]
    cli = [cli_decide(args.cli, o.data, os.path.join(args.work, m.name.replace(" ", "-")), "%s%03d" % (policy, i),
                      options=("--policy", policy, "--weld", repr(weld)))[0] for i, o in enumerate(objects)]
    run_addon(objects, policy=policy, weld_tolerance=weld)
    flips = [reversed_from(o.data, r) for o, r in zip(objects, reference)]
    differ = sum(int(np.count_nonzero(f != c)) for f, c in zip(flips, cli))
    assert differ == 0, "%d faces differ from build/meshfix --policy %s --weld %r (add-on %d, tool %d)" % (
        differ, policy, weld, sum(int(f.sum()) for f in flips), sum(int(c.sum()) for c in cli))
    assert sum(int(f.sum()) for f in flips) > 0, "nothing flipped"


def min_confidence_check(m):
    """A higher minimum confidence selects at least the faces 0.5 did, and minimum confidence 1
    selects every face of a patch whose verdict is less than certain."""
    objects, scrambled = live(m)
    counts = []
    for mc in (0.0, 0.99):
        put(objects, scrambled)
        run_addon(objects, select_doubtful=True, min_confidence=mc)
        s = []
        for o in objects:
            a = np.empty(len(o.data.polygons), bool)
            o.data.polygons.foreach_get("select", a)
            s.append(a)
        counts.append(s)
    low = sum(int(a.sum()) for a in counts[0])
    high = sum(int(a.sum()) for a in counts[1])
    for a, b in zip(counts[0], counts[1]):
        assert not np.any(a & ~b), "a face doubtful at 0.5 is not at 0.99"
    assert high >= low


def table(models):
    rows = ["| model | what | faces | Blender: right after repair | meshfix: right after repair | "
            "meshfix without custom normals | Blender: damaged on correct input | meshfix: damaged | "
            "meshfix without custom normals: damaged |",
            "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for m in models:
        if not m.scores:
            continue
        b, f, n = m.scores["blender"], m.scores["meshfix"], m.scores["meshfix-no-normals"]
        kind = m.what + ("" if m.truth else " (truth: as shipped, not closed)")
        rows.append("| %s | %s | %d | %.2f%% | %.2f%% | %.2f%% | %d | %d | %d |" % (
            m.name, kind, m.faces, b[0], f[0], n[0], b[1], f[1], n[1]))
    return "\n".join(rows) + "\n"


def main():
    global RESULTS
    args = arguments()
    RESULTS = args.results
    os.makedirs(args.work, exist_ok=True)
    if not check("add-on: installs from %s into BLENDER_USER_SCRIPTS and enables; operator and menus registered" %
                 os.path.basename(args.zip), install, args.zip):
        return
    check("add-on: policies are the library's (from the module), sdf left out; bl_options REGISTER, UNDO",
          policies_are_the_librarys)
    only = set(args.only.split(",")) if args.only else None
    models = []
    doubtful_checked = False
    for name, path, what in MODELS:
        if only and name not in only:
            continue
        if not os.path.exists(path):
            say("SKIP %s (%s missing: apt-get install %s)" % (
                name, path, "occt-misc" if path.startswith(OCCT) else "assimp-testmodels"))
            continue
        m = Model(name, path, what)
        rng = np.random.default_rng([args.seed, zlib.crc32(name.encode())])
        if not check("%s (%s): imported, scrambled, repaired and scored" % (name, what), model_checks, m, args, rng):
            continue
        models.append(m)
        # the checks on the scene as it is now (the next model clears it)
        if name == "spider.obj":
            check("%s: one undo step restores the input (object mode)" % name, undo_checks, m)
            check("%s: one undo step restores the input (edit mode)" % name, edit_undo_check, m)
        if name in ("spider.obj", "motor.stl"):
            for policy, weld in (("seed", 0.0), ("majority", 1e-4), ("outward", 1e-3)):
                check("%s: policy %s, weld tolerance %g flip what build/meshfix --policy %s --weld %g flips" % (
                    name, policy, weld, policy, weld), options_check, m, args, policy, weld)
        if name in ("spider.obj", "sh2.stl", "2CylinderEngine.glb"):
            check("%s: edit mode changes only the selected faces, as the tool does on them; custom normals stay" % name,
                  edit_selection_check, m, args)
        if name == "sh2.stl":
            check("%s: edit mode with nothing selected leaves the hidden faces, as the tool does on the others" % name,
                  edit_selection_check, m, args, True)
        if name in ("sh2.stl", "spider.obj"):
            check("%s: edit mode, Inside: only the selected faces change, those the tool does not flip; selected after" %
                  name, edit_selection_check, m, args, False, True)
        if getattr(m, "doubtful", 0) and not doubtful_checked:
            doubtful_checked = check("%s: minimum confidence 0.99 selects at least the faces doubtful at 0.5" % name,
                                     min_confidence_check, m)
    if not doubtful_checked:
        say("SKIP minimum confidence (no model here has a doubtful patch once scrambled)")
    if args.table and models:
        truth = [m for m in models if m.truth]
        text = table(truth) + "\n" + table([m for m in models if not m.truth])
        with open(args.table, "w") as f:
            f.write(text)
        say("# table:\n" + text)


try:
    main()
except Exception:
    failed += 1
    say("FAIL test_addon.py: " + traceback.format_exc().splitlines()[-1])
    traceback.print_exc()
print("\n%d passed, %d failed" % (passed, failed), flush=True)
sys.exit(1 if failed else 0)
