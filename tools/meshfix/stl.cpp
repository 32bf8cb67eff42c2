/* meshfix command-line tool: STL, binary and ASCII, lossless.

   A flipped facet gets its last two vertices swapped and its stored normal
   negated when it pointed along the old winding (a normal that disagreed
   with it, the exporter's word against a wrong winding, is kept); the header, the other facets and the attribute bytes pass
   through as they were. The facet normals are the exporter's word on which
   way each facet faces: they go to the library as evidence. The corners
   are merged into vertices by examples/meshio.h (bit-identical positions,
   as every STL reader of the project does). */
#include "meshfile.h"
#include "text.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>

extern "C" {
#include "../../examples/meshio.h"
}

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

/* Words as examples/meshio.h reads them (that reader builds the mesh): a
   '#' at the start of a word comments out the rest of its line, and a word
   is compared whole (a NUL byte is part of it). */
struct AsciiScanner {
    const std::string &data;
    size_t at = 0;

    bool word(Span &s)
    {
        for (;;) {
            while (at < data.size() && is_space(data[at]))
                ++at;
            if (at < data.size() && data[at] == '#') {
                while (at < data.size() && data[at] != '\n')
                    ++at;
                continue;
            }
            break;
        }
        s.begin = at;
        while (at < data.size() && !is_space(data[at]))
            ++at;
        s.end = at;
        return s.end > s.begin;
    }
    bool is(const Span &s, const char *w) const
    {
        return s.end - s.begin == std::strlen(w) && data.compare(s.begin, s.end - s.begin, w) == 0;
    }
    float number(const Span &s) const
    {
        return std::strtof(data.substr(s.begin, s.end - s.begin).c_str(), nullptr);
    }
};

/* Facet normals and vertex texts, facet by facet, as meshio reads them: a
   facet ends at "endloop" after three vertices. `corners` gets the x y z
   this scanner reads for each corner, for the comparison with meshio's. */
bool scan_ascii(StlFile &file, std::vector<float> &normals, std::vector<float> &corners, std::string &error)
{
    AsciiScanner s{file.data};
    Span w, n[3];
    std::array<Span, 3> normal{}, vertices{};
    float xyz[9];
    int count = 0;
    while (s.word(w)) {
        if (s.is(w, "normal")) {
            double v[3];
            for (int k = 0; k < 3; ++k)
                if (!s.word(n[k]) || !parse_double(file.data.substr(n[k].begin, n[k].end - n[k].begin), v[k])) {
                    error = "bad STL facet normal";
                    return false;
                }
            normal = {n[0], n[1], n[2]};
        } else if (s.is(w, "vertex")) {
            if (count == 3) {
                error = "facet with more than 3 vertices";
                return false;
            }
            for (int k = 0; k < 3; ++k) {
                s.word(n[k]);
                xyz[3 * count + k] = s.number(n[k]);
            }
            vertices[(size_t)count++] = {n[0].begin, n[2].end};
        } else if (s.is(w, "endloop")) {
            float f[3] = {0, 0, 0};
            for (int k = 0; k < 3; ++k)
                if (normal[(size_t)k].end > normal[(size_t)k].begin)
                    f[k] = s.number(normal[(size_t)k]);
            normals.insert(normals.end(), f, f + 3);
            corners.insert(corners.end(), xyz, xyz + 9);
            file.normal_tokens.push_back(normal);
            file.vertex_text.push_back(vertices);
            normal = {};
            count = 0;
        }
    }
    return true;
}

/* Whether meshio's triangles are the facets this scanner found, corner by
   corner: the facets the tool edits must be the ones the library decided
   on. (meshio joins corners at equal positions, -0 = +0.) */
bool same_corners(const Unit &u, const std::vector<float> &corners)
{
    if (corners.size() != 3 * u.indices.size())
        return false;
    for (size_t c = 0; c < u.indices.size(); ++c)
        for (int k = 0; k < 3; ++k) {
            float mine = corners[3 * c + (size_t)k], theirs = (float)u.positions[3 * (size_t)u.indices[c] + (size_t)k];
            if (!(mine == theirs || (mine != mine && theirs != theirs)))
                return false;
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
    mio_mesh mesh;
    char message[256];
    if (!mio_parse(data.data(), data.size(), "stl", &mesh, message, sizeof(message))) {
        error = message;
        return nullptr;
    }
    file->data = data;
    Unit &u = file->units.emplace_back();
    u.positions.assign(mesh.positions, mesh.positions + 3 * mesh.vertex_count);
    u.indices.assign(mesh.indices, mesh.indices + mesh.index_count);
    mio_free(&mesh);
    size_t facets = u.indices.size() / 3;
    /* meshio took the file as binary exactly when its size is 84 + 50 n */
    file->binary = data.size() >= 84 && data.size() == 84 + 50 * (size_t)read_u32le((const unsigned char *)&data[80]);
    std::vector<float> normals, corners;
    if (file->binary) {
        for (size_t f = 0; f < facets; ++f)
            for (int k = 0; k < 3; ++k)
                normals.push_back(read_f32le((const unsigned char *)&data[84 + 50 * f + 4 * (size_t)k]));
    } else if (!scan_ascii(*file, normals, corners, error)) {
        return nullptr;
    } else if (!same_corners(u, corners)) {
        error = "the ASCII STL's facets read two ways (comments or NUL bytes among them): not changed";
        return nullptr;
    }
    if (normals.size() != 3 * facets) {
        error = "the STL facets could not be read consistently";
        return nullptr;
    }
    u.face_count = facets;
    for (size_t f = 0; f < facets; ++f) {
        u.triangle_face.push_back((uint32_t)f);
        u.flat_normals.push_back({(uint32_t)f, {normals[3 * f], normals[3 * f + 1], normals[3 * f + 2]}, (uint32_t)f});
    }
    u.triangle_normals = std::move(normals);
    u.flat_normals_follow_faces = true; /* a facet's normal is negated with it */
    return file;
}

} // namespace tool
