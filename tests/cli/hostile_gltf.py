#!/usr/bin/env python3
"""hostile_gltf.py DIR: writes the crafted glTF files of tests/test_cli_hostile.sh.

Each case is a directory under DIR. The meshes are cubes of 12 triangles
with some faces turned, so a repair has something to write. Standard
library only (json, struct).

  traversal/NAME/a/b/in/scene.gltf  an image or buffer URI that climbs out
      of in/ by an encoding of "..", or names an absolute path; the file it
      aims at exists (traversal/NAME/secret.*), so only the tool's own
      check stands between it and the file
  alias/scene.gltf      two meshes whose index bufferViews are the same
      bytes; mesh A needs 1 flip, mesh B (mirrored positions) 11
  alias_offset/scene.gltf  the same, with the second view starting 6 bytes
      (one triangle) in: the two overlap but are not equal
  deep/scene.gltf, deep/scene.glb  20,000 nested arrays in asset.extras
  fifo/scene.gltf       its buffer is fifo.bin (the test makes the FIFO)
  fifo_image/scene.gltf an image uri naming fifo.png (a FIFO)
  cwd/in/scene.gltf     its buffer cwd.bin is missing beside it, present in
      cwd/ (the directory the test runs from)
  big/in.glb, big/in.gltf + big/in.bin  about 240 KB, a repair to write
  collide/a/s.gltf, collide/b/t.gltf   different files, both with a
      buffer named scene.bin
  empty/scene.gltf      a default material, a default sampler and an empty
      scene ({}: valid glTF, which tinygltf writes back as null)
Round 4 (r4/):
  names/in.gltf         buffers in.bin (the cube) and out.bin: a repair to
      out.gltf beside it must not take out.bin's name
  glb/m.gltf            buffers m1.bin (the cube) and m.bin: m.glb beside it
      must not write m1.bin
  document/scene.gltf   what tinygltf's model loses: a camera without zfar,
      nulls, [] and {} in extras, 9007199254740993, -0, 1E2, escapes, a
      sampler's name, asset.minVersion, unknown members and extensions;
      two meshes share an index accessor (cloned: accessors, bufferViews
      and the buffer's length change)
  normals/scene.gltf    mesh A (a cube, its normals pointing in) and mesh B
      (a quad, its normals right) whose NORMAL accessors share bytes
  same_file/scene.gltf  two buffers naming s.bin: indices through one,
      positions through the other
  skin/scene.gltf       a MAT4 inverse-bind accessor over the first 56
      bytes of the index accessor's, in one bufferView
  plus/scene.gltf       its buffer is a+b.bin ('+' is not a space)
  texture/scene.gltf    an image tex.png beside it; missing/scene.gltf an
      image that is not there
  links/NAME/in/scene.gltf  an image or buffer that is a symbolic link out
      of in/ (the test makes the links)
"""
import base64
import json
import os
import struct
import sys

CUBE = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
# outward (counter-clockwise seen from outside)
CUBE_FACES = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
              (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]


def cube(turned, mirrored=False, offset=(0.0, 0.0, 0.0)):
    """Positions and indices of a cube with the faces in `turned` reversed."""
    positions = [((-x if mirrored else x) + offset[0], y + offset[1], z + offset[2]) for x, y, z in CUBE]
    faces = [(a, c, b) if i in turned else (a, b, c) for i, (a, b, c) in enumerate(CUBE_FACES)]
    return positions, faces


def pack_positions(positions):
    return b"".join(struct.pack("<3f", *p) for p in positions)


def pack_indices(faces):
    data = b"".join(struct.pack("<3H", *f) for f in faces)
    return data + b"\0" * (-len(data) % 4)


def document(meshes, buffer_uri, images=(), extras=None, index_views=None):
    """A glTF document over one buffer: per mesh a POSITION view and an
    index view (index_views, when given, overrides the index views as
    (offset, length) pairs in the buffer). Returns (json dict, bin bytes)."""
    data = b""
    views, accessors, gltf_meshes = [], [], []
    position_views, index_spans = [], []
    for positions, faces in meshes:
        p = pack_positions(positions)
        position_views.append((len(data), len(p), positions))
        data += p
    for positions, faces in meshes:
        i = pack_indices(faces)
        index_spans.append((len(data), 6 * len(faces)))
        data += i
    if index_views is not None:
        index_spans = index_views
    for k, (offset, length, positions) in enumerate(position_views):
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": length, "target": 34962})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": len(positions),
                          "type": "VEC3", "min": [min(p[a] for p in positions) for a in range(3)],
                          "max": [max(p[a] for p in positions) for a in range(3)]})
    for k, (offset, length) in enumerate(index_spans):
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": length, "target": 34963})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5123, "count": length // 2,
                          "type": "SCALAR"})
    n = len(meshes)
    for k in range(n):
        gltf_meshes.append({"primitives": [{"attributes": {"POSITION": k}, "indices": n + k}]})
    doc = {"asset": {"version": "2.0"}, "scene": 0,
           "scenes": [{"nodes": list(range(n))}],
           "nodes": [{"mesh": k, "translation": [2.0 * k, 0, 0]} for k in range(n)],
           "meshes": gltf_meshes, "accessors": accessors, "bufferViews": views,
           "buffers": [{"byteLength": len(data)}]}
    if buffer_uri is not None:
        doc["buffers"][0]["uri"] = buffer_uri
    if images:
        doc["images"] = [{"uri": u} for u in images]
        doc["textures"] = [{"source": k} for k in range(len(images))]
    if extras is not None:
        doc["asset"]["extras"] = extras
    return doc, data


def write(path, text_or_bytes):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    mode = "wb" if isinstance(text_or_bytes, bytes) else "w"
    with open(path, mode) as f:
        f.write(text_or_bytes)


def write_gltf(path, doc, data, bin_name=None):
    """A .gltf with its buffer in bin_name beside it (the doc's uri)."""
    write(path, json.dumps(doc, indent=1))
    if bin_name is not None:
        write(os.path.join(os.path.dirname(path), bin_name), data)


def glb(json_text, data):
    """A GLB of this JSON text and BIN chunk."""
    j = json_text.encode()
    j += b" " * (-len(j) % 4)
    b = data + b"\0" * (-len(data) % 4)
    body = struct.pack("<II", len(j), 0x4E4F534A) + j + struct.pack("<II", len(b), 0x004E4942) + b
    return b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body


def nest_extras(json_text, depth):
    """The document with asset.extras `depth` arrays deep (as text: too
    deep for Python's own json module)."""
    return json_text.replace('"version": "2.0"', '"version": "2.0", "extras": ' + "[" * depth + "]" * depth, 1)


PNG = bytes.fromhex("89504e470d0a1a0a0000000d4948445200000001000000010806000000"
                    "1f15c4890000000d49444154789c6360000002000100e221bc330000000049454e44ae426082")

TRAVERSALS = {
    # image URIs: from a/b/in/, three levels up is traversal/NAME/
    "percent_lower": ("image", "%2e%2e/%2e%2e/%2e%2e/secret.png"),
    "percent_upper": ("image", "%2E%2E/%2E%2E/%2E%2E/secret.png"),
    "percent_half": ("image", ".%2e/%2e./.%2E/secret.png"),
    "percent_slashes": ("image", "%2e%2e%2f%2e%2e%2f%2e%2e%2fsecret.png"),
    "down_then_up": ("image", "x/%2e%2e/%2e%2e/%2e%2e/%2e%2e/secret.png"),
    "backslashes": ("image", "..%5c..%5c..%5csecret.png"),
    "absolute_encoded": ("image", "%2F{secret}"),
    "buffer_percent": ("buffer", "%2e%2e/%2e%2e/%2e%2e/secret.bin"),
    "buffer_mixed": ("buffer", "./%2e./..%2F%2e%2e/secret.bin"),
}


def main():
    root = sys.argv[1]
    good, bad = cube({3}), cube({3}, mirrored=True)

    for name, (kind, uri) in TRAVERSALS.items():
        base = os.path.join(root, "traversal", name)
        doc, data = document([good], "scene.bin" if kind == "image" else None)
        secret_png = os.path.join(os.path.abspath(base), "secret.png")
        uri = uri.replace("{secret}", secret_png.lstrip("/").replace("/", "%2F"))
        if kind == "image":
            doc["images"] = [{"uri": uri}]
            write(os.path.join(base, "a/b/in/scene.bin"), data)
        else:
            doc["buffers"][0]["uri"] = uri
        write(os.path.join(base, "a/b/in/scene.gltf"), json.dumps(doc, indent=1))
        write(os.path.join(base, "secret.png"), PNG)
        write(os.path.join(base, "secret.bin"), data)

    # two meshes over the same index bytes: A right after 1 flip, B after 11
    a, b = good, cube(set(range(12)) - {3}, mirrored=True)
    a_doc, _ = document([a, b], "x.bin")
    first = a_doc["bufferViews"][2]
    for case, shift in (("alias", 0), ("alias_offset", 6)):
        spans = [(first["byteOffset"], 72), (first["byteOffset"] + shift, 72 - shift)]
        doc, data = document([a, (b[0], b[1][shift // 6:])], "scene.bin", index_views=spans)
        # the bytes of mesh A's indices, which mesh B reads too
        data = data[:first["byteOffset"]] + pack_indices(a[1]) + data[first["byteOffset"] + 72:]
        write_gltf(os.path.join(root, case, "scene.gltf"), doc, data, "scene.bin")

    doc, data = document([good], None)
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
    write(os.path.join(root, "deep", "scene.gltf"), nest_extras(json.dumps(doc), 20000))
    doc, data = document([good], None)
    write(os.path.join(root, "deep", "scene.glb"), glb(nest_extras(json.dumps(doc), 20000), data))

    doc, data = document([good], "fifo.bin")
    write_gltf(os.path.join(root, "fifo", "scene.gltf"), doc, data)
    doc, data = document([good], "scene.bin", images=["fifo.png"])
    write_gltf(os.path.join(root, "fifo_image", "scene.gltf"), doc, data, "scene.bin")

    doc, data = document([good], "cwd.bin")
    write_gltf(os.path.join(root, "cwd", "in", "scene.gltf"), doc, data)
    write(os.path.join(root, "cwd", "cwd.bin"), data)

    # about 240 KB: 400 cubes, the first with a turned face
    many = [cube({3} if k == 0 else set(), offset=(2.0 * (k % 10), 2.0 * (k // 10 % 10), 2.0 * (k // 100)))
            for k in range(400)]
    doc, data = document(many, None)
    doc["nodes"] = [{"mesh": k} for k in range(len(many))]
    write(os.path.join(root, "big", "in.glb"), glb(json.dumps(doc), data))
    doc["buffers"][0]["uri"] = "in.bin"
    write_gltf(os.path.join(root, "big", "in.gltf"), doc, data, "in.bin")

    doc, data = document([good], "scene.bin")
    doc["materials"] = [{}]
    doc["samplers"] = [{}]
    doc["scenes"].append({})
    doc["meshes"][0]["primitives"][0]["material"] = 0
    write_gltf(os.path.join(root, "empty", "scene.gltf"), doc, data, "scene.bin")

    for sub, name, mesh in (("a", "s.gltf", good), ("b", "t.gltf", cube({5}))):
        doc, data = document([mesh], "scene.bin")
        write_gltf(os.path.join(root, "collide", sub, name), doc, data, "scene.bin")
    round4(os.path.join(root, "r4"), good)


def face_quads():
    """The cube's faces as quads of 4 corners, counter-clockwise from
    outside, with their outward normals."""
    return [((0, 3, 2, 1), (0, 0, -1)), ((4, 5, 6, 7), (0, 0, 1)), ((0, 1, 5, 4), (0, -1, 0)),
            ((1, 2, 6, 5), (1, 0, 0)), ((2, 3, 7, 6), (0, 1, 0)), ((3, 0, 4, 7), (-1, 0, 0))]


def round4(root, good):
    # 1: names beside the input
    doc, data = document([good], "in.bin")
    doc["buffers"].append({"byteLength": 16, "uri": "out.bin"})
    write_gltf(os.path.join(root, "names", "in.gltf"), doc, data, "in.bin")
    write(os.path.join(root, "names", "out.bin"), b"out.bin's bytes!")
    doc, data = document([good], "m1.bin")
    doc["buffers"].append({"byteLength": 16, "uri": "m.bin"})
    write_gltf(os.path.join(root, "glb", "m.gltf"), doc, data, "m1.bin")
    write(os.path.join(root, "glb", "m.bin"), b"m.bin's bytes!!!")

    # 4: a document tinygltf's model does not keep
    doc, data = document([good], "scene.bin")
    doc["meshes"].append({"primitives": [dict(doc["meshes"][0]["primitives"][0])], "name": "twin"})
    doc["nodes"].append({"mesh": 1, "translation": [3, 0, 0], "extras": [None, 1, None]})
    doc["scenes"][0]["nodes"].append(1)
    doc["asset"]["minVersion"] = "2.0"
    doc["asset"]["extras"] = {"list": [1, None, 2], "empty_list": [], "empty_object": {}, "nested": [[], {}, None]}
    doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "aspectRatio": 1.5}}]
    doc["nodes"][0]["camera"] = 0
    doc["samplers"] = [{"name": "the sampler", "magFilter": 9729}]
    doc["extensionsUsed"] = ["EXT_unknown_to_all"]
    doc["extensions"] = {"EXT_unknown_to_all": {"data": [None, {}, []]}}
    doc["x_unknown_member"] = {"kept": True}
    text = json.dumps(doc, indent=1)
    text = text.replace('"kept": true', '"kept": true, "big": 9007199254740993, "minus_zero": -0, "e": 1E2, '
                        '"escaped": "caf\\u00e9 \\"q\\""')
    write(os.path.join(root, "document", "scene.gltf"), text)
    write(os.path.join(root, "document", "scene.bin"), data)

    # 5: NORMAL bytes shared by two meshes
    positions, normals, faces = [], [], []
    for quad, n in face_quads():
        base = len(positions)
        positions += [CUBE[k] for k in quad]
        normals += [tuple(-c for c in n)] * 4  # pointing in: --fix-normals would negate them
        faces += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
    p, nb, i = pack_positions(positions), pack_positions(normals), pack_indices(faces)
    quad = pack_indices([(0, 2, 1), (0, 3, 2)])  # face 0 turned: its face normal is the stored one
    data = p + nb + i + quad
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": len(p)}, {"buffer": 0, "byteOffset": len(p), "byteLength": len(nb)},
             {"buffer": 0, "byteOffset": len(p) + len(nb), "byteLength": 72},
             {"buffer": 0, "byteOffset": len(p) + len(nb) + len(i), "byteLength": 12}]
    vec3 = lambda view, count, **more: dict({"bufferView": view, "componentType": 5126, "count": count, "type": "VEC3"}, **more)
    accessors = [vec3(0, 24, min=[0, 0, 0], max=[1, 1, 1]), vec3(1, 24),
                 {"bufferView": 2, "componentType": 5123, "count": 36, "type": "SCALAR"},
                 vec3(0, 4, min=[0, 0, 0], max=[1, 1, 0]), vec3(1, 4),
                 {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]
    doc = {"asset": {"version": "2.0"}, "scenes": [{"nodes": [0, 1]}], "nodes": [{"mesh": 0}, {"mesh": 1}],
           "meshes": [{"name": "A", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]},
                      {"name": "B", "primitives": [{"attributes": {"POSITION": 3, "NORMAL": 4}, "indices": 5}]}],
           "accessors": accessors, "bufferViews": views, "buffers": [{"byteLength": len(data), "uri": "scene.bin"}]}
    write_gltf(os.path.join(root, "normals", "scene.gltf"), doc, data, "scene.bin")

    # 6: two buffers, one file
    doc, data = document([good], "s.bin")
    doc["buffers"].append({"byteLength": len(data), "uri": "s.bin"})
    doc["bufferViews"][0]["buffer"] = 1  # positions through the second
    write_gltf(os.path.join(root, "same_file", "scene.gltf"), doc, data, "s.bin")

    # 12: inverse-bind matrices over index bytes, in one bufferView
    p, i = pack_positions(good[0]), pack_indices(good[1])
    data = p + b"\0" * 8 + i
    doc = {"asset": {"version": "2.0"}, "scenes": [{"nodes": [0, 1]}],
           "nodes": [{"mesh": 0, "skin": 0}, {"name": "joint"}], "skins": [{"joints": [1], "inverseBindMatrices": 2}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]},
                         {"bufferView": 1, "byteOffset": 8, "componentType": 5123, "count": 36, "type": "SCALAR"},
                         {"bufferView": 1, "componentType": 5126, "count": 1, "type": "MAT4"}],
           "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(p)},
                           {"buffer": 0, "byteOffset": len(p), "byteLength": 8 + 72}],
           "buffers": [{"byteLength": len(data), "uri": "scene.bin"}]}
    write_gltf(os.path.join(root, "skin", "scene.gltf"), doc, data, "scene.bin")

    # 16, 14: a '+' in a URI; a texture beside the file, and one missing
    doc, data = document([good], "a+b.bin")
    write_gltf(os.path.join(root, "plus", "scene.gltf"), doc, data, "a+b.bin")
    doc, data = document([good], "scene.bin", images=["tex.png"])
    write_gltf(os.path.join(root, "texture", "scene.gltf"), doc, data, "scene.bin")
    write(os.path.join(root, "texture", "tex.png"), PNG)
    doc, data = document([good], "scene.bin", images=["gone.png"])
    write_gltf(os.path.join(root, "missing", "scene.gltf"), doc, data, "scene.bin")

    # round 3: companions that are links out of in/ (the test makes them)
    for name in ("image_relative", "image_absolute", "image_subdirectory", "buffer_relative", "buffer_absolute",
                 "buffer_subdirectory"):
        uri = ("sub/" if name.endswith("subdirectory") else "") + ("tex.png" if name.startswith("image") else "scene.bin")
        doc, data = document([good], uri if name.startswith("buffer") else "scene.bin",
                             images=[uri] if name.startswith("image") else ())
        base = os.path.join(root, "links", name)
        write_gltf(os.path.join(base, "in", "scene.gltf"), doc, data, None if name.startswith("buffer") else "scene.bin")
        write(os.path.join(base, "outside", "tex.png"), PNG)
        write(os.path.join(base, "outside", "scene.bin"), data)


if __name__ == "__main__":
    main()
