/* libFuzzer target for the command-line tool's OBJ, OFF, STL and PLY
   readers and their lossless writers (tools/meshfix): load, repair, write,
   commit, load again, on one file in a scratch directory.

   Input: byte 0 picks the format (its value mod 4: OBJ, OFF, STL, PLY)
   and, with bit 2, --fix-normals; bit 3 writes another format (the one
   after it) through write_triangles instead of the lossless writer. The
   rest is the file. Seeds: tests/cli/text_variants.py's files and the
   assimp-testmodels files of these formats, packed by tests/fuzz/run.sh.

   The oracle: a run must not crash or leak (ASan + UBSan), and an output
   it reports written must load again with as many triangles (the lossless
   writers only swap and negate tokens; a conversion writes triangles). */
#include "../../tools/meshfix/tool.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace {

const char *const formats[4] = {"obj", "off", "stl", "ply"};

/* One directory per process; its files are replaced by each input. */
const std::string &scratch()
{
    static std::string dir;
    if (dir.empty()) {
        char name[] = "/tmp/meshfix_fuzz_text.XXXXXX";
        if (mkdtemp(name) == nullptr)
            std::abort();
        dir = name;
    }
    return dir;
}

size_t triangles(const tool::MeshFile &f)
{
    size_t n = 0;
    for (const tool::Unit &u : f.units)
        n += u.indices.size() / 3;
    return n;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    const char *in_format = formats[data[0] % 4], *out_format = formats[(data[0] + (data[0] & 8 ? 1 : 0)) % 4];
    std::string input = scratch() + "/in." + in_format, output = scratch() + "/out." + out_format, ignored;
    unlink(output.c_str());
    if (!tool::write_bytes(input, std::string((const char *)data + 1, size - 1), ignored))
        std::abort();
    tool::Settings settings;
    settings.fix_normals = (data[0] & 4) != 0;
    tool::Ledger ledger;
    tool::Job job;
    job.input = job.name = input;
    job.output = output;
    tool::run_job(job, settings, ledger);
    if (job.exit == 0 && !job.written.empty()) {
        std::string error;
        std::unique_ptr<tool::MeshFile> again = tool::load_file(output, error);
        if (!again || triangles(*again) != triangles(*job.file)) {
            std::fprintf(stderr, "fuzz_text: the output does not load back as written: %s\n", error.c_str());
            std::abort();
        }
    }
    return 0;
}
