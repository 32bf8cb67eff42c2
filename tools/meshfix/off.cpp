/* meshfix command-line tool: OFF (and COFF), lossless.

   The file passes through byte for byte except the vertex indices of the
   faces that flip, written in reverse order (the first kept first);
   vertex and face colours, comments and spacing stay as they were. */
#include "meshfile.h"
#include "text.h"

namespace tool {
namespace {

class OffFile : public MeshFile {
public:
    const char *format() const override { return "off"; }
    void apply(size_t unit, const Changes &changes) override;
    bool write(const std::string &path, const std::string &target, std::string &error) override;

    std::string data;
    std::vector<Span> corners;      /* every face's index tokens, face after face */
    std::vector<size_t> face_first; /* face f's tokens: [face_first[f], face_first[f + 1]) */
    std::vector<Edit> edits;
};

/* OFF is words across lines (text.h's scanner): counts, coordinates and
   face indices, with what follows them on their line left alone. */
struct OffReader : WordScanner {
    using WordScanner::WordScanner;

    /* A count within `limit`. */
    bool count(unsigned long long limit, unsigned long long &out, Span *where = nullptr)
    {
        Span s;
        double v;
        if (!word(s) || !parse_double(text(s), v) || !(v >= 0 && v <= (double)limit) || v != (double)(unsigned long long)v)
            return false;
        out = (unsigned long long)v;
        if (where != nullptr)
            *where = s;
        return true;
    }
};

} // namespace

bool write_bytes(const std::string &path, const std::string &bytes, std::string &error);

void OffFile::apply(size_t, const Changes &changes)
{
    for (size_t f = 0; f + 1 < face_first.size(); ++f)
        if (changes.face_flipped[f]) {
            std::vector<Span> face(corners.begin() + (long)face_first[f], corners.begin() + (long)face_first[f + 1]);
            reverse_tokens(data, face, edits);
            changed = true;
        }
}

bool OffFile::write(const std::string &path, const std::string &, std::string &error)
{
    return write_bytes(path, edits.empty() ? data : splice(data, edits), error);
}

std::unique_ptr<MeshFile> load_off(const std::string &data, std::string &error)
{
    std::unique_ptr<OffFile> file(new OffFile);
    file->data = data;
    OffReader r(file->data);
    Span s;
    unsigned long long nv, nf, ne;
    if (!r.word(s) || r.text(s).find("OFF") == std::string::npos) {
        error = "missing OFF header";
        return nullptr;
    }
    if (r.text(s).find("BINARY") != std::string::npos || r.text(s).find("4OFF") != std::string::npos ||
        r.text(s).find("nOFF") != std::string::npos) {
        error = "only text OFF in three dimensions is supported ('" + r.text(s) + "')";
        return nullptr;
    }
    if (!r.count(0xFFFFFFFEull, nv) || !r.count(0x7FFFFFFFull, nf) || !r.count(~0ull, ne)) {
        error = "bad OFF counts";
        return nullptr;
    }
    /* every vertex needs at least 6 bytes of text, every face 8 */
    if (nv > (data.size() - r.at) / 6 || nf > (data.size() - r.at) / 8) {
        error = "OFF counts (" + std::to_string(nv) + " vertices, " + std::to_string(nf) + " faces) exceed the file size";
        return nullptr;
    }
    Unit &u = file->units.emplace_back();
    u.positions.resize(3 * nv);
    for (unsigned long long i = 0; i < nv; ++i) {
        for (int k = 0; k < 3; ++k)
            if (!r.word(s) || !parse_double(r.text(s), u.positions[3 * i + (size_t)k])) {
                error = "bad or missing vertex " + std::to_string(i);
                return nullptr;
            }
        r.skip_line(); /* colours, and NOFF's normals, stay as they are */
    }
    file->face_first.push_back(0);
    std::vector<uint32_t> corner_index;
    for (unsigned long long f = 0; f < nf; ++f) {
        unsigned long long n, index;
        if (!r.count(1u << 20, n) || n < 3) {
            error = "bad or missing face " + std::to_string(f);
            return nullptr;
        }
        for (unsigned long long k = 0; k < n; ++k) {
            if (!r.count(0xFFFFFFFFull, index, &s) || index >= nv) {
                error = "bad index in face " + std::to_string(f) + " (" + std::to_string(nv) + " vertices)";
                return nullptr;
            }
            file->corners.push_back(s);
            corner_index.push_back((uint32_t)index);
        }
        r.skip_line(); /* a face colour stays as it is */
        file->face_first.push_back(file->corners.size());
    }
    for (size_t f = 0; f < nf; ++f) {
        size_t a = file->face_first[f], b = file->face_first[f + 1];
        add_face(u, &corner_index[a], b - a, (uint32_t)f);
    }
    u.face_count = nf;
    if (u.indices.empty()) {
        error = "no triangles";
        return nullptr;
    }
    return file;
}

} // namespace tool
