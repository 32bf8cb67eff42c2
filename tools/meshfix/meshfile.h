/* meshfix command-line tool: what every file format gives the repair, and
   what the repair gives back.

   A file is read into one or more units (glTF: one per mesh; other formats:
   one), each the triangles the library decides on. A polygon is one face
   of one or more triangles, so it is flipped whole; the format then
   rewrites only the faces (and normals) that changed and passes every other
   byte through. */
#ifndef MESHFIX_TOOL_MESHFILE_H
#define MESHFIX_TOOL_MESHFILE_H

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "../../meshfix.h"

namespace tool {

class OutputSet;

/* A normal the file stores for faces that all lie in one plane (flat
   shading: one face, or the two triangles of a quad): after the repair it
   must point the way its face does. */
struct FlatNormal {
    uint32_t face;     /* the first face that uses it */
    float normal[3];
    uint32_t slot;     /* the format's number for it (vn index, vertex, ...) */
};

/* The triangles of one decision unit, as the library sees them. */
struct Unit {
    std::string name;                     /* glTF: the mesh's name or "mesh N"; else empty */
    std::vector<double> positions;        /* x y z per vertex */
    std::vector<uint32_t> indices;        /* 3 per triangle */
    std::vector<uint32_t> triangle_face;  /* the face of each triangle, non-decreasing */
    size_t face_count = 0;
    std::vector<float> triangle_normals;  /* empty, or 3 per triangle (STL facet normals) */
    std::vector<float> vertex_normals;    /* empty, or 3 per vertex (OBJ vn, PLY nx, glTF NORMAL) */
    /* The file's own vertices where the library's are split from them
       (OBJ with normals: a vertex per (v, vn) pair): x y z per file
       vertex, and the file vertex of each library vertex; both empty when
       the library's vertices are the file's. A file written in another
       format keeps the file's vertices and how its faces share them. */
    std::vector<double> file_positions;
    std::vector<uint32_t> file_vertex;
    /* The normals the file stores per vertex (OBJ vn, PLY nx ny nz, glTF
       NORMAL): x y z per slot, and the faces that use each, as (slot, face)
       pairs; find_flat_normals turns them into flat_normals. */
    std::vector<float> slot_normals;
    std::vector<std::pair<uint32_t, uint32_t>> slot_faces;
    std::vector<FlatNormal> flat_normals;
    bool flat_normals_follow_faces = false; /* STL: a flipped facet's normal is negated with it
                                               (when it agreed with the old winding) */
};

/* What the repair decided for a unit, per face and per flat normal. */
struct Changes {
    std::vector<unsigned char> face_flipped;
    std::vector<unsigned char> flat_disagree; /* flat normals pointing away from their face as written */
    std::vector<unsigned char> negate_flat;   /* those to negate (--fix-normals; STL: turned with the facet) */
    bool fix_normals = false;
};

/* A loaded file. The formats implement it. */
class MeshFile {
public:
    virtual ~MeshFile() = default;
    /* "obj", "off", "stl", "ply", "gltf" or "glb" */
    virtual const char *format() const = 0;
    /* Looks at what the format alone can check once faces and normals are
       decided (glTF: TANGENT.w), with --inspect too. */
    virtual void review(size_t unit, const Changes &changes) { (void)unit, (void)changes; }
    /* Rewrites the flipped faces and negates the normals asked for. */
    virtual void apply(size_t unit, const Changes &changes) = 0;
    /* Writes the file as it now is to `path` (a temporary of the same
       format); `target` is the final name, for formats that write files
       beside it (glTF buffers and images go to the directory of `path`). */
    virtual bool write(const std::string &path, const std::string &target, std::string &error) = 0;
    /* Plans and writes every file of the output as outputs of the set: by
       default the one file (write to a temporary of `target`, which
       replaces `input` when it is the same file); glTF names its buffers
       and images too. */
    virtual bool write_outputs(OutputSet &outputs, const std::string &input, const std::string &target, std::string &error);
    /* The files read besides the input (glTF buffers and images). */
    virtual std::vector<std::string> files_read() const { return {}; }
    /* Lines for the report that only this format has (glTF: mirrored
       nodes, double-sided materials), and the same as JSON members. */
    virtual std::vector<std::string> notes() const { return {}; }
    virtual std::string json_members() const { return {}; }

    std::vector<Unit> units;
    bool changed = false; /* set by apply when a byte of the file changes */
};

/* Appends face `face`, the polygon of these n vertices, to the unit as
   triangles that all face its way (ear clipping; a fan beyond 256 corners
   or when the polygon crosses itself). Positions must be in the unit. */
void add_face(Unit &unit, const uint32_t *vertices, size_t n, uint32_t face);

/* The normal of each face (the sum of its triangles' cross products,
   right for concave polygons too), 3 doubles per face. */
std::vector<double> face_normals(const Unit &unit);

/* Fills unit.flat_normals from its slots: each slot whose faces all lie in
   one plane (within about half a degree), with its first face. */
void find_flat_normals(Unit &unit);

/* Reads `path` as `format`; on failure nullptr and a one-line message. */
std::unique_ptr<MeshFile> load_obj(const std::string &data, std::string &error);
std::unique_ptr<MeshFile> load_off(const std::string &data, std::string &error);
std::unique_ptr<MeshFile> load_ply(const std::string &data, std::string &error);
std::unique_ptr<MeshFile> load_stl(const std::string &data, std::string &error);
std::unique_ptr<MeshFile> load_gltf(const std::string &path, std::string &error);
/* false in a build without tinygltf (-DMESHFIX_TOOL_NO_GLTF), whose
   load_gltf refuses every file with one line */
extern const bool gltf_supported;

/* The format an extension names ("obj", "off", "stl", "ply", "gltf",
   "glb"), or "" for any other. */
std::string format_of(const std::string &path);

} // namespace tool

#endif
