/* meshfix command-line tool: Wavefront OBJ, lossless.

   Every line is kept as it was except the faces that flip (their corner
   tokens, with their /vt/vn references, written in reverse order, the
   first kept first) and, with --fix-normals, the `vn` lines negated. A
   polygon is one face: it is fan-triangulated for the decision only. */
#include "meshfile.h"
#include "text.h"

#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <unordered_map>

namespace tool {
namespace {

class ObjFile : public MeshFile {
public:
    const char *format() const override { return "obj"; }
    void apply(size_t unit, const Changes &changes) override;
    bool write(const std::string &path, const std::string &target, std::string &error) override;

    std::string data;
    std::vector<Span> corners;          /* every face's corner tokens, face after face */
    std::vector<size_t> face_first;     /* face f's corners: [face_first[f], face_first[f + 1]) */
    std::vector<std::array<Span, 3>> normal_tokens; /* the x y z tokens of each vn line */
    std::vector<Edit> edits;
};

/* A backslash right before a line break joins the next line to its own
   (the OBJ spec's continuation), and one that ends the file joins
   nothing: its length with the break, or 0. */
size_t continuation(const std::string &data, size_t at)
{
    if (data[at] != '\\')
        return 0;
    size_t joined = line_break(data, at + 1);
    return joined != 0 || at + 1 == data.size() ? joined + 1 : 0;
}

/* The tokens of the logical line starting at `at`, up to a '#' comment;
   `at` moves past it and its line break, and `lines` counts the line
   breaks it crossed (LF, CRLF and a lone CR each end a line). */
std::vector<Span> line_tokens(const std::string &data, size_t &at, size_t &lines)
{
    std::vector<Span> tokens;
    size_t n = data.size(), joined;
    while (at < n && line_break(data, at) == 0) {
        char c = data[at];
        if (c == '#') {
            at = line_end(data, at);
            break;
        }
        if ((joined = continuation(data, at)) != 0) {
            at += joined;
            ++lines;
            continue;
        }
        if (is_space(c)) {
            ++at;
            continue;
        }
        size_t begin = at;
        while (at < n && !is_space(data[at]) && data[at] != '#' && continuation(data, at) == 0)
            ++at;
        tokens.push_back({begin, at});
    }
    if (at < n) {
        at += line_break(data, at);
        ++lines;
    }
    return tokens;
}

/* An OBJ index (1-based, or negative: counted back from the last one read)
   as 0-based, or -1 when it is out of range or not a number. */
long long resolve_index(const char *text, const char **end, size_t count)
{
    char *stop;
    errno = 0;
    long long value = std::strtoll(text, &stop, 10);
    *end = stop;
    if (stop == text || errno != 0)
        return -1;
    if (value < 0)
        value += (long long)count + 1;
    return value >= 1 && (unsigned long long)value <= count ? value - 1 : -1;
}

struct ObjReader {
    ObjReader(ObjFile &f, std::string &e) : file(f), error(e) {}
    ObjFile &file;
    std::string &error;
    size_t line = 0;
    std::vector<double> positions;
    std::vector<float> normals;
    /* per corner: the v and vn it names (vn -1 when none) */
    std::vector<long long> corner_v, corner_vn;

    bool numbers(const std::vector<Span> &tokens, size_t count, double *out)
    {
        if (tokens.size() < count + 1)
            return false;
        for (size_t k = 0; k < count; ++k) {
            const Span &s = tokens[k + 1];
            if (!parse_double(file.data.substr(s.begin, s.end - s.begin), out[k]))
                return false;
        }
        return true;
    }

    bool fail(const char *what)
    {
        error = "line " + std::to_string(line) + ": " + what;
        return false;
    }

    bool face(const std::vector<Span> &tokens)
    {
        if (tokens.size() < 4)
            return fail("face with fewer than 3 corners");
        if (file.face_first.size() > 0x7FFFFFFE)
            return fail("too many faces");
        for (size_t k = 1; k < tokens.size(); ++k) {
            std::string token = file.data.substr(tokens[k].begin, tokens[k].end - tokens[k].begin);
            const char *end;
            long long v = resolve_index(token.c_str(), &end, positions.size() / 3);
            if (v < 0 || (*end != 0 && *end != '/'))
                return fail(("face index '" + token + "' out of range or not a number").c_str());
            long long vn = -1;
            const char *slash = std::strchr(token.c_str(), '/');
            if (slash != nullptr && (slash = std::strchr(slash + 1, '/')) != nullptr && slash[1] != 0)
                vn = resolve_index(slash + 1, &end, normals.size() / 3); /* a bad vn is no evidence */
            corner_v.push_back(v);
            corner_vn.push_back(vn);
            file.corners.push_back(tokens[k]);
        }
        file.face_first.push_back(file.corners.size());
        return true;
    }

    bool read()
    {
        size_t at = byte_order_mark(file.data);
        file.face_first.push_back(0);
        size_t lines = 0;
        while (at < file.data.size()) {
            line = lines + 1; /* messages name the line where the logical line starts */
            std::vector<Span> tokens = line_tokens(file.data, at, lines);
            if (tokens.empty())
                continue;
            std::string key = file.data.substr(tokens[0].begin, tokens[0].end - tokens[0].begin);
            double p[3];
            if (key == "v") {
                if (!numbers(tokens, 3, p))
                    return fail("bad vertex");
                if (positions.size() / 3 >= 0xFFFFFFFEu)
                    return fail("too many vertices");
                positions.insert(positions.end(), p, p + 3);
            } else if (key == "vn") {
                if (!numbers(tokens, 3, p))
                    return fail("bad normal");
                normals.insert(normals.end(), {(float)p[0], (float)p[1], (float)p[2]});
                file.normal_tokens.push_back({tokens[1], tokens[2], tokens[3]});
            } else if (key == "f" && !face(tokens)) {
                return false;
            }
        }
        return true;
    }

    /* The library's vertices: one per distinct (v, vn) pair when the file
       has normals (an engine's vertex buffer, split at normal seams; the
       library joins equal positions), else one per v. The file's own v
       stay in the unit for a file written in another format. */
    void build_unit()
    {
        Unit &u = file.units.emplace_back();
        size_t faces = file.face_first.size() - 1;
        std::vector<uint32_t> vertex_of(corner_v.size());
        bool with_normals = false;
        for (long long vn : corner_vn)
            with_normals |= vn >= 0;
        if (!with_normals) {
            u.positions = std::move(positions);
            for (size_t c = 0; c < corner_v.size(); ++c)
                vertex_of[c] = (uint32_t)corner_v[c];
        } else {
            std::unordered_map<unsigned long long, uint32_t> pairs;
            for (size_t c = 0; c < corner_v.size(); ++c) {
                unsigned long long key = (unsigned long long)corner_v[c] << 32 | (unsigned long long)(corner_vn[c] + 1);
                auto found = pairs.emplace(key, (uint32_t)pairs.size());
                if (found.second) {
                    const double *p = &positions[3 * corner_v[c]];
                    u.positions.insert(u.positions.end(), p, p + 3);
                    u.file_vertex.push_back((uint32_t)corner_v[c]);
                    if (corner_vn[c] >= 0)
                        u.vertex_normals.insert(u.vertex_normals.end(), &normals[3 * corner_vn[c]],
                                                &normals[3 * corner_vn[c]] + 3);
                    else
                        u.vertex_normals.insert(u.vertex_normals.end(), {0.0f, 0.0f, 0.0f});
                }
                vertex_of[c] = found.first->second;
            }
            u.file_positions = std::move(positions);
        }
        for (size_t f = 0; f < faces; ++f)
            add_face(u, &vertex_of[file.face_first[f]], file.face_first[f + 1] - file.face_first[f], (uint32_t)f);
        u.face_count = faces;
        collect_normals(u);
    }

    /* Each vn with the faces whose corners name it. */
    void collect_normals(Unit &u)
    {
        u.slot_normals = normals;
        for (size_t f = 0; f + 1 < file.face_first.size(); ++f)
            for (size_t c = file.face_first[f]; c < file.face_first[f + 1]; ++c)
                if (corner_vn[c] >= 0)
                    u.slot_faces.push_back({(uint32_t)corner_vn[c], (uint32_t)f});
        find_flat_normals(u);
    }
};

void ObjFile::apply(size_t, const Changes &changes)
{
    for (size_t f = 0; f + 1 < face_first.size(); ++f)
        if (changes.face_flipped[f]) {
            std::vector<Span> face(corners.begin() + (long)face_first[f], corners.begin() + (long)face_first[f + 1]);
            reverse_tokens(data, face, edits);
            changed = true;
        }
    for (size_t k = 0; k < units[0].flat_normals.size(); ++k)
        if (changes.negate_flat[k]) {
            for (const Span &s : normal_tokens[units[0].flat_normals[k].slot])
                edits.push_back({s.begin, s.end - s.begin, negated_number(data.substr(s.begin, s.end - s.begin))});
            changed = true;
        }
}

} // namespace

bool write_bytes(const std::string &path, const std::string &bytes, std::string &error);

bool ObjFile::write(const std::string &path, const std::string &, std::string &error)
{
    return write_bytes(path, edits.empty() ? data : splice(data, edits), error);
}

std::unique_ptr<MeshFile> load_obj(const std::string &data, std::string &error)
{
    std::unique_ptr<ObjFile> file(new ObjFile);
    file->data = data;
    ObjReader reader(*file, error);
    if (!reader.read())
        return nullptr;
    reader.build_unit();
    if (file->units[0].indices.empty()) {
        error = "no triangles";
        return nullptr;
    }
    return file;
}

} // namespace tool
