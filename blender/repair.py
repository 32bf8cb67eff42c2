"""meshfix for Blender: one mesh through the library (no bpy.ops here).

The library decides per triangle; Blender's faces are polygons, so each is
handed over as Blender's own triangles of it (Mesh.loop_triangles) for the
decision only, and turns whole, the way most of its triangles turned (as
the command-line tool decides OBJ, PLY and OFF polygons). Faces turn through
bmesh.ops.reverse_faces, so UVs, colours, attributes and materials stay on
their corners; custom split normals are put back on the corners they were
on (the reversal would turn them over with the face)."""

import bmesh
import numpy as np

from . import meshfix

NO_PATCH = 0xFFFFFFFF


def policy_names():
    """The library's policies but those that call a distance function (a mesh has none), in its order."""
    return [p.name.lower() for p in meshfix.Policy if not meshfix.policy_info(p).needs_distance]


def policy_description(name):
    """The header's line about a policy, as a sentence for a tooltip."""
    text = meshfix.policy_info(name).description
    return text[:1].upper() + text[1:]


class Decision:
    """What the library said about one mesh, per polygon."""

    def __init__(self, polygon_count):
        self.flip = np.zeros(polygon_count, bool)
        self.doubtful = np.zeros(polygon_count, bool)
        self.in_scope = np.zeros(polygon_count, bool)
        self.split = 0          # polygons whose triangles the library turned different ways
        self.report = None      # meshfix.Report, None when the scope has no triangles
        self.triangles = 0

    def turn(self, inside=False):
        """The polygons to reverse: those the library flipped (outside), or with inside every
        polygon in scope the other way from that: the reverse of what outside leaves."""
        return self.flip ^ self.in_scope if inside else self.flip.copy()


def mesh_arrays(me, scope=None, use_normals=True):
    """The triangles of the polygons in scope (a bool per polygon, None: all) as the library
    takes them: (indices (T, 3) uint32, positions (V, 3) float64, vertex normals (V, 3) float32 or
    None, the polygon of each triangle). With the mesh's custom split normals as evidence, a vertex
    is a distinct (vertex, corner normal) pair (an OBJ's v/vn pairs, the command-line tool's
    vertices); the library joins the corners at equal positions either way."""
    me.calc_loop_triangles()
    tri_count = len(me.loop_triangles)
    tri_loops = np.empty(3 * tri_count, np.int32)
    me.loop_triangles.foreach_get("loops", tri_loops)
    tri_polygon = np.empty(tri_count, np.int32)
    me.loop_triangles.foreach_get("polygon_index", tri_polygon)
    loop_vertex = np.empty(len(me.loops), np.int32)
    me.loops.foreach_get("vertex_index", loop_vertex)
    co = np.empty(3 * len(me.vertices), np.float32)
    me.vertices.foreach_get("co", co)
    positions = co.reshape(-1, 3).astype(np.float64)
    if scope is not None:
        keep = scope[tri_polygon]
        tri_loops = tri_loops.reshape(-1, 3)[keep].reshape(-1)
        tri_polygon = tri_polygon[keep]
    normals = None
    if use_normals and me.has_custom_normals:
        me.calc_normals_split()
        loop_normal = np.empty(3 * len(me.loops), np.float32)
        me.loops.foreach_get("normal", loop_normal)
        loop_normal = loop_normal.reshape(-1, 3)
        # the loops of the polygons in scope, in loop order, each (vertex, normal) pair a vertex
        # in the order the pairs first appear
        starts = np.empty(len(me.polygons), np.int32)
        totals = np.empty(len(me.polygons), np.int32)
        me.polygons.foreach_get("loop_start", starts)
        me.polygons.foreach_get("loop_total", totals)
        loop_polygon = np.repeat(np.arange(len(me.polygons)), totals)
        loops = np.arange(len(me.loops)) if scope is None else np.flatnonzero(scope[loop_polygon])
        keys = np.empty(len(loops), [("v", "<i4"), ("n", "<u4", 3)])
        keys["v"] = loop_vertex[loops]
        keys["n"] = loop_normal[loops].view(np.uint32)
        _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
        order = np.argsort(first, kind="stable")
        rank = np.empty_like(order)
        rank[order] = np.arange(len(order))
        pair_of_loop = np.full(len(me.loops), -1, np.int64)
        pair_of_loop[loops] = rank[inverse]
        pair_loop = loops[first[order]]
        indices = pair_of_loop[tri_loops].astype(np.uint32).reshape(-1, 3)
        normals = np.ascontiguousarray(loop_normal[pair_loop])
        positions = np.ascontiguousarray(positions[loop_vertex[pair_loop]])
    else:
        indices = loop_vertex[tri_loops].astype(np.uint32).reshape(-1, 3)
    return indices, positions, normals, tri_polygon


def options(policy="auto", weld_tolerance=0.0, min_confidence=0.0):
    o = dict(policy=policy, evidence=dict(min_confidence=float(min_confidence)))
    if weld_tolerance > 0.0:
        o.update(topology="weld", weld_tolerance=float(weld_tolerance))
    if policy == "up":
        o["up"] = (0.0, 0.0, 1.0)  # Blender's up
    return o


def decide(me, scope=None, policy="auto", weld_tolerance=0.0, min_confidence=0.0, use_normals=True, threads=None):
    """Runs the library on the polygons in scope and decides each polygon (Decision)."""
    polygon_count = len(me.polygons)
    d = Decision(polygon_count)
    d.in_scope[:] = True if scope is None else scope
    indices, positions, normals, tri_polygon = mesh_arrays(me, scope, use_normals)
    d.triangles = len(indices)
    if len(indices) == 0:
        return d
    o = options(policy, weld_tolerance, min_confidence)
    limit = meshfix.doubtful_below(**o)  # the report's bar: 0.9 under auto, else 0.5, or min_confidence
    if normals is not None:
        o["evidence"]["vertex_normals"] = normals
    if threads:
        o["threads"] = threads
    _, d.report, out = meshfix.orient(indices, positions, outputs=("flipped", "patch_ids", "patch_confidence"), **o)
    # each polygon the way most of its triangles turned; degenerate triangles (no patch) abstain
    decided = out.patch_ids != NO_PATCH
    turned = np.bincount(tri_polygon[decided & out.flipped], minlength=polygon_count)
    kept = np.bincount(tri_polygon[decided & ~out.flipped], minlength=polygon_count)
    d.flip = turned > kept
    d.split = int(np.count_nonzero((turned > 0) & (kept > 0)))
    # doubtful: a triangle of a patch whose verdict confidence is below the library's bar
    confidence = np.append(out.patch_confidence, 1.0)
    patch = np.where(decided, out.patch_ids, len(confidence) - 1).astype(np.int64)
    doubtful_triangle = confidence[patch] < limit
    d.doubtful = np.bincount(tri_polygon[doubtful_triangle], minlength=polygon_count) > 0
    return d


def corner_normals(me):
    """Each loop's normal as Blender shades it: (L, 3) float32, or None without custom normals."""
    if not me.has_custom_normals:
        return None
    me.calc_normals_split()
    n = np.empty(3 * len(me.loops), np.float32)
    me.loops.foreach_get("normal", n)
    return n.reshape(-1, 3)


def loop_vertices(me):
    v = np.empty(len(me.loops), np.int32)
    me.loops.foreach_get("vertex_index", v)
    return v


def old_loop_of_new(me, before_vertices):
    """After faces were reversed (same polygons, same loop_start and loop_total), the loop each
    loop was before it: found on the corner's vertex, so it holds however the reversal rotates."""
    after = loop_vertices(me)
    same = after == before_vertices
    old = np.arange(len(after))
    if same.all():
        return old
    starts = np.empty(len(me.polygons), np.int32)
    totals = np.empty(len(me.polygons), np.int32)
    me.polygons.foreach_get("loop_start", starts)
    me.polygons.foreach_get("loop_total", totals)
    loop_polygon = np.repeat(np.arange(len(me.polygons)), totals)
    changed = np.unique(loop_polygon[~same])
    for p in changed:
        s, n = int(starts[p]), int(totals[p])
        was, now = before_vertices[s:s + n], after[s:s + n]
        for r in range(n):  # the reversal keeping corner r first: now[i] == was[(r - i) % n]
            candidate = (r - np.arange(n)) % n
            if np.array_equal(was[candidate], now):
                old[s:s + n] = s + candidate
                break
        else:
            raise RuntimeError("meshfix: polygon %d changed its corners, not only their order" % p)
    return old


def inside_normals(me, normals, in_scope):
    """The corner normals with those of the polygons in scope negated: Inside turns every face
    in scope the other way from Outside, its custom normals with it."""
    totals = np.empty(len(me.polygons), np.int32)
    me.polygons.foreach_get("loop_total", totals)
    loop_in_scope = np.repeat(in_scope, totals)
    out = normals.copy()
    out[loop_in_scope] *= -1.0
    return out


def restore_corner_normals(me, normals, before_vertices):
    """Puts the corner normals back on the corners they were on, as custom split normals."""
    old = old_loop_of_new(me, before_vertices)
    me.normals_split_custom_set(normals[old])


def flip_bmesh(bm, flip):
    """Reverses the faces whose flag is set (bm's faces in the mesh's polygon order)."""
    bm.faces.ensure_lookup_table()
    faces = [bm.faces[int(i)] for i in np.flatnonzero(flip)]
    if faces:
        bmesh.ops.reverse_faces(bm, faces=faces, flip_multires=True)
    return len(faces)


def select_faces_bmesh(bm, selected):
    """The selection becomes these faces (and their edges and vertices)."""
    bm.faces.ensure_lookup_table()
    for v in bm.verts:
        v.select_set(False)
    for e in bm.edges:
        e.select_set(False)
    for f in bm.faces:
        f.select_set(False)
    for i in np.flatnonzero(selected):
        bm.faces[int(i)].select_set(True)
    bm.select_flush_mode()
