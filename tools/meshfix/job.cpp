/* meshfix command-line tool: one input file from start to end (load,
   repair, write all or nothing), as the batch runner and the fuzz target
   call it. */
#include "tool.h"

#include <cerrno>
#include <cstring>
#include <new>

namespace tool {
namespace {

/* The --mark picture's words and up axis, and the picture. */
bool write_mark_picture(const std::string &path, const Job &job, const Settings &s, std::string &error)
{
    size_t triangles = 0;
    for (const Unit &u : job.file->units)
        triangles += u.indices.size() / 3;
    PictureText text;
    text.title = base_name(job.input) + ": " + std::to_string(triangles) + (triangles == 1 ? " triangle" : " triangles") +
                 ", policy " + s.policy_name + (s.check ? ", --check" : s.inspect ? ", --inspect" : "");
    text.summary = summary_line(job, s);
    text.inspect = s.inspect;
    /* --up when given; else glTF's up (+y) for glTF, +z for the rest */
    float up[3] = {0.0f, 0.0f, 1.0f};
    if (s.up_given)
        up[0] = s.up[0], up[1] = s.up[1], up[2] = s.up[2];
    else if (is_gltf_format(job.file->format()))
        up[1] = 1.0f, up[2] = 0.0f;
    return write_picture(path, *job.file, job.results, up, text, error);
}

bool write_outputs(Job &job, const Settings &settings, Ledger &ledger)
{
    OutputSet outputs(ledger, job.input);
    std::string error, in = job.file->format(), out = job.output.empty() ? "" : format_of(job.output);
    bool ok = true;
    if (!job.output.empty()) {
        std::string path = make_parent_directories(job.output) ? outputs.reserve(job.output, error) : "";
        if (path.empty() && error.empty())
            error = "cannot make the directory of '" + job.output + "': " + std::strerror(errno);
        bool same = in == out || (is_gltf_format(in) && is_gltf_format(out));
        ok = !path.empty() && (same ? job.file->write(path, job.output, error)
                                    : write_triangles(path, *job.file, job.results, false, error));
    }
    if (ok && !job.mark.empty()) {
        std::string path = make_parent_directories(job.mark) ? outputs.reserve(job.mark, error) : "";
        if (path.empty() && error.empty())
            error = "cannot make the directory of '" + job.mark + "': " + std::strerror(errno);
        ok = !path.empty() && (mark_format_of(job.mark) == "png" ? write_mark_picture(path, job, settings, error)
                                                                 : write_triangles(path, *job.file, job.results, true, error));
    }
    if (ok)
        ok = outputs.commit(error);
    job.written = outputs.written;
    if (!ok) {
        job.exit = 1;
        job.error = error;
    }
    return ok;
}

/* Load, repair, write. */
void run_job_steps(Job &job, const Settings &s, Ledger &ledger)
{
    job.file = load_file(job.input, job.error);
    if (!job.file) {
        job.error = job.input + ": " + job.error;
        job.exit = 1;
        return;
    }
    for (size_t i = 0; i < job.file->units.size(); ++i) {
        job.results.push_back(repair_unit(job.file->units[i], s));
        const UnitResult &r = job.results.back();
        if (r.status != MESHFIX_OK && job.exit == 0) {
            std::string where = job.file->units[i].name.empty() ? "" : " (" + job.file->units[i].name + ")";
            job.error = job.input + where + ": " + meshfix_result_string(r.status);
            job.exit = 2;
        }
    }
    if (job.exit != 0)
        return;
    for (size_t i = 0; i < job.file->units.size(); ++i) {
        job.file->review(i, job.results[i].changes);
        if (!s.inspect)
            job.file->apply(i, job.results[i].changes);
    }
    if (!write_outputs(job, s, ledger))
        return;
    if (s.check && something_wrong(job))
        job.exit = 3;
}

} // namespace

/* run_job catches running out of memory: that input fails, the batch goes on. */
void run_job(Job &job, const Settings &s, Ledger &ledger)
{
    try {
        run_job_steps(job, s, ledger);
    } catch (const std::bad_alloc &) {
        job.file.reset();
        job.results.clear();
        job.error = job.input + ": out of memory";
        job.exit = 1;
    }
}

} // namespace tool
