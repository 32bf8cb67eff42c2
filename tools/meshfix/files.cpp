/* meshfix command-line tool: reading inputs, writing outputs all or
   nothing, the --mark file. POSIX (open, rename, mkdir, opendir). */
#include "tool.h"

extern "C" {
#include "../../examples/meshio.h"
}

#include <algorithm>
#include <cerrno>
#include <cstdlib>
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

std::string mark_format_of(const std::string &path)
{
    std::string name = base_name(path);
    size_t dot = name.rfind('.');
    std::string ext = dot == std::string::npos ? "" : name.substr(dot + 1);
    for (char &c : ext)
        c = (char)std::tolower((unsigned char)c);
    return ext == "ply" || ext == "png" ? ext : "";
}

bool is_gltf_format(const std::string &format) { return format == "gltf" || format == "glb"; }

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

/* Every byte written and on the disk before the file is renamed over its
   target: a full disk or a failing device is an error here, never a
   truncated file in place of the user's. */
bool write_bytes(const std::string &path, const std::string &bytes, std::string &error)
{
    int fd;
    do
        fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
    while (fd < 0 && errno == EINTR);
    if (fd < 0) {
        error = "cannot write '" + path + "': " + std::strerror(errno);
        return false;
    }
    size_t done = 0;
    int failure = 0;
    while (done < bytes.size() && failure == 0) {
        ssize_t n = write(fd, bytes.data() + done, bytes.size() - done);
        if (n > 0)
            done += (size_t)n;
        else if (n < 0 && errno != EINTR)
            failure = errno;
        else if (n == 0)
            failure = EIO;
    }
    if (failure == 0 && fsync(fd) != 0 && errno != EINVAL && errno != EROFS)
        failure = errno; /* EINVAL, EROFS: a file system without fsync (a pipe, /dev/null) */
    if (close(fd) != 0 && failure == 0 && errno != EINTR)
        failure = errno;
    if (failure != 0) {
        error = "error writing '" + path + "': " + std::strerror(failure);
        return false;
    }
    return true;
}

bool make_parent_directories(const std::string &file)
{
    /* from the first '/' after the first character: "/a/b/f" makes /a and
       /a/b, "a/b/f" makes a and a/b, "f" nothing */
    for (size_t slash = file.find('/', 1); slash != std::string::npos; slash = file.find('/', slash + 1)) {
        if (file[slash - 1] == '/')
            continue;
        std::string d = file.substr(0, slash);
        if (mkdir(d.c_str(), 0777) != 0 && errno != EEXIST)
            return false;
    }
    return true;
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

} // namespace

std::string path_identity(const std::string &path)
{
    std::string directory = directory_of(path), name = base_name(path);
    if (name == "." || name == "..") {
        directory = path;
        name.clear();
    }
    char *resolved = realpath(directory.c_str(), nullptr);
    if (resolved != nullptr) {
        std::string id = std::string(resolved) + (name.empty() ? "" : "/" + name);
        std::free(resolved);
        return id;
    }
    /* a directory not made yet: the path made absolute and cleaned up as
       text ("a/./b//c" is "a/b/c", "a/x/../b" is "a/b") */
    std::string absolute = path;
    if (path.empty() || path[0] != '/') {
        char *cwd = getcwd(nullptr, 0);
        absolute = std::string(cwd != nullptr ? cwd : ".") + "/" + path;
        std::free(cwd);
    }
    std::vector<std::string> parts;
    for (size_t at = 0; at <= absolute.size();) {
        size_t slash = absolute.find('/', at);
        std::string part = absolute.substr(at, slash == std::string::npos ? std::string::npos : slash - at);
        if (part == "..") {
            if (!parts.empty())
                parts.pop_back();
        } else if (!part.empty() && part != ".") {
            parts.push_back(part);
        }
        if (slash == std::string::npos)
            break;
        at = slash + 1;
    }
    std::string id;
    for (const std::string &part : parts)
        id += "/" + part;
    return id.empty() ? "/" : id;
}

bool Ledger::add_temporary(const std::string &directory)
{
    std::lock_guard<std::mutex> lock(mutex);
    if (stopped)
        return false;
    temporaries.insert(directory);
    return true;
}

void Ledger::remove_temporary(const std::string &directory)
{
    std::lock_guard<std::mutex> lock(mutex);
    temporaries.erase(directory);
}

bool Ledger::claim(const std::vector<std::string> &files, const std::string &owner, std::string &error)
{
    std::vector<std::string> ids;
    for (const std::string &f : files) {
        ids.push_back(path_identity(f));
        auto found = owners.find(ids.back());
        if (found != owners.end() && found->second != owner) {
            error = "cannot write '" + f + "': it was written for '" + found->second + "' in this run";
            return false;
        }
    }
    for (const std::string &id : ids)
        owners.emplace(id, owner);
    return true;
}

void Ledger::stop()
{
    std::lock_guard<std::mutex> lock(mutex);
    stopped = true;
    for (const std::string &d : temporaries)
        remove_tree(d);
    temporaries.clear();
}

std::string OutputSet::reserve(const std::string &target, std::string &error)
{
    /* beside the target, so the final rename stays on one file system;
       named with a leading dot, so a later walk of the directory skips it.
       mkdir fails when the name is taken, so two runs (or two threads
       with the same target) never share a temporary */
    std::string stem = directory_of(target) + "/." + base_name(target) + ".meshfix-" + std::to_string((long)getpid());
    for (int k = 0; k < 100; ++k) {
        std::string directory = stem + "-" + std::to_string(k) + ".tmp";
        if (mkdir(directory.c_str(), 0700) == 0) {
            if (!ledger.add_temporary(directory)) {
                rmdir(directory.c_str());
                error = "cannot write '" + target + "': interrupted";
                return "";
            }
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
    /* one set moves into place under the ledger's lock: an interrupt waits
       for it, so the files of one input (a .gltf and its .bin) never end
       up half old and half new */
    std::lock_guard<std::mutex> lock(ledger.mutex);
    if (ledger.stopped) {
        error = "interrupted";
        return false;
    }
    std::vector<std::pair<std::string, std::string>> moves;
    for (const Item &item : items) {
        std::vector<std::string> files;
        list_files(item.directory, "", files);
        std::sort(files.begin(), files.end());
        for (const std::string &f : files)
            moves.push_back({item.directory + "/" + f, directory_of(item.target) + "/" + f});
    }
    std::vector<std::string> targets;
    for (const auto &m : moves) {
        if (!make_parent_directories(m.second)) {
            error = "cannot write '" + m.second + "': " + std::strerror(errno);
            return false;
        }
        targets.push_back(m.second);
    }
    if (!ledger.claim(targets, owner, error))
        return false;
    for (const auto &m : moves) {
        struct stat st;
        if (stat(m.second.c_str(), &st) == 0 && S_ISREG(st.st_mode))
            chmod(m.first.c_str(), st.st_mode & 07777); /* a replaced file keeps its permissions */
        if (std::rename(m.first.c_str(), m.second.c_str()) != 0) {
            error = "cannot write '" + m.second + "': " + std::strerror(errno);
            return false;
        }
        written.push_back(m.second);
    }
    for (const Item &item : items) {
        remove_tree(item.directory);
        ledger.temporaries.erase(item.directory);
    }
    items.clear();
    return true;
}

void OutputSet::discard()
{
    for (const Item &item : items) {
        remove_tree(item.directory);
        ledger.remove_temporary(item.directory);
    }
    items.clear();
}

/* ---- --mark, and other formats than the input's ---- */

Mark mark_of(const Unit &u, const UnitResult &r, size_t t)
{
    if (r.status != MESHFIX_OK)
        return Mark::none;
    if (r.patch_ids[t] != 0xFFFFFFFFu && doubtful(r, r.patch_ids[t]))
        return Mark::doubtful; /* doubtful, flipped or not: look here first */
    if (r.changes.face_flipped[u.triangle_face[t]])
        return Mark::flipped;
    return r.patch_ids[t] == 0xFFFFFFFFu ? Mark::none : Mark::kept;
}

bool written_flipped(const Unit &u, const UnitResult &r, size_t t)
{
    return r.status == MESHFIX_OK && r.changes.face_flipped[u.triangle_face[t]];
}

void patch_tint(unsigned int patch, unsigned char rgb[3])
{
    unsigned int h = patch * 2654435761u;
    rgb[0] = (unsigned char)(90 + (h >> 8) % 80);
    rgb[1] = (unsigned char)(120 + (h >> 16) % 100);
    rgb[2] = (unsigned char)(140 + (h >> 24) % 100);
}

/* The file's vertex of the unit's vertex v: the written mesh has the
   file's vertices, shared by its faces as in the file, not the library's
   (an OBJ's (v, vn) pairs would split a cube into six loose quads). */
namespace {
uint32_t file_vertex_of(const Unit &u, uint32_t v) { return u.file_vertex.empty() ? v : u.file_vertex[v]; }
} // namespace

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
        for (double p : u.file_vertex.empty() ? u.positions : u.file_positions)
            positions.push_back((float)p);
        for (size_t t = 0; t < u.indices.size() / 3; ++t) {
            bool flipped = written_flipped(u, r, t);
            const uint32_t *corner = &u.indices[3 * t];
            indices.insert(indices.end(), {base + file_vertex_of(u, corner[0]),
                                           base + file_vertex_of(u, corner[flipped ? 2 : 1]),
                                           base + file_vertex_of(u, corner[flipped ? 1 : 2])});
            unsigned char tint[3];
            switch (mark_of(u, r, t)) {
            case Mark::doubtful:
                rgb.insert(rgb.end(), {255, 176, 0});
                break;
            case Mark::flipped:
                rgb.insert(rgb.end(), {230, 30, 30});
                break;
            case Mark::none:
                rgb.insert(rgb.end(), {40, 40, 40});
                break;
            case Mark::kept:
                patch_tint(r.patch_ids[t], tint);
                rgb.insert(rgb.end(), {tint[0], tint[1], tint[2]});
                break;
            }
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
