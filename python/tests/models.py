"""Small loaders for the real models the tests use (Debian's
assimp-testmodels and occt-misc): each returns a dict with "indices"
((T, 3) uint32), "positions" ((V, 3) float32) and, where the file has
them, "triangle_normals" (STL facets) or "vertices" (a PLY's whole
interleaved vertex rows, float32, x y z first) and "vertex_normals".
Polygons are fanned into triangles. An STL stays a soup (three corners
per facet), as an engine would load it: topology joins the corners."""
import os
import struct

import numpy as np

ASSIMP = os.environ.get("MESHFIX_MODELS", "/usr/share/assimp/models")
OCCT = "/usr/share/opencascade/data/stl"

MODELS = {
    "spider.obj": os.path.join(ASSIMP, "OBJ", "spider.obj"),
    "cube.ply": os.path.join(ASSIMP, "PLY", "cube.ply"),
    "cube_binary.ply": os.path.join(ASSIMP, "PLY", "cube_binary.ply"),
    "Wuson.ply": os.path.join(ASSIMP, "PLY", "Wuson.ply"),
    "Spider_binary.stl": os.path.join(ASSIMP, "STL", "Spider_binary.stl"),
    "sphereWithHole.stl": os.path.join(ASSIMP, "STL", "sphereWithHole.stl"),
    "Wuson.stl": os.path.join(ASSIMP, "STL", "Wuson.stl"),
    "3DSMaxExport.STL": os.path.join(ASSIMP, "STL", "3DSMaxExport.STL"),
    "motor.stl": os.path.join(OCCT, "motor.stl"),
}


def package_of(path):
    return "occt-misc" if path.startswith(OCCT) else "assimp-testmodels"


def _fan(polygons):
    triangles = []
    for p in polygons:
        for k in range(1, len(p) - 1):
            triangles.append((p[0], p[k], p[k + 1]))
    return np.array(triangles, dtype=np.uint32).reshape(-1, 3)


def load_obj(path):
    positions, polygons = [], []
    with open(path, "r", encoding="latin-1") as f:
        for line in f:
            words = line.split()
            if not words:
                continue
            if words[0] == "v":
                positions.append([float(x) for x in words[1:4]])
            elif words[0] == "f":
                corners = []
                for w in words[1:]:
                    v = int(w.split("/")[0])
                    corners.append(v - 1 if v > 0 else len(positions) + v)
                polygons.append(corners)
    return {"indices": _fan(polygons), "positions": np.array(positions, dtype=np.float32)}


def load_stl(path):
    with open(path, "rb") as f:
        data = f.read()
    if len(data) >= 84:
        (count,) = struct.unpack_from("<I", data, 80)
        if 84 + 50 * count == len(data):
            records = np.frombuffer(data, dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]),
                                    count=count, offset=84)
            positions = np.ascontiguousarray(records["v"].reshape(-1, 3))
            return {"indices": np.arange(3 * count, dtype=np.uint32).reshape(-1, 3), "positions": positions,
                    "triangle_normals": np.ascontiguousarray(records["n"])}
    normals, corners = [], []
    for line in data.decode("latin-1").splitlines():
        words = line.split()
        if len(words) >= 5 and words[0] == "facet" and words[1] == "normal":
            normals.append([float(x) for x in words[2:5]])
        elif len(words) >= 4 and words[0] == "vertex":
            corners.append([float(x) for x in words[1:4]])
    positions = np.array(corners, dtype=np.float32)
    return {"indices": np.arange(len(corners), dtype=np.uint32).reshape(-1, 3), "positions": positions,
            "triangle_normals": np.array(normals, dtype=np.float32)}


_PLY_TYPES = {"char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2", "int16": "i2",
              "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
              "float": "f4", "float32": "f4", "double": "f8", "float64": "f8"}


def load_ply(path):
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header") + len(b"end_header")
    end = data.index(b"\n", end) + 1
    header = data[:end].decode("latin-1").splitlines()
    fmt, elements = None, []
    for line in header:
        words = line.split()
        if not words:
            continue
        if words[0] == "format":
            fmt = words[1]
        elif words[0] == "element":
            elements.append((words[1], int(words[2]), []))
        elif words[0] == "property":
            elements[-1][2].append(words[1:])
    body = data[end:]
    vertex_rows, polygons = None, []
    if fmt == "ascii":
        tokens = body.decode("latin-1").split()
        at = 0
        for name, count, props in elements:
            for _ in range(count):
                row = []
                for p in props:
                    if p[0] == "list":
                        n = int(tokens[at])
                        row.append([int(t) for t in tokens[at + 1:at + 1 + n]])
                        at += 1 + n
                    else:
                        row.append(float(tokens[at]))
                        at += 1
                if name == "vertex":
                    vertex_rows = vertex_rows if vertex_rows is not None else []
                    vertex_rows.append(row)
                elif name == "face":
                    polygons.append(next(v for v in row if isinstance(v, list)))
        vertices = np.array(vertex_rows, dtype=np.float32)
        names = [p[-1] for p in elements[0][2]]
    elif fmt == "binary_little_endian":
        at = 0
        vertices, names = None, []
        for name, count, props in elements:
            if name == "vertex":
                dtype = np.dtype([(p[-1], "<" + _PLY_TYPES[p[0]]) for p in props])
                rows = np.frombuffer(body, dtype=dtype, count=count, offset=at)
                at += dtype.itemsize * count
                names = [p[-1] for p in props]
                vertices = np.stack([rows[n].astype(np.float32) for n in names], axis=1)
            else:
                for _ in range(count):
                    for p in props:
                        if p[0] == "list":
                            ct, it = np.dtype("<" + _PLY_TYPES[p[1]]), np.dtype("<" + _PLY_TYPES[p[2]])
                            n = int(np.frombuffer(body, ct, 1, at)[0])
                            values = np.frombuffer(body, it, n, at + ct.itemsize)
                            at += ct.itemsize + it.itemsize * n
                            if name == "face":
                                polygons.append([int(v) for v in values])
                        else:
                            at += np.dtype(_PLY_TYPES[p[0]]).itemsize
    else:
        raise ValueError("unsupported PLY format %s" % fmt)
    column = {n: i for i, n in enumerate(names)}
    xyz = [column["x"], column["y"], column["z"]]
    mesh = {"indices": _fan(polygons), "positions": np.ascontiguousarray(vertices[:, xyz])}
    if xyz == [0, 1, 2] and vertices.shape[1] > 3:
        mesh["vertices"] = vertices
    if all(n in column for n in ("nx", "ny", "nz")):
        mesh["vertex_normals"] = np.ascontiguousarray(vertices[:, [column["nx"], column["ny"], column["nz"]]])
    return mesh


def load(name):
    path = MODELS[name]
    loader = {".obj": load_obj, ".stl": load_stl, ".ply": load_ply}[os.path.splitext(path)[1].lower()]
    return loader(path)
