/* meshfix command-line tool: STL, binary and ASCII, lossless.

   A flipped facet gets its last two vertices swapped and its stored normal
   negated when it pointed along the old winding (a normal that disagreed
   with it, the exporter's word against a wrong winding, is kept); the
   header, the other facets and the attribute bytes pass through as they
   were. The facet normals are the exporter's word on which way each facet
   faces: they go to the library as evidence. The file is read once: the
   facets the library decides on are the ones the tool edits. Corners with
   bit-identical positions (-0 = +0) are merged into vertices by
   meshfix_weld, as every STL reader of the project does. */
#include "meshfile.h"
#include "text.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace tool {
namespace {

class StlFile : public MeshFile {
public:
    const char *format() const override { return "stl"; }
    void apply(size_t unit, const Changes &changes) override;
    bool write(const std::string &path, const std::string &target, std::string &error) override;

    std::string data;
    bool binary = false;
    /* ASCII: per facet, the normal's three tokens (begin == end when the
       facet has none) and the text of each vertex's coordinates */
    std::vector<std::array<Span, 3>> normal_tokens;
    std::vector<std::array<Span, 3>> vertex_text;
    std::vector<Edit> edits;
};

uint32_t read_u32le(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

float read_f32le(const unsigned char *p)
{
    uint32_t bits = read_u32le(p);
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
}

/* Negates a stored little-endian float in place; zero and NaN stay as they
   are (-0 would change bytes and nothing else). */
void negate_f32le(unsigned char *p)
{
    float f = read_f32le(p);
    if (f != 0.0f && f == f)
        p[3] ^= 0x80u;
}

/* The facets as the file stores them: a normal (3 floats) and three
   corners (9 floats) each. */
struct Facets {
    std::vector<float> normals, corners;
};

/* The library's bound on indices, 0x7FFFFFFF, in whole triangles. */
const size_t max_facets = 0x7FFFFFFC / 3;

/* A binary STL is exactly 84 + 50 n bytes for the n facets its header
   declares; any other file is read as text. */
bool is_binary(const std::string &data)
{
    return data.size() >= 84 &&
           (unsigned long long)data.size() == 84 + 50 * (unsigned long long)read_u32le((const unsigned char *)&data[80]);
}

/* Whether the text starts with "solid" (after a byte-order mark). */
bool says_solid(const std::string &data) { return data.compare(byte_order_mark(data), 5, "solid") == 0; }

bool read_binary(const std::string &data, Facets &facets, std::string &error)
{
    size_t n = (data.size() - 84) / 50;
    if (n > max_facets) {
        error = "too many triangles";
        return false;
    }
    facets.normals.resize(3 * n);
    facets.corners.resize(9 * n);
    for (size_t f = 0; f < n; ++f) {
        const unsigned char *facet = (const unsigned char *)&data[84 + 50 * f];
        for (size_t k = 0; k < 3; ++k)
            facets.normals[3 * f + k] = read_f32le(facet + 4 * k);
        for (size_t k = 0; k < 9; ++k)
            facets.corners[9 * f + k] = read_f32le(facet + 12 + 4 * k);
    }
    return true;
}

/* A number token as a float, the whole token (a NUL byte ends none). */
bool read_float(const std::string &token, float &out)
{
    char *end = nullptr;
    out = std::strtof(token.c_str(), &end);
    return !token.empty() && end == token.c_str() + token.size();
}

/* ASCII STL, word by word (text.h's scanner): "normal" and its three
   numbers, "vertex" and its three, and "endloop", which ends a facet of
   three vertices; other words ("solid", "facet", "outer loop", names) are
   passed over. Each facet's normal and vertex texts are kept for the
   edits. */
bool read_ascii(StlFile &file, Facets &facets, std::string &error)
{
    WordScanner s(file.data);
    Span w, n[3];
    std::array<Span, 3> normal{}, vertices{};
    float normal_value[3] = {0, 0, 0}, xyz[9];
    int count = 0;
    while (s.word(w)) {
        if (s.is(w, "normal")) {
            for (int k = 0; k < 3; ++k)
                if (!s.word(n[k]) || !read_float(s.text(n[k]), normal_value[k])) {
                    error = "bad STL facet normal";
                    return false;
                }
            normal = {n[0], n[1], n[2]};
        } else if (s.is(w, "vertex")) {
            if (count == 3) {
                error = "facet with more than 3 vertices";
                return false;
            }
            for (int k = 0; k < 3; ++k)
                if (!s.word(n[k]) || !read_float(s.text(n[k]), xyz[3 * count + k])) {
                    error = "bad STL vertex";
                    return false;
                }
            vertices[(size_t)count++] = {n[0].begin, n[2].end};
        } else if (s.is(w, "endloop")) {
            if (count != 3 || facets.normals.size() / 3 == max_facets) {
                error = count != 3 ? "facet with " + std::to_string(count) + " vertices" : "too many triangles";
                return false;
            }
            if (normal[0].end == normal[0].begin)
                normal_value[0] = normal_value[1] = normal_value[2] = 0.0f; /* a facet without one */
            facets.normals.insert(facets.normals.end(), normal_value, normal_value + 3);
            facets.corners.insert(facets.corners.end(), xyz, xyz + 9);
            file.normal_tokens.push_back(normal);
            file.vertex_text.push_back(vertices);
            normal = {};
            count = 0;
        }
    }
    if (facets.normals.empty() && file.data.size() >= 5 && !says_solid(file.data)) {
        error = "not an STL file";
        return false;
    }
    return true;
}

bool finite3(const float *p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

/* The unit's vertices and triangles from the facets' corners: corners at
   bit-identical finite positions (-0 = +0) are one vertex, numbered by
   its first corner in file order; a NaN or infinite corner stays a vertex
   of its own (meshfix_weld refuses it, and judging it is the library's
   job, not the reader's). */
bool weld_corners(std::vector<float> &corners, Unit &u, std::string &error)
{
    size_t n = corners.size() / 3;
    for (float &c : corners)
        if (c == 0.0f)
            c = 0.0f;
    std::vector<uint32_t> finite; /* the corners meshfix_weld is given, in order */
    std::vector<float> packed;    /* their positions, when some corner is left out */
    for (size_t i = 0; i < n; ++i)
        if (finite3(&corners[3 * i]))
            finite.push_back((uint32_t)i);
    if (finite.size() < n)
        for (uint32_t i : finite)
            packed.insert(packed.end(), &corners[3 * (size_t)i], &corners[3 * (size_t)i] + 3);
    std::vector<unsigned int> remap(finite.size());
    meshfix_result result = meshfix_weld(remap.data(), packed.empty() ? corners.data() : packed.data(), finite.size(),
                                         3 * sizeof(float), 0.0f, nullptr, nullptr);
    if (result != MESHFIX_OK) {
        error = result == MESHFIX_ERROR_OUT_OF_MEMORY ? "out of memory merging " + std::to_string(n) + " STL corners"
                                                      : std::string("cannot merge STL corners: ") + meshfix_result_string(result);
        return false;
    }
    u.indices.resize(n);
    for (size_t i = 0, j = 0; i < n; ++i) {
        bool welded = j < finite.size() && finite[j] == i;
        if (welded && remap[j] != j) {
            u.indices[i] = u.indices[finite[remap[j]]]; /* remap[j] < j: numbered already */
        } else {
            u.indices[i] = (uint32_t)(u.positions.size() / 3);
            u.positions.insert(u.positions.end(), &corners[3 * i], &corners[3 * i] + 3);
        }
        j += welded;
    }
    return true;
}

} // namespace

bool write_bytes(const std::string &path, const std::string &bytes, std::string &error);

void StlFile::apply(size_t, const Changes &changes)
{
    size_t facets = changes.face_flipped.size();
    for (size_t f = 0; f < facets; ++f) {
        bool flip = changes.face_flipped[f] != 0, negate = changes.negate_flat[f] != 0;
        if (!flip && !negate)
            continue;
        changed = true;
        if (binary) {
            unsigned char *facet = (unsigned char *)&data[84 + 50 * f];
            if (flip)
                std::swap_ranges(facet + 24, facet + 36, facet + 36);
            if (negate)
                for (int k = 0; k < 3; ++k)
                    negate_f32le(facet + 4 * k);
            continue;
        }
        if (flip) {
            const Span &b = vertex_text[f][1], &c = vertex_text[f][2];
            edits.push_back({b.begin, b.end - b.begin, data.substr(c.begin, c.end - c.begin)});
            edits.push_back({c.begin, c.end - c.begin, data.substr(b.begin, b.end - b.begin)});
        }
        if (negate)
            for (const Span &s : normal_tokens[f])
                if (s.end > s.begin)
                    edits.push_back({s.begin, s.end - s.begin, negated_number(data.substr(s.begin, s.end - s.begin))});
    }
}

bool StlFile::write(const std::string &path, const std::string &, std::string &error)
{
    return write_bytes(path, edits.empty() ? data : splice(data, edits), error);
}

std::unique_ptr<MeshFile> load_stl(const std::string &data, std::string &error)
{
    std::unique_ptr<StlFile> file(new StlFile);
    file->data = data;
    file->binary = is_binary(data);
    if (data.size() >= 84 && !file->binary && !says_solid(data)) {
        error = "binary STL of " + std::to_string(data.size()) + " bytes cannot hold the " +
                std::to_string(read_u32le((const unsigned char *)&data[80])) + " triangles it declares";
        return nullptr;
    }
    Facets facets;
    if (!(file->binary ? read_binary(file->data, facets, error) : read_ascii(*file, facets, error)))
        return nullptr;
    if (facets.normals.empty()) {
        error = "no triangles";
        return nullptr;
    }
    Unit &u = file->units.emplace_back();
    if (!weld_corners(facets.corners, u, error))
        return nullptr;
    size_t n = facets.normals.size() / 3;
    u.face_count = n;
    for (size_t f = 0; f < n; ++f) {
        const float *normal = &facets.normals[3 * f];
        u.triangle_face.push_back((uint32_t)f);
        u.flat_normals.push_back({(uint32_t)f, {normal[0], normal[1], normal[2]}, (uint32_t)f});
    }
    u.triangle_normals = std::move(facets.normals);
    u.flat_normals_follow_faces = true; /* a facet's normal is negated with it */
    return file;
}

} // namespace tool
