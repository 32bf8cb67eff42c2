// OpenMesh as an independent oracle for meshfix.h (C++, links OpenMeshCore).
//
// OpenMesh builds a half-edge structure and refuses a face that would make an
// edge "complex": a face that runs an edge in the direction an earlier face
// already used. So:
//   - a scrambled manifold mesh loses faces when loaded into OpenMesh;
//   - after meshfix_orient it must load with no face refused;
//   - OpenMesh's own counts of faces, edges, boundary edges, used vertices
//     and face-connected components must equal meshfix's report.
// Prints "N passed, N failed".
#define MESHFIX_IMPLEMENTATION
#include "../meshfix.h"
#define MESHIO_IMPLEMENTATION
#include "../examples/meshio.h"
#define MESHGEN_IMPLEMENTATION
#include "../examples/meshgen.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

typedef OpenMesh::TriMesh_ArrayKernelT<> OmMesh;

struct OmCounts {
    size_t refused = 0, faces = 0, edges = 0, boundary = 0, vertices_used = 0, components = 0;
    bool aborted = false; // OpenMesh hit one of its own assertions
};

static OmCounts count_in_openmesh(const mio_mesh &g, const unsigned int *indices)
{
    OmMesh om;
    OmCounts c;
    std::vector<OmMesh::VertexHandle> v(g.vertex_count);
    for (size_t i = 0; i < g.vertex_count; ++i)
        v[i] = om.add_vertex(OmMesh::Point(g.positions[3 * i], g.positions[3 * i + 1], g.positions[3 * i + 2]));
    for (size_t t = 0; t < g.index_count / 3; ++t) {
        const unsigned int *i = indices + 3 * t;
        if (i[0] == i[1] || i[1] == i[2] || i[0] == i[2])
            continue; // a repeated vertex: no face at all (meshfix leaves it out of the topology too)
        OmMesh::FaceHandle f = om.add_face(v[indices[3 * t]], v[indices[3 * t + 1]], v[indices[3 * t + 2]]);
        if (!f.is_valid())
            c.refused++;
    }
    c.faces = om.n_faces();
    c.edges = om.n_edges();
    for (OmMesh::EdgeIter e = om.edges_begin(); e != om.edges_end(); ++e)
        c.boundary += om.is_boundary(*e) ? 1 : 0;
    for (OmMesh::VertexIter vi = om.vertices_begin(); vi != om.vertices_end(); ++vi)
        c.vertices_used += om.is_isolated(*vi) ? 0 : 1;
    // face-connected components, by OpenMesh's own adjacency
    std::vector<char> seen(om.n_faces(), 0);
    std::vector<OmMesh::FaceHandle> stack;
    for (OmMesh::FaceIter f = om.faces_begin(); f != om.faces_end(); ++f) {
        if (seen[f->idx()])
            continue;
        c.components++;
        seen[f->idx()] = 1;
        stack.push_back(*f);
        while (!stack.empty()) {
            OmMesh::FaceHandle cur = stack.back();
            stack.pop_back();
            for (OmMesh::FaceFaceIter n = om.ff_iter(cur); n.is_valid(); ++n)
                if (!seen[n->idx()]) {
                    seen[n->idx()] = 1;
                    stack.push_back(*n);
                }
        }
    }
    return c;
}

// Debian's OpenMesh keeps its assertions, and add_face can abort on input
// it cannot link (seen: "boundary_prev.is_valid()"). Each load runs in a
// child process; an abort is reported, not fatal to the test.
static OmCounts load_into_openmesh(const mio_mesh &g, const unsigned int *indices)
{
    OmCounts c;
    int fds[2], status = 0;
    if (pipe(fds) != 0)
        return c;
    std::fflush(stdout);
    pid_t child = fork();
    if (child == 0) {
        close(fds[0]);
        OmCounts counted = count_in_openmesh(g, indices);
        ssize_t written = write(fds[1], &counted, sizeof(counted));
        _exit(written == (ssize_t)sizeof(counted) ? 0 : 1);
    }
    close(fds[1]);
    ssize_t got = child > 0 ? read(fds[0], &c, sizeof(c)) : -1;
    close(fds[0]);
    if (child > 0)
        waitpid(child, &status, 0);
    if (got != (ssize_t)sizeof(c) || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        c = OmCounts();
        c.aborted = true;
    }
    return c;
}

static int failures = 0;
#define EXPECT_EQ(name, a, b)                                                                                  \
    do {                                                                                                       \
        if ((size_t)(a) != (size_t)(b)) {                                                                      \
            std::printf("    %s: %s == %lu, expected %s == %lu\n", name, #a, (unsigned long)(a), #b,           \
                        (unsigned long)(b));                                                                   \
            failures++;                                                                                        \
        }                                                                                                      \
    } while (0)

// One mesh: scramble, check OpenMesh refuses faces, repair, check it refuses
// none and agrees with the report.
static bool check_mesh(const char *name, const mio_mesh &g)
{
    int before = failures;
    std::vector<unsigned int> scrambled(g.indices, g.indices + g.index_count);
    mio_mesh s = g;
    s.indices = scrambled.data();
    gen_flip_random(&s, 0.3, 77, NULL);

    // OpenMesh joins faces by vertex index: meshfix is asked to do the same
    meshfix_options by_index = {};
    by_index.topology = MESHFIX_TOPOLOGY_INDICES;
    meshfix_report input, r;
    EXPECT_EQ(name, meshfix_inspect(s.indices, s.index_count, s.positions, s.vertex_count, 12, &by_index, &input, NULL),
              MESHFIX_OK);
    OmCounts bad = load_into_openmesh(g, s.indices);
    if (input.mesh.edges_inconsistent == 0 || (bad.refused == 0 && !bad.aborted)) {
        std::printf("    %s: scrambled input should be inconsistent and refused by OpenMesh (%lu edges, %lu faces)\n",
                    name, (unsigned long)input.mesh.edges_inconsistent, (unsigned long)bad.refused);
        failures++;
    }

    std::vector<unsigned int> fixed(g.index_count);
    EXPECT_EQ(name, meshfix_orient(fixed.data(), s.indices, s.index_count, s.positions, s.vertex_count, 12, &by_index, &r, NULL),
              MESHFIX_OK);
    EXPECT_EQ(name, r.mesh.edges_inconsistent, 0);
    OmCounts good = load_into_openmesh(g, fixed.data());
    bool manifold = r.mesh.vertices_non_manifold == 0 && r.mesh.edges_non_manifold == 0;
    if (manifold) {
        // a manifold mesh: OpenMesh must take every face
        EXPECT_EQ(name, good.aborted, false);
        EXPECT_EQ(name, good.refused, 0);
    }
    if (manifold || (good.refused == 0 && !good.aborted)) {
        // whenever it took every face, it must count as we do
        EXPECT_EQ(name, good.faces, r.mesh.triangles - r.mesh.triangles_degenerate);
        EXPECT_EQ(name, good.edges, r.mesh.edges);
        EXPECT_EQ(name, good.boundary, r.mesh.edges_boundary);
        EXPECT_EQ(name, good.vertices_used, r.mesh.vertices_used);
        EXPECT_EQ(name, good.components, r.mesh.components);
    } else if (r.mesh.edges_inconsistent != 0) {
        std::printf("    %s: non-manifold and still inconsistent\n", name);
        failures++;
    }
    // OpenMesh refuses consistent faces only at complex (non-manifold)
    // vertices: every refusal must be explained by one meshfix reports.
    if ((good.refused != 0 || good.aborted) && r.mesh.vertices_non_manifold == 0) {
        std::printf("    %s: OpenMesh refused repaired faces but meshfix reports no non-manifold vertex\n", name);
        failures++;
    }
    bool ok = failures == before;
    char refused[64];
    if (bad.aborted)
        std::snprintf(refused, sizeof(refused), "OpenMesh aborted");
    else
        std::snprintf(refused, sizeof(refused), "%lu faces refused", (unsigned long)bad.refused);
    std::printf("%s %s: %lu triangles; scrambled: %s; repaired: %s%lu refused (%lu non-manifold vertices), "
                "boundary %lu, components %lu\n",
                ok ? "ok  " : "FAIL", name, (unsigned long)(g.index_count / 3), refused,
                good.aborted ? "OpenMesh aborted, " : "", (unsigned long)good.refused,
                (unsigned long)r.mesh.vertices_non_manifold, (unsigned long)good.boundary, (unsigned long)good.components);
    return ok;
}

int main()
{
    omerr().disable(); // it prints every refused face
    size_t passed = 0, failed = 0;
    const char *dir = std::getenv("MESHFIX_MODELS") ? std::getenv("MESHFIX_MODELS") : "/usr/share/assimp/models";

    // generated meshes
    struct Generated {
        const char *name;
        int kind;
    } generated[] = {{"sphere", 0}, {"torus", 1}, {"terrain sheet", 2}, {"sphere + torus", 3}};
    for (const Generated &gm : generated) {
        mio_mesh g, extra;
        bool made = false;
        if (gm.kind == 0)
            made = gen_sphere(&g, 60, 90, 0, 0, 0, 1);
        else if (gm.kind == 1)
            made = gen_torus(&g, 120, 40, 2, 0.6f);
        else if (gm.kind == 2)
            made = gen_grid(&g, 100, 80);
        else if ((made = gen_sphere(&g, 30, 40, 0, 0, 0, 1) && gen_torus(&extra, 50, 20, 3, 0.5f))) {
            made = gen_append(&g, &extra);
            mio_free(&extra);
        }
        if (!made) {
            failed++;
            continue;
        }
        (check_mesh(gm.name, g) ? passed : failed)++;
        mio_free(&g);
    }

    // real models: the manifold ones of Debian's assimp-testmodels
    const char *files[] = {"OBJ/WusonOBJ.obj", "OBJ/spider.obj", "OBJ/regr01.obj",      "OBJ/box.obj",
                           "OFF/Wuson.off",    "OFF/Cube.off",   "PLY/cube_binary.ply", "STL/Spider_binary.stl",
                           "STL/Wuson.stl",    "STL/sphereWithHole.stl"};
    for (const char *file : files) {
        std::string path = std::string(dir) + "/" + file;
        char error[256];
        mio_mesh g;
        if (!mio_load(path.c_str(), &g, error, sizeof(error))) {
            std::printf("FAIL %s: %s (install Debian's assimp-testmodels)\n", path.c_str(), error);
            failed++;
            continue;
        }
        (check_mesh(file, g) ? passed : failed)++;
        mio_free(&g);
    }
    std::printf("%lu passed, %lu failed\n", (unsigned long)passed, (unsigned long)failed);
    return failed != 0;
}
