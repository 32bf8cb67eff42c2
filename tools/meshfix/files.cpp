/* meshfix command-line tool: reading inputs, writing outputs all or
   nothing, the --mark file. POSIX (open, rename, mkdir, opendir). */
#include "tool.h"

extern "C" {
#include "../../examples/meshio.h"
}

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace tool {

std::string format_of(const std::string &path)
{
    std::string name = base_name(path);
    size_t dot = name.rfind('.');
    if (dot == std::string::npos)
        return "";
    std::string ext = name.substr(dot + 1);
    for (char &c : ext)
        c = (char)std::tolower((unsigned char)c);
    for (const char *known : {"obj", "off", "stl", "ply", "gltf", "glb"})
        if (ext == known)
            return ext;
    return "";
}

std::string directory_of(const std::string &path)
{
    size_t slash = path.rfind('/');
    return slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
}

std::string base_name(const std::string &path)
{
    size_t slash = path.rfind('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

bool is_directory(const std::string &path)
{
    struct stat st;
    return stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

bool read_file(const std::string &path, std::string &data, std::string &error)
{
    /* O_NONBLOCK: opening a FIFO does not wait for a writer (it is refused
       below), and nothing is read before the file is known to be regular */
    int fd;
    do
        fd = open(path.c_str(), O_RDONLY | O_NONBLOCK);
    while (fd < 0 && errno == EINTR);
    if (fd < 0) {
        error = "cannot open '" + path + "': " + std::strerror(errno);
        return false;
    }
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        bool directory = S_ISDIR(st.st_mode);
        error = "'" + path + (directory ? "' is a directory, not a mesh file" : "' is not a regular file (a FIFO, socket or device)");
        close(fd);
        return false;
    }
    try {
        data.resize((size_t)st.st_size);
    } catch (const std::exception &) {
        close(fd);
        error = "out of memory reading '" + path + "'";
        return false;
    }
    size_t got = 0;
    while (got < data.size()) {
        ssize_t n = read(fd, &data[got], data.size() - got);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            break;
        got += (size_t)n;
    }
    close(fd);
    if (got != data.size()) {
        error = "cannot read '" + path + "'";
        return false;
    }
    return true;
}

bool write_bytes(const std::string &path, const std::string &bytes, std::string &error)
{
    FILE *f = std::fopen(path.c_str(), "wb");
    if (f == nullptr) {
        error = "cannot write '" + path + "': " + std::strerror(errno);
        return false;
    }
    bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    ok = std::fclose(f) == 0 && ok;
    if (!ok)
        error = "error writing '" + path + "'";
    return ok;
}

bool check_target(const std::string &target, std::string &error)
{
    struct stat st;
    if (stat(target.c_str(), &st) == 0) {
        if (!S_ISREG(st.st_mode)) {
            error = "cannot write '" + target + "': " +
                    (S_ISDIR(st.st_mode) ? "it is a directory" : "it is not a regular file (a FIFO, socket or device)");
            return false;
        }
        /* a read-only target stays refused, as when it was written in place */
        if (access(target.c_str(), W_OK) != 0) {
            error = "cannot write '" + target + "': " + std::strerror(errno);
            return false;
        }
        return true;
    }
    std::string directory = directory_of(target);
    if (!is_directory(directory) || access(directory.c_str(), W_OK | X_OK) != 0) {
        error = "cannot write '" + target + "': " + (is_directory(directory) ? std::strerror(errno) : "no such directory");
        return false;
    }
    return true;
}

std::unique_ptr<MeshFile> load_file(const std::string &path, std::string &error)
{
    std::string format = format_of(path), data;
    if (format == "gltf" || format == "glb") {
        /* tinygltf reads the file itself: refuse what is not a regular file first */
        if (!read_file(path, data, error))
            return nullptr;
        return load_gltf(path, error);
    }
    if (!read_file(path, data, error))
        return nullptr;
    if (format == "obj")
        return load_obj(data, error);
    if (format == "off")
        return load_off(data, error);
    if (format == "stl")
        return load_stl(data, error);
    if (format == "ply")
        return load_ply(data, error);
    error = "unknown format (use .obj, .off, .stl, .ply, .gltf or .glb)";
    return nullptr;
}

/* ---- all or nothing ---- */

namespace {

/* Every regular file under `directory`, as paths relative to it. */
void list_files(const std::string &directory, const std::string &prefix, std::vector<std::string> &out)
{
    DIR *d = opendir(directory.c_str());
    if (d == nullptr)
        return;
    while (struct dirent *e = readdir(d)) {
        std::string name = e->d_name;
        if (name == "." || name == "..")
            continue;
        if (is_directory(directory + "/" + name))
            list_files(directory + "/" + name, prefix + name + "/", out);
        else
            out.push_back(prefix + name);
    }
    closedir(d);
}

void remove_tree(const std::string &directory)
{
    std::vector<std::string> files;
    list_files(directory, "", files);
    for (const std::string &f : files)
        std::remove((directory + "/" + f).c_str());
    /* subdirectories deepest first: longer paths sort after their parents */
    std::vector<std::string> dirs;
    for (const std::string &f : files)
        for (size_t slash = f.find('/'); slash != std::string::npos; slash = f.find('/', slash + 1))
            dirs.push_back(directory + "/" + f.substr(0, slash));
    std::sort(dirs.begin(), dirs.end(), [](const std::string &a, const std::string &b) { return a.size() > b.size(); });
    for (const std::string &d : dirs)
        rmdir(d.c_str());
    rmdir(directory.c_str());
}

bool make_directories(const std::string &base, const std::string &relative)
{
    for (size_t slash = relative.find('/'); slash != std::string::npos; slash = relative.find('/', slash + 1)) {
        std::string d = base + "/" + relative.substr(0, slash);
        if (mkdir(d.c_str(), 0777) != 0 && errno != EEXIST)
            return false;
    }
    return true;
}

} // namespace

std::string OutputSet::reserve(const std::string &target, std::string &error)
{
    /* mkdir fails when the name is taken, so two runs (or two threads with
       the same target) never share a temporary */
    for (int k = 0; k < 100; ++k) {
        std::string directory = target + ".meshfix-" + std::to_string((long)getpid()) + "-" + std::to_string(k) + ".tmp";
        if (mkdir(directory.c_str(), 0700) == 0) {
            items.push_back({target, directory});
            return directory + "/" + base_name(target);
        }
        if (errno != EEXIST)
            break;
    }
    error = "cannot write '" + target + "': " + std::strerror(errno);
    return "";
}

bool OutputSet::commit(std::string &error)
{
    for (const Item &item : items) {
        std::vector<std::string> files;
        list_files(item.directory, "", files);
        std::string destination = directory_of(item.target);
        for (const std::string &f : files) {
            std::string from = item.directory + "/" + f, to = destination + "/" + f;
            struct stat st;
            if (stat(to.c_str(), &st) == 0 && S_ISREG(st.st_mode))
                chmod(from.c_str(), st.st_mode & 07777); /* a replaced file keeps its permissions */
            if (!make_directories(destination, f) || std::rename(from.c_str(), to.c_str()) != 0) {
                error = "cannot write '" + to + "': " + std::strerror(errno);
                return false;
            }
            written.push_back(to);
        }
    }
    discard();
    return true;
}

void OutputSet::discard()
{
    for (const Item &item : items)
        remove_tree(item.directory);
    items.clear();
}

/* ---- --mark, and other formats than the input's ---- */

bool write_triangles(const std::string &path, const MeshFile &file, const std::vector<UnitResult> &results,
                     bool colours, std::string &error)
{
    std::vector<float> positions;
    std::vector<unsigned int> indices;
    std::vector<unsigned char> rgb;
    for (size_t i = 0; i < file.units.size(); ++i) {
        const Unit &u = file.units[i];
        const UnitResult &r = results[i];
        unsigned int base = (unsigned int)(positions.size() / 3);
        for (double p : u.positions)
            positions.push_back((float)p);
        for (size_t t = 0; t < u.indices.size() / 3; ++t) {
            bool flipped = r.status == MESHFIX_OK && r.changes.face_flipped[u.triangle_face[t]];
            unsigned int patch = r.status == MESHFIX_OK ? r.patch_ids[t] : 0xFFFFFFFFu;
            indices.insert(indices.end(), {base + u.indices[3 * t], base + u.indices[3 * t + (flipped ? 2 : 1)],
                                           base + u.indices[3 * t + (flipped ? 1 : 2)]});
            unsigned int h = patch * 2654435761u;
            if (patch != 0xFFFFFFFFu && doubtful(r, patch))
                rgb.insert(rgb.end(), {255, 176, 0}); /* doubtful, flipped or not: look here first */
            else if (flipped)
                rgb.insert(rgb.end(), {230, 30, 30});
            else if (patch == 0xFFFFFFFFu)
                rgb.insert(rgb.end(), {40, 40, 40});
            else
                rgb.insert(rgb.end(), {(unsigned char)(90 + (h >> 8) % 80), (unsigned char)(120 + (h >> 16) % 100),
                                       (unsigned char)(140 + (h >> 24) % 100)});
        }
    }
    mio_mesh mesh;
    mesh.positions = positions.data();
    mesh.vertex_count = positions.size() / 3;
    mesh.indices = indices.data();
    mesh.index_count = indices.size();
    char message[256];
    if (!mio_save(path.c_str(), &mesh, colours ? rgb.data() : nullptr, message, sizeof(message))) {
        error = message;
        return false;
    }
    return true;
}

} // namespace tool
