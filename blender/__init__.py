"""meshfix for Blender: "Recalculate Outside (meshfix)", winding repair by meshfix.h.

Mesh > Normals in edit mode (the selected faces, or all when none are),
Object in object mode (every selected mesh object). blender/README.md has
the options and how to build and install the add-on."""

bl_info = {
    "name": "meshfix: Recalculate Outside",
    "author": "meshfix.h",
    "version": (0, 2, 0),
    "blender": (3, 4, 0),
    "location": "Edit Mode: Mesh > Normals; Object Mode: Object",
    "description": "Face orientation repair that copes with overlapping faces that share no vertices, "
                   "open parts and gaps (meshfix.h)",
    "category": "Mesh",
}

import os

import bmesh
import bpy
import numpy as np
from bpy.props import BoolProperty, EnumProperty, FloatProperty

from . import meshfix, repair

def _policy_items():
    """The menu: each policy a file can use, with the header's line about it (meshfix_policy_info)."""
    return [(name, name.capitalize(), repair.policy_description(name)) for name in repair.policy_names()]


def _threads():
    return max(1, min(8, os.cpu_count() or 1))


def _count(n, one, many):
    return "%d %s" % (n, one if n == 1 else many)


class MESH_OT_meshfix_recalculate_outside(bpy.types.Operator):
    """Make face orientation consistent and outward with meshfix: copes with faces that overlap without \
joined vertices, open parts and gaps"""
    bl_idname = "mesh.meshfix_recalculate_outside"
    bl_label = "Recalculate Outside (meshfix)"
    bl_options = {'REGISTER', 'UNDO'}

    policy: EnumProperty(name="Policy", items=_policy_items(), default="auto",
                         description="How each patch of consistently wound faces chooses its side")
    weld_tolerance: FloatProperty(
        name="Weld Tolerance", default=0.0, min=0.0, soft_max=0.01, precision=6, step=0.001, subtype='DISTANCE',
        description="Treat vertices closer than this as one for the decision (0: only equal positions join; "
                    "the mesh's vertices are not merged)")
    min_confidence: FloatProperty(
        name="Minimum Confidence", default=0.0, min=0.0, max=1.0, subtype='FACTOR',
        description="A patch whose verdict is less certain than this keeps the side most of its area faces")
    use_custom_normals: BoolProperty(
        name="Custom Normals as Evidence", default=True,
        description="Use the mesh's custom split normals (when it has them) as evidence of the outside")
    inside: BoolProperty(
        name="Inside", default=False,
        description="Face the inside: every face the other way from what Outside leaves it, its custom "
                    "normals too (as Blender's Recalculate Inside)")
    select_flipped: BoolProperty(
        name="Select Flipped Faces", default=False,
        description="Select the faces this run reversed (the selection is replaced; with Select Doubtful "
                    "Faces, both)")
    select_doubtful: BoolProperty(
        name="Select Doubtful Faces", default=False,
        description="Select the faces of patches whose verdict confidence is below 0.5 or the minimum "
                    "confidence (the selection is replaced; with Select Flipped Faces, both)")

    @classmethod
    def poll(cls, context):
        if context.mode == 'EDIT_MESH':
            return True
        if context.mode == 'OBJECT':
            return any(o.type == 'MESH' for o in context.selected_objects)
        return False

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        for name in ("inside", "policy", "weld_tolerance", "min_confidence", "use_custom_normals",
                     "select_flipped", "select_doubtful"):
            layout.prop(self, name)

    def _settings(self):
        return dict(policy=self.policy, weld_tolerance=self.weld_tolerance, min_confidence=self.min_confidence,
                    use_normals=self.use_custom_normals, threads=_threads())

    def _selecting(self):
        return self.select_flipped or self.select_doubtful

    def _selection(self, d, turn):
        """The faces to select: those reversed and/or those doubtful, as asked."""
        return (turn & self.select_flipped) | (d.doubtful & self.select_doubtful)

    def _object_mode(self, context):
        done, results = set(), []
        for ob in context.selected_objects:
            if ob.type != 'MESH' or ob.data in done or ob.data.library is not None:
                continue
            done.add(ob.data)
            me = ob.data
            before = repair.loop_vertices(me)
            normals = repair.corner_normals(me)
            d = repair.decide(me, None, **self._settings())
            turn = d.turn(self.inside)
            bm = bmesh.new()
            bm.from_mesh(me)
            flipped = repair.flip_bmesh(bm, turn)
            if self._selecting():
                repair.select_faces_bmesh(bm, self._selection(d, turn))
            if flipped or self._selecting():
                bm.to_mesh(me)
            bm.free()
            if normals is not None and (flipped or self.inside):
                repair.restore_corner_normals(me, repair.inside_normals(me, normals, d.in_scope) if self.inside
                                              else normals, before)
            me.update()
            results.append((ob.name, d, flipped))
        return results

    def _edit_mode(self, context):
        results = []
        for ob in context.objects_in_mode_unique_data:
            if ob.type != 'MESH':
                continue
            ob.update_from_editmode()
            me = ob.data
            selected = np.empty(len(me.polygons), bool)
            me.polygons.foreach_get("select", selected)
            hidden = np.empty(len(me.polygons), bool)
            me.polygons.foreach_get("hide", hidden)
            # the selected faces, or all but the hidden ones when none is selected
            scope = selected if selected.any() else (~hidden if hidden.any() else None)
            before = repair.loop_vertices(me)
            normals = repair.corner_normals(me)
            d = repair.decide(me, scope, **self._settings())
            turn = d.turn(self.inside)
            bm = bmesh.from_edit_mesh(me)
            flipped = repair.flip_bmesh(bm, turn)
            if self._selecting():
                repair.select_faces_bmesh(bm, self._selection(d, turn))
            bmesh.update_edit_mesh(me, loop_triangles=True, destructive=False)
            if normals is not None and (flipped or self.inside):
                # custom normals are set on the Mesh: the edit mesh is written out, mended and read back
                ob.update_from_editmode()
                repair.restore_corner_normals(me, repair.inside_normals(me, normals, d.in_scope) if self.inside
                                              else normals, before)
                bm.clear()
                bm.from_mesh(me)
                bmesh.update_edit_mesh(me, loop_triangles=True, destructive=True)
            results.append((ob.name, d, flipped))
        return results

    def execute(self, context):
        try:
            results = self._edit_mode(context) if context.mode == 'EDIT_MESH' else self._object_mode(context)
        except meshfix.MeshfixError as e:
            self.report({'ERROR'}, "meshfix: %s" % e)
            return {'CANCELLED'}
        if not results:
            self.report({'WARNING'}, "meshfix: no mesh to repair")
            return {'CANCELLED'}
        if len(results) > 1:
            for name, d, flipped in results:
                self.report({'INFO'}, "%s: %s" % (name, mesh_line(d, flipped, self.inside)))
        self.report({'INFO'}, summary_line(results, self.select_doubtful, self.inside, self.select_flipped))
        return {'FINISHED'}


def mesh_line(d, flipped, inside=False):
    """The library's summary of one mesh, with the faces (polygons) flipped when they are not its
    triangles; with Inside, what was turned for it."""
    if d.report is None:
        return "no faces"
    text = d.report.summary
    if inside:
        text += "; Inside: %s reversed, every face the other way" % _count(flipped, "face", "faces")
    elif flipped and flipped != d.report.triangles_flipped:
        text += " (%s)" % _count(flipped, "face", "faces")
    if d.split:
        text += "; %s split between the sides" % _count(d.split, "face", "faces")
    return text


def summary_line(results, select_doubtful=False, inside=False, select_flipped=False):
    """One mesh: its line; several (each reported on its own before): their counts summed."""
    doubtful = sum(int(np.count_nonzero(d.doubtful)) for _, d, _ in results)
    if len(results) == 1:
        line = mesh_line(results[0][1], results[0][2], inside)
    else:
        reports = [d.report for _, d, _ in results if d.report is not None]
        faces = sum(flipped for _, _, flipped in results)
        triangles = sum(r.triangles_flipped for r in reports)
        patches = sum(r.patches_flipped for r in reports)
        line = "%s: %s flipped (%s in %s)" % (
            _count(len(results), "mesh", "meshes"), _count(faces, "face", "faces"),
            _count(triangles, "triangle", "triangles"), _count(patches, "patch", "patches"))
        unsure = sum(r.patches_doubtful for r in reports)
        if unsure:
            line += "; %s doubtful" % _count(unsure, "patch", "patches")
        if inside:
            line += "; Inside"
    if select_flipped:
        line += "; %s selected" % _count(sum(f for _, _, f in results), "flipped face", "flipped faces")
    if select_doubtful:
        line += "; %s selected" % _count(doubtful, "doubtful face", "doubtful faces")
    return line


def _menu(self, context):
    self.layout.separator()
    self.layout.operator(MESH_OT_meshfix_recalculate_outside.bl_idname)
    self.layout.operator(MESH_OT_meshfix_recalculate_outside.bl_idname, text="Recalculate Inside (meshfix)").inside = True


def register():
    bpy.utils.register_class(MESH_OT_meshfix_recalculate_outside)
    bpy.types.VIEW3D_MT_edit_mesh_normals.append(_menu)
    bpy.types.VIEW3D_MT_object.append(_menu)


def unregister():
    bpy.types.VIEW3D_MT_object.remove(_menu)
    bpy.types.VIEW3D_MT_edit_mesh_normals.remove(_menu)
    bpy.utils.unregister_class(MESH_OT_meshfix_recalculate_outside)
