/* meshfix command-line tool: reading inputs, writing outputs all or
   nothing, the --mark file. POSIX (open, rename, mkdir, opendir). */
#include "tool.h"

extern "C" {
#include "../../examples/meshio.h"
}

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
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

bool make_parent_directories(const std::string &file, std::vector<std::string> *made)
{
    /* from the first '/' after the first character: "/a/b/f" makes /a and
       /a/b, "a/b/f" makes a and a/b, "f" nothing */
    for (size_t slash = file.find('/', 1); slash != std::string::npos; slash = file.find('/', slash + 1)) {
        if (file[slash - 1] == '/')
            continue;
        std::string d = file.substr(0, slash);
        if (mkdir(d.c_str(), 0777) == 0) {
            if (made != nullptr)
                made->push_back(d);
        } else if (errno != EEXIST) {
            return false;
        }
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

/* Removes a temporary directory and everything in it (symbolic links
   not followed: a temporary holds only what the tool made). */
void remove_tree(const std::string &directory)
{
    DIR *d = opendir(directory.c_str());
    if (d != nullptr) {
        std::vector<std::string> names;
        while (struct dirent *e = readdir(d))
            if (std::strcmp(e->d_name, ".") != 0 && std::strcmp(e->d_name, "..") != 0)
                names.push_back(e->d_name);
        closedir(d);
        for (const std::string &name : names) {
            std::string path = directory + "/" + name;
            struct stat st;
            if (lstat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
                remove_tree(path);
            else
                std::remove(path.c_str());
        }
    }
    rmdir(directory.c_str());
}

/* The temporaries' names: short (".meshfix-PID-N.tmp", whatever the
   target's name: a name of 255 bytes still has a temporary), with a
   leading dot so that a later walk of the directory skips them, and a
   number no other set of this process uses. */
std::atomic<unsigned> temporary_count{0};

} // namespace

FileId file_id(const std::string &path)
{
    FileId id;
    struct stat st;
    char *resolved = nullptr;
    if (stat(path.c_str(), &st) == 0 && (resolved = realpath(path.c_str(), nullptr)) != nullptr) {
        id.path = resolved;
        id.exists = true;
        id.device = (unsigned long long)st.st_dev;
        id.inode = (unsigned long long)st.st_ino;
        std::free(resolved);
        return id;
    }
    id.path = path_identity(path);
    return id;
}

bool same_file(const FileId &a, const FileId &b)
{
    return a.path == b.path || (a.exists && b.exists && a.device == b.device && a.inode == b.inode);
}

void FileMap::add(const FileId &id, const std::string &name)
{
    by_path.emplace(id.path, name);
    if (id.exists)
        by_inode.emplace(std::make_pair(id.device, id.inode), name);
}

const std::string *FileMap::find(const FileId &id) const
{
    auto path = by_path.find(id.path);
    if (path != by_path.end())
        return &path->second;
    auto inode = id.exists ? by_inode.find(std::make_pair(id.device, id.inode)) : by_inode.end();
    return inode != by_inode.end() ? &inode->second : nullptr;
}

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

void Ledger::stop()
{
    std::lock_guard<std::mutex> lock(mutex);
    stopped = true;
    for (const std::string &d : temporaries)
        remove_tree(d);
    temporaries.clear();
}

void OutputSet::add_read(const std::string &path)
{
    FileId id = file_id(path);
    if (reads.find(id) != nullptr)
        return;
    reads.add(id, path);
    read_list.push_back({id, path});
    /* known to the run at once: another input's commit before this one's
       must not replace it either */
    std::lock_guard<std::mutex> lock(ledger.mutex);
    ledger.read.add(id, owner);
}

/* One temporary directory per target directory: the renames stay on one
   file system. mkdir fails when the name is taken, so two runs never
   share one. */
std::string OutputSet::temporary_directory(const std::string &directory, std::string &error)
{
    auto found = directories.find(directory);
    if (found != directories.end())
        return found->second;
    std::string stem = directory + "/.meshfix-" + std::to_string((long)getpid()) + "-";
    for (int tries = 0; tries < 100; ++tries) {
        std::string temporary = stem + std::to_string(temporary_count++) + ".tmp";
        if (mkdir(temporary.c_str(), 0700) == 0) {
            if (!ledger.add_temporary(temporary)) {
                rmdir(temporary.c_str());
                error = "interrupted";
                return "";
            }
            if (mkdir((temporary + "/new").c_str(), 0700) != 0 || mkdir((temporary + "/old").c_str(), 0700) != 0) {
                error = "cannot make a temporary in '" + directory + "': " + std::strerror(errno);
                remove_tree(temporary);
                ledger.remove_temporary(temporary);
                return "";
            }
            directories[directory] = temporary;
            return temporary;
        }
        if (errno != EEXIST)
            break;
    }
    error = "cannot make a temporary in '" + directory + "': " + std::strerror(errno);
    return "";
}

std::string OutputSet::reserve(const std::string &target, const std::string &replaces, std::string &error)
{
    Item item;
    item.target = target;
    /* an existing symbolic link is written through: the file it names is
       replaced, the link kept */
    char *resolved = realpath(target.c_str(), nullptr);
    struct stat st;
    bool link = lstat(target.c_str(), &st) == 0 && S_ISLNK(st.st_mode);
    item.real = link && resolved != nullptr ? resolved : target;
    std::free(resolved);
    item.id = file_id(item.real);
    const std::string *read = reads.find(item.id);
    if (read != nullptr && (replaces.empty() || !same_file(item.id, file_id(replaces)))) {
        error = "cannot write '" + target + "': it is '" + *read + "', which " + (*read == owner ? "is the input" : "'" + owner + "' reads") +
                ": nothing written";
        return "";
    }
    const std::string *other = planned.find(item.id);
    if (other != nullptr) {
        error = "'" + owner + "' would write '" + target + "' twice" + (*other == target ? "" : " (also as '" + *other + "')") +
                ": nothing written";
        return "";
    }
    if (!make_parent_directories(item.real, &made)) {
        error = "cannot make the directory of '" + target + "': " + std::strerror(errno);
        return "";
    }
    if (!check_target(item.real, error))
        return "";
    item.temporary = temporary_directory(directory_of(item.real), error);
    if (item.temporary.empty())
        return "";
    planned.add(item.id, target);
    items.push_back(item);
    return item.temporary + "/new/" + base_name(item.real);
}

/* Whether another input of the run wrote or read a file of this set, or
   wrote one it read (call with the ledger's lock held). */
bool OutputSet::check_run(std::string &error) const
{
    for (const Item &item : items) {
        const std::string *other = ledger.written.find(item.id);
        if (other == nullptr || *other == owner)
            other = ledger.read.find(item.id);
        if (other != nullptr && *other != owner) {
            error = "cannot write '" + item.target + "': '" + *other + "' " +
                    (ledger.written.find(item.id) != nullptr ? "wrote it" : "reads it") + " in this run";
            return false;
        }
    }
    for (const auto &r : read_list) {
        const std::string *other = ledger.written.find(r.first);
        if (other != nullptr && *other != owner) {
            error = "'" + r.second + "' was written for '" + *other + "' in this run: nothing written for '" + owner + "'";
            return false;
        }
    }
    return true;
}

/* Puts one output in place: the file it replaces is kept as a backup
   first (a hard link, or, where the file system has none, the file moved
   aside), so that the set can be put back. */
bool OutputSet::move(Item &item, std::string &error)
{
    std::string temporary = item.temporary + "/new/" + base_name(item.real);
    std::string backup = item.temporary + "/old/" + base_name(item.real);
    struct stat st;
    item.existed = lstat(item.real.c_str(), &st) == 0;
    if (item.existed) {
        chmod(temporary.c_str(), st.st_mode & 07777); /* a replaced file keeps its permissions */
        if (link(item.real.c_str(), backup.c_str()) != 0 && std::rename(item.real.c_str(), backup.c_str()) != 0) {
            error = "cannot write '" + item.target + "': " + std::strerror(errno);
            return false;
        }
        item.backup = backup;
    }
    if (std::rename(temporary.c_str(), item.real.c_str()) != 0) {
        error = "cannot write '" + item.target + "': " + std::strerror(errno);
        if (item.existed && access(item.real.c_str(), F_OK) != 0)
            std::rename(backup.c_str(), item.real.c_str()); /* moved aside above: back */
        return false;
    }
    item.moved = true;
    return true;
}

/* After a move failed: every output already moved is taken back, the file
   it replaced put back in its place. */
void OutputSet::restore(std::string &error)
{
    for (size_t i = items.size(); i-- > 0;) {
        Item &item = items[i];
        if (!item.moved)
            continue;
        bool back = item.existed ? std::rename(item.backup.c_str(), item.real.c_str()) == 0
                                 : std::remove(item.real.c_str()) == 0;
        if (!back) {
            error += "; '" + item.target + "' could not be put back (" + std::strerror(errno) + ")" +
                     (item.existed ? ": the old file is '" + item.backup + "'" : "");
            directories.clear(); /* the backups stay */
        }
        item.moved = false;
    }
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
    if (!check_run(error))
        return false;
    for (Item &item : items)
        if (!move(item, error)) {
            restore(error);
            return false;
        }
    for (Item &item : items) {
        ledger.written.add(item.id, owner);
        written.push_back(item.target);
    }
    for (const auto &d : directories) {
        remove_tree(d.second);
        ledger.temporaries.erase(d.second);
    }
    directories.clear();
    items.clear();
    made.clear();
    return true;
}

void OutputSet::discard()
{
    for (const auto &d : directories) {
        remove_tree(d.second);
        ledger.remove_temporary(d.second);
    }
    directories.clear();
    items.clear();
    /* the directories made for nothing, deepest first (rmdir leaves one
       that holds anything) */
    for (size_t i = made.size(); i-- > 0;)
        rmdir(made[i].c_str());
    made.clear();
}

bool write_output(OutputSet &outputs, const std::string &target, const std::string &replaces, const std::string &bytes,
                  std::string &error)
{
    std::string path = outputs.reserve(target, replaces, error);
    return !path.empty() && write_bytes(path, bytes, error);
}

bool MeshFile::write_outputs(OutputSet &outputs, const std::string &input, const std::string &target, std::string &error)
{
    std::string path = outputs.reserve(target, input, error);
    return !path.empty() && write(path, target, error);
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

/* Hues from yellow-green to sea green (70 to 160 degrees), pale: never
   near red, amber or the picture's back-face blue, whatever the patch. */
void patch_tint(unsigned int patch, unsigned char rgb[3])
{
    unsigned int h = patch * 2654435761u;
    double hue = 70.0 + (double)((h >> 8) % 91u), s = 0.22 + 0.01 * (double)((h >> 16) % 24u),
           v = 0.70 + 0.01 * (double)((h >> 24) % 21u);
    double sector = hue / 60.0, f = sector - std::floor(sector);
    double p = v * (1.0 - s), q = v * (1.0 - s * f), t = v * (1.0 - s * (1.0 - f));
    double c[3]; /* HSV to RGB in the two sectors the hues are in */
    if (sector < 2.0) /* 70 to 120: yellow-green to green */
        c[0] = q, c[1] = v, c[2] = p;
    else /* 120 to 160: green to sea green */
        c[0] = p, c[1] = v, c[2] = t;
    for (int k = 0; k < 3; ++k)
        rgb[k] = (unsigned char)std::lround(255.0 * c[k]);
}

/* The file's vertex of the unit's vertex v: the written mesh has the
   file's vertices, shared by its faces as in the file, not the library's
   (an OBJ's (v, vn) pairs would split a cube into six loose quads). */
namespace {
uint32_t file_vertex_of(const Unit &u, uint32_t v) { return u.file_vertex.empty() ? v : u.file_vertex[v]; }

/* The colour of a triangle in the --mark PLY. */
void mark_colour(const Unit &u, const UnitResult &r, size_t t, unsigned char rgb[3])
{
    static const unsigned char flipped[3] = {230, 30, 30}, doubtful_rgb[3] = {255, 176, 0}, none[3] = {40, 40, 40};
    const unsigned char *c = none;
    switch (mark_of(u, r, t)) {
    case Mark::doubtful:
        c = doubtful_rgb;
        break;
    case Mark::flipped:
        c = flipped;
        break;
    case Mark::none:
        break;
    case Mark::kept:
        patch_tint(r.patch_ids[t], rgb);
        return;
    }
    rgb[0] = c[0], rgb[1] = c[1], rgb[2] = c[2];
}

void put_u32le(std::string &out, uint32_t v)
{
    for (int k = 0; k < 4; ++k)
        out += (char)(unsigned char)(v >> (8 * k));
}

void put_f32le(std::string &out, float f)
{
    uint32_t v;
    std::memcpy(&v, &f, 4);
    put_u32le(out, v);
}

/* The --mark PLY: binary little-endian, a colour per face and per vertex
   (Blender's PLY importer reads only the vertices' colours, MeshLab
   either). Vertex i is the file's vertex i, coloured as the first face
   that uses it; where a face of another colour uses it too, that face
   gets a copy of it in its colour (after the file's vertices, in the
   order the faces first need them), so that every corner of a face has
   the face's colour exactly. */
bool write_mark_ply(const std::string &path, const std::vector<float> &positions, const std::vector<unsigned int> &indices,
                    const std::vector<unsigned char> &face_rgb, std::string &error)
{
    const size_t n = positions.size() / 3, faces = indices.size() / 3;
    const uint32_t unset = 0xFFFFFFFFu;
    std::vector<uint32_t> colour_of(n, unset); /* the colour (r << 16 | g << 8 | b) vertex i has */
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> copies; /* (vertex, colour) -> its copy */
    std::vector<uint32_t> copy_of;                            /* the vertex each copy repeats */
    std::vector<unsigned int> corners(indices.size());
    for (size_t f = 0; f < faces; ++f) {
        const unsigned char *c = &face_rgb[3 * f];
        uint32_t colour = (uint32_t)c[0] << 16 | (uint32_t)c[1] << 8 | c[2];
        for (size_t k = 0; k < 3; ++k) {
            uint32_t v = indices[3 * f + k];
            if (colour_of[v] == unset)
                colour_of[v] = colour;
            if (colour_of[v] == colour) {
                corners[3 * f + k] = v;
                continue;
            }
            auto found = copies.emplace(std::make_pair(v, colour), (uint32_t)(n + copy_of.size()));
            if (found.second)
                copy_of.push_back(v), colour_of.push_back(colour);
            corners[3 * f + k] = found.first->second;
        }
    }
    if (n + copy_of.size() > 0xFFFFFFFFu) {
        error = "cannot write '" + path + "': too many vertices for the --mark PLY";
        return false;
    }
    std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by meshfix: --mark\n"
                      "element vertex " + std::to_string(n + copy_of.size()) +
                      "\nproperty float x\nproperty float y\nproperty float z\n"
                      "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                      "element face " + std::to_string(faces) +
                      "\nproperty list uchar uint vertex_indices\n"
                      "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
    out.reserve(out.size() + 15 * (n + copy_of.size()) + 16 * faces);
    for (size_t i = 0; i < n + copy_of.size(); ++i) {
        size_t v = i < n ? i : copy_of[i - n];
        uint32_t colour = colour_of[i] == unset ? 0x282828u : colour_of[i]; /* unused: the colour of no patch */
        for (size_t k = 0; k < 3; ++k)
            put_f32le(out, positions[3 * v + k]);
        out += (char)(unsigned char)(colour >> 16), out += (char)(unsigned char)(colour >> 8), out += (char)(unsigned char)colour;
    }
    for (size_t f = 0; f < faces; ++f) {
        out += (char)3;
        for (size_t k = 0; k < 3; ++k)
            put_u32le(out, corners[3 * f + k]);
        out.append((const char *)&face_rgb[3 * f], 3);
    }
    return write_bytes(path, out, error);
}
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
            unsigned char c[3];
            mark_colour(u, r, t, c);
            rgb.insert(rgb.end(), {c[0], c[1], c[2]});
        }
    }
    if (colours)
        return write_mark_ply(path, positions, indices, rgb, error);
    mio_mesh mesh;
    mesh.positions = positions.data();
    mesh.vertex_count = positions.size() / 3;
    mesh.indices = indices.data();
    mesh.index_count = indices.size();
    char message[256];
    if (!mio_save(path.c_str(), &mesh, nullptr, message, sizeof(message))) {
        error = message;
        return false;
    }
    return true;
}

} // namespace tool

namespace tool {

bool resolves_inside(const std::string &path, const std::string &directory)
{
    char *file = realpath(path.c_str(), nullptr), *base = realpath(directory.empty() ? "." : directory.c_str(), nullptr);
    std::string f = file != nullptr ? file : "", d = base != nullptr ? base : "";
    std::free(file);
    std::free(base);
    std::string prefix = d == "/" ? d : d + "/";
    return !f.empty() && !d.empty() && f.compare(0, prefix.size(), prefix) == 0;
}

namespace {

/* Whether a name in a file (an OBJ's mtllib, a map in its .mtl) is a path
   that stays below the directory it is read from: relative, no "..", no
   backslash or drive, and, its symbolic links followed, inside it. */
bool stays_inside(const std::string &directory, const std::string &name)
{
    if (name.empty() || name[0] == '/' || name.find('\\') != std::string::npos || name.find(':') != std::string::npos ||
        name.find('\0') != std::string::npos)
        return false;
    for (size_t at = 0; at <= name.size();) {
        size_t slash = std::min(name.find('/', at), name.size());
        if (name.compare(at, slash - at, "..") == 0 && slash - at == 2)
            return false;
        at = slash + 1;
    }
    struct stat st;
    return resolves_inside(directory + "/" + name, directory) && stat((directory + "/" + name).c_str(), &st) == 0 &&
           S_ISREG(st.st_mode);
}

/* "sub/../tex/t.png" as "tex/t.png": a ".." that goes back into the
   directory is no way out of it (one that goes above is kept, and
   refused). */
std::string collapse(const std::string &path)
{
    std::vector<std::string> parts;
    for (size_t at = 0; at <= path.size();) {
        size_t slash = std::min(path.find('/', at), path.size());
        std::string part = path.substr(at, slash - at);
        if (part == ".." && !parts.empty() && parts.back() != "..")
            parts.pop_back();
        else if (!part.empty() && part != ".")
            parts.push_back(part);
        at = slash + 1;
    }
    std::string out;
    for (const std::string &part : parts)
        out += (out.empty() ? "" : "/") + part;
    return out;
}

/* The file names a line gives after its keyword: the rest of the line when
   that names a file (a name with spaces), else each word. */
std::vector<std::string> line_names(const std::string &directory, const std::string &rest)
{
    std::string trimmed = rest;
    while (!trimmed.empty() && std::isspace((unsigned char)trimmed.back()))
        trimmed.pop_back();
    size_t start = trimmed.find_first_not_of(" \t");
    trimmed = start == std::string::npos ? "" : trimmed.substr(start);
    if (stays_inside(directory, trimmed))
        return {trimmed};
    std::vector<std::string> words;
    for (size_t at = 0; at < trimmed.size();) {
        size_t end = trimmed.find_first_of(" \t", at);
        end = end == std::string::npos ? trimmed.size() : end;
        if (end > at)
            words.push_back(trimmed.substr(at, end - at));
        at = end + 1;
    }
    return words;
}

/* The lines of a text file that start with one of `keywords`, each as the
   rest of the line. */
std::vector<std::string> keyword_lines(const std::string &text, const std::vector<std::string> &keywords)
{
    std::vector<std::string> found;
    for (size_t at = 0; at < text.size();) {
        size_t end = text.find_first_of("\r\n", at);
        end = end == std::string::npos ? text.size() : end;
        std::string line = text.substr(at, end - at);
        size_t start = line.find_first_not_of(" \t");
        if (start != std::string::npos) {
            size_t word_end = line.find_first_of(" \t", start);
            std::string word = line.substr(start, word_end == std::string::npos ? std::string::npos : word_end - start);
            for (const std::string &k : keywords)
                if (word == k && word_end != std::string::npos)
                    found.push_back(line.substr(word_end));
        }
        at = end + 1;
    }
    return found;
}

} // namespace

std::vector<std::string> obj_companions(const std::string &obj_path, const std::string &obj_text)
{
    std::string directory = directory_of(obj_path), data, error;
    std::vector<std::string> files;
    auto add = [&](const std::string &given) {
        std::string name = collapse(given);
        if (stays_inside(directory, name) && std::find(files.begin(), files.end(), name) == files.end()) {
            files.push_back(name);
            return true;
        }
        return false;
    };
    static const std::vector<std::string> maps = {"map_Ka", "map_Kd", "map_Ks", "map_Ke", "map_Ns", "map_d", "map_bump",
                                                  "map_Bump", "bump", "disp", "decal", "refl", "norm", "map_Pr",
                                                  "map_Pm", "map_Ps"};
    for (const std::string &rest : keyword_lines(obj_text, {"mtllib"}))
        for (const std::string &mtl : line_names(directory, rest)) {
            if (!add(mtl) || !read_file(directory + "/" + collapse(mtl), data, error))
                continue;
            /* a map's name is the last word of its line (options come first),
               relative to the .mtl's directory */
            std::string mtl_directory = collapse(mtl).find('/') == std::string::npos ? "" : directory_of(collapse(mtl)) + "/";
            for (const std::string &line : keyword_lines(data, maps)) {
                std::vector<std::string> words = line_names(directory + "/" + mtl_directory, line);
                if (!words.empty())
                    add(mtl_directory + words.back());
            }
        }
    return files;
}

} // namespace tool
