/* meshfix command-line tool: glTF 2.0 (.gltf with its buffers, and .glb)
   through tinygltf (Debian's libtinygltf-dev).

   Each mesh is one decision, across all of its triangle primitives (modes
   4, 5 and 6), in mesh space. A primitive whose triangles all keep their
   winding is left as it is; otherwise its index accessor is rewritten in
   place, or, when other primitives share it, it is a strip or fan, or the
   primitive has no indices, a new triangle-list accessor is added to the
   first buffer. Nodes whose transform mirrors (negative determinant: the
   spec reverses their winding) and double-sided materials are reported,
   never changed. A file nothing changed in is written back byte for byte,
   its buffers and images copied beside it. Images are never decoded. */
#include "json_edit.h"
#include "text.h"
#include "tool.h"

#ifndef MESHFIX_TOOL_NO_GLTF
#include <tiny_gltf.h>
#endif

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <map>
#include <set>
#include <sys/stat.h>

namespace tool {

#ifdef MESHFIX_TOOL_NO_GLTF
/* The Makefile builds this when tinygltf or nlohmann json is not installed. */
const bool gltf_supported = false;

std::unique_ptr<MeshFile> load_gltf(const std::string &, std::string &error)
{
    error = "this meshfix was built without glTF support (install libtinygltf-dev and nlohmann-json3-dev, "
            "then build it again)";
    return nullptr;
}
#else
const bool gltf_supported = true;

namespace {

/* Where a primitive's triangles are in its unit, and which vertices
   (numbers in the primitive's own vertex attributes) they use. */
struct PrimitiveTriangles {
    int mesh, primitive;
    size_t first_triangle;
    std::vector<uint32_t> corners; /* 3 per triangle, as the spec defines them for the mode */
};

/* A flat normal: the element of a NORMAL accessor, the TANGENT and
   TEXCOORD (of the normal texture) accessors of the same vertices (-1 when
   none), and the first triangle that uses it, by its vertices in the
   primitive. */
struct NormalSlot {
    int normal, tangent, texcoord;
    uint32_t element;
    uint32_t corners[3];
};

class GltfFile : public MeshFile {
public:
    const char *format() const override { return binary ? "glb" : "gltf"; }
    void review(size_t unit, const Changes &changes) override;
    void apply(size_t unit, const Changes &changes) override;
    bool write(const std::string &path, const std::string &target, std::string &error) override;
    bool write_outputs(OutputSet &outputs, const std::string &input, const std::string &target, std::string &error) override;
    std::vector<std::string> files_read() const override;
    std::vector<std::string> notes() const override;
    std::string json_members() const override;

    tinygltf::Model model;
    std::string path, raw;
    bool binary = false;
    /* the JSON as written (a .glb's first chunk), parsed for editing; false
       when it does not match the model (a changed file is then refused) */
    std::string text;
    JsonValue document;
    bool document_matches = false;
    /* what the repair adds or changes, for the edits of the document */
    size_t first_new_accessor = 0, first_new_view = 0;
    std::vector<size_t> buffer_sizes;            /* as read */
    std::vector<unsigned char> buffer_changed;
    std::set<std::pair<int, int>> primitives_changed; /* (mesh, primitive) given new indices */
    /* The file each external buffer and image was read from ("" for none:
       a data URI, the GLB's chunk, a bufferView, an image not found), and
       per buffer the first buffer read from the same file: their bytes are
       one, edited together. */
    std::vector<std::string> buffer_files, image_files;
    std::vector<int> buffer_file_first;
    /* per accessor: what uses it other than as NORMAL or TANGENT, or as the
       indices of a primitive (a morph target, a skin, an animation, or
       another attribute) */
    std::vector<int> other_uses, normal_uses; /* normal_uses: as NORMAL or TANGENT */
    std::vector<std::vector<PrimitiveTriangles>> unit_primitives;
    std::vector<std::vector<NormalSlot>> unit_slots;
    std::vector<int> index_uses; /* per accessor: primitives that use it as indices */
    /* reported */
    std::vector<std::pair<int, int>> mirrored; /* node, mesh */
    std::vector<int> double_sided;
    size_t accessors_cloned = 0, lists_written = 0, indices_added = 0, normals_negated = 0, tangents_negated = 0;
    size_t tangents_disagree = 0;
    std::vector<std::vector<unsigned char>> unit_negate_w; /* per flat normal: TANGENT.w to negate */
    size_t primitives_skipped = 0;
};

/* ---- reading accessors, every range checked ---- */

struct ElementView {
    const unsigned char *base = nullptr; /* nullptr: an accessor without a bufferView (zeros) */
    size_t stride = 0, size = 0, count = 0;
};

size_t component_size(int type)
{
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

int components(int type)
{
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;
    }
}

/* The bytes of `count` elements of `size` bytes at `offset` of a
   bufferView, or false when they are not all inside it and its buffer. */
bool view_range(const tinygltf::Model &m, int view, size_t offset, size_t count, size_t size, size_t stride_or_0,
                ElementView &out, std::string &error)
{
    if (view < 0 || (size_t)view >= m.bufferViews.size()) {
        error = "bufferView " + std::to_string(view) + " does not exist";
        return false;
    }
    const tinygltf::BufferView &v = m.bufferViews[(size_t)view];
    if (v.buffer < 0 || (size_t)v.buffer >= m.buffers.size()) {
        error = "buffer " + std::to_string(v.buffer) + " does not exist";
        return false;
    }
    const std::vector<unsigned char> &data = m.buffers[(size_t)v.buffer].data;
    size_t stride = stride_or_0 != 0 ? stride_or_0 : v.byteStride != 0 ? v.byteStride : size;
    bool fits = v.byteOffset <= data.size() && v.byteLength <= data.size() - v.byteOffset && offset <= v.byteLength &&
                (count == 0 || (stride >= size && (count - 1) <= (v.byteLength - offset - std::min(size, v.byteLength - offset)) / stride &&
                                size <= v.byteLength - offset));
    if (!fits) {
        error = "an accessor reaches past the end of bufferView " + std::to_string(view) + " or of its buffer";
        return false;
    }
    out.base = data.data() + v.byteOffset + offset;
    out.stride = stride;
    out.size = size;
    out.count = count;
    return true;
}

double read_component(const unsigned char *p, int type, bool normalized)
{
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float f;
        std::memcpy(&f, p, 4);
        return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0 : p[0];
    case TINYGLTF_COMPONENT_TYPE_BYTE: return normalized ? std::max((signed char)p[0] / 127.0, -1.0) : (signed char)p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
    default: return 0.0;
    }
}

/* An accessor's elements as doubles, `width` per element (sparse values
   applied). */
bool read_accessor(const tinygltf::Model &m, int index, int width, std::vector<double> &out, std::string &error)
{
    if (index < 0 || (size_t)index >= m.accessors.size()) {
        error = "accessor " + std::to_string(index) + " does not exist";
        return false;
    }
    const tinygltf::Accessor &a = m.accessors[(size_t)index];
    size_t csize = component_size(a.componentType);
    if (csize == 0 || components(a.type) != width) {
        error = "accessor " + std::to_string(index) + " has the wrong type";
        return false;
    }
    if (a.count > ((size_t)1 << 31)) {
        error = "accessor " + std::to_string(index) + " is too large";
        return false;
    }
    size_t size = csize * (size_t)width;
    ElementView v;
    if (a.bufferView >= 0 && !view_range(m, a.bufferView, a.byteOffset, a.count, size, 0, v, error))
        return false;
    /* an accessor without a bufferView is zeros (and its sparse values):
       real ones are no longer than the data of the file */
    size_t bytes = 1024;
    for (const tinygltf::Buffer &b : m.buffers)
        bytes += b.data.size();
    if (a.bufferView < 0 && a.count > bytes) {
        error = "accessor " + std::to_string(index) + " has no data for its " + std::to_string(a.count) + " elements";
        return false;
    }
    out.assign(a.count * (size_t)width, 0.0); /* both bounds checked: within the file's size */
    for (size_t i = 0; v.base != nullptr && i < a.count; ++i)
        for (int k = 0; k < width; ++k)
            out[i * (size_t)width + (size_t)k] = read_component(v.base + i * v.stride + (size_t)k * csize, a.componentType, a.normalized);
    if (a.sparse.isSparse) {
        ElementView idx, val;
        size_t n = (size_t)std::max(a.sparse.count, 0);
        size_t isize = component_size(a.sparse.indices.componentType);
        if (isize == 0 || !view_range(m, a.sparse.indices.bufferView, (size_t)std::max(a.sparse.indices.byteOffset, 0), n, isize, isize, idx, error) ||
            !view_range(m, a.sparse.values.bufferView, (size_t)std::max(a.sparse.values.byteOffset, 0), n, size, size, val, error))
            return false;
        for (size_t s = 0; s < n; ++s) {
            size_t target = (size_t)read_component(idx.base + s * isize, a.sparse.indices.componentType, false);
            if (target >= a.count) {
                error = "sparse index out of range in accessor " + std::to_string(index);
                return false;
            }
            for (int k = 0; k < width; ++k)
                out[target * (size_t)width + (size_t)k] = read_component(val.base + s * size + (size_t)k * csize, a.componentType, a.normalized);
        }
    }
    return true;
}

/* ---- triangles of a primitive ---- */

int primitive_mode(const tinygltf::Primitive &p) { return p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode; }

bool is_triangles(int mode)
{
    return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

/* The triangles of an index stream as the spec defines them: a strip's
   triangle i is (i, i+1, i+2) for even i and (i, i+2, i+1) for odd i; a
   fan's is (i+1, i+2, 0). */
std::vector<uint32_t> triangles_of(const std::vector<uint32_t> &stream, int mode)
{
    std::vector<uint32_t> t;
    size_t n = stream.size();
    if (mode == TINYGLTF_MODE_TRIANGLES)
        t.assign(stream.begin(), stream.begin() + (long)(n - n % 3));
    else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
        for (size_t i = 0; i + 2 < n; ++i)
            t.insert(t.end(), {stream[i], stream[i + 1 + i % 2], stream[i + 2 - i % 2]});
    else
        for (size_t i = 0; i + 2 < n; ++i)
            t.insert(t.end(), {stream[i + 1], stream[i + 2], stream[0]});
    return t;
}

const char *const compression_extensions[] = {"KHR_draco_mesh_compression", "EXT_meshopt_compression",
                                              "KHR_meshopt_compression"};

std::string compression_message(const std::string &extension)
{
    return std::string(extension.find("draco") != std::string::npos ? "Draco" : "meshopt") + "-compressed primitives (" +
           extension + ") are not supported; nothing written";
}

/* The compression extension a model uses, or "". */
std::string compression_of(const tinygltf::Model &m)
{
    for (const std::string &e : m.extensionsRequired)
        for (const char *c : compression_extensions)
            if (e == c)
                return e;
    for (const tinygltf::Mesh &mesh : m.meshes)
        for (const tinygltf::Primitive &p : mesh.primitives)
            if (p.extensions.count(compression_extensions[0]))
                return compression_extensions[0];
    for (const tinygltf::BufferView &v : m.bufferViews)
        for (const char *c : compression_extensions)
            if (v.extensions.count(c))
                return c;
    return "";
}

/* ---- the units ---- */

bool aliased(const GltfFile &f, int accessor);

struct MeshReader {
    GltfFile &file;
    std::string &error;

    /* Which meshes use each accessor as NORMAL or TANGENT: a normal fixed in
       one mesh must not change another. */
    std::map<int, std::set<int>> attribute_meshes;

    bool read_indices(const tinygltf::Primitive &p, size_t vertex_count, std::vector<uint32_t> &stream)
    {
        if (p.indices < 0) {
            for (size_t i = 0; i < vertex_count; ++i)
                stream.push_back((uint32_t)i);
            return true;
        }
        std::vector<double> values;
        if (!read_accessor(file.model, p.indices, 1, values, error))
            return false;
        int type = file.model.accessors[(size_t)p.indices].componentType;
        if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
            error = "index accessor " + std::to_string(p.indices) + " is not of unsigned integers";
            return false;
        }
        for (double v : values) {
            if (v >= (double)vertex_count) {
                error = "index " + std::to_string((unsigned long)v) + " out of range (" + std::to_string(vertex_count) + " vertices)";
                return false;
            }
            stream.push_back((uint32_t)v);
        }
        return true;
    }

    /* Adds a primitive's positions (once per POSITION accessor), normals
       and triangles to the unit. */
    bool add_primitive(int mesh, int index, Unit &u, std::map<int, uint32_t> &bases, std::vector<PrimitiveTriangles> &prims)
    {
        const tinygltf::Primitive &p = file.model.meshes[(size_t)mesh].primitives[(size_t)index];
        auto position = p.attributes.find("POSITION");
        if (!is_triangles(primitive_mode(p)) || position == p.attributes.end()) {
            file.primitives_skipped += !is_triangles(primitive_mode(p)) ? 0 : 1;
            return true;
        }
        std::vector<double> xyz, normals;
        if (!read_accessor(file.model, position->second, 3, xyz, error))
            return false;
        size_t count = xyz.size() / 3;
        auto found = bases.find(position->second);
        uint32_t base = found != bases.end() ? found->second : (uint32_t)(u.positions.size() / 3);
        if (found == bases.end()) {
            if (u.positions.size() / 3 + count > 0xFFFFFFF0u) {
                error = "too many vertices";
                return false;
            }
            bases[position->second] = base;
            u.positions.insert(u.positions.end(), xyz.begin(), xyz.end());
            u.vertex_normals.resize(u.positions.size(), 0.0f);
            auto normal = p.attributes.find("NORMAL");
            if (normal != p.attributes.end() && read_accessor(file.model, normal->second, 3, normals, error) &&
                normals.size() == xyz.size())
                for (size_t i = 0; i < normals.size(); ++i)
                    u.vertex_normals[3 * base + i] = (float)normals[i];
            error.clear(); /* a bad NORMAL is no evidence, not a reason to refuse the file */
        }
        std::vector<uint32_t> stream;
        if (!read_indices(p, count, stream))
            return false;
        PrimitiveTriangles pt{mesh, index, u.indices.size() / 3, triangles_of(stream, primitive_mode(p))};
        for (uint32_t v : pt.corners)
            u.indices.push_back(base + v);
        prims.push_back(std::move(pt));
        return true;
    }

    /* Each NORMAL element the tool can negate (float, not sparse, this
       mesh's own) is a slot, with the triangles that use it. */
    void collect_normals(int mesh, Unit &u, const std::vector<PrimitiveTriangles> &prims, std::vector<NormalSlot> &slots)
    {
        std::map<std::pair<int, uint32_t>, uint32_t> slot_of;
        std::map<int, std::vector<double>> values;
        for (const PrimitiveTriangles &pt : prims) {
            const tinygltf::Primitive &p = file.model.meshes[(size_t)mesh].primitives[(size_t)pt.primitive];
            auto normal = p.attributes.find("NORMAL");
            std::string ignored;
            if (normal == p.attributes.end() || !negatable(normal->second, 3, mesh) ||
                (!values.count(normal->second) && !read_accessor(file.model, normal->second, 3, values[normal->second], ignored)))
                continue;
            const std::vector<double> &n = values[normal->second];
            auto tangent = p.attributes.find("TANGENT");
            int tangent_accessor = tangent != p.attributes.end() && negatable(tangent->second, 4, mesh) ? tangent->second : -1;
            int set = p.material >= 0 && (size_t)p.material < file.model.materials.size()
                          ? file.model.materials[(size_t)p.material].normalTexture.texCoord : 0;
            auto texcoord = p.attributes.find("TEXCOORD_" + std::to_string(std::max(set, 0)));
            int texcoord_accessor = texcoord != p.attributes.end() ? texcoord->second : -1;
            for (size_t c = 0; c < pt.corners.size(); ++c) {
                uint32_t element = pt.corners[c];
                if (3 * (size_t)element + 2 >= n.size())
                    continue;
                auto found = slot_of.emplace(std::make_pair(normal->second, element), (uint32_t)slots.size());
                if (found.second) {
                    const uint32_t *t = &pt.corners[c - c % 3];
                    slots.push_back({normal->second, tangent_accessor, texcoord_accessor, element, {t[0], t[1], t[2]}});
                    u.slot_normals.insert(u.slot_normals.end(), {(float)n[3 * element], (float)n[3 * element + 1], (float)n[3 * element + 2]});
                }
                u.slot_faces.push_back({found.first->second, (uint32_t)(pt.first_triangle + c / 3)});
            }
        }
        find_flat_normals(u);
    }

    bool negatable(int accessor, int width, int mesh)
    {
        if (accessor < 0 || (size_t)accessor >= file.model.accessors.size())
            return false;
        const tinygltf::Accessor &a = file.model.accessors[(size_t)accessor];
        ElementView v;
        std::string ignored;
        /* this mesh's alone: no other use of the accessor, nor of its bytes */
        return a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT && components(a.type) == width && !a.sparse.isSparse &&
               a.bufferView >= 0 && attribute_meshes[accessor] == std::set<int>{mesh} &&
               file.other_uses[(size_t)accessor] == 0 && file.index_uses[(size_t)accessor] == 0 &&
               view_range(file.model, a.bufferView, a.byteOffset, a.count, 4 * (size_t)width, 0, v, ignored) &&
               !aliased(file, accessor);
    }

    /* Every use of each accessor: as indices, as NORMAL or TANGENT (by
       which meshes), and any other. */
    void count_uses()
    {
        const tinygltf::Model &m = file.model;
        file.index_uses.assign(m.accessors.size(), 0);
        file.other_uses.assign(m.accessors.size(), 0);
        file.normal_uses.assign(m.accessors.size(), 0);
        auto other = [&](int a) {
            if (a >= 0 && (size_t)a < m.accessors.size())
                file.other_uses[(size_t)a]++;
        };
        for (size_t mesh = 0; mesh < m.meshes.size(); ++mesh)
            for (const tinygltf::Primitive &p : m.meshes[mesh].primitives) {
                if (p.indices >= 0 && (size_t)p.indices < m.accessors.size())
                    file.index_uses[(size_t)p.indices]++;
                for (const auto &a : p.attributes) {
                    if ((a.first == "NORMAL" || a.first == "TANGENT") && a.second >= 0 && (size_t)a.second < m.accessors.size()) {
                        attribute_meshes[a.second].insert((int)mesh);
                        file.normal_uses[(size_t)a.second]++;
                    } else {
                        other(a.second);
                    }
                }
                for (const auto &target : p.targets)
                    for (const auto &a : target)
                        other(a.second);
            }
        for (const tinygltf::Skin &skin : m.skins)
            other(skin.inverseBindMatrices);
        for (const tinygltf::Animation &animation : m.animations)
            for (const tinygltf::AnimationSampler &sampler : animation.samplers)
                other(sampler.input), other(sampler.output);
    }

    bool read()
    {
        tinygltf::Model &m = file.model;
        count_uses();
        for (size_t mesh = 0; mesh < m.meshes.size(); ++mesh) {
            Unit u;
            std::map<int, uint32_t> bases;
            std::vector<PrimitiveTriangles> prims;
            std::vector<NormalSlot> slots;
            u.name = m.meshes[mesh].name.empty() ? "mesh " + std::to_string(mesh) : "mesh " + std::to_string(mesh) + " '" + m.meshes[mesh].name + "'";
            for (size_t p = 0; p < m.meshes[mesh].primitives.size(); ++p)
                if (!add_primitive((int)mesh, (int)p, u, bases, prims)) {
                    error = u.name + ", primitive " + std::to_string(p) + ": " + error;
                    return false;
                }
            if (u.indices.empty())
                continue;
            u.face_count = u.indices.size() / 3;
            for (size_t t = 0; t < u.face_count; ++t)
                u.triangle_face.push_back((uint32_t)t);
            collect_normals((int)mesh, u, prims, slots);
            file.units.push_back(std::move(u));
            file.unit_primitives.push_back(std::move(prims));
            file.unit_slots.push_back(std::move(slots));
        }
        return true;
    }
};

/* Nodes that draw a mesh under a transform of negative determinant. The
   sign of a product's determinant is the product of the signs, so only
   each node's own sign is needed. */
void find_mirrored(GltfFile &file)
{
    const tinygltf::Model &m = file.model;
    std::vector<int> parent(m.nodes.size(), -1);
    for (size_t n = 0; n < m.nodes.size(); ++n)
        for (int c : m.nodes[n].children)
            if (c >= 0 && (size_t)c < m.nodes.size() && parent[(size_t)c] < 0 && (size_t)c != n)
                parent[(size_t)c] = (int)n;
    auto own_sign = [&](const tinygltf::Node &node) {
        double det;
        if (node.matrix.size() == 16) {
            const std::vector<double> &a = node.matrix; /* column-major */
            det = a[0] * (a[5] * a[10] - a[9] * a[6]) - a[4] * (a[1] * a[10] - a[9] * a[2]) + a[8] * (a[1] * a[6] - a[5] * a[2]);
        } else {
            det = node.scale.size() == 3 ? node.scale[0] * node.scale[1] * node.scale[2] : 1.0;
        }
        return det < 0 ? -1 : 1;
    };
    for (size_t n = 0; n < m.nodes.size(); ++n) {
        if (m.nodes[n].mesh < 0)
            continue;
        int sign = 1;
        size_t steps = 0;
        for (int at = (int)n; at >= 0 && steps <= m.nodes.size(); at = parent[(size_t)at], ++steps)
            sign *= own_sign(m.nodes[(size_t)at]);
        if (sign < 0)
            file.mirrored.push_back({(int)n, m.nodes[n].mesh});
    }
    std::set<int> used;
    for (const tinygltf::Mesh &mesh : m.meshes)
        for (const tinygltf::Primitive &p : mesh.primitives)
            if (is_triangles(primitive_mode(p)) && p.material >= 0 && (size_t)p.material < m.materials.size() &&
                m.materials[(size_t)p.material].doubleSided)
                used.insert(p.material);
    file.double_sided.assign(used.begin(), used.end());
}

/* Images are never decoded: the loader keeps the encoded bytes (a data URI
   is written back from them). */
bool keep_image_bytes(tinygltf::Image *image, const int, std::string *, std::string *, int, int,
                      const unsigned char *bytes, int size, void *)
{
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}

std::string base64(const std::vector<unsigned char> &data)
{
    static const char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < data.size(); i += 3) {
        unsigned v = (unsigned)data[i] << 16 | (i + 1 < data.size() ? (unsigned)data[i + 1] << 8 : 0) |
                     (i + 2 < data.size() ? data[i + 2] : 0);
        out += digits[v >> 18 & 63];
        out += digits[v >> 12 & 63];
        out += i + 1 < data.size() ? digits[v >> 6 & 63] : '=';
        out += i + 2 < data.size() ? digits[v & 63] : '=';
    }
    return out;
}

bool data_uri(const std::string &uri) { return uri.compare(0, 5, "data:") == 0; }

/* ---- writing ---- */

int shared_buffer(const GltfFile &f, int buffer);
void share_bytes(GltfFile &f, int buffer);

/* Puts `values` into the accessor's own bytes, in its component type. */
void write_indices_in_place(GltfFile &f, int accessor, const std::vector<uint32_t> &values)
{
    tinygltf::Model &m = f.model;
    const tinygltf::Accessor &a = m.accessors[(size_t)accessor];
    tinygltf::BufferView &v = m.bufferViews[(size_t)a.bufferView];
    size_t size = component_size(a.componentType), stride = v.byteStride != 0 ? v.byteStride : size;
    int buffer = shared_buffer(f, v.buffer);
    unsigned char *base = m.buffers[(size_t)buffer].data.data() + v.byteOffset + a.byteOffset;
    for (size_t i = 0; i < values.size(); ++i) {
        uint32_t x = values[i];
        if (size == 1)
            base[i * stride] = (unsigned char)x;
        else if (size == 2) {
            uint16_t s = (uint16_t)x;
            std::memcpy(base + i * stride, &s, 2);
        } else
            std::memcpy(base + i * stride, &x, 4);
    }
    share_bytes(f, buffer);
}

/* A new index accessor (in its own bufferView at the end of buffer 0)
   holding `values`; returns its index. */
int add_index_accessor(GltfFile &f, const std::vector<uint32_t> &values, int component_type)
{
    tinygltf::Model &m = f.model;
    if (m.buffers.empty()) {
        m.buffers.emplace_back();
        f.buffer_changed.push_back(1);
        f.buffer_file_first.push_back(0);
        f.buffer_files.push_back("");
    }
    int buffer = shared_buffer(f, 0);
    std::vector<unsigned char> &data = m.buffers[(size_t)buffer].data;
    while (data.size() % 4 != 0)
        data.push_back(0);
    size_t size = component_size(component_type), offset = data.size();
    data.resize(offset + size * values.size());
    for (size_t i = 0; i < values.size(); ++i) {
        uint32_t x = values[i];
        if (size == 1)
            data[offset + i] = (unsigned char)x;
        else if (size == 2) {
            uint16_t s = (uint16_t)x;
            std::memcpy(&data[offset + 2 * i], &s, 2);
        } else
            std::memcpy(&data[offset + 4 * i], &x, 4);
    }
    share_bytes(f, buffer);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = size * values.size();
    view.target = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;
    m.bufferViews.push_back(view);
    tinygltf::Accessor a;
    a.bufferView = (int)m.bufferViews.size() - 1;
    a.byteOffset = 0;
    a.componentType = component_type;
    a.count = values.size();
    a.type = TINYGLTF_TYPE_SCALAR;
    m.accessors.push_back(a);
    return (int)m.accessors.size() - 1;
}

/* The bytes an accessor's elements take in their buffer: `count` runs of
   `size` bytes, `stride` apart, from `begin` (interleaved attributes share
   a span and no byte). Buffers read from one file are one buffer here. */
struct ByteRuns {
    int buffer = -1; /* -1: none (no bufferView, or no elements) */
    size_t begin = 0, size = 0, stride = 0, count = 0;
    size_t end() const { return begin + (count - 1) * stride + size; }
};

/* The size of an element as the spec lays it out: a matrix's columns each
   start on 4 bytes (a MAT3 of bytes is 12 bytes, of shorts 24). */
size_t element_size(const tinygltf::Accessor &a)
{
    size_t c = component_size(a.componentType);
    auto columns = [c](size_t n, size_t rows) { return n * ((rows * c + 3) / 4 * 4); };
    switch (a.type) {
    case TINYGLTF_TYPE_MAT2: return columns(2, 2);
    case TINYGLTF_TYPE_MAT3: return columns(3, 3);
    case TINYGLTF_TYPE_MAT4: return columns(4, 4);
    default: return c * (size_t)std::max(components(a.type), 1);
    }
}

int shared_buffer(const GltfFile &f, int buffer)
{
    return buffer >= 0 && (size_t)buffer < f.buffer_file_first.size() ? f.buffer_file_first[(size_t)buffer] : buffer;
}

ByteRuns contiguous(const GltfFile &f, int buffer, size_t begin, size_t length)
{
    ByteRuns r;
    if (length == 0)
        return r;
    r.buffer = shared_buffer(f, buffer);
    r.begin = begin;
    r.size = r.stride = length;
    r.count = 1;
    return r;
}

ByteRuns accessor_runs(const GltfFile &f, const tinygltf::Accessor &a)
{
    const tinygltf::Model &m = f.model;
    ByteRuns r;
    if (a.bufferView < 0 || (size_t)a.bufferView >= m.bufferViews.size() || a.count == 0)
        return r;
    const tinygltf::BufferView &v = m.bufferViews[(size_t)a.bufferView];
    ElementView e;
    std::string ignored;
    size_t size = element_size(a);
    if (size == 0 || !view_range(m, a.bufferView, a.byteOffset, a.count, size, 0, e, ignored))
        return contiguous(f, v.buffer, v.byteOffset, v.byteLength); /* not readable: its whole view, to be safe */
    r.buffer = shared_buffer(f, v.buffer);
    r.begin = v.byteOffset + a.byteOffset;
    r.size = size;
    r.stride = e.stride;
    r.count = a.count;
    return r;
}

/* Whether two sets of runs share a byte: the runs walked in order from
   where the spans meet (after a bounded walk, taken as yes). */
bool runs_overlap(const ByteRuns &a, const ByteRuns &b)
{
    if (a.buffer < 0 || a.buffer != b.buffer || a.begin >= b.end() || b.begin >= a.end())
        return false;
    auto first_reaching = [](const ByteRuns &r, size_t from) -> size_t {
        return from < r.begin + r.size ? 0 : (from - r.begin - r.size) / r.stride + 1;
    };
    size_t i = first_reaching(a, b.begin), j = first_reaching(b, a.begin);
    for (size_t steps = 0; i < a.count && j < b.count; ++steps) {
        size_t a0 = a.begin + i * a.stride, b0 = b.begin + j * b.stride;
        if (a0 < b0 + b.size && b0 < a0 + a.size)
            return true;
        if (steps > 4000000)
            return true;
        if (a0 + a.size <= b0 + b.size)
            ++i;
        else
            ++j;
    }
    return false;
}

/* Whether anything else in the file can see the bytes of this accessor:
   another accessor over them (in its bufferView or another), another
   bufferView over them (an image, an extension's data) or a sparse
   block. Rewriting them in place would change that too. */
bool aliased(const GltfFile &f, int accessor)
{
    const tinygltf::Model &m = f.model;
    ByteRuns mine = accessor_runs(f, m.accessors[(size_t)accessor]);
    if (mine.buffer < 0)
        return true;
    auto view_runs = [&](int view, size_t offset, size_t length) {
        if (view < 0 || (size_t)view >= m.bufferViews.size())
            return ByteRuns();
        const tinygltf::BufferView &v = m.bufferViews[(size_t)view];
        return contiguous(f, v.buffer, v.byteOffset + offset, length == 0 ? v.byteLength : length);
    };
    for (size_t i = 0; i < m.accessors.size(); ++i) {
        const tinygltf::Accessor &a = m.accessors[i];
        if ((int)i != accessor && runs_overlap(mine, accessor_runs(f, a)))
            return true;
        if (a.sparse.isSparse && (runs_overlap(mine, view_runs(a.sparse.indices.bufferView, 0, 0)) ||
                                  runs_overlap(mine, view_runs(a.sparse.values.bufferView, 0, 0))))
            return true;
    }
    int own = m.accessors[(size_t)accessor].bufferView;
    for (size_t i = 0; i < m.bufferViews.size(); ++i)
        if ((int)i != own && runs_overlap(mine, view_runs((int)i, 0, 0)))
            return true;
    return false;
}

/* After a buffer's bytes changed: every buffer read from the same file
   gets them too (the file is written once, with every change). */
void share_bytes(GltfFile &f, int buffer)
{
    int first = shared_buffer(f, buffer);
    f.buffer_changed[(size_t)first] = 1;
    for (size_t b = 0; b < f.model.buffers.size(); ++b)
        if ((int)b != first && shared_buffer(f, (int)b) == first) {
            f.model.buffers[b].data = f.model.buffers[(size_t)first].data;
            f.buffer_changed[b] = 1;
        }
}

void negate_floats(GltfFile &f, int accessor, uint32_t element, int first, int count)
{
    tinygltf::Model &m = f.model;
    const tinygltf::Accessor &a = m.accessors[(size_t)accessor];
    const tinygltf::BufferView &v = m.bufferViews[(size_t)a.bufferView];
    size_t size = 4 * (size_t)components(a.type), stride = v.byteStride != 0 ? v.byteStride : size;
    int buffer = shared_buffer(f, v.buffer);
    unsigned char *p = m.buffers[(size_t)buffer].data.data() + v.byteOffset + a.byteOffset + element * stride;
    for (int k = first; k < first + count; ++k) {
        float x;
        std::memcpy(&x, p + 4 * k, 4);
        if (x != 0.0f) /* -0 would change bytes and nothing else */
            x = -x;
        std::memcpy(p + 4 * k, &x, 4);
    }
    share_bytes(f, buffer);
}

} // namespace

void GltfFile::apply(size_t unit, const Changes &changes)
{
    for (PrimitiveTriangles &pt : unit_primitives[unit]) {
        size_t n = pt.corners.size() / 3;
        std::vector<uint32_t> list = pt.corners;
        bool any = false;
        for (size_t t = 0; t < n; ++t)
            if (changes.face_flipped[pt.first_triangle + t]) {
                std::swap(list[3 * t + 1], list[3 * t + 2]);
                any = true;
            }
        if (!any)
            continue;
        changed = true;
        tinygltf::Primitive &p = model.meshes[(size_t)pt.mesh].primitives[(size_t)pt.primitive];
        int mode = primitive_mode(p);
        if (mode == TINYGLTF_MODE_TRIANGLES && p.indices >= 0 && index_uses[(size_t)p.indices] == 1 &&
            other_uses[(size_t)p.indices] == 0 && normal_uses[(size_t)p.indices] == 0 && !model.accessors[(size_t)p.indices].sparse.isSparse &&
            model.accessors[(size_t)p.indices].bufferView >= 0 && !aliased(*this, p.indices)) {
            write_indices_in_place(*this, p.indices, list);
            continue;
        }
        uint32_t highest = 0;
        for (uint32_t v : list)
            highest = std::max(highest, v);
        int type = p.indices >= 0 ? model.accessors[(size_t)p.indices].componentType
                   : highest < 65535 ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        if (mode != TINYGLTF_MODE_TRIANGLES)
            ++lists_written;
        else if (p.indices < 0)
            ++indices_added;
        else
            ++accessors_cloned;
        p.indices = add_index_accessor(*this, list, type);
        p.mode = TINYGLTF_MODE_TRIANGLES;
        primitives_changed.insert({pt.mesh, pt.primitive});
    }
    for (size_t k = 0; k < units[unit].flat_normals.size(); ++k) {
        const NormalSlot &s = unit_slots[unit][units[unit].flat_normals[k].slot];
        if (changes.negate_flat[k]) {
            negate_floats(*this, s.normal, s.element, 0, 3);
            ++normals_negated;
            changed = true;
        }
        if (changes.fix_normals && unit_negate_w[unit][k]) {
            negate_floats(*this, s.tangent, s.element, 3, 1);
            ++tangents_negated;
            changed = true;
        }
    }
}

/* TANGENT.w of a flat vertex is the handedness of its tangent frame: the
   bitangent cross(normal, tangent.xyz) * w must run the way the texture's
   v does across the face. That direction, from the face's positions and
   texture coordinates, does not depend on the winding, so w is checked
   against the normal as it will be (negated when it disagrees with its
   face). */
void GltfFile::review(size_t unit, const Changes &changes)
{
    const Unit &u = units[unit];
    std::map<int, std::vector<double>> values;
    auto read = [&](int accessor, int width) -> const std::vector<double> & {
        auto found = values.find(accessor);
        if (found != values.end())
            return found->second;
        std::string ignored;
        std::vector<double> &v = values[accessor];
        if (!read_accessor(model, accessor, width, v, ignored))
            v.clear();
        return v;
    };
    unit_negate_w.resize(units.size());
    unit_negate_w[unit].assign(u.flat_normals.size(), 0);
    for (size_t k = 0; k < u.flat_normals.size(); ++k) {
        const FlatNormal &fn = u.flat_normals[k];
        const NormalSlot &s = unit_slots[unit][fn.slot];
        if (s.tangent < 0 || s.texcoord < 0)
            continue;
        const std::vector<double> &tangents = read(s.tangent, 4), &uv = read(s.texcoord, 2);
        if (4 * (size_t)s.element + 3 >= tangents.size() || 2 * (size_t)std::max(std::max(s.corners[0], s.corners[1]), s.corners[2]) + 1 >= uv.size())
            continue;
        const double *p[3];
        for (int i = 0; i < 3; ++i)
            p[i] = &u.positions[3 * (size_t)u.indices[3 * (size_t)fn.face + (size_t)i]];
        double du1 = uv[2 * s.corners[1]] - uv[2 * s.corners[0]], dv1 = uv[2 * s.corners[1] + 1] - uv[2 * s.corners[0] + 1];
        double du2 = uv[2 * s.corners[2]] - uv[2 * s.corners[0]], dv2 = uv[2 * s.corners[2] + 1] - uv[2 * s.corners[0] + 1];
        double r = du1 * dv2 - dv1 * du2, bitangent[3], n[3], dot = 0.0;
        const double *t = &tangents[4 * (size_t)s.element];
        for (int i = 0; i < 3; ++i) {
            bitangent[i] = ((p[2][i] - p[0][i]) * du1 - (p[1][i] - p[0][i]) * du2) * (r < 0 ? -1.0 : 1.0);
            n[i] = (double)fn.normal[i] * (changes.flat_disagree[k] ? -1.0 : 1.0);
        }
        if (r == 0.0)
            continue;
        double c[3] = {n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0]};
        for (int i = 0; i < 3; ++i)
            dot += c[i] * bitangent[i];
        if (dot != 0.0 && (dot < 0.0) != (t[3] < 0.0)) {
            ++tangents_disagree;
            unit_negate_w[unit][k] = 1;
        }
    }
}

namespace {

/* ---- the files beside a .gltf ---- */

/* The relative path a URI names (RFC 3986: %XX decoded, nothing else), or
   false when it is not one that stays in the glTF's directory: absolute,
   with a scheme or a drive, a ".." segment (also when written %2e%2e), a
   backslash, a NUL, or a broken escape. Decided on the decoded path, so
   no encoding gets around it. */
bool companion_path(const std::string &uri, std::string &path)
{
    auto hex = [](char c) { return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1; };
    path.clear();
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] != '%') {
            path += uri[i];
            continue;
        }
        if (i + 2 >= uri.size() || hex(uri[i + 1]) < 0 || hex(uri[i + 2]) < 0)
            return false;
        path += (char)(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
        i += 2;
    }
    if (path.empty() || path[0] == '/' || path.find('\0') != std::string::npos || path.find('\\') != std::string::npos ||
        path.find(':') != std::string::npos)
        return false;
    for (size_t at = 0; at <= path.size();) {
        size_t slash = std::min(path.find('/', at), path.size());
        if (path.compare(at, slash - at, "..") == 0 && slash - at == 2)
            return false;
        at = slash + 1;
    }
    return true;
}

/* tinygltf's file system, narrowed to what the glTF may read: regular
   files inside its own directory (no FIFO to block on, no device, no
   fallback to the current directory), each opened without blocking. */
struct Companions {
    std::string base;                  /* the .gltf's directory, as given to tinygltf */
    std::set<std::string> read;        /* relative paths tinygltf read */
    std::string refused;               /* the first path refused, for the message */

    /* The path relative to `base`, or "" when it is not below it. */
    std::string relative(const std::string &path) const
    {
        std::string prefix = base.empty() || base.back() == '/' ? base : base + "/";
        return path.compare(0, prefix.size(), prefix) == 0 ? path.substr(prefix.size()) : "";
    }
    /* Whether tinygltf may read `path`. A path outside `base` is its
       fallback to the current directory: not found, whatever is there. */
    bool allowed(const std::string &path)
    {
        std::string rel = relative(path), decoded;
        if (rel.empty())
            return false;
        struct stat st;
        /* tinygltf hands over the URI decoded: it must be a safe path as it is */
        bool safe = companion_path(rel, decoded) && decoded == rel;
        if (safe && stat(path.c_str(), &st) != 0)
            return false; /* missing: tinygltf says so */
        if (!safe || !S_ISREG(st.st_mode) || !inside(path)) {
            if (refused.empty())
                refused = rel + (!safe ? "', outside its directory" : !S_ISREG(st.st_mode) ? "', not a regular file"
                                                                     : "', a symbolic link out of its directory");
            return false;
        }
        return true;
    }
    /* A symbolic link out of the glTF's directory would copy any file it
       names beside the output. */
    bool inside(const std::string &path) const { return resolves_inside(path, base); }
};

bool companion_exists(const std::string &path, void *user) { return ((Companions *)user)->allowed(path); }

std::string companion_expand(const std::string &path, void *) { return path; }

bool companion_read(std::vector<unsigned char> *out, std::string *err, const std::string &path, void *user)
{
    Companions &c = *(Companions *)user;
    std::string data, error;
    if (!c.allowed(path) || !read_file(path, data, error)) {
        if (err)
            *err = error.empty() ? "not a regular file inside the glTF's directory" : error;
        return false;
    }
    out->assign(data.begin(), data.end());
    c.read.insert(c.relative(path));
    return true;
}

bool companion_write(std::string *err, const std::string &, const std::vector<unsigned char> &, void *)
{
    if (err)
        *err = "the tool writes glTF files itself";
    return false;
}

/* The deepest nesting of [ and { in JSON text (strings skipped): refused
   above a limit before tinygltf parses it, as its parser recurses. */
size_t json_depth(const char *text, size_t size)
{
    size_t depth = 0, deepest = 0;
    bool in_string = false;
    for (size_t i = 0; i < size; ++i) {
        char c = text[i];
        if (in_string) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

const size_t json_depth_limit = 128;

/* The JSON text of a .gltf, or of a .glb's first chunk (the header read as
   far as it is there; tinygltf checks the rest). */
void json_text(const std::string &raw, bool binary, const char **text, size_t *size)
{
    *text = raw.data();
    *size = raw.size();
    if (!binary || raw.size() < 20)
        return;
    uint32_t length = (uint32_t)(unsigned char)raw[12] | (uint32_t)(unsigned char)raw[13] << 8 |
                      (uint32_t)(unsigned char)raw[14] << 16 | (uint32_t)(unsigned char)raw[15] << 24;
    *text = raw.data() + 20;
    *size = std::min<size_t>(length, raw.size() - 20);
}

/* A GLB container of the JSON and the BIN chunk (spec: chunks padded to 4
   bytes, JSON with spaces, BIN with zeros). */
std::string glb_bytes(const std::string &json, const std::vector<unsigned char> &bin, bool with_bin)
{
    auto put32 = [](std::string &s, uint32_t v) {
        for (int k = 0; k < 4; ++k)
            s += (char)(v >> (8 * k) & 0xFF);
    };
    std::string j = json, out = "glTF";
    while (j.size() % 4 != 0)
        j += ' ';
    size_t bin_padded = (bin.size() + 3) / 4 * 4;
    put32(out, 2);
    put32(out, (uint32_t)(12 + 8 + j.size() + (with_bin ? 8 + bin_padded : 0)));
    put32(out, (uint32_t)j.size());
    put32(out, 0x4E4F534Au);
    out += j;
    if (with_bin) {
        put32(out, (uint32_t)bin_padded);
        put32(out, 0x004E4942u);
        out.append((const char *)bin.data(), bin.size());
        out.append(bin_padded - bin.size(), '\0');
    }
    return out;
}

/* A GLB with its JSON chunk replaced, the chunks after it as they were. */
std::string with_json_chunk(const std::string &raw, const std::string &json)
{
    uint32_t length = (uint32_t)(unsigned char)raw[12] | (uint32_t)(unsigned char)raw[13] << 8 |
                      (uint32_t)(unsigned char)raw[14] << 16 | (uint32_t)(unsigned char)raw[15] << 24;
    std::string rest = 20 + (size_t)length <= raw.size() ? raw.substr(20 + (size_t)length) : "";
    std::string j = json;
    while (j.size() % 4 != 0)
        j += ' ';
    std::string out = raw.substr(0, 8);
    uint32_t total = (uint32_t)(20 + j.size() + rest.size());
    for (uint32_t v : {total, (uint32_t)j.size()})
        for (int k = 0; k < 4; ++k)
            out += (char)(v >> (8 * k) & 0xFF);
    return out + raw.substr(16, 4) + j + rest;
}

/* RFC 3986 leaves '+' in a URI as it is, but tinygltf decodes it as a
   space (form encoding): each buffer and image URI with a '+' is given to
   it as %2B, which it decodes back to '+'. */
std::string literal_plus(const std::string &text, const JsonValue &root)
{
    JsonEdits edits(text);
    for (const char *array : {"buffers", "images"}) {
        const JsonValue *a = root.member(array);
        for (size_t i = 0; a != nullptr && i < a->items.size(); ++i) {
            const JsonValue *uri = a->items[i].member("uri");
            if (uri == nullptr || uri->kind != '"' || uri->string.find('+') == std::string::npos ||
                uri->string.compare(0, 5, "data:") == 0)
                continue;
            std::string escaped;
            for (char c : uri->string)
                escaped += c == '+' ? std::string("%2B") : std::string(1, c);
            edits.set(a->items[i], "uri", json_quote(escaped));
        }
    }
    return edits.result();
}

/* Whether entry i of the document's arrays is the model's i (tinygltf
   refuses entries that are not objects, so they always are). */
bool document_matches(const JsonValue &root, const tinygltf::Model &m)
{
    auto entries = [&](const JsonValue *array, size_t count) {
        if (array == nullptr)
            return count == 0;
        if (array->kind != '[' || array->items.size() != count)
            return false;
        for (const JsonValue &item : array->items)
            if (item.kind != '{')
                return false;
        return true;
    };
    if (root.kind != '{' || !entries(root.member("accessors"), m.accessors.size()) ||
        !entries(root.member("bufferViews"), m.bufferViews.size()) || !entries(root.member("buffers"), m.buffers.size()) ||
        !entries(root.member("meshes"), m.meshes.size()))
        return false;
    for (size_t i = 0; i < m.meshes.size(); ++i)
        if (!entries(root.member("meshes")->items[i].member("primitives"), m.meshes[i].primitives.size()))
            return false;
    return true;
}

/* A file name as a URI: bytes other than letters, digits and -._~ as %XX. */
std::string uri_of(const std::string &name)
{
    static const char digits[] = "0123456789ABCDEF";
    std::string uri;
    for (char ch : name) {
        unsigned char c = (unsigned char)ch;
        if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~')
            uri += (char)c;
        else
            uri += '%', uri += digits[c >> 4], uri += digits[c & 15];
    }
    return uri;
}

/* The files of one glTF output, planned as outputs of the job's set: the
   buffers and images beside it, then the document. */
struct GltfWriter {
    GltfFile &file;
    OutputSet &outputs;
    std::string input, target, out_dir, stem;
    bool in_place, to_binary;
    JsonEdits edits;
    std::vector<unsigned char> bin;
    bool with_bin = false;
    std::vector<std::pair<FileId, const std::vector<unsigned char> *>> companions;

    GltfWriter(GltfFile &f, OutputSet &o, const std::string &in, const std::string &out)
        : file(f), outputs(o), input(in), target(out), out_dir(directory_of(out)),
          stem(base_name(out).substr(0, base_name(out).rfind('.'))), in_place(same_file(file_id(out), file_id(in))),
          to_binary(format_of(out) == "glb"), edits(f.text)
    {
    }

    /* A file beside the output, once: another name for a file already
       written is skipped when the bytes are the same (two buffers read
       from one file), refused when they differ. */
    bool put(const std::string &to, const std::string &replaces, const std::vector<unsigned char> &bytes, std::string &error)
    {
        FileId id = file_id(to);
        for (const auto &c : companions)
            if (same_file(c.first, id)) {
                if (*c.second == bytes)
                    return true;
                error = "cannot write '" + to + "': two of its buffers or images name it, with different bytes: nothing written";
                return false;
            }
        companions.push_back({id, &bytes});
        return write_output(outputs, to, replaces, std::string(bytes.begin(), bytes.end()), error);
    }

    /* A new file name for a buffer beside the output: <stem>.bin,
       <stem>1.bin, ...: the first that is no file the job reads or writes
       (never one of the input's own files). */
    std::string fresh_name() const
    {
        for (size_t k = 0;; ++k) {
            std::string name = stem + (k != 0 ? std::to_string(k) : "") + ".bin", to = out_dir + "/" + name;
            if (!outputs.was_read(to) && !outputs.is_planned(to))
                return name;
        }
    }

    /* Images are never changed: each goes beside the output as read,
       unless it is there already (in place, or in the same directory). */
    bool images(std::string &error)
    {
        for (const tinygltf::Image &image : file.model.images) {
            std::string relative;
            if (image.uri.empty() || data_uri(image.uri))
                continue;
            if (!companion_path(image.uri, relative)) {
                error = file.path + ": image '" + image.uri + "' is not a file beside it: nothing written";
                return false;
            }
            std::string to = out_dir + "/" + relative;
            if (same_file(file_id(to), file_id(directory_of(file.path) + "/" + relative)))
                continue;
            if (image.image.empty()) {
                error = file.path + ": image '" + image.uri + "' is missing beside it, so it cannot be copied beside '" +
                        target + "': nothing written";
                return false;
            }
            if (!put(to, "", image.image, error))
                return false;
        }
        return true;
    }

    /* Buffer i's file, when it is one beside the output: written, unless
       it is unchanged and there already; in place over its own file, else
       under a new name when its own is a file the job reads. Fills the
       changes to its entry (uri); with no changes (the document written
       as it was) a new name is refused. */
    bool external_buffer(size_t i, const std::string &uri, std::vector<std::pair<std::string, std::string>> *changes,
                         std::string &error)
    {
        const std::vector<unsigned char> &data = file.model.buffers[i].data;
        std::string relative, to, replaces;
        if (!uri.empty()) {
            if (!companion_path(uri, relative)) {
                error = file.path + ": buffer '" + uri + "' is not a file beside it: nothing written";
                return false;
            }
            to = out_dir + "/" + relative;
            bool there = same_file(file_id(to), file_id(file.buffer_files[i]));
            if (there && !file.buffer_changed[i])
                return true;
            if (there && in_place)
                replaces = file.buffer_files[i];
        }
        if (to.empty() || (replaces.empty() && (outputs.was_read(to) || outputs.is_planned(to)))) {
            if (changes == nullptr) {
                error = "cannot write '" + to + "': it is a file the input reads: nothing written";
                return false;
            }
            std::string name = fresh_name();
            to = out_dir + "/" + name;
            changes->push_back({"uri", json_quote(uri_of(name))});
        }
        return put(to, replaces, data, error);
    }

    /* Every buffer: the GLB's chunk, a data URI (written again when its
       bytes changed) or a file; entries the repair added appended. */
    bool buffers(std::string &error)
    {
        const JsonValue *array = file.document.member("buffers");
        std::vector<std::string> added;
        for (size_t i = 0; i < file.model.buffers.size(); ++i) {
            const tinygltf::Buffer &b = file.model.buffers[i];
            const JsonValue *entry = array != nullptr && i < array->items.size() ? &array->items[i] : nullptr;
            const JsonValue *uri_value = entry != nullptr ? entry->member("uri") : nullptr;
            std::string uri = uri_value != nullptr && uri_value->kind == '"' ? uri_value->string : "";
            std::vector<std::pair<std::string, std::string>> changes;
            if (entry == nullptr || b.data.size() != file.buffer_sizes[i])
                changes.push_back({"byteLength", std::to_string(b.data.size())});
            if (to_binary && i == 0 && !data_uri(uri)) {
                bin = b.data; /* the first buffer is the GLB's BIN chunk */
                with_bin = true;
                if (uri_value != nullptr)
                    changes.push_back({"uri", ""});
            } else if (data_uri(uri)) {
                size_t comma = uri.find(',');
                bool base64_uri = comma != std::string::npos && comma >= 7 && uri.compare(comma - 7, 7, ";base64") == 0;
                std::string prefix = base64_uri ? uri.substr(0, comma + 1) : "data:application/octet-stream;base64,";
                if (file.buffer_changed[i])
                    changes.push_back({"uri", json_quote(prefix + base64(b.data))});
            } else if (!external_buffer(i, uri, &changes, error)) {
                return false;
            }
            if (entry != nullptr && !changes.empty()) {
                edits.update(*entry, changes);
            } else if (entry == nullptr) {
                std::string object;
                for (const auto &c : changes)
                    if (!c.second.empty())
                        object += (object.empty() ? "" : ",") + json_quote(c.first) + ":" + c.second;
                added.push_back("{" + object + "}");
            }
        }
        add_entries("buffers", added);
        return true;
    }

    void add_entries(const char *name, const std::vector<std::string> &entries)
    {
        if (entries.empty())
            return;
        const JsonValue *array = file.document.member(name);
        if (array != nullptr) {
            edits.append(*array, entries);
            return;
        }
        std::string joined;
        for (const std::string &e : entries)
            joined += (joined.empty() ? "" : ",") + e;
        edits.set(file.document, name, "[" + joined + "]");
    }

    /* The primitives given new indices, and the accessors and bufferViews
       the repair added. */
    void indices()
    {
        const tinygltf::Model &m = file.model;
        for (const auto &mp : file.primitives_changed) {
            const JsonValue &entry = file.document.member("meshes")->items[(size_t)mp.first].member("primitives")->items[(size_t)mp.second];
            std::vector<std::pair<std::string, std::string>> changes = {
                {"indices", std::to_string(m.meshes[(size_t)mp.first].primitives[(size_t)mp.second].indices)}};
            if (entry.member("mode") != nullptr)
                changes.push_back({"mode", "4"});
            edits.update(entry, changes);
        }
        std::vector<std::string> accessors, views;
        for (size_t i = file.first_new_accessor; i < m.accessors.size(); ++i) {
            const tinygltf::Accessor &a = m.accessors[i];
            accessors.push_back("{\"bufferView\":" + std::to_string(a.bufferView) + ",\"componentType\":" +
                                std::to_string(a.componentType) + ",\"count\":" + std::to_string(a.count) + ",\"type\":\"SCALAR\"}");
        }
        for (size_t i = file.first_new_view; i < m.bufferViews.size(); ++i) {
            const tinygltf::BufferView &v = m.bufferViews[i];
            views.push_back("{\"buffer\":" + std::to_string(v.buffer) + ",\"byteOffset\":" + std::to_string(v.byteOffset) +
                            ",\"byteLength\":" + std::to_string(v.byteLength) + ",\"target\":34963}");
        }
        add_entries("accessors", accessors);
        add_entries("bufferViews", views);
    }

    /* The document as read, with the changes; GLB: no byte-order mark and
       no padding of the old chunk. */
    std::string document_bytes()
    {
        std::string json = edits.result();
        if (json.compare(0, 3, "\xEF\xBB\xBF") == 0 && to_binary)
            json.erase(0, 3);
        if (file.binary)
            while (!json.empty() && (json.back() == ' ' || json.back() == '\0'))
                json.pop_back();
        if (to_binary)
            return glb_bytes(json, bin, with_bin);
        return file.binary ? json + "\n" : json;
    }

    bool write(std::string &error)
    {
        if (!images(error))
            return false;
        if (!file.changed && to_binary == file.binary) {
            for (size_t i = 0; i < file.model.buffers.size(); ++i) {
                const std::string &uri = file.model.buffers[i].uri;
                if (!uri.empty() && !data_uri(uri) && !external_buffer(i, uri, nullptr, error))
                    return false;
            }
            return write_output(outputs, target, input, file.raw, error);
        }
        if (!file.document_matches) {
            error = file.path + ": its JSON could not be read as tinygltf read it, so it cannot be edited: nothing written";
            return false;
        }
        indices();
        return buffers(error) && write_output(outputs, target, input, document_bytes(), error);
    }
};

} // namespace

bool GltfFile::write(const std::string &, const std::string &target, std::string &error)
{
    error = "cannot write '" + target + "': a glTF is written with its buffers (write_outputs)";
    return false;
}

bool GltfFile::write_outputs(OutputSet &outputs, const std::string &input, const std::string &target, std::string &error)
{
    GltfWriter writer(*this, outputs, input, target);
    return writer.write(error);
}

std::vector<std::string> GltfFile::files_read() const
{
    std::vector<std::string> files;
    for (const std::string &f : buffer_files)
        if (!f.empty())
            files.push_back(f);
    for (const std::string &f : image_files)
        if (!f.empty())
            files.push_back(f);
    return files;
}

std::vector<std::string> GltfFile::notes() const
{
    std::vector<std::string> lines;
    for (const auto &nm : mirrored) {
        const tinygltf::Node &node = model.nodes[(size_t)nm.first];
        lines.push_back("note: node " + std::to_string(nm.first) + (node.name.empty() ? "" : " '" + node.name + "'") +
                        " draws mesh " + std::to_string(nm.second) +
                        " mirrored (negative determinant): glTF reverses its winding there; left as it is");
    }
    for (int m : double_sided)
        lines.push_back("note: material " + std::to_string(m) +
                        (model.materials[(size_t)m].name.empty() ? "" : " '" + model.materials[(size_t)m].name + "'") +
                        " is double-sided: back faces are drawn, so wrong winding may not show; left as it is");
    if (accessors_cloned + lists_written + indices_added != 0)
        lines.push_back("note: " + std::to_string(accessors_cloned) + " shared index accessors cloned, " +
                        std::to_string(lists_written) + " strips or fans written as triangle lists, " +
                        std::to_string(indices_added) + " non-indexed primitives given indices");
    if (normals_negated + tangents_negated != 0)
        lines.push_back("note: " + std::to_string(normals_negated) + " NORMAL and " + std::to_string(tangents_negated) +
                        " TANGENT.w values negated");
    if (tangents_disagree != tangents_negated)
        lines.push_back("note: " + std::to_string(tangents_disagree) +
                        " TANGENT.w of flat vertices against their texture coordinates (--fix-normals negates them)");
    return lines;
}

std::string GltfFile::json_members() const
{
    std::string s = ",\"gltf\":{\"mirrored_nodes\":[";
    for (size_t i = 0; i < mirrored.size(); ++i)
        s += (i ? "," : "") + std::string("{\"node\":") + std::to_string(mirrored[i].first) + ",\"mesh\":" +
             std::to_string(mirrored[i].second) + "}";
    s += "],\"double_sided_materials\":[";
    for (size_t i = 0; i < double_sided.size(); ++i)
        s += (i ? "," : "") + std::to_string(double_sided[i]);
    s += "],\"index_accessors_cloned\":" + std::to_string(accessors_cloned) +
         ",\"strips_fans_as_lists\":" + std::to_string(lists_written) +
         ",\"indices_added\":" + std::to_string(indices_added) + ",\"normals_negated\":" + std::to_string(normals_negated) +
         ",\"tangents_negated\":" + std::to_string(tangents_negated) +
         ",\"tangents_disagree\":" + std::to_string(tangents_disagree) + "}";
    return s;
}

namespace {

/* What the writer needs to know of the file as read: the files of its
   buffers and images, which buffers are one file, their sizes, and where
   the accessors and bufferViews the repair adds begin. */
void note_files(GltfFile &f, const std::string &base)
{
    const tinygltf::Model &m = f.model;
    for (size_t i = 0; i < m.buffers.size(); ++i) {
        std::string relative, uri = m.buffers[i].uri;
        bool file = !uri.empty() && !data_uri(uri) && companion_path(uri, relative);
        f.buffer_files.push_back(file ? base + "/" + relative : "");
        f.buffer_sizes.push_back(m.buffers[i].data.size());
        f.buffer_changed.push_back(0);
        f.buffer_file_first.push_back((int)i);
        for (size_t j = 0; file && j < i; ++j)
            if (!f.buffer_files[j].empty() && same_file(file_id(f.buffer_files[j]), file_id(f.buffer_files[i]))) {
                f.buffer_file_first[i] = f.buffer_file_first[j];
                break;
            }
    }
    for (const tinygltf::Image &image : m.images) {
        std::string relative;
        bool file = !image.uri.empty() && !data_uri(image.uri) && !image.image.empty() && companion_path(image.uri, relative);
        f.image_files.push_back(file ? base + "/" + relative : "");
    }
    f.first_new_accessor = m.accessors.size();
    f.first_new_view = m.bufferViews.size();
}

} // namespace

std::unique_ptr<MeshFile> load_gltf(const std::string &path, std::string &error)
{
    std::unique_ptr<GltfFile> file(new GltfFile);
    file->path = path;
    if (!read_file(path, file->raw, error))
        return nullptr;
    file->binary = file->raw.compare(0, 4, "glTF") == 0;
    const char *json;
    size_t json_size;
    json_text(file->raw, file->binary, &json, &json_size);
    if (json_depth(json, json_size) > json_depth_limit) {
        error = "its JSON nests deeper than " + std::to_string(json_depth_limit) + " levels: refused";
        return nullptr;
    }
    /* the document as written, for the edits; tinygltf reads it with each
       '+' in a URI kept a '+' */
    file->text.assign(json, json_size);
    bool parsed = parse_json(file->text, file->document);
    std::string loaded = file->raw;
    if (parsed) {
        std::string literal = literal_plus(file->text, file->document);
        if (literal != file->text)
            loaded = file->binary ? with_json_chunk(file->raw, literal) : literal;
    }
    Companions companions;
    companions.base = directory_of(path);
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(keep_image_bytes, nullptr);
    loader.SetFsCallbacks({companion_exists, companion_expand, companion_read, companion_write, &companions});
    std::string err, warn;
    bool ok = file->binary ? loader.LoadBinaryFromMemory(&file->model, &err, &warn, (const unsigned char *)loaded.data(),
                                                         (unsigned)loaded.size(), companions.base)
                           : loader.LoadASCIIFromString(&file->model, &err, &warn, loaded.data(),
                                                        (unsigned)loaded.size(), companions.base);
    if (!companions.refused.empty()) {
        error = "refers to '" + companions.refused + ": refused";
        return nullptr;
    }
    if (!ok) {
        /* tinygltf refuses most compressed files itself (their accessors
           have no bufferView): say why, from the extension's name */
        for (const char *name : compression_extensions)
            if (file->raw.find(name) != std::string::npos) {
                error = compression_message(name);
                return nullptr;
            }
        size_t end = err.find('\n');
        error = "not a readable glTF 2.0 file: " + (err.empty() ? std::string("tinygltf refused it") : err.substr(0, end));
        return nullptr;
    }
    /* every external URI must name the file tinygltf read for it */
    std::vector<std::string> uris;
    for (const tinygltf::Buffer &b : file->model.buffers)
        uris.push_back(b.uri);
    for (const tinygltf::Image &i : file->model.images)
        if (!i.image.empty())
            uris.push_back(i.uri);
    for (const std::string &uri : uris) {
        std::string relative;
        if (uri.empty() || data_uri(uri))
            continue;
        if (!companion_path(uri, relative) || !companions.read.count(relative)) {
            error = "refers to '" + uri + "', which is not a file beside it: refused";
            return nullptr;
        }
    }
    /* tinygltf reads a glTF 1.0 file as an empty 2.0 one: say so instead
       of calling it clean */
    if (file->model.asset.version.compare(0, 1, "2") != 0) {
        error = "glTF " + (file->model.asset.version.empty() ? std::string("without a version") : file->model.asset.version) +
                " is not supported (glTF 2.0 only)";
        return nullptr;
    }
    std::string compression = compression_of(file->model);
    if (!compression.empty()) {
        error = compression_message(compression);
        return nullptr;
    }
    file->document_matches = parsed && document_matches(file->document, file->model);
    note_files(*file, companions.base);
    MeshReader reader{*file, error, {}};
    if (!reader.read())
        return nullptr;
    find_mirrored(*file);
    return file;
}

#endif

} // namespace tool
