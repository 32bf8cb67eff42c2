/* meshfix - command-line winding repair for asset pipelines, built on meshfix.h

   Reads OBJ, OFF, STL, PLY and glTF 2.0 (.gltf, .glb), repairs the winding
   and writes the file back as it was except the faces that flipped (and
   the normals --fix-normals negates). `meshfix --help` lists the options;
   README.md ("Command-line tool") has the exit statuses and the --json
   schema. */
#include "tool.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <map>
#include <mutex>
#include <pthread.h>
#include <set>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>

namespace tool {
namespace {

const char *const usage_text =
    "usage: meshfix [OPTIONS] INPUT OUTPUT          repair one file\n"
    "       meshfix [OPTIONS] INPUT... -o DIRECTORY  repair files and directories into DIRECTORY\n"
    "       meshfix --inspect|--check [OPTIONS] INPUT...\n"
    "\n"
    "Formats: .obj .off .stl .ply .gltf .glb. The output keeps everything the repair does not\n"
    "change; another format than the input's (OBJ, OFF, STL, PLY) gets positions and faces only.\n"
    "\n"
    "  --policy P        how each patch turns (default auto); the policies:\n"
    "%POLICIES%"
    "  --up AXIS         x, y, z, -x, -y or -z: the axis of --policy up (default z) and the\n"
    "                    picture's up (default: glTF y; STL, PLY, OFF z; OBJ y unless the mesh\n"
    "                    stands on z = 0 or has its flat base at its lowest z)\n"
    "  --weld TOLERANCE  treat vertices closer than TOLERANCE as one (soups, CAD exports)\n"
    "  --fix-normals     negate flat normals (used by one face) that point away from their face\n"
    "  --ignore-normals  decide by geometry alone: the file's normals are not evidence\n"
    "  --mark FILE.ply   also write the mesh with face and vertex colours (Blender, MeshLab):\n"
    "                    flipped red, doubtful amber, kept pale green by patch;\n"
    "                    with several inputs, a directory for one FILE.ply per input\n"
    "  --mark FILE.png   a picture instead: front, back, top and oblique views before (back\n"
    "                    faces culled) and after (flipped red, doubtful amber, faces seen from\n"
    "                    behind blue, small marks ringed), a legend with counts, the summary\n"
    "  --mark-format F   ply (default) or png: what --mark DIRECTORY holds for each input\n"
    "  --inspect         report only; with --mark, mark what a repair would flip\n"
    "  --check           --inspect, and exit status 3 when something is wrong (CI)\n"
    "  --json            print the report as JSON on stdout instead of text\n"
    "  -o, --output-dir DIRECTORY   where several inputs go (created if missing)\n"
    "  -j, --jobs N      files repaired at once (default: one per core)\n"
    "  --progress        a progress line on stderr (on by default when stderr is a terminal)\n"
    "  -q, --quiet       no report on stdout\n"
    "  -h, --help        this text\n"
    "  --version         the version, and whether this build reads glTF and writes PNG\n"
    "\n"
    "Exit status: 0 clean or repaired; 1 bad arguments, or a file could not be read or written;\n"
    "2 the library refused a mesh; 3 (--check) something is wrong.\n";

/* The command line, checked whole before any file is read. */
struct CommandLine {
    Settings settings;
    std::vector<std::string> inputs;
    std::string output, output_dir, mark;
    std::string mark_format; /* "" (from --mark's extension; ply for a directory), "ply" or "png" */
};

int fail_usage(const std::string &message)
{
    std::fprintf(stderr, "meshfix: %s\n", message.c_str());
    return 1;
}

/* The library's policies a file can use: all but those that call a
   distance function (a file has none). */
bool file_policy(meshfix_policy policy)
{
    const meshfix_policy_facts *facts = meshfix_policy_info(policy);
    return facts != nullptr && !facts->needs_distance;
}

bool parse_policy(const std::string &name, Settings &s)
{
    meshfix_policy policy = meshfix_policy_from_string(name.c_str());
    if (!file_policy(policy))
        return false;
    s.policy = policy;
    s.policy_name = name;
    return true;
}

std::string policy_names()
{
    std::string names;
    for (int p = 0; p < (int)MESHFIX_POLICY_COUNT; ++p)
        if (file_policy((meshfix_policy)p))
            names += (names.empty() ? "" : ", ") + std::string(meshfix_policy_string((meshfix_policy)p));
    return names;
}

/* The help text, each policy with the header's line about it, wrapped to
   fit 92 columns below its name. */
std::string usage()
{
    const int indent = 32, width = 92;
    std::string policies;
    for (int p = 0; p < (int)MESHFIX_POLICY_COUNT; ++p) {
        if (!file_policy((meshfix_policy)p))
            continue;
        const meshfix_policy_facts *facts = meshfix_policy_info((meshfix_policy)p);
        std::string line = std::string(20, ' ') + facts->name;
        line.resize(indent, ' ');
        std::string word, text = std::string(facts->description) + " ";
        size_t column = line.size();
        for (char c : text) {
            if (c != ' ') {
                word += c;
                continue;
            }
            if (column > (size_t)indent && column + 1 + word.size() > (size_t)width) {
                line += "\n" + std::string(indent, ' ');
                column = indent;
            } else if (column > (size_t)indent) {
                line += ' ', ++column;
            }
            line += word, column += word.size();
            word.clear();
        }
        policies += line + "\n";
    }
    std::string text = usage_text;
    text.replace(text.find("%POLICIES%"), 10, policies);
    return text;
}

bool parse_up(const std::string &name, Settings &s)
{
    static const char *const axes[] = {"x", "y", "z", "-x", "-y", "-z", "+x", "+y", "+z"};
    for (int i = 0; i < 9; ++i)
        if (name == axes[i]) {
            int axis = i % 3;
            s.up[0] = s.up[1] = s.up[2] = 0.0f;
            s.up[axis] = i >= 3 && i < 6 ? -1.0f : 1.0f;
            s.up_name = name;
            return true;
        }
    return false;
}

/* Returns -1 when the command line is good, else the exit status (after
   printing help, the version or a one-line error). */
int parse(int argc, char **argv, CommandLine &c)
{
    std::vector<std::string> positional;
    Settings &s = c.settings;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto value = [&](std::string &out) {
            if (i + 1 >= argc)
                return false;
            out = argv[++i];
            return true;
        };
        std::string v;
        if (a == "--help" || a == "-h") {
            std::fputs(usage().c_str(), stdout);
            return 0;
        } else if (a == "--version") {
            std::printf("meshfix %d.%d.%d (meshfix.h %d.%d.%d; %s; %s)\n", MESHFIX_VERSION_MAJOR, MESHFIX_VERSION_MINOR,
                        MESHFIX_VERSION_PATCH, MESHFIX_VERSION_MAJOR, MESHFIX_VERSION_MINOR, MESHFIX_VERSION_PATCH,
                        gltf_supported ? "glTF through tinygltf" : "built without glTF support",
                        png_supported() ? "PNG marks through libpng" : "without PNG support");
            return 0;
        } else if (a == "--policy") {
            if (!value(v) || !parse_policy(v, s))
                return fail_usage("unknown policy '" + v + "' (" + policy_names() + ")");
        } else if (a == "--up") {
            if (!value(v) || !parse_up(v, s))
                return fail_usage("--up takes x, y, z, -x, -y or -z, not '" + v + "'");
            s.up_given = true;
        } else if (a == "--weld") {
            char *end = nullptr;
            if (value(v))
                s.weld_tolerance = std::strtof(v.c_str(), &end);
            /* a number >= 0; the library judges its range (infinity: status 2) */
            if (end == nullptr || *end != 0 || v.empty() || !(s.weld_tolerance >= 0.0f))
                return fail_usage("--weld takes a tolerance >= 0, not '" + v + "'");
        } else if (a == "--mark") {
            if (!value(c.mark))
                return fail_usage("--mark needs a file name");
        } else if (a == "--mark-format") {
            if (!value(c.mark_format) || (c.mark_format != "ply" && c.mark_format != "png"))
                return fail_usage("--mark-format takes ply or png, not '" + c.mark_format + "'");
        } else if (a == "-o" || a == "--output-dir") {
            if (!value(c.output_dir))
                return fail_usage(a + " needs a directory");
        } else if (a == "-j" || a == "--jobs") {
            char *end = nullptr;
            long n = value(v) ? std::strtol(v.c_str(), &end, 10) : 0;
            if (end == nullptr || *end != 0 || v.empty() || n < 1 || n > 256)
                return fail_usage(a + " takes a number of files from 1 to 256, not '" + v + "'");
            s.jobs = (unsigned)n;
        } else if (a == "--fix-normals") {
            s.fix_normals = true;
        } else if (a == "--ignore-normals") {
            s.ignore_normals = true;
        } else if (a == "--inspect") {
            s.inspect = true;
        } else if (a == "--check") {
            s.inspect = s.check = true;
        } else if (a == "--json") {
            s.json = true;
        } else if (a == "--quiet" || a == "-q") {
            s.quiet = true;
        } else if (a == "--progress") {
            s.progress = true;
        } else if (a.size() > 1 && a[0] == '-') {
            return fail_usage("unknown option '" + a + "' (meshfix --help lists them)");
        } else {
            positional.push_back(a);
        }
    }
    if (positional.empty())
        return fail_usage("no input (meshfix --help)");
    if (s.ignore_normals && s.policy == MESHFIX_POLICY_NORMALS)
        return fail_usage("--policy normals decides by the file's normals: not with --ignore-normals");
    if (!s.inspect && c.output_dir.empty()) {
        if (positional.size() != 2)
            return fail_usage(positional.size() == 1 ? "no output: give INPUT OUTPUT, -o DIRECTORY or --inspect"
                                                     : "several inputs go to a directory: -o DIRECTORY");
        c.output = positional[1];
        positional.pop_back();
    }
    c.inputs = positional;
    return -1;
}

/* ---- the jobs ---- */

/* A directory's device and inode: the walk enters each once. */
using DirectoryId = std::pair<unsigned long long, unsigned long long>;

/* Mesh files under a directory, sorted, recursively. Each directory is
   walked once (a symbolic link back up, or two links to one directory,
   add nothing), and a symbolic link that leads out of the directory
   given is not followed: the walk stays inside what was named. */
void collect(const std::string &directory, const std::string &relative, const std::string &root,
             std::set<DirectoryId> &walked, std::vector<std::pair<std::string, std::string>> &out)
{
    struct stat st;
    if (stat(directory.c_str(), &st) != 0 || !walked.insert({(unsigned long long)st.st_dev, (unsigned long long)st.st_ino}).second)
        return;
    DIR *d = opendir(directory.c_str());
    if (d == nullptr)
        return;
    std::vector<std::string> names;
    while (struct dirent *e = readdir(d))
        if (e->d_name[0] != '.')
            names.push_back(e->d_name);
    closedir(d);
    std::sort(names.begin(), names.end());
    for (const std::string &name : names) {
        std::string path = directory + "/" + name;
        struct stat link;
        if (lstat(path.c_str(), &link) == 0 && S_ISLNK(link.st_mode) && !resolves_inside(path, root)) {
            std::fprintf(stderr, "meshfix: '%s' is a symbolic link out of '%s': skipped\n", path.c_str(), root.c_str());
            continue;
        }
        if (is_directory(path))
            collect(path, relative + name + "/", root, walked, out);
        else if (!format_of(name).empty())
            out.push_back({path, relative + name});
    }
}

/* A job per input file (directories walked), named for the output and
   --mark directories when there are several; false after a one-line
   message. */
bool expand_inputs(const CommandLine &c, std::vector<Job> &jobs)
{
    bool batch = !c.output_dir.empty() || c.inputs.size() > 1;
    for (const std::string &input : c.inputs) {
        std::vector<std::pair<std::string, std::string>> files;
        if (is_directory(input)) {
            if (!batch && !c.settings.inspect)
                return fail_usage("'" + input + "' is a directory: repair it into another with -o DIRECTORY") , false;
            std::set<DirectoryId> walked;
            collect(input, "", input, walked, files);
            if (files.empty())
                return fail_usage("'" + input + "' is a directory with no mesh files in it"), false;
        } else {
            if (format_of(input).empty())
                return fail_usage("'" + input + "': unknown format (use .obj, .off, .stl, .ply, .gltf or .glb)"), false;
            files.push_back({input, base_name(input)});
        }
        for (const auto &f : files) {
            Job job;
            job.input = f.first;
            job.name = f.first;
            if (!c.settings.inspect)
                job.output = batch ? c.output_dir + "/" + f.second : c.output;
            if (!c.mark.empty())
                job.mark = batch ? c.mark + "/" + f.second + "." + (c.mark_format.empty() ? "ply" : c.mark_format)
                                 : c.mark;
            jobs.push_back(std::move(job));
        }
    }
    return true;
}

/* Two inputs whose outputs (or --mark files) would be one file, an output
   that is another input, a --mark file that is any input or the job's own
   output, are refused before anything is read: one repair would be lost,
   or read half written, or an input replaced by the mark. (What a glTF
   reads besides itself is checked once it is read: OutputSet.) */
bool check_collisions(const std::vector<Job> &jobs)
{
    FileMap inputs, outputs; /* -> the job's number */
    for (size_t i = 0; i < jobs.size(); ++i)
        if (inputs.find(file_id(jobs[i].input)) == nullptr)
            inputs.add(file_id(jobs[i].input), std::to_string(i));
    for (size_t i = 0; i < jobs.size(); ++i)
        for (const std::string *target : {&jobs[i].output, &jobs[i].mark}) {
            if (target->empty())
                continue;
            bool mark = target == &jobs[i].mark;
            FileId id = file_id(*target);
            const std::string *taken = outputs.find(id);
            size_t other = taken != nullptr ? std::stoul(*taken) : i;
            if (taken == nullptr)
                outputs.add(id, std::to_string(i));
            else
                return fail_usage(other == i
                                      ? "'" + *target + "' is both the output and the --mark file of '" + jobs[i].input +
                                            "': give them different names"
                                      : "'" + jobs[other].input + "' and '" + jobs[i].input +
                                            "' would both be written to '" + *target +
                                            "': repair them in separate runs or into separate directories"),
                       false;
            const std::string *input = inputs.find(id);
            /* a job's own input is its output in place; never its mark */
            bool own = input != nullptr && same_file(file_id(jobs[i].input), id);
            if (input != nullptr && (mark || !own))
                return fail_usage("'" + *target + "', the " + (mark ? "--mark file" : "output") + " for '" + jobs[i].input +
                                  "', is " + (own ? "that input" : "also an input")),
                       false;
        }
    return true;
}

/* Whether every output can be written, before any input is read. */
bool check_outputs(const CommandLine &c)
{
    bool batch = !c.output_dir.empty() || c.inputs.size() > 1;
    std::string error;
    if (!c.output.empty()) {
        std::string in = format_of(c.inputs[0]), out = format_of(c.output);
        if (out.empty())
            return fail_usage("unknown output format '" + c.output + "' (use .obj, .off, .stl, .ply, .gltf or .glb)"), false;
        if (is_gltf_format(out) && !is_gltf_format(in))
            return fail_usage("glTF output needs a glTF input ('" + c.output + "')"), false;
        if (!check_target(c.output, error))
            return fail_usage(error), false;
    }
    if (!c.output_dir.empty() && !is_directory(c.output_dir)) {
        /* made with its parents: the nearest that exists must take them */
        std::string parent = directory_of(c.output_dir);
        while (!is_directory(parent) && parent != directory_of(parent))
            parent = directory_of(parent);
        if (!is_directory(parent) || access(parent.c_str(), W_OK) != 0)
            return fail_usage("cannot make the output directory '" + c.output_dir + "'"), false;
    }
    if (!c.mark_format.empty() && c.mark.empty())
        return fail_usage("--mark-format without --mark"), false;
    if (!c.mark.empty()) {
        if (batch && !is_directory(c.mark))
            return fail_usage("with several inputs, --mark names an existing directory ('" + c.mark + "')"), false;
        std::string mark = batch ? (c.mark_format.empty() ? "ply" : c.mark_format) : mark_format_of(c.mark);
        if (mark.empty())
            return fail_usage("--mark writes PLY (face colours) or PNG (a picture): give a .ply or .png file"), false;
        if (!batch && !c.mark_format.empty() && c.mark_format != mark)
            return fail_usage("--mark-format " + c.mark_format + " but --mark '" + c.mark + "' is ." + mark), false;
        if (mark == "png" && !png_supported())
            return fail_usage(std::string(batch ? "--mark-format png" : "--mark FILE.png") +
                              ": this meshfix was built without PNG support (no libpng)"),
                   false;
        if (!batch && !check_target(c.mark, error))
            return fail_usage(error), false;
    }
    return true;
}

/* The jobs on worker threads; main prints each job's report in input
   order as soon as it and those before it are done. */
class Runner {
public:
    Runner(std::vector<Job> &all, const Settings &settings, Ledger &run)
        : jobs(all), s(settings), ledger(run), done(all.size(), 0) {}

    void run(unsigned threads, bool progress, std::chrono::milliseconds delay)
    {
        std::vector<std::thread> workers;
        for (unsigned t = 0; t < threads; ++t)
            workers.emplace_back([this] { work(); });
        std::thread reporter;
        if (progress)
            reporter = std::thread([this, delay] { report_progress(delay); });
        for (std::thread &w : workers)
            w.join();
        {
            std::lock_guard<std::mutex> lock(mutex);
            finished = true;
        }
        changed.notify_all();
        if (reporter.joinable())
            reporter.join();
    }

    /* Blocks until job i is done. */
    void wait(size_t i)
    {
        std::unique_lock<std::mutex> lock(mutex);
        changed.wait(lock, [&] { return done[i] != 0; });
    }

private:
    void work()
    {
        for (;;) {
            size_t i = next++;
            if (i >= jobs.size())
                return;
            run_job(jobs[i], s, ledger);
            {
                std::lock_guard<std::mutex> lock(mutex);
                done[i] = 1;
                ++count;
            }
            changed.notify_all();
        }
    }

    /* A line on stderr each second once the work has lasted `delay`
       (a second when shown because stderr is a terminal, a quarter of one
       with --progress): files done of all, and what is being worked on. */
    void report_progress(std::chrono::milliseconds delay)
    {
        bool terminal = isatty(2) != 0, shown = false;
        auto start = std::chrono::steady_clock::now() + delay - std::chrono::seconds(1);
        std::unique_lock<std::mutex> lock(mutex);
        while (!finished) {
            changed.wait_for(lock, std::chrono::milliseconds(50));
            if (finished || std::chrono::steady_clock::now() - start < std::chrono::seconds(1))
                continue;
            size_t working = std::min(next.load(), jobs.size());
            std::string current = working > 0 && working - 1 < jobs.size() ? jobs[working - 1].name : "";
            std::fprintf(stderr, "%smeshfix: %zu of %zu files done; working on %s%s", terminal ? "\r\033[K" : "", count,
                         jobs.size(), current.c_str(), terminal ? "" : "\n");
            std::fflush(stderr);
            shown = true;
            start += std::chrono::seconds(1);
        }
        if (shown && terminal)
            std::fprintf(stderr, "\r\033[K");
    }

    std::vector<Job> &jobs;
    const Settings &s;
    Ledger &ledger;
    std::vector<char> done;
    std::atomic<size_t> next{0};
    size_t count = 0;
    bool finished = false;
    std::mutex mutex;
    std::condition_variable changed;
};

/* SIGINT, SIGTERM and SIGHUP go to one thread that waits for them: it
   removes the temporaries (after a commit under way has finished) and ends
   the process by the same signal, so the caller sees it was interrupted.
   Called before any other thread starts, which then inherit the mask. */
void watch_interrupts(Ledger &ledger)
{
    sigset_t signals;
    sigemptyset(&signals);
    for (int signal : {SIGINT, SIGTERM, SIGHUP})
        sigaddset(&signals, signal);
    if (pthread_sigmask(SIG_BLOCK, &signals, nullptr) != 0)
        return;
    std::thread([&ledger, signals] {
        int signal = 0;
        if (sigwait(&signals, &signal) != 0)
            return;
        ledger.stop();
        std::fprintf(stderr, "meshfix: interrupted; temporary files removed\n");
        std::signal(signal, SIG_DFL);
        pthread_sigmask(SIG_UNBLOCK, &signals, nullptr);
        raise(signal);
        _exit(128 + signal);
    }).detach();
}

/* The first status that applies, in the order 1, 2, 3, else 0. */
int overall_exit(const std::vector<Job> &jobs)
{
    for (int status : {1, 2, 3})
        for (const Job &j : jobs)
            if (j.exit == status)
                return status;
    return 0;
}

std::string table_row(const Job &j, const Settings &s)
{
    meshfix_report r = combined_report(j.results, true);
    size_t triangles = 0, disagree = 0;
    for (size_t i = 0; i < j.results.size(); ++i) {
        triangles += j.file->units[i].indices.size() / 3;
        disagree += j.results[i].normals_disagree;
    }
    char row[512];
    std::snprintf(row, sizeof(row), "%-40s %10zu %9zu %8zu %9zu %8zu  %s", j.name.c_str(), triangles,
                  r.triangles_flipped, r.patches_flipped, r.patches_doubtful, disagree,
                  j.exit == 1 || j.exit == 2 ? "failed" : s.inspect ? meshfix_verdict_string(combined_report(j.results, false).verdict)
                                                               : meshfix_verdict_string(r.verdict));
    return row;
}

void print_table(const std::vector<Job> &jobs, const Settings &s)
{
    std::printf("\n%-40s %10s %9s %8s %9s %8s  %s\n", "file", "triangles", s.inspect ? "to flip" : "flipped", "patches",
                "doubtful", "normals", "result");
    size_t clean = 0, repaired = 0, doubtful = 0, failed = 0, wrong = 0;
    for (const Job &j : jobs) {
        std::printf("%s\n", table_row(j, s).c_str());
        if (j.exit == 1 || j.exit == 2) {
            ++failed;
            continue;
        }
        meshfix_report r = combined_report(j.results, true);
        wrong += something_wrong(j);
        if (r.verdict == MESHFIX_VERDICT_DOUBTFUL || r.verdict == MESHFIX_VERDICT_NOT_ORIENTABLE)
            ++doubtful;
        else if (r.triangles_flipped != 0)
            ++repaired;
        else
            ++clean;
    }
    if (s.inspect)
        std::printf("%zu files: %zu with nothing wrong, %zu with something to repair, %zu could not be inspected\n",
                    jobs.size(), jobs.size() - wrong - failed, wrong, failed);
    else
        std::printf("%zu files: %zu clean, %zu repaired, %zu doubtful or not orientable, %zu failed\n", jobs.size(),
                    clean, repaired, doubtful, failed);
}

} // namespace
} // namespace tool

int main(int argc, char **argv)
{
    using namespace tool;
    CommandLine c;
    int status = parse(argc, argv, c);
    if (status >= 0)
        return status;
    std::vector<Job> jobs;
    if (!expand_inputs(c, jobs) || !check_collisions(jobs) || !check_outputs(c))
        return 1;
    const Settings &s = c.settings;
    bool batch = jobs.size() > 1 || !c.output_dir.empty();
    if (!c.output_dir.empty() && !make_parent_directories(c.output_dir + "/."))
        return fail_usage("cannot make the output directory '" + c.output_dir + "': " + std::strerror(errno));
    /* never destroyed: the watcher may use it until the process ends */
    Ledger &ledger = *new Ledger;
    watch_interrupts(ledger);
    unsigned threads = s.jobs != 0 ? s.jobs : std::max(1u, std::thread::hardware_concurrency());
    threads = std::min<unsigned>(threads, (unsigned)jobs.size());
    Runner runner(jobs, s, ledger);
    std::thread pool([&] {
        runner.run(threads, s.progress || (batch && isatty(2)), std::chrono::milliseconds(s.progress ? 250 : 1000));
    });
    if (s.json)
        std::printf("{\"meshfix\":\"%d.%d.%d\",\"mode\":\"%s\",\"policy\":%s,\"files\":[", MESHFIX_VERSION_MAJOR,
                    MESHFIX_VERSION_MINOR, MESHFIX_VERSION_PATCH, s.check ? "check" : s.inspect ? "inspect" : "repair",
                    json_string(s.policy_name).c_str());
    for (size_t i = 0; i < jobs.size(); ++i) {
        runner.wait(i);
        const Job &j = jobs[i];
        if (j.exit == 1 || j.exit == 2)
            std::fprintf(stderr, "meshfix: %s\n", j.error.c_str());
        if (s.json)
            std::printf("%s%s", i ? "," : "", json_report(j, s).c_str());
        else if (!s.quiet && batch)
            std::printf("%s: %s\n", j.name.c_str(), summary_line(j, s).c_str());
        else if (!s.quiet && j.exit != 1 && j.exit != 2)
            std::printf("%s%s\n", text_report(j, s).c_str(), summary_line(j, s).c_str());
        std::fflush(stdout);
    }
    pool.join();
    status = overall_exit(jobs);
    if (s.json)
        std::printf("],\"exit\":%d}\n", status);
    else if (!s.quiet && batch)
        print_table(jobs, s);
    /* a report that could not be written (a full disk, a closed pipe) is
       a failure: the caller would read a short or empty report as the
       answer */
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
        std::fprintf(stderr, "meshfix: cannot write the report to stdout: %s\n", std::strerror(errno != 0 ? errno : EIO));
        return 1;
    }
    return status;
}
