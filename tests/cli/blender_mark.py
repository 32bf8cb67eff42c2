"""Imports a --mark PLY in Blender (run inside it, headless) and says what
Blender shows: tests/test_cli.sh and tests/test_cli_files.sh run it as

    blender -b --factory-startup --python-exit-code 1 --python tests/cli/blender_mark.py -- MARK.ply OUT.txt

and compare OUT.txt with the faces they turned. OUT.txt has the lines
    faces N                       the faces Blender imported
    colour NAME DOMAIN TYPE       its first colour attribute (none: "colour none")
    mixed N                       faces whose corners are not all one colour
    red X Y Z X Y Z X Y Z         a red face: its corners (float32, repr), sorted
    amber ...                     a doubtful one, the same way
Red and amber are told by their hue, so that Blender's colour space (byte
colours read back linear) does not matter."""
import bpy
import sys

path, out = sys.argv[sys.argv.index("--") + 1:][:2]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_mesh.ply(filepath=path)
mesh = bpy.context.selected_objects[0].data
lines = ["faces %d" % len(mesh.polygons)]


def kind(c):
    r, g, b = c[0], c[1], c[2]
    if r > 0.2 and g < 0.25 * r and b < 0.25 * r:
        return "red"
    if r > 0.2 and 0.2 * r <= g <= 0.7 * r and b < 0.1 * r:
        return "amber"
    return None


if len(mesh.color_attributes) == 0:
    lines.append("colour none")
else:
    attribute = mesh.color_attributes[0]
    lines.append("colour %s %s %s" % (attribute.name, attribute.domain, attribute.data_type))
    data = attribute.data
    mixed = 0
    for poly in mesh.polygons:
        if attribute.domain == "CORNER":
            colours = [tuple(data[i].color) for i in poly.loop_indices]
        else:
            colours = [tuple(data[v].color) for v in poly.vertices]
        if any(c != colours[0] for c in colours):
            mixed += 1
            continue
        k = kind(colours[0])
        if k is not None:
            corners = sorted(tuple(mesh.vertices[v].co) for v in poly.vertices)
            lines.append(k + " " + " ".join(repr(x) for p in corners for x in p))
    lines.insert(2, "mixed %d" % mixed)
with open(out, "w") as f:
    f.write("\n".join(lines) + "\n")
