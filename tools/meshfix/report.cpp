/* meshfix command-line tool: the report as text and as JSON. */
#include "tool.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <sstream>

namespace tool {
namespace {

std::string format(const char *f, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char *f, ...)
{
    char buffer[1024];
    va_list args;
    va_start(args, f);
    std::vsnprintf(buffer, sizeof(buffer), f, args);
    va_end(args);
    return buffer;
}

unsigned long n(size_t x) { return (unsigned long)x; }

std::string count(size_t x, const char *one, const char *many)
{
    return std::to_string(x) + " " + (x == 1 ? one : many);
}

/* The facts in the layout scripts of earlier versions grep for. */
std::string facts_text(const std::string &title, const meshfix_report &r)
{
    const meshfix_mesh_facts &m = r.mesh;
    std::string s = title + "\n";
    s += format("  triangles %lu (degenerate %lu, zero area %lu, duplicate %lu)\n", n(m.triangles),
                n(m.triangles_degenerate), n(m.triangles_zero_area), n(m.triangles_duplicate));
    s += format("  vertices  %lu used (%lu not finite, %lu non-manifold)\n", n(m.vertices_used),
                n(m.vertices_non_finite), n(m.vertices_non_manifold));
    s += format("  edges     %lu: boundary %lu, manifold %lu, non-manifold %lu, inconsistent %lu\n", n(m.edges),
                n(m.edges_boundary), n(m.edges_manifold), n(m.edges_non_manifold), n(m.edges_inconsistent));
    s += format("  patches   %lu (closed %lu, inside-out %lu)\n", n(m.patches), n(m.patches_closed),
                n(m.patches_inside_out));
    s += format("  components %lu (closed %lu, non-orientable %lu), Euler characteristic %ld\n", n(m.components),
                n(m.components_closed), n(m.components_non_orientable), m.euler_characteristic);
    s += format("  area %.6g, signed volume of closed patches %.6g\n", m.area, m.signed_volume);
    return s;
}

std::string evidence_text(const meshfix_report &r)
{
    const meshfix_evidence_counts &e = r.evidence;
    std::string s = format("  decided by volume %lu, parity %lu, visibility %lu, normals %lu; kept %lu", n(e.patches_by_volume),
                           n(e.patches_by_parity), n(e.patches_by_visibility), n(e.patches_by_normals), n(e.patches_kept));
    if (e.rays_cast != 0)
        s += format("; %lu rays", n(e.rays_cast));
    if (e.shells_inward != 0)
        s += format("; %lu shells facing in", n(e.shells_inward));
    if (r.patches_doubtful != 0)
        s += format("; doubtful %lu patches, %lu triangles", n(r.patches_doubtful), n(r.triangles_doubtful));
    return s + "\n";
}

std::string unit_title(const Job &job, size_t i, const std::string &path)
{
    const Unit &u = job.file->units[i];
    return job.file->units.size() > 1 || !u.name.empty() ? path + ": " + u.name : path;
}

/* ---- JSON ---- */

std::string number(double x)
{
    if (!std::isfinite(x))
        return "null";
    return format("%.9g", x);
}

std::string facts_json(const meshfix_report &r)
{
    const meshfix_mesh_facts &m = r.mesh;
    std::string s = "{";
    s += "\"verdict\":" + json_string(meshfix_verdict_string(r.verdict));
    s += format(",\"triangles\":%lu,\"triangles_degenerate\":%lu,\"triangles_zero_area\":%lu,\"triangles_duplicate\":%lu",
                n(m.triangles), n(m.triangles_degenerate), n(m.triangles_zero_area), n(m.triangles_duplicate));
    s += format(",\"vertices_used\":%lu,\"vertices_joined\":%lu,\"vertices_non_finite\":%lu,\"vertices_non_manifold\":%lu",
                n(m.vertices_used), n(m.vertices_joined), n(m.vertices_non_finite), n(m.vertices_non_manifold));
    s += format(",\"edges\":%lu,\"edges_boundary\":%lu,\"edges_manifold\":%lu,\"edges_non_manifold\":%lu,"
                "\"edges_inconsistent\":%lu",
                n(m.edges), n(m.edges_boundary), n(m.edges_manifold), n(m.edges_non_manifold), n(m.edges_inconsistent));
    s += format(",\"patches\":%lu,\"patches_closed\":%lu,\"patches_inside_out\":%lu", n(m.patches),
                n(m.patches_closed), n(m.patches_inside_out));
    s += format(",\"components\":%lu,\"components_closed\":%lu,\"components_non_orientable\":%lu,"
                "\"euler_characteristic\":%ld",
                n(m.components), n(m.components_closed), n(m.components_non_orientable), m.euler_characteristic);
    s += ",\"area\":" + number(m.area) + ",\"signed_volume\":" + number(m.signed_volume) + "}";
    return s;
}

std::string evidence_json(const meshfix_evidence_counts &e)
{
    return format("{\"patches_by_volume\":%lu,\"patches_by_parity\":%lu,\"patches_by_visibility\":%lu,"
                  "\"patches_by_normals\":%lu,\"patches_kept\":%lu,\"shells_inward\":%lu,\"rays_cast\":%lu,"
                  "\"patch_pairs\":%lu,\"patches_merged\":%lu,\"pairs_conflicting\":%lu,\"triangles_against_normals\":%lu}",
                  n(e.patches_by_volume), n(e.patches_by_parity), n(e.patches_by_visibility), n(e.patches_by_normals),
                  n(e.patches_kept), n(e.shells_inward), n(e.rays_cast), n(e.patch_pairs), n(e.patches_merged),
                  n(e.pairs_conflicting), n(e.triangles_against_normals));
}

std::string unit_json(const Unit &u, const UnitResult &r)
{
    std::string s = "{\"name\":" + json_string(u.name);
    s += format(",\"faces\":%lu,\"triangles\":%lu", n(u.face_count), n(u.indices.size() / 3));
    if (r.status != MESHFIX_OK)
        return s + ",\"refused\":" + json_string(meshfix_result_string(r.status)) + "}";
    const meshfix_report &a = r.after;
    double share = a.mesh.area > 0 ? a.area_doubtful / a.mesh.area
                   : a.mesh.triangles != 0 ? (double)a.triangles_doubtful / (double)a.mesh.triangles : 0.0;
    s += ",\"before\":" + facts_json(r.before) + ",\"after\":" + facts_json(a);
    s += format(",\"flipped\":{\"triangles\":%lu,\"patches\":%lu,\"faces\":%lu,\"faces_split\":%lu}",
                n(a.triangles_flipped), n(a.patches_flipped), n(r.faces_flipped), n(r.faces_split));
    s += format(",\"doubtful\":{\"patches\":%lu,\"triangles\":%lu,\"area\":%s,\"share\":%s}", n(a.patches_doubtful),
                n(a.triangles_doubtful), number(a.area_doubtful).c_str(), number(share).c_str());
    s += ",\"evidence\":" + evidence_json(a.evidence);
    s += format(",\"normals\":{\"flat\":%lu,\"disagree\":%lu,\"fixed\":%lu,\"turned_with_faces\":%lu}",
                n(u.flat_normals.size()), n(r.normals_disagree), n(r.normals_fixed), n(r.normals_turned));
    char line[256];
    meshfix_summary(&a, line, sizeof(line));
    return s + ",\"summary\":" + json_string(line) + "}";
}

size_t total(const Job &job, size_t UnitResult::*field)
{
    size_t sum = 0;
    for (const UnitResult &r : job.results)
        sum += r.*field;
    return sum;
}

} // namespace

namespace {

/* The length of the well-formed UTF-8 sequence at text[i] (overlong forms,
   surrogates and code points beyond U+10FFFF are not), or 0. */
size_t utf8_length(const std::string &text, size_t i)
{
    unsigned char c = (unsigned char)text[i];
    size_t n = c < 0x80 ? 1 : (c & 0xE0) == 0xC0 ? 2 : (c & 0xF0) == 0xE0 ? 3 : (c & 0xF8) == 0xF0 ? 4 : 0;
    if (n == 0 || i + n > text.size())
        return 0;
    unsigned long code = n == 1 ? c : c & (0x7Fu >> n);
    for (size_t k = 1; k < n; ++k) {
        unsigned char d = (unsigned char)text[i + k];
        if ((d & 0xC0) != 0x80)
            return 0;
        code = code << 6 | (d & 0x3Fu);
    }
    static const unsigned long least[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (code < least[n] || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF))
        return 0;
    return n;
}

/* A path's exact bytes, percent-escaped: what a script must open when the
   path is not UTF-8 (its JSON string has U+FFFD for those bytes). */
std::string percent_bytes(const std::string &path)
{
    std::string bytes;
    for (unsigned char c : path)
        bytes += c > 0x20 && c < 0x7F && c != '%' ? std::string(1, (char)c) : format("%%%02X", c);
    return bytes;
}

} // namespace

bool valid_utf8(const std::string &text)
{
    for (size_t i = 0, n; i < text.size(); i += n)
        if ((n = utf8_length(text, i)) == 0)
            return false;
    return true;
}

std::string json_string(const std::string &text)
{
    std::string s = "\"";
    for (size_t i = 0, n; i < text.size(); i += n) {
        unsigned char c = (unsigned char)text[i];
        n = utf8_length(text, i);
        if (n == 0) {
            s += "\\ufffd"; /* a byte that is not UTF-8 (a path's raw bytes: see json_path) */
            n = 1;
        } else if (c == '"' || c == '\\') {
            s += '\\', s += (char)c;
        } else if (c < 0x20 || c == 0x7F) {
            s += format("\\u%04x", c);
        } else {
            s.append(text, i, n);
        }
    }
    return s + "\"";
}

/* "name":"path", and "name_bytes":"..." when the path is not UTF-8. */
std::string json_path(const std::string &name, const std::string &path)
{
    std::string s = "\"" + name + "\":" + json_string(path);
    return valid_utf8(path) ? s : s + ",\"" + name + "_bytes\":" + json_string(percent_bytes(path));
}

bool something_wrong(const Job &job)
{
    for (const UnitResult &r : job.results) {
        if (r.status != MESHFIX_OK)
            return true;
        meshfix_verdict v = r.before.verdict;
        if (v == MESHFIX_VERDICT_INCONSISTENT || v == MESHFIX_VERDICT_INSIDE_OUT || v == MESHFIX_VERDICT_NOT_ORIENTABLE ||
            r.after.triangles_flipped != 0 || r.normals_disagree != 0)
            return true;
    }
    return false;
}

std::string summary_line(const Job &job, const Settings &settings)
{
    if (job.exit == 1 || job.exit == 2)
        return job.error;
    char line[256];
    meshfix_report before = combined_report(job.results, false), after = combined_report(job.results, true);
    std::string s;
    if (settings.inspect) {
        meshfix_summary(&before, line, sizeof(line));
        s = line;
        if (after.triangles_flipped != 0)
            s += "; the repair would flip " + count(after.triangles_flipped, "triangle", "triangles") + " in " +
                 count(after.patches_flipped, "patch", "patches");
        else if (after.patches_doubtful != 0)
            s += "; " + count(after.patches_doubtful, "patch", "patches") + " doubtful";
    } else {
        meshfix_summary(&after, line, sizeof(line));
        s = line;
    }
    size_t disagree = total(job, &UnitResult::normals_disagree), fixed = total(job, &UnitResult::normals_fixed);
    size_t turned = total(job, &UnitResult::normals_turned);
    if (turned != 0)
        s += "; " + count(turned, "facet normal", "facet normals") + " turned with the facets";
    if (fixed != 0)
        s += "; negated " + count(fixed, "flat normal", "flat normals") + " that pointed away from their faces";
    else if (disagree != 0)
        s += "; " + count(disagree, "flat normal", "flat normals") +
             " pointing away from their faces (--fix-normals negates them)";
    return s;
}

std::string text_report(const Job &job, const Settings &settings)
{
    std::string s;
    for (size_t i = 0; i < job.results.size(); ++i) {
        const UnitResult &r = job.results[i];
        if (r.status != MESHFIX_OK)
            continue;
        s += facts_text(unit_title(job, i, job.input), r.before);
        if (settings.inspect) {
            s += format("would flip %lu of %lu triangles (policy %s)\n", n(r.after.triangles_flipped),
                        n(r.after.mesh.triangles), settings.policy_name.c_str());
            s += evidence_text(r.after);
            continue;
        }
        s += format("repair (policy %s): flipped %lu of %lu triangles", settings.policy_name.c_str(),
                    n(r.after.triangles_flipped), n(r.after.mesh.triangles));
        if (r.faces_flipped != r.after.triangles_flipped)
            s += format(" (%lu faces)", n(r.faces_flipped));
        s += "\n" + evidence_text(r.after);
        if (r.faces_split != 0)
            s += format("  %lu polygons had triangles turned both ways: each turned as most of it did\n",
                        n(r.faces_split));
        s += facts_text(unit_title(job, i, job.output.empty() ? job.input : job.output), r.after);
    }
    if (job.file)
        for (const std::string &note : job.file->notes())
            s += note + "\n";
    for (const std::string &w : job.written)
        s += "wrote " + w + "\n";
    return s;
}

std::string json_report(const Job &job, const Settings &settings)
{
    std::string s = "{" + json_path("input", job.input);
    s += "," + (job.output.empty() ? std::string("\"output\":null") : json_path("output", job.output));
    s += ",\"format\":" + (job.file ? json_string(job.file->format()) : std::string("null"));
    s += format(",\"exit\":%d", job.exit);
    s += ",\"error\":" + (job.error.empty() ? std::string("null") : json_string(job.error));
    s += ",\"summary\":" + json_string(summary_line(job, settings));
    s += ",\"wrong\":" + std::string(job.exit == 0 || job.exit == 3 ? (something_wrong(job) ? "true" : "false") : "null");
    s += ",\"written\":[";
    bool raw = false;
    for (size_t i = 0; i < job.written.size(); ++i) {
        s += (i ? "," : "") + json_string(job.written[i]);
        raw |= !valid_utf8(job.written[i]);
    }
    s += "]";
    if (raw) {
        s += ",\"written_bytes\":[";
        for (size_t i = 0; i < job.written.size(); ++i)
            s += (i ? "," : "") + json_string(percent_bytes(job.written[i]));
        s += "]";
    }
    s += ",\"meshes\":[";
    for (size_t i = 0; i < job.results.size(); ++i)
        s += (i ? "," : "") + unit_json(job.file->units[i], job.results[i]);
    s += "]";
    if (job.file)
        s += job.file->json_members();
    return s + "}";
}

} // namespace tool
