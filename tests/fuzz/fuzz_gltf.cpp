/* libFuzzer target for the command-line tool's glTF path (tools/meshfix):
   its loader, the repair, the writer and the all-or-nothing commit, on a
   .gltf or .glb with its companion files, in a scratch directory.

   Input: byte 0 picks the format (even: .gltf, odd: .glb); then the main
   file's length (4 bytes, little endian) and bytes; then companions, each
   a name (1 byte of length, then the name) and its bytes (4 bytes of
   length, then the bytes), until the input ends. Names are kept to
   [A-Za-z0-9._-] so every file stays in the scratch directory: the target
   fuzzes what a file says, not where the harness puts it.
   tests/fuzz/gltf_seeds.py packs real files into this form.

   The oracle: a run must not crash or leak (ASan + UBSan), and an output
   it reports written must load again, with as many meshes and triangles. */
#include "../../tools/meshfix/tool.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <dirent.h>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace {

/* One directory per process, emptied before each input. */
const std::string &scratch()
{
    static std::string dir;
    if (dir.empty()) {
        char name[] = "/tmp/meshfix_fuzz_gltf.XXXXXX";
        if (mkdtemp(name) == nullptr)
            std::abort();
        dir = name;
    }
    return dir;
}

void empty_directory(const std::string &dir)
{
    DIR *d = opendir(dir.c_str());
    if (d == nullptr)
        return;
    while (struct dirent *e = readdir(d)) {
        std::string name = e->d_name, path = dir + "/" + name;
        if (name == "." || name == "..")
            continue;
        struct stat st;
        if (lstat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) {
            empty_directory(path);
            rmdir(path.c_str());
        } else {
            unlink(path.c_str());
        }
    }
    closedir(d);
}

uint32_t read_u32(const uint8_t *p) { return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24; }

bool write_file(const std::string &path, const uint8_t *data, size_t size)
{
    std::string ignored;
    return tool::write_bytes(path, std::string((const char *)data, size), ignored);
}

/* Unpacks the input into the scratch directory; the main file's path, or "". */
std::string unpack(const uint8_t *data, size_t size)
{
    if (size < 5)
        return "";
    std::string main = scratch() + "/in/scene." + (data[0] % 2 ? "glb" : "gltf");
    size_t length = read_u32(data + 1), at = 5;
    if (length > size - at)
        length = size - at;
    mkdir((scratch() + "/in").c_str(), 0700);
    if (!write_file(main, data + at, length))
        return "";
    at += length;
    while (at + 1 <= size) {
        size_t name_length = data[at++];
        if (name_length == 0 || name_length > size - at)
            break;
        std::string name((const char *)data + at, name_length);
        at += name_length;
        if (at + 4 > size)
            break;
        size_t bytes = std::min<size_t>(read_u32(data + at), size - at - 4);
        at += 4;
        bool plain = name != "." && name != "..";
        for (char c : name)
            plain &= (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' ||
                     c == '_' || c == '-';
        if (plain && name != "scene.gltf" && name != "scene.glb")
            write_file(scratch() + "/in/" + name, data + at, bytes);
        at += bytes;
    }
    return main;
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
    empty_directory(scratch());
    std::string input = unpack(data, size);
    if (input.empty())
        return 0;
    tool::Settings settings;
    settings.fix_normals = size > 5 && (data[1] & 1) != 0; /* the length's low bit: free to vary */
    tool::Ledger ledger;
    tool::Job job;
    job.input = job.name = input;
    /* bit 1 of byte 0: the other glTF form as output (.gltf to .glb, .glb to .gltf) */
    bool glb = (data[0] % 2 != 0) != ((data[0] & 2) != 0);
    job.output = scratch() + "/out/result." + (glb ? "glb" : "gltf");
    mkdir((scratch() + "/out").c_str(), 0700);
    tool::run_job(job, settings, ledger);
    if (job.exit == 0 && !job.written.empty()) {
        std::string error;
        std::unique_ptr<tool::MeshFile> again = tool::load_file(job.output, error);
        if (!again || again->units.size() != job.file->units.size() || triangles(*again) != triangles(*job.file)) {
            std::fprintf(stderr, "fuzz_gltf: the output does not load back as written: %s\n", error.c_str());
            std::abort();
        }
    }
    return 0;
}
