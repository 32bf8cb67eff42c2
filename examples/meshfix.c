/* meshfix - command-line winding repair built on meshfix.h

   usage: meshfix [--policy auto|seed|majority|outward|visibility|up]
                  [--weld TOLERANCE] [--mark FILE.ply] [--inspect] [--quiet]
                  INPUT OUTPUT

   Reads INPUT (.obj .off .stl .ply), --weld merges vertices closer than
   TOLERANCE (polygon soups, CAD exports), prints the inspect report, repairs the
   winding with the chosen policy, prints the report of the result and
   writes OUTPUT in the format its extension names. --mark writes the
   result with face colours: flipped faces red, the others tinted by patch.
   --inspect only reports (no OUTPUT). Exit status: 0 success, 1 bad
   arguments or file, 2 the library refused the mesh.

   INPUT must be a regular file (a directory or FIFO is refused before it
   is read). The outputs are written all or nothing: each goes to a new
   temporary file next to its target, created before the input is read,
   and the temporaries are renamed into place only after all of them were
   written; on any failure they are removed and no target is touched.
   POSIX (open, fdopen, rename). */
#define _POSIX_C_SOURCE 200809L
#define _FILE_OFFSET_BITS 64 /* stat and read files over 2 GiB on 32-bit systems */
#define MESHFIX_IMPLEMENTATION
#include "../meshfix.h"
#define MESHIO_IMPLEMENTATION
#include "meshio.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* the policies a file can use (SDF needs a function: see sdf_demo.c) */
#define POLICY_NAMES 6
static const char *const policy_names[POLICY_NAMES] = {"auto", "seed", "majority", "outward", "visibility", "up"};
static const meshfix_policy policy_values[POLICY_NAMES] = {MESHFIX_POLICY_AUTO,    MESHFIX_POLICY_SEED,
                                                           MESHFIX_POLICY_MAJORITY, MESHFIX_POLICY_OUTWARD,
                                                           MESHFIX_POLICY_VISIBILITY, MESHFIX_POLICY_UP};

static const char *policy_name(meshfix_policy p)
{
    int i;
    for (i = 0; i < POLICY_NAMES; ++i)
        if (policy_values[i] == p)
            return policy_names[i];
    return "?";
}

/* Merges vertices closer than `tolerance` and rewrites the indices. */
static int weld(mio_mesh *mesh, float tolerance)
{
    unsigned int *remap = (unsigned int *)malloc(mesh->vertex_count * sizeof(unsigned int) + 1);
    size_t i, unique = 0;
    meshfix_result r;
    if (remap == NULL)
        return 0;
    r = meshfix_weld(remap, mesh->positions, mesh->vertex_count, 12, tolerance, NULL, &unique);
    if (r != MESHFIX_OK) {
        fprintf(stderr, "meshfix: weld: %s\n", meshfix_result_string(r));
        free(remap);
        return 0;
    }
    for (i = 0; i < mesh->index_count; ++i)
        mesh->indices[i] = remap[mesh->indices[i]];
    printf("welded %lu vertices into %lu (tolerance %g)\n", (unsigned long)mesh->vertex_count, (unsigned long)unique,
           (double)tolerance);
    free(remap);
    return 1;
}

static void print_report(const char *title, const meshfix_report *r)
{
    printf("%s\n", title);
    printf("  triangles %lu (degenerate %lu, zero area %lu, duplicate %lu)\n", (unsigned long)r->mesh.triangles,
           (unsigned long)r->mesh.triangles_degenerate, (unsigned long)r->mesh.triangles_zero_area,
           (unsigned long)r->mesh.triangles_duplicate);
    printf("  vertices  %lu used (%lu not finite, %lu non-manifold)\n", (unsigned long)r->mesh.vertices_used,
           (unsigned long)r->mesh.vertices_non_finite, (unsigned long)r->mesh.vertices_non_manifold);
    printf("  edges     %lu: boundary %lu, manifold %lu, non-manifold %lu, inconsistent %lu\n",
           (unsigned long)r->mesh.edges, (unsigned long)r->mesh.edges_boundary, (unsigned long)r->mesh.edges_manifold,
           (unsigned long)r->mesh.edges_non_manifold, (unsigned long)r->mesh.edges_inconsistent);
    printf("  patches   %lu (closed %lu, inside-out %lu)\n", (unsigned long)r->mesh.patches,
           (unsigned long)r->mesh.patches_closed, (unsigned long)r->mesh.patches_inside_out);
    printf("  components %lu (closed %lu, non-orientable %lu), Euler characteristic %ld\n",
           (unsigned long)r->mesh.components, (unsigned long)r->mesh.components_closed,
           (unsigned long)r->mesh.components_non_orientable, r->mesh.euler_characteristic);
    printf("  area %.6g, signed volume of closed patches %.6g\n", r->mesh.area, r->mesh.signed_volume);
    if (r->evidence.rays_cast != 0 || r->evidence.shells_inward != 0)
        printf("  visibility: %lu rays cast, %lu patch pairs, %lu merges, %lu pairs left against their coherence, "
               "%lu cavities\n", (unsigned long)r->evidence.rays_cast, (unsigned long)r->evidence.patch_pairs,
               (unsigned long)r->evidence.patches_merged, (unsigned long)r->evidence.pairs_conflicting, (unsigned long)r->evidence.shells_inward);
}

/* Flipped faces red; the rest a muted colour per patch, so patch seams show. */
static unsigned char *face_colours(const unsigned char *flipped, const unsigned int *patch_ids, size_t triangles)
{
    unsigned char *rgb = (unsigned char *)malloc(3 * triangles + 1);
    size_t t;
    if (rgb == NULL)
        return NULL;
    for (t = 0; t < triangles; ++t) {
        unsigned int h = patch_ids[t] * 2654435761u;
        if (flipped[t]) {
            rgb[3 * t] = 230, rgb[3 * t + 1] = 30, rgb[3 * t + 2] = 30;
        } else if (patch_ids[t] == 0xFFFFFFFFu) {
            rgb[3 * t] = 40, rgb[3 * t + 1] = 40, rgb[3 * t + 2] = 40;
        } else {
            rgb[3 * t] = (unsigned char)(90 + (h >> 8) % 80);
            rgb[3 * t + 1] = (unsigned char)(120 + (h >> 16) % 100);
            rgb[3 * t + 2] = (unsigned char)(140 + (h >> 24) % 100);
        }
    }
    return rgb;
}

/* An output being written: a temporary file next to `target`, renamed onto
   it by output_commit, removed by output_discard. */
typedef struct output_file {
    const char *target;
    const char *format;
    char *temporary; /* NULL when there is none (not opened, committed or discarded) */
    FILE *f;
} output_file;

/* Checks the target and creates its temporary; 0 (after a one-line
   message) when the target cannot be written. */
static int output_open(output_file *o, const char *target)
{
    struct stat st;
    size_t size = strlen(target) + 64;
    int fd = -1, k, exists;
    memset(o, 0, sizeof(*o));
    o->target = target;
    if ((o->format = mio_format(target)) == NULL) {
        fprintf(stderr, "meshfix: unknown output format '%s' (use .obj, .off, .stl or .ply)\n", target);
        return 0;
    }
    exists = stat(target, &st) == 0;
    if (exists && !S_ISREG(st.st_mode)) {
        fprintf(stderr, "meshfix: cannot write '%s': %s\n", target,
                S_ISDIR(st.st_mode) ? "it is a directory" : "it is not a regular file");
        return 0;
    }
    /* a read-only target stays refused, as when it was written in place */
    if (exists && access(target, W_OK) != 0) {
        fprintf(stderr, "meshfix: cannot write '%s': %s\n", target, strerror(errno));
        return 0;
    }
    if ((o->temporary = (char *)malloc(size)) == NULL) {
        fprintf(stderr, "meshfix: out of memory\n");
        return 0;
    }
    /* O_EXCL: never write through a file or link that is already there */
    for (k = 0; k < 100 && fd < 0; ++k) {
        snprintf(o->temporary, size, "%s.meshfix-%ld-%d.tmp", target, (long)getpid(), k);
        fd = open(o->temporary, O_WRONLY | O_CREAT | O_EXCL, 0666);
        if (fd < 0 && errno != EEXIST)
            break;
    }
    if (fd < 0) {
        fprintf(stderr, "meshfix: cannot write '%s': %s\n", target, strerror(errno));
        free(o->temporary);
        o->temporary = NULL;
        return 0;
    }
    if (exists)
        (void)fchmod(fd, st.st_mode & 07777); /* a replaced file keeps its permissions */
    if ((o->f = fdopen(fd, "wb")) == NULL) {
        fprintf(stderr, "meshfix: cannot write '%s': %s\n", target, strerror(errno));
        close(fd);
        remove(o->temporary);
        free(o->temporary);
        o->temporary = NULL;
        return 0;
    }
    return 1;
}

/* Writes the mesh into the temporary and closes it. */
static int output_write(output_file *o, const mio_mesh *mesh, const unsigned char *face_rgb)
{
    char error[256];
    int ok = mio_write(o->f, o->format, mesh, face_rgb, o->target, error, sizeof(error));
    if (fclose(o->f) != 0 && ok) {
        snprintf(error, sizeof(error), "error writing '%s'", o->target);
        ok = 0;
    }
    o->f = NULL;
    if (!ok)
        fprintf(stderr, "meshfix: %s\n", error);
    return ok;
}

static int output_commit(output_file *o)
{
    if (rename(o->temporary, o->target) != 0) {
        fprintf(stderr, "meshfix: cannot write '%s': %s\n", o->target, strerror(errno));
        return 0;
    }
    free(o->temporary);
    o->temporary = NULL;
    return 1;
}

/* Removes the temporary, if any is left; safe to call more than once. */
static void output_discard(output_file *o)
{
    if (o->f != NULL)
        fclose(o->f);
    o->f = NULL;
    if (o->temporary != NULL)
        remove(o->temporary);
    free(o->temporary);
    o->temporary = NULL;
}

static int usage(void)
{
    fprintf(stderr, "usage: meshfix [--policy auto|seed|majority|outward|visibility|up] [--weld TOLERANCE]\n"
                    "               [--mark FILE.ply] [--quiet] INPUT OUTPUT\n"
                    "       meshfix --inspect [--weld TOLERANCE] INPUT\n");
    return 1;
}

int main(int argc, char **argv)
{
    const char *input = NULL, *output = NULL, *mark = NULL;
    int quiet = 0, inspect_only = 0, i, status = 0;
    float weld_tolerance = -1.0f;
    char error[256];
    mio_mesh mesh;
    meshfix_options options;
    meshfix_outputs outputs;
    meshfix_report before, after;
    meshfix_result r;
    output_file out, marked;
    size_t triangles;

    memset(&options, 0, sizeof(options));

    memset(&outputs, 0, sizeof(outputs));
    memset(&out, 0, sizeof(out));
    memset(&marked, 0, sizeof(marked));
    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--policy") == 0 && i + 1 < argc) {
            int p;
            for (p = 0; p < POLICY_NAMES && strcmp(argv[i + 1], policy_names[p]) != 0; ++p) {
            }
            if (p == POLICY_NAMES) {
                fprintf(stderr, "meshfix: unknown policy '%s'\n", argv[i + 1]);
                return 1;
            }
            options.policy = policy_values[p];
            ++i;
        } else if (strcmp(argv[i], "--weld") == 0 && i + 1 < argc) {
            char *end;
            weld_tolerance = strtof(argv[++i], &end);
            if (*end != 0 || !(weld_tolerance >= 0.0f)) {
                fprintf(stderr, "meshfix: --weld takes a tolerance >= 0, not '%s'\n", argv[i]);
                return 1;
            }
        } else if (strcmp(argv[i], "--mark") == 0 && i + 1 < argc) {
            size_t n = strlen(argv[++i]);
            mark = argv[i];
            if (n < 4 || strcmp(mark + n - 4, ".ply") != 0) {
                fprintf(stderr, "meshfix: --mark writes PLY (face colours): give a .ply file\n");
                return 1;
            }
        } else if (strcmp(argv[i], "--quiet") == 0) {
            quiet = 1;
        } else if (strcmp(argv[i], "--inspect") == 0) {
            inspect_only = 1;
        } else if (argv[i][0] == '-' && argv[i][1] != 0) {
            return usage();
        } else if (input == NULL) {
            input = argv[i];
        } else if (output == NULL) {
            output = argv[i];
        } else {
            return usage();
        }
    }
    if (input == NULL || (output == NULL && !inspect_only))
        return usage();

    /* every output must be writable before anything is read or repaired */
    if (!inspect_only && (!output_open(&out, output) || (mark != NULL && !output_open(&marked, mark)))) {
        output_discard(&out);
        output_discard(&marked);
        return 1;
    }
    if (!mio_load(input, &mesh, error, sizeof(error))) {
        fprintf(stderr, "meshfix: %s: %s\n", input, error);
        output_discard(&out);
        output_discard(&marked);
        return 1;
    }
    if (weld_tolerance >= 0.0f && !weld(&mesh, weld_tolerance)) {
        status = 2;
    } else if ((r = meshfix_inspect(mesh.indices, mesh.index_count, mesh.positions, mesh.vertex_count, 12, NULL,
                                    &before, NULL)) != MESHFIX_OK) {
        fprintf(stderr, "meshfix: %s: %s\n", input, meshfix_result_string(r));
        status = 2;
    } else if (!quiet) {
        print_report(input, &before);
    }
    if (status != 0 || inspect_only) {
        output_discard(&out);
        output_discard(&marked);
        mio_free(&mesh);
        return status;
    }

    triangles = mesh.index_count / 3;
    outputs.flipped = (unsigned char *)malloc(triangles + 1);
    outputs.patch_ids = (unsigned int *)malloc(sizeof(unsigned int) * triangles + 1);
    if (outputs.flipped == NULL || outputs.patch_ids == NULL) {
        fprintf(stderr, "meshfix: out of memory\n");
        status = 1;
    } else if ((r = meshfix_orient(mesh.indices, mesh.indices, mesh.index_count, mesh.positions, mesh.vertex_count,
                                   12, &options, &after, &outputs)) != MESHFIX_OK) {
        fprintf(stderr, "meshfix: %s: %s\n", input, meshfix_result_string(r));
        status = 2;
    } else {
        unsigned char *rgb = NULL;
        if (!quiet) {
            printf("repair (policy %s): flipped %lu of %lu triangles\n", policy_name(options.policy),
                   (unsigned long)after.triangles_flipped, (unsigned long)after.mesh.triangles);
            print_report(output, &after);
        }
        if (mark != NULL && (rgb = face_colours(outputs.flipped, outputs.patch_ids, triangles)) == NULL) {
            fprintf(stderr, "meshfix: out of memory\n");
            status = 1;
        } else if (!output_write(&out, &mesh, NULL) || (mark != NULL && !output_write(&marked, &mesh, rgb))) {
            status = 1;
        } else if (!output_commit(&out) || (mark != NULL && !output_commit(&marked))) {
            status = 1;
        }
        free(rgb);
    }
    output_discard(&out);
    output_discard(&marked);
    free(outputs.flipped);
    free(outputs.patch_ids);
    mio_free(&mesh);
    return status;
}
