/* meshfix command-line tool: one input file from start to end (load,
   repair, write all or nothing), as the batch runner and the fuzz target
   call it. */
#include "tool.h"

#include <cerrno>
#include <cstring>
#include <new>

namespace tool {
namespace {

/* The --mark picture's words and up axis (said in its title), and the picture. */
bool write_mark_picture(const std::string &path, const Job &job, const Settings &s, std::string &error)
{
    size_t triangles = 0;
    for (const Unit &u : job.file->units)
        triangles += u.indices.size() / 3;
    /* --up when given; else the format's convention (picture_up) */
    float up[3] = {s.up[0], s.up[1], s.up[2]};
    std::string why = "--up";
    if (!s.up_given)
        picture_up(*job.file, up, why);
    std::string axis = std::string(up[0] + up[1] + up[2] > 0.0f ? "+" : "-") + (up[0] != 0.0f ? "x" : up[1] != 0.0f ? "y" : "z");
    PictureText text;
    text.title = base_name(job.input) + ": " + std::to_string(triangles) + (triangles == 1 ? " triangle" : " triangles") +
                 ", policy " + s.policy_name + (s.check ? ", --check" : s.inspect ? ", --inspect" : "") + ", up " + axis +
                 " (" + why + ")";
    text.summary = summary_line(job, s);
    text.inspect = s.inspect;
    return write_picture(path, *job.file, job.results, up, text, error);
}

/* An OBJ written into another directory takes its materials along (its
   .mtl files and their maps), as a glTF its buffers and images. */
bool copy_materials(const Job &job, OutputSet &outputs, std::string &error)
{
    std::string text, data;
    if (!read_file(job.input, text, error))
        return false;
    for (const std::string &name : obj_companions(job.input, text)) {
        std::string from = directory_of(job.input) + "/" + name, to = directory_of(job.output) + "/" + name;
        if (same_file(file_id(from), file_id(to)))
            continue; /* beside it already */
        outputs.add_read(from);
        if (!read_file(from, data, error) || !write_output(outputs, to, "", data, error))
            return false;
    }
    return true;
}

/* The output in the input's format (every file it names), or in another
   (positions and faces only). */
bool write_output_file(Job &job, OutputSet &outputs, std::string &error)
{
    std::string in = job.file->format(), out = format_of(job.output);
    if (in == "obj" && out == "obj")
        return copy_materials(job, outputs, error) && job.file->write_outputs(outputs, job.input, job.output, error);
    if (in == out || (is_gltf_format(in) && is_gltf_format(out)))
        return job.file->write_outputs(outputs, job.input, job.output, error);
    std::string path = outputs.reserve(job.output, "", error);
    return !path.empty() && write_triangles(path, *job.file, job.results, false, error);
}

bool write_mark(const Job &job, const Settings &settings, OutputSet &outputs, std::string &error)
{
    std::string path = outputs.reserve(job.mark, "", error);
    if (path.empty())
        return false;
    return mark_format_of(job.mark) == "png" ? write_mark_picture(path, job, settings, error)
                                             : write_triangles(path, *job.file, job.results, true, error);
}

/* Every output planned and written to its temporary, then all moved into
   place, or none. */
bool write_outputs(Job &job, const Settings &settings, OutputSet &outputs)
{
    std::string error;
    bool ok = (job.output.empty() || write_output_file(job, outputs, error)) &&
              (job.mark.empty() || write_mark(job, settings, outputs, error)) && outputs.commit(error);
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
    OutputSet outputs(ledger, job.input);
    outputs.add_read(job.input);
    for (const std::string &f : job.file->files_read())
        outputs.add_read(f);
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
    if (!write_outputs(job, s, outputs))
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
