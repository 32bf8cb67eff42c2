// Part 3 of `make bench`: quality, by the evaluation programs of tests/eval
// (built by the Makefile's bench rule, or by hand:
//   cc -std=c99 -O2 -I. -o build/stl_truth tests/eval/stl_truth.c -lm
//   cc -std=c99 -O2 -I. -o build/scenes_eval tests/eval/scenes_eval.c -lm).
//
// (a) STL stored-normal truth over the corpus of tests/corpus/fetch.sh
//     (build/corpus): stl_truth under the default policy without and with
//     --normals, and under seed and majority; its "total:" line gives, in %
//     of clear triangles, agreement as shipped, after repair, the damaged
//     count, and after reversing a random half and repairing.
// (b) the generated scenes (tests/scenes.h): scenes_eval under the default
//     policy, its totals line, how many correct inputs came back unchanged,
//     and the rows summed per corruption (from --csv).
// Both programs are run with popen from the repository root.
#include "common.h"

#include <cstdio>
#include <algorithm>
#include <map>
#include <sys/stat.h>
#include <sys/wait.h>

namespace bench {
namespace {

static bool exists(const std::string &path)
{
    struct stat st;
    return stat(path.c_str(), &st) == 0;
}

// Where the programs' standard error goes; its last line is shown when one fails.
static std::string errors_path;

static std::string last_error_line()
{
    std::string text, last;
    if (FILE *f = std::fopen(errors_path.c_str(), "r")) {
        char buffer[1024];
        while (std::fgets(buffer, sizeof(buffer), f))
            if (buffer[0] != '\n')
                last = buffer;
        std::fclose(f);
    }
    while (!last.empty() && (last.back() == '\n' || last.back() == '\r'))
        last.pop_back();
    return last;
}

// Runs a command (its standard error to errors_path) and returns its
// standard output; *status gets its exit status.
static std::string run(const std::string &command_line, int *status)
{
    std::string out, command = command_line + " 2>'" + errors_path + "'";
    FILE *p = popen(command.c_str(), "r");
    if (!p) {
        *status = -1;
        return out;
    }
    char buffer[4096];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof(buffer), p)) > 0)
        out.append(buffer, n);
    int s = pclose(p);
    *status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
    return out;
}

static std::vector<std::string> lines_of(const std::string &text)
{
    std::vector<std::string> lines;
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos)
            end = text.size();
        lines.push_back(text.substr(start, end - start));
        start = end + 1;
    }
    return lines;
}

// The numbers of a stl_truth "total..." line.
struct TruthTotals {
    bool found = false;
    unsigned long files = 0, triangles = 0, clear = 0, damaged = 0;
    double ship = 0, best = 0, fix = 0, half = 0, ms = 0;
};

static TruthTotals parse_truth(const std::string &line)
{
    TruthTotals t;
    size_t colon = line.find(": ");
    if (colon == std::string::npos)
        return t;
    const char *p = line.c_str() + colon + 2;
    if (std::sscanf(p, "%lu files, %lu triangles, %lu clear", &t.files, &t.triangles, &t.clear) != 3)
        return t;
    const char *q = std::strstr(p, "ship ");
    if (!q || std::sscanf(q, "ship %lf%%, best %lf%%, fix %lf%%, damaged %lu, half %lf%%, orient %lf ms", &t.ship,
                          &t.best, &t.fix, &t.damaged, &t.half, &t.ms) != 6)
        return t;
    t.found = true;
    return t;
}

// The package directories of one half of the corpus, quoted for a shell.
static std::string corpus_half(const char *half, const std::string &corpus)
{
    int code = 0;
    std::string dirs;
    for (const std::string &d : lines_of(run(std::string("bash tests/corpus/split.sh ") + half + " '" + corpus + "'", &code)))
        if (!d.empty())
            dirs += " '" + d + "'";
    return dirs;
}

static int stl_table(const Settings &s, std::vector<std::string> *summary)
{
    std::string program = s.build_dir + "/stl_truth";
    std::printf("\n### 3a. STL stored-normal truth over the corpus (%s): agreement with the normals the exporters "
                "stored, in %% of clear triangles (higher is better; \"damaged\" = right as shipped, wrong after)\n\n",
                s.corpus.c_str());
    if (!exists(s.corpus) || !exists(s.corpus + "/manifest.tsv")) {
        std::printf("(no corpus in %s: build it with `bash tests/corpus/fetch.sh` (Debian packages via apt-get "
                    "download; run `apt-get update` first), then `make bench` again. Skipped.)\n",
                    s.corpus.c_str());
        summary->push_back("quality (a): skipped, no corpus (bash tests/corpus/fetch.sh)");
        return 0;
    }
    if (!exists(program)) {
        std::printf("(%s missing: `make %s` or `cc -std=c99 -O2 -I. -o %s tests/eval/stl_truth.c -lm`. Skipped.)\n",
                    program.c_str(), program.c_str(), program.c_str());
        return 0;
    }
    // the halves of the split fixed before tuning (tests/corpus/split.sh):
    // the held-out half is the one the numbers are reported on
    std::string tune = corpus_half("tune", s.corpus), heldout = corpus_half("heldout", s.corpus);
    std::string all_files = "'" + s.corpus + "'";
    struct Run {
        const char *label, *arguments;
        const std::string *files;
    } runs[] = {{"default, held-out half", "--policy default", &heldout},
                {"default + stored normals, held-out half", "--policy default --normals", &heldout},
                {"default, tune half", "--policy default", &tune},
                {"default + stored normals, tune half", "--policy default --normals", &tune},
                {"default, all", "--policy default", &all_files},
                {"default + stored normals, all", "--policy default --normals", &all_files},
                {"seed (flood fill), all", "--policy seed", &all_files},
                {"majority, all", "--policy majority", &all_files}};
    std::printf("| policy | files | clear triangles | as shipped | best by whole patches | after repair | damaged | "
                "half reversed, repaired | after repair, truth-ok files | orient ms (all files) |\n"
                "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    int status = 0;
    for (const Run &r : runs) {
        int code = 0;
        std::string command = program + " " + r.arguments + " " + *r.files;
        std::string out = run(command, &code);
        TruthTotals all, ok;
        for (const std::string &line : lines_of(out)) {
            if (line.compare(0, 6, "total:") == 0)
                all = parse_truth(line);
            else if (line.compare(0, 16, "total, truth ok:") == 0)
                ok = parse_truth(line);
        }
        if (!all.found) {
            std::printf("| %s | (no total line; exit %d: %s) |\n", r.label, code, last_error_line().c_str());
            summary->push_back(std::string("quality (a) STL truth, ") + r.label + ": FAILED, " + last_error_line());
            status = 1;
            continue;
        }
        std::printf("| %s | %lu | %lu | %.2f%% | %.2f%% | %.2f%% | %lu | %.2f%% | %.2f%% | %.0f |%s\n", r.label,
                    all.files, all.clear, all.ship, all.best, all.fix, all.damaged, all.half, ok.found ? ok.fix : 0.0,
                    all.ms, code == 2 ? " (a meshfix call failed on some file)" : "");
        std::fflush(stdout);
        char line[256];
        std::snprintf(line, sizeof(line),
                      "quality (a) STL truth, %s: as shipped %.2f%%, after repair %.2f%% (damaged %lu), half reversed "
                      "then repaired %.2f%%",
                      r.label, all.ship, all.fix, all.damaged, all.half);
        summary->push_back(line);
    }
    // where the default policy damages most: its CSV, one row per file
    // (1 file, 5 clear, 12 damaged, 15 patches, 18 inconsistent edges as shipped)
    {
        int code = 0;
        std::string csv = run(program + " --csv --policy default '" + s.corpus + "'", &code);
        std::vector<std::vector<std::string>> damaged;
        for (const std::string &line : lines_of(csv)) {
            std::vector<std::string> f;
            size_t start = 0;
            for (;;) {
                size_t comma = line.find(',', start);
                f.push_back(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
                if (comma == std::string::npos)
                    break;
                start = comma + 1;
            }
            if (f.size() >= 18 && f[0] != "file" && std::strtoul(f[11].c_str(), nullptr, 10) > 0)
                damaged.push_back(f);
        }
        std::sort(damaged.begin(), damaged.end(), [](const std::vector<std::string> &a, const std::vector<std::string> &b) {
            return std::strtoul(a[11].c_str(), nullptr, 10) > std::strtoul(b[11].c_str(), nullptr, 10);
        });
        std::printf("\nFiles the default policy damages most (%zu files damage any):\n\n| damaged | clear | patches | "
                    "inconsistent edges as shipped | file |\n|---:|---:|---:|---:|---|\n",
                    damaged.size());
        for (size_t i = 0; i < damaged.size() && i < 6; ++i)
            std::printf("| %s | %s | %s | %s | %s |\n", damaged[i][11].c_str(), damaged[i][4].c_str(),
                        damaged[i][14].c_str(), damaged[i][17].c_str(), damaged[i][0].c_str());
    }
    std::printf("\nCommand: %s [--normals] [--csv] --policy NAME %s (the \"total:\" and \"total, truth ok:\" lines)\n",
                program.c_str(), s.corpus.c_str());
    return status;
}

static std::vector<std::string> split_csv(const std::string &line)
{
    std::vector<std::string> fields;
    size_t start = 0;
    for (;;) {
        size_t comma = line.find(',', start);
        fields.push_back(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (comma == std::string::npos)
            break;
        start = comma + 1;
    }
    return fields;
}

static int scenes_table(const Settings &s, std::vector<std::string> *summary)
{
    std::string program = s.build_dir + "/scenes_eval";
    const char *size = s.quick ? "small" : "large";
    std::printf("\n### 3b. Generated scenes with known truth (tests/scenes.h), %s size, default policy: triangles "
                "facing the intended way before and after the repair\n\n",
                size);
    if (!exists(program)) {
        std::printf("(%s missing: `make %s` or `cc -std=c99 -O2 -I. -o %s tests/eval/scenes_eval.c -lm`. Skipped.)\n",
                    program.c_str(), program.c_str(), program.c_str());
        return 0;
    }
    int code = 0;
    std::string text = run(program + " --policy default --size " + size, &code);
    std::string totals, unchanged, header;
    for (const std::string &line : lines_of(text)) {
        if (line.compare(0, 6, "scene ") == 0)
            header = line;
        if (line.compare(0, 6, "total ") == 0)
            totals = line;
        if (line.find("correct inputs returned unchanged") != std::string::npos)
            unchanged = line;
    }
    std::printf("```\n%s\n%s\n%s\n```\n\n", header.c_str(), totals.c_str(), unchanged.c_str());
    if (totals.empty() || code != 0) {
        std::printf("(scenes_eval exit %d: %s)\n", code, last_error_line().c_str());
        return 1;
    }
    // per corruption, from the CSV
    std::string csv = run(program + " --policy default --csv --size " + size, &code);
    struct Sum {
        unsigned long rows = 0, triangles = 0, scored = 0, before = 0, after = 0, damaged = 0, flips = 0, undecided = 0;
        double ms = 0;
    };
    std::vector<std::string> order;
    std::map<std::string, Sum> sums;
    for (const std::string &line : lines_of(csv)) {
        std::vector<std::string> f = split_csv(line);
        if (f.size() < 16)
            continue;
        if (f[0] == "scene")
            continue;
        // scene,size,corruption,policy,triangles,scored,right_before,right_after,area_scored,
        // area_right_after,damaged,flips,changed_otherwise,undecided,undecided_up_after,ms
        if (!sums.count(f[2]))
            order.push_back(f[2]);
        Sum &x = sums[f[2]];
        x.rows++;
        x.triangles += std::strtoul(f[4].c_str(), nullptr, 10);
        x.scored += std::strtoul(f[5].c_str(), nullptr, 10);
        x.before += std::strtoul(f[6].c_str(), nullptr, 10);
        x.after += std::strtoul(f[7].c_str(), nullptr, 10);
        x.damaged += std::strtoul(f[10].c_str(), nullptr, 10);
        x.flips += std::strtoul(f[11].c_str(), nullptr, 10);
        x.undecided += std::strtoul(f[13].c_str(), nullptr, 10);
        x.ms += std::strtod(f[15].c_str(), nullptr);
    }
    std::printf("| corruption | scenes | triangles | scored | right before | right after | damaged | flips | "
                "undecided | ms per 100k |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const std::string &c : order) {
        const Sum &x = sums[c];
        std::printf("| %s | %lu | %lu | %lu | %.2f%% | %.2f%% | %lu | %lu | %lu | %.1f |\n", c.c_str(), x.rows,
                    x.triangles, x.scored, 100.0 * x.before / std::max(1ul, x.scored),
                    100.0 * x.after / std::max(1ul, x.scored), x.damaged, x.flips, x.undecided,
                    x.ms * 1e5 / std::max(1ul, x.triangles));
    }
    std::printf("\nCommand: %s --policy default --size %s [--csv]\n", program.c_str(), size);
    summary->push_back("quality (b) scenes, " + std::string(size) + ": " + unchanged);
    // "total  default  triangles scored before% after% area% ..." -> after%
    char policy[64];
    unsigned long triangles = 0, scored = 0;
    double before = 0, after = 0;
    if (std::sscanf(totals.c_str(), "total %63s %lu %lu %lf %lf", policy, &triangles, &scored, &before, &after) == 5) {
        char line[256];
        std::snprintf(line, sizeof(line), "quality (b) scenes, %s: %lu scored triangles, right before %.2f%%, after %.2f%%",
                      size, scored, before, after);
        summary->push_back(line);
    }
    return 0;
}

// A program's whole output in a code block, and its last line for the summary.
static int program_block(const Settings &s, const char *name, const std::string &arguments, const char *label,
                         std::vector<std::string> *summary)
{
    std::string program = s.build_dir + "/" + name;
    if (!exists(program)) {
        std::printf("(%s missing: `make %s`. Skipped.)\n", program.c_str(), program.c_str());
        return 0;
    }
    int code = 0;
    std::string out = run(program + " " + arguments, &code);
    std::printf("```\n%s```\n\nCommand: %s %s\n", out.c_str(), program.c_str(), arguments.c_str());
    std::vector<std::string> lines = lines_of(out);
    std::string last;
    for (const std::string &l : lines)
        if (l.compare(0, 4, "all:") == 0 || l.compare(0, 15, "total corrupted") == 0 || l.compare(0, 13, "total correct") == 0)
            last = l;
    summary->push_back(std::string(label) + (code == 0 ? ": " + last : ": FAILED, " + last_error_line()));
    return code == 0 ? 0 : 1;
}

// (c) the trust suite's families, cut as real exports are (tests/eval/trust_eval.c)
static int trust_table(const Settings &s, std::vector<std::string> *summary)
{
    std::printf("\n### 3c. The trust families cut as exported: K patches, seams exact, gapped (3%% to the middle) or "
                "jittered (0.5-1e-4 of the diagonal, gaps and overlaps); as cut (every flip is damage) and corrupted "
                "(half the patches reversed, then 2%% of the triangles). Ablation: patches each kind of evidence "
                "decided, and how many of those ended right\n\n");
    return program_block(s, "trust_eval", std::string("--ablation --size ") + (s.quick ? "small" : "large"),
                         "quality (c) trust families", summary);
}

// (d) real models under eleven corruptions (tests/eval/models_eval.c), per half
static int models_table(const Settings &s, std::vector<std::string> *summary)
{
    std::printf("\n### 3d. Real models (closed, consistent, outward as shipped, from the corpus) under eleven "
                "corruptions: %% of triangles facing as shipped after the repair\n\n");
    if (!exists(s.corpus)) {
        std::printf("(no corpus in %s: `bash tests/corpus/fetch.sh`. Skipped.)\n", s.corpus.c_str());
        return 0;
    }
    std::printf("Held-out half (tests/corpus/split.sh heldout):\n\n");
    int status = program_block(s, "models_eval", "--quiet" + corpus_half("heldout", s.corpus),
                               "quality (d) real models x 11 corruptions, held-out half", summary);
    std::printf("\nTune half:\n\n");
    status |= program_block(s, "models_eval", "--quiet" + corpus_half("tune", s.corpus),
                            "quality (d) real models x 11 corruptions, tune half", summary);
    return status;
}

} // namespace

int part_quality(const Settings &s, std::vector<std::string> *summary)
{
    std::printf("\n## Part 3. Quality: winding against independent truth (stored STL normals; scenes built with a "
                "known facing; real models as shipped)\n");
    errors_path = s.build_dir + "/bench_eval_stderr.txt";
    int status = stl_table(s, summary);
    status |= scenes_table(s, summary);
    status |= trust_table(s, summary);
    status |= models_table(s, summary);
    return status;
}

} // namespace bench
