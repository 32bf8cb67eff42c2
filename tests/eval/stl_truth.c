/* stl_truth.c - scores meshfix winding repair against the facet normals stored in STL files

   An STL file keeps, beside each triangle, the normal its exporter computed
   (a CAD kernel, a slicer, a CFD tool): a record, independent of meshfix, of
   the side each triangle was meant to face. A stored normal is clear when it
   is finite and non-zero, the triangle's geometric normal (b - a) x (c - a)
   is not zero, and the two lie within 60 degrees of one line (|cos| >= 0.5);
   a clear triangle agrees when they point the same way. Per file, after
   welding the corners with meshfix_weld, in % of clear triangles:

       ship%     agree as shipped (no repair);
       best%     the most that turning whole patches can reach (below
                 ship% only where the shipped winding contradicts itself);
       fix%      agree after meshfix_orient on the shipped winding;
       damaged   clear triangles that agreed as shipped and do not after it;
       half%     agree after reversing a seeded random half of the
                 triangles and repairing that: the shipped winding no
                 longer hints at the answer;
       ms        the orient call on the shipped winding (report included);
       patches, parts (components), boundary edges, and inconsistent edges
       as shipped: its report.

   A file is marked when its normals cannot serve as truth: no clear
   normal at all, or more oblique normals than clear ones (normals written
   in another frame). The totals, weighted by clear triangles, and the mean
   of the files are given over all files and over the unmarked ones.
   --csv writes one row per file with counts instead of percentages, and a
   note column for files that were not scored; no total rows.

   Build:  cc -std=c99 -O2 -I. tests/eval/stl_truth.c -lm
   --normals passes the stored normals to meshfix as evidence (what the
   command-line tool does with a file's normals).

   --rows FILE writes a line per patch for tests/eval/fit.c, and the text
   output ends with the reliability of the reported confidence
   (tests/eval/calibration.h).

   Usage:  stl_truth [--policy NAME] [--normals] [--seed N] [--csv] [--rows FILE] FILE_OR_DIRECTORY...
           NAME: default (options NULL), auto, seed, majority, outward,
           visibility, up. Directories are searched for *.stl recursively.
   Exit:   0; 1 for bad usage; 2 when a meshfix call failed on a file.

   The STL reader is this file's own: examples/meshio.h drops the stored
   normals. Files are not trusted: the triangle count of a binary file is
   checked against its size and every ASCII token is validated; a bad file
   is refused with a message. */
#define _POSIX_C_SOURCE 200809L
#define CALIBRATION_IMPLEMENTATION
#include "tests/eval/calibration.h"
#define MESHFIX_IMPLEMENTATION
#include "meshfix.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#define ERROR_SIZE 256
/* meshfix takes at most 2^31 - 1 indices. */
#define MAX_TRIANGLES (0x7FFFFFFFu / 3u)

/* ---- policies ---- */

typedef struct policy_choice {
    const char *name;
    int named;             /* 0: the library default, options NULL */
    meshfix_policy policy; /* when named */
} policy_choice;

static const policy_choice POLICIES[] = {
    {"default", 0, MESHFIX_POLICY_AUTO},
    {"auto", 1, MESHFIX_POLICY_AUTO},
    {"seed", 1, MESHFIX_POLICY_SEED},
    {"majority", 1, MESHFIX_POLICY_MAJORITY},
    {"outward", 1, MESHFIX_POLICY_OUTWARD},
    {"visibility", 1, MESHFIX_POLICY_VISIBILITY},
    {"up", 1, MESHFIX_POLICY_UP},
    {"normals", 1, MESHFIX_POLICY_NORMALS},
};

static const policy_choice *find_policy(const char *name)
{
    size_t i;
    for (i = 0; i < sizeof(POLICIES) / sizeof(POLICIES[0]); i++)
        if (strcmp(POLICIES[i].name, name) == 0)
            return &POLICIES[i];
    return NULL;
}

/* ---- small helpers ---- */

static int fail(char *error, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vsnprintf(error, ERROR_SIZE, format, args);
    va_end(args);
    return 0;
}

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

/* splitmix64: a fixed generator, so --seed N reverses the same triangles
   on every machine. */
static uint64_t next_random(uint64_t *state)
{
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static int has_stl_extension(const char *path)
{
    size_t n = strlen(path);
    const char *ext = ".stl";
    size_t i;
    if (n < 4)
        return 0;
    for (i = 0; i < 4; i++)
        if (tolower((unsigned char)path[n - 4 + i]) != ext[i])
            return 0;
    return 1;
}

/* ---- reading an STL file ---- */

typedef struct stl_mesh {
    size_t triangles, capacity;
    float *normals; /* 3 per triangle, as stored */
    float *corners; /* 9 per triangle */
    const char *format;
} stl_mesh;

static void stl_free(stl_mesh *mesh)
{
    free(mesh->normals);
    free(mesh->corners);
    memset(mesh, 0, sizeof(*mesh));
}

static int stl_reserve(stl_mesh *mesh, size_t triangles)
{
    float *normals, *corners;
    if (triangles <= mesh->capacity)
        return 1;
    if (triangles > SIZE_MAX / (9 * sizeof(float)))
        return 0;
    normals = (float *)realloc(mesh->normals, triangles * 3 * sizeof(float));
    if (normals != NULL)
        mesh->normals = normals;
    corners = (float *)realloc(mesh->corners, triangles * 9 * sizeof(float));
    if (corners != NULL)
        mesh->corners = corners;
    if (normals == NULL || corners == NULL)
        return 0;
    mesh->capacity = triangles;
    return 1;
}

static int stl_add(stl_mesh *mesh, const float normal[3], const float corners[9], char *error)
{
    if (mesh->triangles == MAX_TRIANGLES)
        return fail(error, "more than %u triangles", MAX_TRIANGLES);
    if (mesh->triangles == mesh->capacity &&
        !stl_reserve(mesh, mesh->capacity ? 2 * mesh->capacity : 1024))
        return fail(error, "out of memory");
    memcpy(mesh->normals + 3 * mesh->triangles, normal, 3 * sizeof(float));
    memcpy(mesh->corners + 9 * mesh->triangles, corners, 9 * sizeof(float));
    mesh->triangles++;
    return 1;
}

static int read_whole_file(const char *path, unsigned char **data, size_t *size, char *error)
{
    FILE *f = fopen(path, "rb");
    size_t capacity = 1 << 20, n = 0;
    unsigned char *buffer, *grown;
    int failed, code;
    if (f == NULL)
        return fail(error, "cannot open: %s", strerror(errno));
    buffer = (unsigned char *)malloc(capacity);
    while (buffer != NULL) {
        n += fread(buffer + n, 1, capacity - n, f);
        if (n < capacity)
            break; /* the end, or an error */
        grown = capacity <= SIZE_MAX / 2 ? (unsigned char *)realloc(buffer, 2 * capacity) : NULL;
        if (grown == NULL)
            free(buffer);
        buffer = grown;
        capacity *= 2;
    }
    failed = ferror(f);
    code = errno;
    fclose(f);
    if (buffer == NULL)
        return fail(error, "out of memory");
    if (failed) {
        free(buffer);
        return fail(error, "read error: %s", strerror(code));
    }
    *data = buffer;
    *size = n;
    return 1;
}

/* Little-endian on disk, whatever the machine. */
static uint32_t read_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static float read_f32(const unsigned char *p)
{
    uint32_t bits = read_u32(p);
    float value;
    memcpy(&value, &bits, sizeof(value));
    return value;
}

/* Binary STL: an 80-byte header, a triangle count, then 50 bytes per
   triangle: normal, three corners (12 floats) and a 2-byte attribute. */
static int stl_parse_binary(const unsigned char *data, stl_mesh *mesh, char *error)
{
    uint32_t count = read_u32(data + 80);
    float values[12];
    size_t t, k;
    if (count == 0)
        return fail(error, "binary STL with no triangles");
    if (count > MAX_TRIANGLES)
        return fail(error, "binary STL declares %lu triangles, too many", (unsigned long)count);
    if (!stl_reserve(mesh, count))
        return fail(error, "out of memory");
    for (t = 0; t < count; t++) {
        const unsigned char *record = data + 84 + 50 * t;
        for (k = 0; k < 12; k++)
            values[k] = read_f32(record + 4 * k);
        if (!stl_add(mesh, values, values + 3, error))
            return 0;
    }
    mesh->format = "binary";
    return 1;
}

/* ASCII STL: whitespace-separated tokens, keywords in any case. */
typedef struct stl_text {
    const char *start, *at, *end;
} stl_text;

static int is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

/* The next token, or 0 at the end of the text. */
static int text_token(stl_text *text, const char **token, size_t *length)
{
    while (text->at < text->end && is_blank(*text->at))
        text->at++;
    *token = text->at;
    while (text->at < text->end && !is_blank(*text->at))
        text->at++;
    *length = (size_t)(text->at - *token);
    return *length > 0;
}

static void text_skip_line(stl_text *text)
{
    while (text->at < text->end && *text->at != '\n')
        text->at++;
}

static size_t text_line_number(const stl_text *text)
{
    const char *p;
    size_t line = 1;
    for (p = text->start; p < text->at; p++)
        line += *p == '\n';
    return line;
}

static int token_is(const char *token, size_t length, const char *word)
{
    size_t i;
    if (strlen(word) != length)
        return 0;
    for (i = 0; i < length; i++)
        if (tolower((unsigned char)token[i]) != word[i])
            return 0;
    return 1;
}

/* A token for a message: at most 32 characters, control bytes as '?'. */
static const char *printable(char *out, const char *token, size_t length)
{
    size_t i, n = length < 32 ? length : 32;
    for (i = 0; i < n; i++)
        out[i] = isprint((unsigned char)token[i]) ? token[i] : '?';
    out[n] = '\0';
    return out;
}

static int text_expect(stl_text *text, const char *word, char *error)
{
    const char *token;
    size_t length;
    if (text_token(text, &token, &length) && token_is(token, length, word))
        return 1;
    return fail(error, "line %lu: '%s' expected", (unsigned long)text_line_number(text), word);
}

static int text_floats(stl_text *text, float *values, int count, char *error)
{
    const char *token;
    size_t length;
    char number[64], *stop, shown[33];
    int i;
    for (i = 0; i < count; i++) {
        if (!text_token(text, &token, &length))
            return fail(error, "line %lu: number expected", (unsigned long)text_line_number(text));
        if (length < sizeof(number)) {
            memcpy(number, token, length);
            number[length] = '\0';
            values[i] = (float)strtod(number, &stop);
            if (stop == number + length)
                continue;
        }
        return fail(error, "line %lu: '%s' is not a number", (unsigned long)text_line_number(text),
                    printable(shown, token, length));
    }
    return 1;
}

/* facet normal n n n outer loop (vertex x y z) x3 endloop endfacet,
   after the word "facet" has been read. */
static int text_facet(stl_text *text, stl_mesh *mesh, char *error)
{
    float normal[3], corners[9];
    int v;
    if (!text_expect(text, "normal", error) || !text_floats(text, normal, 3, error) ||
        !text_expect(text, "outer", error) || !text_expect(text, "loop", error))
        return 0;
    for (v = 0; v < 3; v++)
        if (!text_expect(text, "vertex", error) || !text_floats(text, corners + 3 * v, 3, error))
            return 0;
    if (!text_expect(text, "endloop", error) || !text_expect(text, "endfacet", error))
        return 0;
    return stl_add(mesh, normal, corners, error);
}

/* One or more "solid NAME ... endsolid NAME" blocks; a missing final
   endsolid is forgiven. */
static int stl_parse_ascii(const unsigned char *data, size_t size, stl_mesh *mesh, char *error)
{
    stl_text text;
    const char *token;
    size_t length;
    char shown[33];
    int in_solid = 0;
    text.start = text.at = (const char *)data;
    text.end = text.start + size;
    while (text_token(&text, &token, &length)) {
        if (!in_solid && token_is(token, length, "solid")) {
            text_skip_line(&text); /* the name may hold any words */
            in_solid = 1;
        } else if (in_solid && token_is(token, length, "facet")) {
            if (!text_facet(&text, mesh, error))
                return 0;
        } else if (in_solid && token_is(token, length, "endsolid")) {
            text_skip_line(&text);
            in_solid = 0;
        } else {
            text.at = token;
            return fail(error, "line %lu: unexpected '%s'", (unsigned long)text_line_number(&text),
                        printable(shown, token, length));
        }
    }
    if (mesh->triangles == 0)
        return fail(error, "ASCII STL with no triangles");
    mesh->format = "ascii";
    return 1;
}

static int starts_with_solid(const unsigned char *data, size_t size)
{
    size_t i = 0;
    while (i < size && is_blank((char)data[i]))
        i++;
    return size - i >= 5 && token_is((const char *)data + i, 5, "solid");
}

/* A file whose size is exactly what its binary header declares is binary,
   even when the header starts with "solid" (many exporters write that).
   Otherwise "solid" means ASCII, unless that fails and the file holds the
   triangles its binary count declares, with trailing bytes: an ASCII text
   read as a count asks for more than 500 million triangles. */
static int stl_parse(const unsigned char *data, size_t size, stl_mesh *mesh, char *error)
{
    int fits_binary = 0, exact_binary = 0;
    if (size >= 84) {
        uint32_t count = read_u32(data + 80);
        fits_binary = count <= (size - 84) / 50;
        exact_binary = fits_binary && (size - 84) % 50 == 0 && (size - 84) / 50 == count;
    }
    if (exact_binary)
        return stl_parse_binary(data, mesh, error);
    if (starts_with_solid(data, size)) {
        if (stl_parse_ascii(data, size, mesh, error))
            return 1;
        if (!fits_binary)
            return 0;
        stl_free(mesh); /* binary after all, its header starting with "solid" */
    }
    if (fits_binary)
        return stl_parse_binary(data, mesh, error);
    if (size == 0)
        return fail(error, "empty file");
    return fail(error, "not STL: no 'solid' and shorter than its binary triangle count needs");
}

static int stl_load(const char *path, stl_mesh *mesh, char *error)
{
    unsigned char *data = NULL;
    size_t size = 0;
    int ok;
    memset(mesh, 0, sizeof(*mesh));
    if (!read_whole_file(path, &data, &size, error))
        return 0;
    ok = stl_parse(data, size, mesh, error);
    free(data);
    if (!ok)
        stl_free(mesh);
    return ok;
}

/* ---- truth: what each stored normal says ---- */

typedef enum facet_truth {
    FACET_AGREES,     /* clear, same side as the winding */
    FACET_DISAGREES,  /* clear, the other side */
    FACET_NO_NORMAL,  /* stored normal zero or not finite */
    FACET_DEGENERATE, /* geometric normal of zero length */
    FACET_OBLIQUE     /* more than 60 degrees off the triangle's line */
} facet_truth;

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static facet_truth judge_facet(const float stored[3], const float corners[9])
{
    double n[3], u[3], v[3], g[3], nn, gg, cosine;
    int k;
    for (k = 0; k < 3; k++) {
        n[k] = stored[k];
        u[k] = (double)corners[3 + k] - corners[k];
        v[k] = (double)corners[6 + k] - corners[k];
    }
    g[0] = u[1] * v[2] - u[2] * v[1];
    g[1] = u[2] * v[0] - u[0] * v[2];
    g[2] = u[0] * v[1] - u[1] * v[0];
    nn = dot3(n, n); /* in double: no float normal or corner overflows here */
    gg = dot3(g, g);
    if (!isfinite(nn) || nn == 0.0)
        return FACET_NO_NORMAL;
    if (!isfinite(gg) || gg == 0.0)
        return FACET_DEGENERATE;
    cosine = dot3(n, g) / sqrt(nn * gg);
    if (fabs(cosine) < 0.5)
        return FACET_OBLIQUE;
    return cosine > 0.0 ? FACET_AGREES : FACET_DISAGREES;
}

/* ---- one file ---- */

typedef struct file_score {
    const char *format;
    size_t triangles, clear, no_normal, degenerate, oblique;
    size_t agree_shipped, agree_repaired, damaged, agree_half;
    size_t agree_best; /* the most that turning whole patches can reach */
    double orient_ms;
    size_t patches, components, edges_boundary;
    size_t edges_inconsistent; /* as shipped: 0 when the winding agrees with itself */
} file_score;

typedef enum file_status { FILE_SCORED, FILE_REFUSED, FILE_SKIPPED, FILE_FAILED } file_status;

/* Everything a file needs, freed in one place. */
typedef struct file_work {
    stl_mesh mesh;
    signed char *truth;      /* +1 agrees, -1 disagrees, 0 unclear */
    unsigned int *indices;   /* welded, shipped winding */
    unsigned int *altered;   /* half reversed */
    unsigned int *repaired;
    unsigned char *flipped;  /* by the repair of the shipped winding */
    unsigned char *reversed; /* the random half */
    unsigned char *flipped_half;
    unsigned char *flipped_seed; /* by the seed policy, for best_by_patch */
    unsigned int *patch_ids;
    size_t *patch_votes; /* per patch: clear triangles agreeing, disagreeing */
} file_work;

static void free_work(file_work *w)
{
    stl_free(&w->mesh);
    free(w->truth);
    free(w->indices);
    free(w->altered);
    free(w->repaired);
    free(w->flipped);
    free(w->reversed);
    free(w->flipped_half);
    free(w->flipped_seed);
    free(w->patch_ids);
    free(w->patch_votes);
}

static int allocate_work(file_work *w)
{
    size_t t = w->mesh.triangles;
    w->truth = (signed char *)malloc(t);
    w->indices = (unsigned int *)malloc(3 * t * sizeof(unsigned int));
    w->altered = (unsigned int *)malloc(3 * t * sizeof(unsigned int));
    w->repaired = (unsigned int *)malloc(3 * t * sizeof(unsigned int));
    w->flipped = (unsigned char *)malloc(t);
    w->reversed = (unsigned char *)calloc(t, 1);
    w->flipped_half = (unsigned char *)malloc(t);
    w->flipped_seed = (unsigned char *)malloc(t);
    w->patch_ids = (unsigned int *)malloc(t * sizeof(unsigned int));
    w->patch_votes = (size_t *)calloc(2 * t, sizeof(size_t)); /* at most one patch per triangle */
    return w->truth && w->indices && w->altered && w->repaired && w->flipped && w->reversed && w->flipped_half &&
           w->flipped_seed && w->patch_ids && w->patch_votes;
}

/* Repairs (indices, positions) under the policy and sets flipped[t] for
   each triangle the call reversed. The one place that runs a policy: new
   options (authored normals as evidence, ...) belong here. */
static calib_table reliability; /* of the reported confidence, over every repair */

/* The patches of a repair scored against the clear normals into
   `reliability` (truth per shipped triangle; reversed: the triangles the
   input reversed from the shipped winding, or NULL). */
static void score_confidence(const signed char *truth, const unsigned char *reversed, size_t triangles,
                             const unsigned char *flipped, const unsigned int *patch_ids, const float *confidence,
                             size_t patches)
{
    unsigned char *right_as_given = (unsigned char *)malloc(triangles + 1);
    size_t t;
    if (right_as_given == NULL)
        return;
    for (t = 0; t < triangles; t++) {
        int r = reversed != NULL && reversed[t];
        right_as_given[t] = truth[t] == 0 ? 2 : (truth[t] > 0) != r;
    }
    calib_score(&reliability, triangles, right_as_given, flipped, patch_ids, confidence, patches);
    free(right_as_given);
}

/* Repairs (indices, positions) under the policy and sets flipped[t] for
   each triangle the call reversed; scores the confidence it reports. The
   one place that runs a policy: new options (authored normals as
   evidence, ...) belong here. */
static meshfix_result repair(const policy_choice *policy, const float *normals, const unsigned int *indices,
                             size_t triangles, const float *positions, size_t vertex_count, unsigned int *repaired,
                             unsigned char *flipped, meshfix_report *report, const signed char *truth,
                             const unsigned char *reversed)
{
    meshfix_options options;
    meshfix_outputs outputs;
    meshfix_result r = MESHFIX_ERROR_OUT_OF_MEMORY;
    unsigned int *patch_ids = (unsigned int *)malloc(triangles * sizeof(unsigned int) + 4);
    float *confidence = (float *)malloc(triangles * sizeof(float) + 4);
    size_t t;
    memset(&options, 0, sizeof(options));
    memset(&outputs, 0, sizeof(outputs));
    options.policy = policy->policy;
    options.evidence.triangle_normals = normals; /* the stored normals as evidence (--normals), or NULL */
    outputs.patch_ids = patch_ids;
    outputs.patch_confidence = confidence;
    outputs.patch_confidence_capacity = triangles;
    calib_begin();
    if (patch_ids != NULL && confidence != NULL)
        r = meshfix_orient(repaired, indices, 3 * triangles, positions, vertex_count, 3 * sizeof(float),
                           policy->named || normals != NULL ? &options : NULL, report, &outputs);
    if (r == MESHFIX_OK) {
        /* a flip writes (a, c, b): the second index tells */
        for (t = 0; t < triangles; t++)
            flipped[t] = repaired[3 * t + 1] != indices[3 * t + 1];
        score_confidence(truth, reversed, triangles, flipped, patch_ids, confidence, report->mesh.patches);
    }
    free(patch_ids);
    free(confidence);
    return r;
}

static void judge_all(file_work *w, file_score *score)
{
    size_t t;
    for (t = 0; t < w->mesh.triangles; t++) {
        facet_truth truth = judge_facet(w->mesh.normals + 3 * t, w->mesh.corners + 9 * t);
        w->truth[t] = truth == FACET_AGREES ? 1 : truth == FACET_DISAGREES ? -1 : 0;
        score->clear += truth == FACET_AGREES || truth == FACET_DISAGREES;
        score->no_normal += truth == FACET_NO_NORMAL;
        score->degenerate += truth == FACET_DEGENERATE;
        score->oblique += truth == FACET_OBLIQUE;
    }
}

/* Reverses exactly half of the triangles (rounded down), chosen by a
   Fisher-Yates shuffle of the flags; the generator restarts per file so a
   file's result does not depend on the files before it. */
static void reverse_random_half(file_work *w, unsigned int seed)
{
    uint64_t state = seed;
    size_t n = w->mesh.triangles, t;
    for (t = 0; t < n / 2; t++)
        w->reversed[t] = 1;
    for (t = n; t > 1; t--) {
        size_t j = (size_t)(next_random(&state) % t); /* bias below 2^-32 for any real mesh */
        unsigned char swap = w->reversed[t - 1];
        w->reversed[t - 1] = w->reversed[j];
        w->reversed[j] = swap;
    }
    for (t = 0; t < n; t++) {
        unsigned int *tri = w->altered + 3 * t;
        memcpy(tri, w->indices + 3 * t, 3 * sizeof(unsigned int));
        if (w->reversed[t]) {
            tri[1] = w->indices[3 * t + 2];
            tri[2] = w->indices[3 * t + 1];
        }
    }
}

/* Clear triangles that agree once reversed from the shipped winding where
   exactly one of a[t], b[t] is set (either may be NULL: none set). */
static size_t count_agreeing(const signed char *truth, size_t n, const unsigned char *a, const unsigned char *b)
{
    size_t t, agree = 0;
    for (t = 0; t < n; t++) {
        int reversed = (a != NULL && a[t]) != (b != NULL && b[t]);
        agree += reversed ? truth[t] < 0 : truth[t] > 0;
    }
    return agree;
}

static size_t count_damaged(const signed char *truth, size_t n, const unsigned char *flipped)
{
    size_t t, damaged = 0;
    for (t = 0; t < n; t++)
        damaged += truth[t] > 0 && flipped[t];
    return damaged;
}

/* The most clear triangles that any policy turning whole patches could make
   agree: the seed policy makes each patch consistent, then each patch is
   counted on its better side. It is below the shipped agreement when the
   shipped winding is inconsistent where the normals are too (gmsh writes
   each CAD face with its own orientation). */
static meshfix_result best_by_patch(file_work *w, size_t *best)
{
    meshfix_options options;
    meshfix_outputs outputs;
    size_t n = w->mesh.triangles, t, p;
    meshfix_result r;
    memset(&options, 0, sizeof(options));
    memset(&outputs, 0, sizeof(outputs));
    options.policy = MESHFIX_POLICY_SEED;
    outputs.patch_ids = w->patch_ids;
    outputs.flipped = w->flipped_seed;
    r = meshfix_orient(NULL, w->indices, 3 * n, w->mesh.corners, 3 * n, 3 * sizeof(float), &options, NULL, &outputs);
    if (r != MESHFIX_OK)
        return r;
    for (t = 0; t < n; t++) {
        int agrees = w->flipped_seed[t] ? w->truth[t] < 0 : w->truth[t] > 0;
        if (w->truth[t] != 0 && w->patch_ids[t] < n) /* degenerate triangles have no patch */
            w->patch_votes[2 * w->patch_ids[t] + (agrees ? 0 : 1)]++;
    }
    *best = 0;
    for (p = 0; p < n; p++)
        *best += w->patch_votes[2 * p] > w->patch_votes[2 * p + 1] ? w->patch_votes[2 * p] : w->patch_votes[2 * p + 1];
    return MESHFIX_OK;
}

/* Welds the corners: indices[i] = remap[i], into the corner array itself. */
static meshfix_result weld(file_work *w)
{
    return meshfix_weld(w->indices, w->mesh.corners, 3 * w->mesh.triangles, 3 * sizeof(float), 0.0f, NULL, NULL);
}

/* Repairs the shipped winding (timed, with a report), then a copy with a
   random half of the triangles reversed. */
static meshfix_result repair_both(file_work *w, const policy_choice *policy, int use_normals, unsigned int seed,
                                  file_score *score)
{
    meshfix_report report;
    size_t n = w->mesh.triangles;
    const float *normals = use_normals ? w->mesh.normals : NULL;
    double start = now_ms();
    meshfix_result r = repair(policy, normals, w->indices, n, w->mesh.corners, 3 * n, w->repaired, w->flipped,
                              &report, w->truth, NULL);
    score->orient_ms = now_ms() - start;
    if (r != MESHFIX_OK)
        return r;
    score->patches = report.mesh.patches;
    score->components = report.mesh.components;
    score->edges_boundary = report.mesh.edges_boundary;
    score->edges_inconsistent = report.edges_inconsistent_before;
    reverse_random_half(w, seed);
    return repair(policy, normals, w->altered, n, w->mesh.corners, 3 * n, w->repaired, w->flipped_half, &report,
                  w->truth, w->reversed);
}

static file_status score_file(const char *path, const policy_choice *policy, int use_normals, unsigned int seed,
                              file_score *score, char *error)
{
    file_work w;
    meshfix_result r;
    size_t n;
    memset(&w, 0, sizeof(w));
    memset(score, 0, sizeof(*score));
    if (!stl_load(path, &w.mesh, error))
        return FILE_REFUSED;
    n = w.mesh.triangles;
    score->format = w.mesh.format;
    score->triangles = n;
    if (!allocate_work(&w)) {
        free_work(&w);
        fail(error, "out of memory for %lu triangles", (unsigned long)n);
        return FILE_REFUSED;
    }
    judge_all(&w, score);
    r = weld(&w);
    if (r == MESHFIX_OK)
        r = best_by_patch(&w, &score->agree_best);
    if (r == MESHFIX_OK)
        r = repair_both(&w, policy, use_normals, seed, score);
    if (r != MESHFIX_OK) {
        fail(error, "%s", meshfix_result_string(r));
        free_work(&w);
        return r == MESHFIX_ERROR_NON_FINITE ? FILE_SKIPPED : FILE_FAILED;
    }
    score->agree_shipped = count_agreeing(w.truth, n, NULL, NULL);
    score->agree_repaired = count_agreeing(w.truth, n, w.flipped, NULL);
    score->damaged = count_damaged(w.truth, n, w.flipped);
    score->agree_half = count_agreeing(w.truth, n, w.reversed, w.flipped_half);
    free_work(&w);
    return FILE_SCORED;
}

/* ---- output ---- */

/* Whether a file's stored normals can serve as truth. */
static const char *truth_quality(const file_score *s)
{
    if (s->clear == 0)
        return "none"; /* all zero, or no usable triangle */
    if (s->oblique > s->clear)
        return "oblique"; /* written in another frame, or for other triangles */
    return "ok";
}

/* Sums over a set of scored files. */
typedef struct file_group {
    size_t files, with_clear;
    file_score sum;         /* counts added up */
    double ship, best, fix, half; /* percentages added up over files with clear triangles */
} file_group;

typedef struct totals {
    file_group all, trusted; /* trusted: files whose truth is "ok" */
    size_t refused, skipped, failed;
} totals;

static double percent(size_t part, size_t whole)
{
    return whole ? 100.0 * (double)part / (double)whole : 0.0;
}

/* Rounded down, so that 100.00 means all and a single miss still shows. */
static const char *format_percent(char *out, size_t part, size_t whole)
{
    if (whole == 0)
        return "-";
    snprintf(out, 16, "%.2f", floor(percent(part, whole) * 100.0) / 100.0);
    return out;
}

static void add_to_group(file_group *g, const file_score *s)
{
    g->files++;
    g->sum.triangles += s->triangles;
    g->sum.clear += s->clear;
    g->sum.no_normal += s->no_normal;
    g->sum.degenerate += s->degenerate;
    g->sum.oblique += s->oblique;
    g->sum.agree_shipped += s->agree_shipped;
    g->sum.agree_repaired += s->agree_repaired;
    g->sum.damaged += s->damaged;
    g->sum.agree_half += s->agree_half;
    g->sum.agree_best += s->agree_best;
    g->sum.orient_ms += s->orient_ms;
    g->sum.patches += s->patches;
    g->sum.components += s->components;
    g->sum.edges_boundary += s->edges_boundary;
    g->sum.edges_inconsistent += s->edges_inconsistent;
    if (s->clear > 0) {
        g->with_clear++;
        g->ship += percent(s->agree_shipped, s->clear);
        g->best += percent(s->agree_best, s->clear);
        g->fix += percent(s->agree_repaired, s->clear);
        g->half += percent(s->agree_half, s->clear);
    }
}

static const char *truth_mark(const file_score *s)
{
    const char *truth = truth_quality(s);
    if (strcmp(truth, "none") == 0)
        return "  [no clear normal]";
    if (strcmp(truth, "oblique") == 0)
        return "  [normals mostly oblique]";
    return "";
}

static void print_count(size_t n, int width)
{
    printf("%*lu ", width, (unsigned long)n);
}

static void print_share(size_t part, size_t whole)
{
    char p[16];
    printf("%7s ", format_percent(p, part, whole));
}

static void print_text_header(const policy_choice *policy, unsigned int seed)
{
    printf("policy %s, seed %u; %% of clear triangles that agree with their stored normal\n", policy->name, seed);
    printf("%9s %9s %7s %7s %7s %8s %7s %8s %7s %5s %8s %6s  file\n", "triangles", "clear", "ship%", "best%",
           "fix%", "damaged", "half%", "ms", "patches", "parts", "boundary", "incons");
}

static void print_text_row(const char *path, const file_score *s)
{
    print_count(s->triangles, 9);
    print_count(s->clear, 9);
    print_share(s->agree_shipped, s->clear);
    print_share(s->agree_best, s->clear);
    print_share(s->agree_repaired, s->clear);
    print_count(s->damaged, 8);
    print_share(s->agree_half, s->clear);
    printf("%8.1f ", s->orient_ms);
    print_count(s->patches, 7);
    print_count(s->components, 5);
    print_count(s->edges_boundary, 8);
    print_count(s->edges_inconsistent, 6);
    printf(" %s%s\n", path, truth_mark(s));
}

static void print_group(const char *label, const file_group *g)
{
    const file_score *s = &g->sum;
    char p[4][16];
    printf("%s: %lu files, %lu triangles, %lu clear (%lu no normal, %lu degenerate, %lu oblique): "
           "ship %s%%, best %s%%, fix %s%%, damaged %lu, half %s%%, orient %.1f ms\n",
           label, (unsigned long)g->files, (unsigned long)s->triangles, (unsigned long)s->clear,
           (unsigned long)s->no_normal, (unsigned long)s->degenerate, (unsigned long)s->oblique,
           format_percent(p[0], s->agree_shipped, s->clear), format_percent(p[1], s->agree_best, s->clear),
           format_percent(p[2], s->agree_repaired, s->clear), (unsigned long)s->damaged,
           format_percent(p[3], s->agree_half, s->clear), s->orient_ms);
    if (g->with_clear > 0)
        printf("%s, mean of %lu files: ship %.2f%%, best %.2f%%, fix %.2f%%, half %.2f%%\n", label,
               (unsigned long)g->with_clear, g->ship / (double)g->with_clear, g->best / (double)g->with_clear,
               g->fix / (double)g->with_clear, g->half / (double)g->with_clear);
}

static void print_text_totals(const totals *all)
{
    print_group("total", &all->all);
    print_group("total, truth ok", &all->trusted);
    printf("not scored: %lu refused, %lu skipped (non-finite), %lu failed\n", (unsigned long)all->refused,
           (unsigned long)all->skipped, (unsigned long)all->failed);
}

/* CSV field: quoted when it holds a comma, a quote or a line break. */
static void print_csv_text(const char *text)
{
    const char *c;
    if (strpbrk(text, ",\"\n\r") == NULL) {
        fputs(text, stdout);
        return;
    }
    putchar('"');
    for (c = text; *c; c++) {
        if (*c == '"')
            putchar('"');
        putchar(*c);
    }
    putchar('"');
}

#define CSV_COLUMNS "file,format,truth,triangles,clear,no_normal,degenerate,oblique,agree_shipped,agree_best," \
                    "agree_repaired,damaged,agree_half,orient_ms,patches,components,edges_boundary," \
                    "edges_inconsistent,note"

static void print_csv_row(const char *path, const file_score *s, const char *note)
{
    print_csv_text(path);
    if (note != NULL) {
        fputs(",,,,,,,,,,,,,,,,,,", stdout); /* every column but the first and the last */
        print_csv_text(note);
        putchar('\n');
        return;
    }
    printf(",%s,%s,%lu,%lu,%lu,%lu,%lu,%lu,%lu,%lu,%lu,%lu,%.3f,%lu,%lu,%lu,%lu,\n", s->format,
           truth_quality(s), (unsigned long)s->triangles, (unsigned long)s->clear, (unsigned long)s->no_normal,
           (unsigned long)s->degenerate, (unsigned long)s->oblique, (unsigned long)s->agree_shipped,
           (unsigned long)s->agree_best, (unsigned long)s->agree_repaired, (unsigned long)s->damaged,
           (unsigned long)s->agree_half, s->orient_ms, (unsigned long)s->patches, (unsigned long)s->components,
           (unsigned long)s->edges_boundary, (unsigned long)s->edges_inconsistent);
}

/* ---- files and directories ---- */

typedef struct path_list {
    char **paths;
    size_t count, capacity;
} path_list;

static int add_path(path_list *list, const char *path)
{
    char *copy;
    if (list->count == list->capacity) {
        size_t capacity = list->capacity ? 2 * list->capacity : 64;
        char **grown = (char **)realloc(list->paths, capacity * sizeof(char *));
        if (grown == NULL)
            return 0;
        list->paths = grown;
        list->capacity = capacity;
    }
    copy = (char *)malloc(strlen(path) + 1);
    if (copy == NULL)
        return 0;
    strcpy(copy, path);
    list->paths[list->count++] = copy;
    return 1;
}

static int ends_with_slash(const char *path)
{
    size_t n = strlen(path);
    return n > 0 && path[n - 1] == '/';
}

/* Every *.stl below directory, any depth. Symbolic links are not followed,
   so a link loop cannot trap the walk. */
static int collect_stl(path_list *list, const char *directory)
{
    DIR *dir = opendir(directory);
    struct dirent *entry;
    struct stat info;
    char path[4096];
    int ok = 1;
    if (dir == NULL) {
        fprintf(stderr, "stl_truth: cannot read directory %s\n", directory);
        return 1;
    }
    while (ok && (entry = readdir(dir)) != NULL) {
        if (strcmp(entry->d_name, ".") == 0 || strcmp(entry->d_name, "..") == 0)
            continue;
        if (snprintf(path, sizeof(path), "%s%s%s", directory, ends_with_slash(directory) ? "" : "/",
                     entry->d_name) >= (int)sizeof(path))
            continue;
        if (lstat(path, &info) != 0)
            continue;
        if (S_ISDIR(info.st_mode))
            ok = collect_stl(list, path);
        else if (S_ISREG(info.st_mode) && has_stl_extension(path))
            ok = add_path(list, path);
    }
    closedir(dir);
    return ok;
}

static int compare_paths(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* A file as given; a directory's files in sorted order, so runs compare. */
static int add_argument(path_list *list, const char *argument)
{
    struct stat info;
    size_t first = list->count;
    if (stat(argument, &info) != 0 || !S_ISDIR(info.st_mode))
        return add_path(list, argument);
    if (!collect_stl(list, argument))
        return 0;
    qsort(list->paths + first, list->count - first, sizeof(char *), compare_paths);
    return 1;
}

static void free_paths(path_list *list)
{
    size_t i;
    for (i = 0; i < list->count; i++)
        free(list->paths[i]);
    free(list->paths);
}

/* ---- main ---- */

typedef struct settings {
    const policy_choice *policy;
    unsigned int seed;
    int csv;
    int normals; /* pass the stored normals to meshfix as evidence */
} settings;

static int usage(void)
{
    fprintf(stderr, "usage: stl_truth [--policy default|auto|seed|majority|outward|visibility|up|normals] "
                    "[--normals] [--seed N] [--csv] [--rows FILE] FILE_OR_DIRECTORY...\n");
    return 1;
}

/* Reads the options; returns the index of the first path, or 0 on bad usage. */
static int parse_settings(int argc, char **argv, settings *s)
{
    int i;
    char *end;
    s->policy = &POLICIES[0];
    s->seed = 1;
    s->csv = 0;
    s->normals = 0;
    for (i = 1; i < argc && strncmp(argv[i], "--", 2) == 0; i++) {
        if (strcmp(argv[i], "--csv") == 0) {
            s->csv = 1;
        } else if (strcmp(argv[i], "--normals") == 0) {
            s->normals = 1;
        } else if (strcmp(argv[i], "--rows") == 0 && i + 1 < argc) {
            if (!calib_open_rows(argv[++i]))
                return 0;
        } else if (strcmp(argv[i], "--policy") == 0 && i + 1 < argc) {
            s->policy = find_policy(argv[++i]);
            if (s->policy == NULL)
                return 0;
        } else if (strcmp(argv[i], "--seed") == 0 && i + 1 < argc) {
            unsigned long seed = strtoul(argv[++i], &end, 10);
            if (*end != '\0' || seed > 0xFFFFFFFFul)
                return 0;
            s->seed = (unsigned int)seed;
        } else {
            return 0;
        }
    }
    return i < argc ? i : 0;
}

static void report_file(const settings *s, const char *path, file_status status, const file_score *score,
                        const char *error, totals *all)
{
    const char *kind = status == FILE_REFUSED ? "refused" : status == FILE_SKIPPED ? "skipped" : "FAILED";
    if (status == FILE_SCORED) {
        add_to_group(&all->all, score);
        if (strcmp(truth_quality(score), "ok") == 0)
            add_to_group(&all->trusted, score);
        if (s->csv)
            print_csv_row(path, score, NULL);
        else
            print_text_row(path, score);
        return;
    }
    all->refused += status == FILE_REFUSED;
    all->skipped += status == FILE_SKIPPED;
    all->failed += status == FILE_FAILED;
    if (s->csv) {
        char note[ERROR_SIZE + 16];
        snprintf(note, sizeof(note), "%s: %s", kind, error);
        print_csv_row(path, score, note);
    } else {
        printf("%10s  %s: %s  %s\n", "-", kind, error, path);
    }
}

int main(int argc, char **argv)
{
    settings s;
    path_list list = {NULL, 0, 0};
    totals all;
    int first = parse_settings(argc, argv, &s), i;
    size_t f;
    if (first == 0)
        return usage();
    for (i = first; i < argc; i++) {
        if (!add_argument(&list, argv[i])) {
            fprintf(stderr, "stl_truth: out of memory\n");
            return 1;
        }
    }
    memset(&all, 0, sizeof(all));
    if (s.csv)
        puts(CSV_COLUMNS);
    else
        print_text_header(s.policy, s.seed);
    for (f = 0; f < list.count; f++) {
        file_score score;
        char error[ERROR_SIZE] = "";
        file_status status = score_file(list.paths[f], s.policy, s.normals, s.seed, &score, error);
        report_file(&s, list.paths[f], status, &score, error, &all);
        fflush(stdout);
    }
    if (!s.csv) {
        print_text_totals(&all);
        printf("reliability of the reported confidence (both repairs of every file, clear triangles):\n");
        calib_print(&reliability, stdout);
    }
    calib_close_rows();
    free_paths(&list);
    return all.failed > 0 ? 2 : 0;
}
