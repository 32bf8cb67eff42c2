/* meshfix command-line tool: settings, per-unit results, files and reports
   (the parts main.cpp puts together). */
#ifndef MESHFIX_TOOL_TOOL_H
#define MESHFIX_TOOL_TOOL_H

#include "meshfile.h"

#include <map>
#include <mutex>
#include <set>
#include <string>
#include <vector>

namespace tool {

/* What the command line asked for, checked before any work. */
struct Settings {
    meshfix_policy policy = MESHFIX_POLICY_AUTO;
    std::string policy_name = "auto";
    float up[3] = {0.0f, 0.0f, 1.0f};
    std::string up_name = "z";
    bool up_given = false; /* --up on the command line (the --mark picture's up axis) */
    float weld_tolerance = -1.0f; /* < 0: topology from bit-identical positions */
    bool fix_normals = false;
    bool ignore_normals = false; /* the file's normals are not passed as evidence */
    bool inspect = false; /* --inspect or --check: nothing written but --mark */
    bool check = false;   /* --check: exit status 3 when something is wrong */
    bool json = false;
    bool quiet = false;
    bool progress = false;
    unsigned jobs = 0; /* 0: one per core */
};

/* What the repair found and decided for one unit. */
struct UnitResult {
    meshfix_result status = MESHFIX_OK; /* not OK: the library refused the unit */
    meshfix_report before{}, after{};   /* inspect, and orient (what it returns, or would) */
    std::vector<unsigned char> triangle_flipped;
    std::vector<unsigned int> patch_ids;
    std::vector<float> patch_confidence;
    Changes changes;
    size_t faces_flipped = 0;
    size_t faces_split = 0;       /* polygons whose triangles the library turned different ways */
    size_t normals_disagree = 0;  /* flat normals against their face as written */
    size_t normals_fixed = 0;
    size_t normals_turned = 0;    /* STL: facet normals negated with their flipped facet */
};

/* Runs meshfix_inspect and meshfix_orient (report only: the format
   rewrites the faces) on a unit and decides faces and normals. */
UnitResult repair_unit(const Unit &unit, const Settings &settings);

/* Whether a patch's verdict is doubtful (the library's rule). */
bool doubtful(const UnitResult &r, unsigned int patch);

/* One line of words for several units: their reports summed. */
meshfix_report combined_report(const std::vector<UnitResult> &results, bool after);

/* ---- files (files.cpp) ---- */

/* Reads a regular file whole; a directory, FIFO or device is refused
   before anything is read from it. */
bool read_file(const std::string &path, std::string &data, std::string &error);
/* Writes the file whole and syncs it; false and an error on any failure
   (a full disk included). */
bool write_bytes(const std::string &path, const std::string &bytes, std::string &error);
/* mkdir -p of the directories a file goes into; false when one cannot be made. */
bool make_parent_directories(const std::string &file);
/* Whether `target` can be written: its directory exists and it is not a
   directory, FIFO or read-only file. */
bool check_target(const std::string &target, std::string &error);
bool is_directory(const std::string &path);
/* What a --mark file is by its extension: "ply", "png" or "". */
std::string mark_format_of(const std::string &path);
/* "gltf" or "glb" (format_of's names): written from each other */
bool is_gltf_format(const std::string &format);
std::string directory_of(const std::string &path);
std::string base_name(const std::string &path);
/* The file a path names, as one string for comparisons: resolved by the
   file system (symbolic links, "..") as far as the path exists, the rest
   as text. */
std::string path_identity(const std::string &path);
/* Loads any supported file (the format from the extension). */
std::unique_ptr<MeshFile> load_file(const std::string &path, std::string &error);

/* What one run of the tool writes: the temporary directories in use
   (removed when the run is interrupted) and every file moved into place,
   so that two inputs of a batch never write the same file. */
class Ledger {
public:
    /* false once the run is stopping: the caller makes no temporary */
    bool add_temporary(const std::string &directory);
    void remove_temporary(const std::string &directory);
    /* Removes every temporary; from now on nothing is reserved or committed. */
    void stop();

private:
    friend class OutputSet;
    /* Claims the files for `owner` (call with `mutex` held); false and an
       error naming the first file another owner wrote. */
    bool claim(const std::vector<std::string> &files, const std::string &owner, std::string &error);
    std::mutex mutex;
    bool stopped = false;
    std::set<std::string> temporaries;
    std::map<std::string, std::string> owners; /* resolved path -> the input it was written for */
};

/* Outputs written all or nothing: each target is written into a new
   temporary directory beside it, and only when every output of the set
   was written are the files moved into place. */
class OutputSet {
public:
    OutputSet(Ledger &run, const std::string &input) : ledger(run), owner(input) {}
    ~OutputSet() { discard(); }
    /* The path to write the target's contents to (inside the temporary
       directory, under the target's own name); "" and an error when the
       temporary cannot be made. */
    std::string reserve(const std::string &target, std::string &error);
    bool commit(std::string &error);
    void discard();
    std::vector<std::string> written; /* after commit: every file moved into place */

private:
    struct Item {
        std::string target, directory;
    };
    Ledger &ledger;
    std::string owner;
    std::vector<Item> items;
};

/* Writes every unit's triangles, as repaired, in the format `path` names
   (OBJ, OFF, STL or PLY; polygons as fans). colours (PLY, --mark): flipped
   faces red, doubtful patches amber, the rest tinted by patch. */
bool write_triangles(const std::string &path, const MeshFile &file, const std::vector<UnitResult> &results,
                     bool colours, std::string &error);

/* What the --mark file (PLY or picture) shows for a triangle. */
enum class Mark { kept, flipped, doubtful, none /* in no patch: degenerate, or its unit refused */ };
Mark mark_of(const Unit &unit, const UnitResult &result, size_t triangle);
/* Whether triangle t is written turned over (its face flipped). */
bool written_flipped(const Unit &unit, const UnitResult &result, size_t triangle);
/* The PLY's colour of a kept triangle's patch (a hash of its number). */
void patch_tint(unsigned int patch, unsigned char rgb[3]);

/* ---- the --mark picture (render.cpp) ---- */

/* false when built with MESHFIX_TOOL_NO_PNG (no libpng) */
bool png_supported();

/* What the picture says beside the views. */
struct PictureText {
    std::string title;   /* the first line (the input, its triangles, the policy) */
    std::string summary; /* the last line, as the report prints it */
    bool inspect = false; /* --inspect: the legend says "would be flipped" */
};

/* Draws every unit as repaired (faces as written) in four views, front,
   back, top and oblique, with `up` up (a unit axis), flat-shaded with a
   z-buffer: flipped faces red, doubtful patches amber, faces seen from
   behind blue (striped with red or amber when marked too), the rest grey
   tinted by patch; a legend and the text. Writes it to `path` as PNG
   (deterministic: the same input gives the same bytes). */
bool write_picture(const std::string &path, const MeshFile &file, const std::vector<UnitResult> &results,
                   const float up[3], const PictureText &text, std::string &error);

/* One input file: what to do with it and, once done, what happened. */
struct Job {
    std::string input, output, mark; /* output "" with --inspect; mark "" without --mark */
    std::string name;                /* as the summary table shows it */
    int exit = 0;                    /* 0, 1 (read or write failed), 2 (refused), 3 (--check: wrong) */
    std::string error;               /* one line, when exit is 1 or 2 */
    std::unique_ptr<MeshFile> file;
    std::vector<UnitResult> results;
    std::vector<std::string> written;
};

/* Runs one job: load, repair, write all or nothing. */
void run_job(Job &job, const Settings &settings, Ledger &ledger);

/* ---- reports (report.cpp) ---- */

/* The facts before and after, mesh by mesh, as a person reads them. */
std::string text_report(const Job &job, const Settings &settings);
/* The last line in plain words ("fixed 72 triangles in 3 patches", ...). */
std::string summary_line(const Job &job, const Settings &settings);
/* Whether --check finds something wrong. */
bool something_wrong(const Job &job);
/* The job as one JSON object (README: "The --json report"). */
std::string json_report(const Job &job, const Settings &settings);
/* Escapes a string for JSON, quotes included; bytes that are not UTF-8
   become U+FFFD, so the document is valid for a strict parser. */
std::string json_string(const std::string &text);
bool valid_utf8(const std::string &text);
/* "name":"path" and, when the path is not UTF-8, "name_bytes": its bytes
   percent-escaped. */
std::string json_path(const std::string &name, const std::string &path);

} // namespace tool

#endif
