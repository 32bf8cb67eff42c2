/* meshfix command-line tool: PLY, ASCII and binary of either endianness,
   lossless.

   The header and every element and property (colours, normals, texture
   coordinates, face properties, elements the tool does not know) pass
   through byte for byte; a flipped face has its vertex list written in
   reverse order (the first kept first), values of the same type in the
   same bytes; with --fix-normals a flat vertex normal is negated in
   place. */
#include "meshfile.h"
#include "text.h"

#include <array>
#include <cmath>
#include <cstring>

namespace tool {
namespace {

enum Encoding { ASCII, LITTLE, BIG };

struct Property {
    std::string name;
    int type = 0;       /* byte size; negative for signed integers, 40 / 80 for float / double */
    int count_type = 0; /* 0 for a scalar, else the type of a list's length */
};

struct Element {
    std::string name;
    unsigned long long count = 0;
    std::vector<Property> properties;
};

/* PLY type names: the byte size, negative for signed integers, and
   40 / 80 for float / double. */
int type_of(const std::string &name)
{
    static const struct {
        const char *name;
        int type;
    } types[] = {{"char", -1},  {"int8", -1},   {"uchar", 1},   {"uint8", 1},    {"short", -2},  {"int16", -2},
                 {"ushort", 2}, {"uint16", 2},  {"int", -4},    {"int32", -4},   {"uint", 4},    {"uint32", 4},
                 {"float", 40}, {"float32", 40}, {"double", 80}, {"float64", 80}};
    for (const auto &t : types)
        if (name == t.name)
            return t.type;
    return 0;
}

size_t size_of(int type) { return type >= 40 ? (size_t)type / 10 : (size_t)std::abs(type); }

/* Where a value lies: its bytes (binary) or its token (ASCII). */
struct Place {
    size_t begin, end;
};

class PlyFile : public MeshFile {
public:
    const char *format() const override { return "ply"; }
    void apply(size_t unit, const Changes &changes) override;
    bool write(const std::string &path, const std::string &target, std::string &error) override;

    std::string data;
    Encoding encoding = ASCII;
    std::vector<Place> corners;     /* every face's indices, face after face */
    std::vector<size_t> face_first; /* face f's indices: [face_first[f], face_first[f + 1]) */
    int index_type = 0;
    int normal_type = 0;
    std::vector<std::array<Place, 3>> normal_places; /* of each vertex with nx ny nz */
    std::vector<Edit> edits;
};

struct PlyReader {
    PlyReader(PlyFile &f, std::string &e) : file(f), error(e) {}
    PlyFile &file;
    std::string &error;
    size_t at = 0;
    std::vector<Element> elements;

    bool fail(const std::string &message)
    {
        error = message;
        return false;
    }

    /* One header line as words; `at` moves past it and its line break
       (LF, CRLF or a lone CR). */
    std::vector<std::string> header_line()
    {
        std::vector<std::string> words;
        size_t end = line_end(file.data, at);
        std::string line = file.data.substr(at, end - at);
        at = end + line_break(file.data, end);
        size_t i = 0;
        while (i < line.size()) {
            while (i < line.size() && is_space(line[i]))
                ++i;
            size_t b = i;
            while (i < line.size() && !is_space(line[i]))
                ++i;
            if (i > b)
                words.push_back(line.substr(b, i - b));
        }
        return words;
    }

    bool header()
    {
        at = byte_order_mark(file.data);
        std::vector<std::string> w = header_line();
        if (w.size() != 1 || w[0] != "ply")
            return fail("not a PLY file");
        /* a header written with lone CRs ends with one: the binary data
           after it may start with a 0x0A byte */
        bool lone_cr = file.data[at - 1] == '\r';
        bool format = false;
        while (at < file.data.size()) {
            w = header_line();
            if (w.empty() || w[0] == "comment" || w[0] == "obj_info")
                continue;
            if (w[0] == "end_header") {
                if (lone_cr && file.data[at - 1] == '\n')
                    --at;
                return format || fail("PLY header without format");
            }
            if (w[0] == "format" && w.size() >= 2) {
                format = true;
                if (w[1] == "ascii")
                    file.encoding = ASCII;
                else if (w[1] == "binary_little_endian")
                    file.encoding = LITTLE;
                else if (w[1] == "binary_big_endian")
                    file.encoding = BIG;
                else
                    return fail("unknown PLY format '" + w[1] + "'");
            } else if (w[0] == "element" && w.size() == 3) {
                Element e;
                double count;
                e.name = w[1];
                if (!parse_double(w[2], count) || !(count >= 0 && count <= 4294967295.0) || count != std::floor(count))
                    return fail("bad PLY element count");
                e.count = (unsigned long long)count;
                elements.push_back(e);
            } else if (w[0] == "property" && !elements.empty()) {
                Property p;
                if (w.size() == 5 && w[1] == "list") {
                    p.count_type = type_of(w[2]), p.type = type_of(w[3]), p.name = w[4];
                    if (p.count_type == 0 || p.count_type >= 40 || p.type == 0)
                        return fail("bad PLY list types");
                } else if (w.size() == 3) {
                    p.type = type_of(w[1]), p.name = w[2];
                    if (p.type == 0)
                        return fail("unknown PLY type '" + w[1] + "'");
                } else {
                    return fail("bad PLY property line");
                }
                elements.back().properties.push_back(p);
            }
            /* anything else (exporters write free text, as Blender's "Created
               by") passes through untouched, as other readers let it */
        }
        return fail("PLY header without end_header");
    }

    /* The next value of `type` as a double, and where it lies. */
    bool value(int type, double &out, Place &place)
    {
        const std::string &d = file.data;
        if (file.encoding == ASCII) {
            while (at < d.size() && is_space(d[at]))
                ++at;
            place.begin = at;
            while (at < d.size() && !is_space(d[at]))
                ++at;
            place.end = at;
            return (place.end > place.begin && parse_double(d.substr(place.begin, place.end - place.begin), out)) ||
                   fail("bad or missing PLY value");
        }
        size_t n = size_of(type);
        if (d.size() - at < n)
            return fail("PLY data ends early");
        unsigned char b[8];
        for (size_t k = 0; k < n; ++k)
            b[k] = (unsigned char)d[at + (file.encoding == LITTLE ? k : n - 1 - k)];
        place = {at, at + n};
        at += n;
        unsigned long long bits = 0;
        for (size_t k = n; k-- > 0;)
            bits = bits << 8 | b[k];
        if (type == 40) {
            float f;
            uint32_t u = (uint32_t)bits;
            std::memcpy(&f, &u, 4);
            out = f;
        } else if (type == 80) {
            std::memcpy(&out, &bits, 8);
        } else if (type < 0) {
            unsigned long long sign = 1ull << (8 * n - 1);
            out = (double)(long long)((bits ^ sign) - sign);
        } else {
            out = (double)bits;
        }
        return true;
    }

    bool vertices(const Element &e, Unit &u)
    {
        int x = -1, y = -1, z = -1, nx = -1, ny = -1, nz = -1;
        for (size_t i = 0; i < e.properties.size(); ++i) {
            const std::string &n = e.properties[i].name;
            int *slot = n == "x" ? &x : n == "y" ? &y : n == "z" ? &z : n == "nx" ? &nx : n == "ny" ? &ny : n == "nz" ? &nz : nullptr;
            if (slot != nullptr && e.properties[i].count_type == 0)
                *slot = (int)i;
        }
        if (x < 0 || y < 0 || z < 0)
            return fail("PLY vertex without x, y and z");
        bool normals = nx >= 0 && ny >= 0 && nz >= 0;
        if (normals)
            file.normal_type = e.properties[(size_t)nx].type;
        u.positions.resize(3 * e.count);
        if (normals)
            u.vertex_normals.resize(3 * e.count);
        for (unsigned long long v = 0; v < e.count; ++v) {
            std::array<Place, 3> normal_at{};
            for (size_t i = 0; i < e.properties.size(); ++i) {
                double value;
                Place place;
                if (!property(e.properties[i], value, place))
                    return false;
                int k = (int)i;
                if (k == x || k == y || k == z)
                    u.positions[3 * v + (size_t)(k == x ? 0 : k == y ? 1 : 2)] = value;
                if (normals && (k == nx || k == ny || k == nz)) {
                    size_t axis = k == nx ? 0 : k == ny ? 1 : 2;
                    u.vertex_normals[3 * v + axis] = (float)value;
                    normal_at[axis] = place;
                }
            }
            if (normals)
                file.normal_places.push_back(normal_at);
        }
        return true;
    }

    /* Reads one property (a list: its length and values); `value` and
       `place` are the scalar's. Faces are read by `faces`. */
    bool property(const Property &p, double &value, Place &place)
    {
        if (p.count_type == 0)
            return this->value(p.type, value, place);
        double n;
        if (!this->value(p.count_type, n, place))
            return false;
        if (!(n >= 0 && n <= 1e9) || n > (double)(file.data.size() - at))
            return fail("bad PLY list length");
        for (double k = 0; k < n; ++k)
            if (!this->value(p.type, value, place))
                return false;
        return true;
    }

    bool faces(const Element &e, Unit &u, size_t vertex_count, std::vector<uint32_t> &corner_vertex)
    {
        file.face_first.push_back(0);
        for (unsigned long long f = 0; f < e.count; ++f) {
            bool seen = false;
            for (const Property &p : e.properties) {
                double value;
                Place place;
                if (p.count_type == 0 || (p.name != "vertex_indices" && p.name != "vertex_index") || seen) {
                    if (!property(p, value, place))
                        return false;
                    continue;
                }
                seen = true;
                double n;
                if (!this->value(p.count_type, n, place))
                    return false;
                if (!(n >= 3 && n <= 65536))
                    return fail("PLY face " + std::to_string(f) + " has " + std::to_string((long long)n) + " corners");
                file.index_type = p.type;
                for (double k = 0; k < n; ++k) {
                    if (!this->value(p.type, value, place))
                        return false;
                    if (!(value >= 0 && value < (double)vertex_count))
                        return fail("PLY face index " + std::to_string((long long)value) + " out of range (" +
                                    std::to_string(vertex_count) + " vertices)");
                    file.corners.push_back(place);
                    corner_vertex.push_back((uint32_t)value);
                }
            }
            if (!seen)
                return fail("PLY face without vertex_indices");
            file.face_first.push_back(file.corners.size());
        }
        u.face_count = e.count;
        return true;
    }

    /* The fewest bytes one instance of the element takes: 1 per value in
       binary (a list at least its length), 2 in ASCII (a digit and a space). */
    size_t bytes_per_instance(const Element &e) const
    {
        size_t n = 0;
        for (const Property &p : e.properties)
            n += file.encoding == ASCII ? 2 : size_of(p.count_type != 0 ? p.count_type : p.type);
        return n > 0 ? n : 1;
    }

    bool read()
    {
        if (!header())
            return false;
        Unit &u = file.units.emplace_back();
        std::vector<uint32_t> corner_vertex;
        bool seen_vertices = false, seen_faces = false;
        for (const Element &e : elements) {
            /* refuse counts the file cannot hold before reserving anything */
            if (e.count > (file.data.size() - at) / bytes_per_instance(e) + 1)
                return fail("PLY element '" + e.name + "' count " + std::to_string(e.count) + " exceeds the file size");
            if (e.name == "vertex" && !seen_vertices) {
                seen_vertices = true;
                if (!vertices(e, u))
                    return false;
            } else if (e.name == "face" && !seen_faces) {
                if (!seen_vertices)
                    return fail("PLY faces before vertices");
                seen_faces = true;
                if (!faces(e, u, u.positions.size() / 3, corner_vertex))
                    return false;
            } else {
                for (unsigned long long i = 0; i < e.count; ++i)
                    for (const Property &p : e.properties) {
                        double value;
                        Place place;
                        if (!property(p, value, place))
                            return false;
                    }
            }
        }
        triangulate(u, corner_vertex);
        collect_normals(u, corner_vertex);
        return !u.indices.empty() || fail("no triangles");
    }

    void triangulate(Unit &u, const std::vector<uint32_t> &corner_vertex)
    {
        for (size_t f = 0; f + 1 < file.face_first.size(); ++f) {
            size_t a = file.face_first[f];
            add_face(u, &corner_vertex[a], file.face_first[f + 1] - a, (uint32_t)f);
        }
    }

    /* Each vertex normal with the faces that use its vertex. */
    void collect_normals(Unit &u, const std::vector<uint32_t> &corner_vertex)
    {
        if (file.normal_places.empty())
            return;
        u.slot_normals = u.vertex_normals;
        for (size_t f = 0; f + 1 < file.face_first.size(); ++f)
            for (size_t c = file.face_first[f]; c < file.face_first[f + 1]; ++c)
                u.slot_faces.push_back({corner_vertex[c], (uint32_t)f});
        find_flat_normals(u);
    }
};

/* Negates a binary float or double in place by its sign bit, unless it
   is zero (-0 would change bytes and nothing else) or NaN; integer normals
   are left alone. */
void negate_binary(std::string &data, const Place &p, int type, Encoding encoding)
{
    size_t n = p.end - p.begin;
    unsigned char b[8];
    if (type < 40)
        return;
    for (size_t k = 0; k < n; ++k)
        b[k] = (unsigned char)data[p.begin + (encoding == LITTLE ? k : n - 1 - k)];
    double value;
    if (n == 4) {
        float f;
        std::memcpy(&f, b, 4);
        value = f;
    } else {
        std::memcpy(&value, b, 8);
    }
    if (value == 0.0 || value != value)
        return;
    data[encoding == LITTLE ? p.end - 1 : p.begin] ^= (char)0x80;
}

} // namespace

bool write_bytes(const std::string &path, const std::string &bytes, std::string &error);

void PlyFile::apply(size_t, const Changes &changes)
{
    for (size_t f = 0; f + 1 < face_first.size(); ++f) {
        if (!changes.face_flipped[f])
            continue;
        changed = true;
        size_t first = face_first[f], n = face_first[f + 1] - first;
        if (encoding == ASCII) {
            std::vector<Span> face;
            for (size_t c = first; c < first + n; ++c)
                face.push_back({corners[c].begin, corners[c].end});
            reverse_tokens(data, face, edits);
            continue;
        }
        std::vector<std::string> values;
        for (size_t c = first; c < first + n; ++c)
            values.push_back(data.substr(corners[c].begin, corners[c].end - corners[c].begin));
        for (size_t i = 0; i < n; ++i)
            data.replace(corners[first + reversed_corner(i, n)].begin, values[i].size(), values[i]);
    }
    for (size_t k = 0; k < units[0].flat_normals.size(); ++k) {
        if (!changes.negate_flat[k])
            continue;
        for (const Place &p : normal_places[units[0].flat_normals[k].slot]) {
            if (encoding == ASCII)
                edits.push_back({p.begin, p.end - p.begin, negated_number(data.substr(p.begin, p.end - p.begin))});
            else
                negate_binary(data, p, normal_type, encoding);
        }
        changed = true;
    }
}

bool PlyFile::write(const std::string &path, const std::string &, std::string &error)
{
    return write_bytes(path, edits.empty() ? data : splice(data, edits), error);
}

std::unique_ptr<MeshFile> load_ply(const std::string &data, std::string &error)
{
    std::unique_ptr<PlyFile> file(new PlyFile);
    file->data = data;
    PlyReader reader(*file, error);
    if (!reader.read())
        return nullptr;
    return file;
}

} // namespace tool
