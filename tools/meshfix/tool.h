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
    meshfix_report before{}, after{};   /* the unit as given (as inspect reports it), and as orient returns it (or would) */
    std::vector<unsigned char> triangle_flipped;
    std::vector<unsigned int> patch_ids;
    std::vector<float> patch_confidence;
    float doubtful_below = 0.5f;  /* the library's bar for this unit's options (meshfix_doubtful_below) */
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
/* mkdir -p of the directories a file goes into; false when one cannot be
   made. Those it made are added to `made` (parents first), when given. */
bool make_parent_directories(const std::string &file, std::vector<std::string> *made = nullptr);
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
/* Whether `path`, its symbolic links followed (its own, or a directory's
   on the way), is inside `directory` (resolved too): false when either
   does not exist. */
bool resolves_inside(const std::string &path, const std::string &directory);
/* The files an OBJ names beside it: its mtllib files and the maps they
   name, as paths relative to its directory, each one that stays inside it
   (no "..", no link out) and exists. */
std::vector<std::string> obj_companions(const std::string &obj_path, const std::string &obj_text);
/* Loads any supported file (the format from the extension). */
std::unique_ptr<MeshFile> load_file(const std::string &path, std::string &error);

/* What a file is, for telling whether a file written is one read: its
   resolved path, and where it exists its device and inode (a hard link or
   a symbolic link to it is the same file). */
struct FileId {
    std::string path;
    bool exists = false;
    unsigned long long device = 0, inode = 0;
};
FileId file_id(const std::string &path);
bool same_file(const FileId &a, const FileId &b);

/* Files by FileId, each with a name (the input it was read or written
   for, or the path it was given as). */
class FileMap {
public:
    void add(const FileId &id, const std::string &name);
    /* the name of the file `id` is, or nullptr */
    const std::string *find(const FileId &id) const;

private:
    std::map<std::string, std::string> by_path;
    std::map<std::pair<unsigned long long, unsigned long long>, std::string> by_inode;
};

/* What one run of the tool reads and writes: the temporary directories in
   use (removed when the run is interrupted), every file moved into place
   and every file read, so that no input of a batch writes a file that
   another writes or reads. */
class Ledger {
public:
    /* false once the run is stopping: the caller makes no temporary */
    bool add_temporary(const std::string &directory);
    void remove_temporary(const std::string &directory);
    /* Removes every temporary; from now on nothing is committed. */
    void stop();

private:
    friend class OutputSet;
    std::mutex mutex;
    bool stopped = false;
    std::set<std::string> temporaries;
    FileMap written, read; /* -> the input they were written or read for */
};

/* Every file one input writes (its output, a glTF's buffers and images, an
   OBJ's materials, the --mark file), named before anything is written and
   checked against every file the input's job read and every other file it
   writes, in this job and the run; each written to a temporary beside its
   target, and all moved into place together or none (a move that fails
   puts back the files already replaced). */
class OutputSet {
public:
    OutputSet(Ledger &run, const std::string &input) : ledger(run), owner(input) {}
    ~OutputSet() { discard(); }
    /* A file the job read: no output may be it, but the one that replaces
       it (in place). */
    void add_read(const std::string &path);
    bool was_read(const std::string &path) const { return reads.find(file_id(path)) != nullptr; }
    /* Whether a file is already one of the outputs. */
    bool is_planned(const std::string &path) const { return planned.find(file_id(path)) != nullptr; }
    /* The path to write the target's contents to (a temporary under the
       target's own name), after checking the target: a regular file or
       none, writable, not a file read (but `replaces`, the file read it is
       the new version of, "" for none) nor another output. "" and an
       error when refused or when the temporary cannot be made. */
    std::string reserve(const std::string &target, const std::string &replaces, std::string &error);
    /* Moves every output into place, or none. */
    bool commit(std::string &error);
    void discard();
    std::vector<std::string> written; /* after commit: every file moved into place */

private:
    struct Item {
        std::string target;    /* as named */
        std::string real;      /* where it goes: an existing symbolic link resolved */
        FileId id;
        std::string temporary; /* the temporary directory it is written in */
        std::string backup;    /* the file it replaced, kept until the commit ends */
        bool existed = false, moved = false;
    };
    std::string temporary_directory(const std::string &directory, std::string &error);
    bool check_run(std::string &error) const;
    bool move(Item &item, std::string &error);
    void restore(std::string &error);
    Ledger &ledger;
    std::string owner;
    std::vector<Item> items;
    std::map<std::string, std::string> directories; /* target directory -> its temporary */
    std::vector<std::string> made;                  /* directories made for the outputs */
    FileMap reads, planned;
    std::vector<std::pair<FileId, std::string>> read_list; /* what reads holds, for the ledger */
};

/* Writes `bytes` as an output of the set (reserve, then write_bytes). */
bool write_output(OutputSet &outputs, const std::string &target, const std::string &replaces, const std::string &bytes,
                  std::string &error);

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
/* The PLY's colour of a kept triangle's patch (a hash of its number): a
   pale green of some hue, never red, amber or blue. */
void patch_tint(unsigned int patch, unsigned char rgb[3]);

/* ---- the --mark picture (render.cpp) ---- */

/* false when built with MESHFIX_TOOL_NO_PNG (no libpng) */
bool png_supported();

/* What the picture says beside the views. */
struct PictureText {
    std::string title;   /* the first line (the input, its triangles, the policy) */
    std::string summary; /* the last line, as the report prints it */
    bool inspect = false; /* --inspect: the legend says "would flip" */
};

/* The picture's up axis when --up is not given, by the format's
   convention: glTF +y; STL, PLY and OFF +z; OBJ +y (what Blender, Maya,
   3ds Max and most exporters write) unless the mesh itself says +z: it
   stands on z = 0 (its lowest z within 0.5% of its size from 0, its lowest
   y more than 5% away), or its flat base is at its lowest z (faces within
   1% of its size of the lowest z and within 25 degrees of level: 1% of
   its area or more, and 3 times what lies so at its lowest y). `why` is
   the reason in a few words ("OBJ standing on z = 0"). */
void picture_up(const MeshFile &file, float up[3], std::string &why);

/* Draws every unit twice, in four views each, front, back, top and
   oblique, with `up` up (a unit axis), flat-shaded with a z-buffer:
   "before", the faces as read with those seen from behind culled, as a
   renderer draws them; "after", the faces as written, flipped ones red,
   doubtful patches amber, faces seen from behind blue (striped with red or
   amber when marked too), the rest grey tinted by patch; marked faces too
   small to see ringed; a legend with counts and the text. Writes it to
   `path` as PNG (deterministic: the same input gives the same bytes). */
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
