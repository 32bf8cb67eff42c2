/* meshfix command-line tool: the --mark picture (--mark FILE.png).

   A small rasterizer of its own: every unit's triangles as they are
   written (faces flipped by the repair turned over), in four orthographic
   views (front, back, top and oblique), flat-shaded with a z-buffer at
   2 x 2 samples a pixel; a legend and the report's words in a built-in
   5 x 9 bitmap font; the PNG through libpng (Debian's libpng-dev). Built
   with MESHFIX_TOOL_NO_PNG (no libpng), write_picture refuses in one line.

   Colours: flipped faces red, doubtful patches amber, faces seen from
   behind (as written, from that camera: what renders inside-out) blue,
   flipped or doubtful ones seen from behind striped with blue, the rest
   grey tinted by patch (the PLY's tint, paler), triangles in no patch dark
   grey.

   Layout, top to bottom (tests/test_cli.sh reads it):
   - the title at (12, 10);
   - the legend: swatches of 18 x 18 pixels at x 12 and 330, y 40 and 66
     (red, amber; blue, grey), each followed by its words;
   - the views from y 100: front, back, top, oblique in a grid of 2 x 2,
     4 x 1 or 1 x 4, whichever draws the model largest (a wide model in a
     column, a tall one in a row), front, back and top at one scale, the
     oblique view fitted on its own, each labelled with where its camera is;
   - the summary under them, wrapped at spaces.
   The tEXt chunk "meshfix views" has a line per view,
     NAME X Y W H OX OY S RX RY RZ UX UY UZ
   its rectangle in the image and its projection: a point p lands at pixel
   (OX + S (p . R), OY - S (p . U)), pixel (i, j) covering [i, i+1) x [j, j+1).

   Deterministic: the same file gives the same bytes (no clock, no
   threads; ties in the z-buffer go to the first triangle drawn). */
#include "tool.h"

#ifndef MESHFIX_TOOL_NO_PNG
#include <png.h>
#endif

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <set>

namespace tool {

bool png_supported()
{
#ifdef MESHFIX_TOOL_NO_PNG
    return false;
#else
    return true;
#endif
}

namespace {

struct Rgb {
    unsigned char r, g, b;
};

const Rgb red{230, 30, 30}, amber{255, 176, 0}, back_blue{80, 60, 220}, no_patch{70, 70, 70};
const Rgb white{255, 255, 255}, panel{238, 240, 243}, ink{30, 30, 30}, muted{100, 100, 100};
const unsigned char grey = 190; /* kept faces: this grey, 40% of the way to the patch's tint */

/* ---- the font: 5 x 9 cells (capitals and digits 7 high, descenders
   below), ASCII 32 to 126, drawn at twice the size ---- */

const int glyph_w = 5, glyph_h = 9, text_scale = 2, advance = (glyph_w + 1) * text_scale, line_height = 24;

const char font[95][glyph_w * glyph_h + 1] = {
    "....."  "....."  "....."  "....."  "....."  "....."  "....."  "....."  ".....", /*   */
    "..#.."  "..#.."  "..#.."  "..#.."  "..#.."  "....."  "..#.."  "....."  ".....", /* ! */
    ".#.#."  ".#.#."  ".#.#."  "....."  "....."  "....."  "....."  "....."  ".....", /* " */
    ".#.#."  ".#.#."  "#####"  ".#.#."  "#####"  ".#.#."  ".#.#."  "....."  ".....", /* # */
    "..#.."  ".####"  "#.#.."  ".###."  "..#.#"  "####."  "..#.."  "....."  ".....", /* $ */
    "##..."  "##..#"  "...#."  "..#.."  ".#..."  "#..##"  "...##"  "....."  ".....", /* % */
    ".##.."  "#..#."  "#.#.."  ".#..."  "#.#.#"  "#..#."  ".##.#"  "....."  ".....", /* & */
    "..#.."  "..#.."  ".#..."  "....."  "....."  "....."  "....."  "....."  ".....", /* quote */
    "...#."  "..#.."  ".#..."  ".#..."  ".#..."  "..#.."  "...#."  "....."  ".....", /* ( */
    ".#..."  "..#.."  "...#."  "...#."  "...#."  "..#.."  ".#..."  "....."  ".....", /* ) */
    "....."  "..#.."  "#.#.#"  ".###."  "#.#.#"  "..#.."  "....."  "....."  ".....", /* star */
    "....."  "..#.."  "..#.."  "#####"  "..#.."  "..#.."  "....."  "....."  ".....", /* + */
    "....."  "....."  "....."  "....."  "....."  ".##.."  ".##.."  "..#.."  ".#...", /* , */
    "....."  "....."  "....."  "#####"  "....."  "....."  "....."  "....."  ".....", /* - */
    "....."  "....."  "....."  "....."  "....."  ".##.."  ".##.."  "....."  ".....", /* . */
    "....."  "....#"  "...#."  "..#.."  ".#..."  "#...."  "....."  "....."  ".....", /* slash */
    ".###."  "#...#"  "#..##"  "#.#.#"  "##..#"  "#...#"  ".###."  "....."  ".....", /* 0 */
    "..#.."  ".##.."  "..#.."  "..#.."  "..#.."  "..#.."  ".###."  "....."  ".....", /* 1 */
    ".###."  "#...#"  "....#"  "...#."  "..#.."  ".#..."  "#####"  "....."  ".....", /* 2 */
    "#####"  "...#."  "..#.."  "...#."  "....#"  "#...#"  ".###."  "....."  ".....", /* 3 */
    "...#."  "..##."  ".#.#."  "#..#."  "#####"  "...#."  "...#."  "....."  ".....", /* 4 */
    "#####"  "#...."  "####."  "....#"  "....#"  "#...#"  ".###."  "....."  ".....", /* 5 */
    "..##."  ".#..."  "#...."  "####."  "#...#"  "#...#"  ".###."  "....."  ".....", /* 6 */
    "#####"  "....#"  "...#."  "..#.."  ".#..."  ".#..."  ".#..."  "....."  ".....", /* 7 */
    ".###."  "#...#"  "#...#"  ".###."  "#...#"  "#...#"  ".###."  "....."  ".....", /* 8 */
    ".###."  "#...#"  "#...#"  ".####"  "....#"  "...#."  ".##.."  "....."  ".....", /* 9 */
    "....."  ".##.."  ".##.."  "....."  ".##.."  ".##.."  "....."  "....."  ".....", /* : */
    "....."  ".##.."  ".##.."  "....."  ".##.."  ".##.."  "..#.."  ".#..."  ".....", /* ; */
    "...#."  "..#.."  ".#..."  "#...."  ".#..."  "..#.."  "...#."  "....."  ".....", /* < */
    "....."  "....."  "#####"  "....."  "#####"  "....."  "....."  "....."  ".....", /* = */
    ".#..."  "..#.."  "...#."  "....#"  "...#."  "..#.."  ".#..."  "....."  ".....", /* > */
    ".###."  "#...#"  "....#"  "...#."  "..#.."  "....."  "..#.."  "....."  ".....", /* ? */
    ".###."  "#...#"  "#.###"  "#.#.#"  "#.###"  "#...."  ".###."  "....."  ".....", /* @ */
    ".###."  "#...#"  "#...#"  "#####"  "#...#"  "#...#"  "#...#"  "....."  ".....", /* A */
    "####."  "#...#"  "#...#"  "####."  "#...#"  "#...#"  "####."  "....."  ".....", /* B */
    ".###."  "#...#"  "#...."  "#...."  "#...."  "#...#"  ".###."  "....."  ".....", /* C */
    "###.."  "#..#."  "#...#"  "#...#"  "#...#"  "#..#."  "###.."  "....."  ".....", /* D */
    "#####"  "#...."  "#...."  "####."  "#...."  "#...."  "#####"  "....."  ".....", /* E */
    "#####"  "#...."  "#...."  "####."  "#...."  "#...."  "#...."  "....."  ".....", /* F */
    ".###."  "#...#"  "#...."  "#.###"  "#...#"  "#...#"  ".####"  "....."  ".....", /* G */
    "#...#"  "#...#"  "#...#"  "#####"  "#...#"  "#...#"  "#...#"  "....."  ".....", /* H */
    ".###."  "..#.."  "..#.."  "..#.."  "..#.."  "..#.."  ".###."  "....."  ".....", /* I */
    "..###"  "...#."  "...#."  "...#."  "...#."  "#..#."  ".##.."  "....."  ".....", /* J */
    "#...#"  "#..#."  "#.#.."  "##..."  "#.#.."  "#..#."  "#...#"  "....."  ".....", /* K */
    "#...."  "#...."  "#...."  "#...."  "#...."  "#...."  "#####"  "....."  ".....", /* L */
    "#...#"  "##.##"  "#.#.#"  "#.#.#"  "#...#"  "#...#"  "#...#"  "....."  ".....", /* M */
    "#...#"  "#...#"  "##..#"  "#.#.#"  "#..##"  "#...#"  "#...#"  "....."  ".....", /* N */
    ".###."  "#...#"  "#...#"  "#...#"  "#...#"  "#...#"  ".###."  "....."  ".....", /* O */
    "####."  "#...#"  "#...#"  "####."  "#...."  "#...."  "#...."  "....."  ".....", /* P */
    ".###."  "#...#"  "#...#"  "#...#"  "#.#.#"  "#..#."  ".##.#"  "....."  ".....", /* Q */
    "####."  "#...#"  "#...#"  "####."  "#.#.."  "#..#."  "#...#"  "....."  ".....", /* R */
    ".####"  "#...."  "#...."  ".###."  "....#"  "....#"  "####."  "....."  ".....", /* S */
    "#####"  "..#.."  "..#.."  "..#.."  "..#.."  "..#.."  "..#.."  "....."  ".....", /* T */
    "#...#"  "#...#"  "#...#"  "#...#"  "#...#"  "#...#"  ".###."  "....."  ".....", /* U */
    "#...#"  "#...#"  "#...#"  "#...#"  "#...#"  ".#.#."  "..#.."  "....."  ".....", /* V */
    "#...#"  "#...#"  "#...#"  "#.#.#"  "#.#.#"  "#.#.#"  ".#.#."  "....."  ".....", /* W */
    "#...#"  "#...#"  ".#.#."  "..#.."  ".#.#."  "#...#"  "#...#"  "....."  ".....", /* X */
    "#...#"  "#...#"  ".#.#."  "..#.."  "..#.."  "..#.."  "..#.."  "....."  ".....", /* Y */
    "#####"  "....#"  "...#."  "..#.."  ".#..."  "#...."  "#####"  "....."  ".....", /* Z */
    ".###."  ".#..."  ".#..."  ".#..."  ".#..."  ".#..."  ".###."  "....."  ".....", /* [ */
    "....."  "#...."  ".#..."  "..#.."  "...#."  "....#"  "....."  "....."  ".....", /* backslash */
    ".###."  "...#."  "...#."  "...#."  "...#."  "...#."  ".###."  "....."  ".....", /* ] */
    "..#.."  ".#.#."  "#...#"  "....."  "....."  "....."  "....."  "....."  ".....", /* ^ */
    "....."  "....."  "....."  "....."  "....."  "....."  "....."  "#####"  ".....", /* _ */
    ".#..."  "..#.."  "...#."  "....."  "....."  "....."  "....."  "....."  ".....", /* ` */
    "....."  "....."  ".###."  "....#"  ".####"  "#...#"  ".####"  "....."  ".....", /* a */
    "#...."  "#...."  "#.##."  "##..#"  "#...#"  "#...#"  "####."  "....."  ".....", /* b */
    "....."  "....."  ".###."  "#...."  "#...."  "#...#"  ".###."  "....."  ".....", /* c */
    "....#"  "....#"  ".##.#"  "#..##"  "#...#"  "#...#"  ".####"  "....."  ".....", /* d */
    "....."  "....."  ".###."  "#...#"  "#####"  "#...."  ".###."  "....."  ".....", /* e */
    "..##."  ".#..#"  ".#..."  "###.."  ".#..."  ".#..."  ".#..."  "....."  ".....", /* f */
    "....."  "....."  ".####"  "#...#"  "#...#"  "#...#"  ".####"  "....#"  ".###.", /* g */
    "#...."  "#...."  "#.##."  "##..#"  "#...#"  "#...#"  "#...#"  "....."  ".....", /* h */
    "..#.."  "....."  ".##.."  "..#.."  "..#.."  "..#.."  ".###."  "....."  ".....", /* i */
    "...#."  "....."  "..##."  "...#."  "...#."  "...#."  "...#."  "#..#."  ".##..", /* j */
    "#...."  "#...."  "#..#."  "#.#.."  "##..."  "#.#.."  "#..#."  "....."  ".....", /* k */
    ".##.."  "..#.."  "..#.."  "..#.."  "..#.."  "..#.."  ".###."  "....."  ".....", /* l */
    "....."  "....."  "##.#."  "#.#.#"  "#.#.#"  "#.#.#"  "#.#.#"  "....."  ".....", /* m */
    "....."  "....."  "#.##."  "##..#"  "#...#"  "#...#"  "#...#"  "....."  ".....", /* n */
    "....."  "....."  ".###."  "#...#"  "#...#"  "#...#"  ".###."  "....."  ".....", /* o */
    "....."  "....."  "####."  "#...#"  "#...#"  "#...#"  "####."  "#...."  "#....", /* p */
    "....."  "....."  ".####"  "#...#"  "#...#"  "#...#"  ".####"  "....#"  "....#", /* q */
    "....."  "....."  "#.##."  "##..#"  "#...."  "#...."  "#...."  "....."  ".....", /* r */
    "....."  "....."  ".####"  "#...."  ".###."  "....#"  "####."  "....."  ".....", /* s */
    ".#..."  ".#..."  "###.."  ".#..."  ".#..."  ".#..#"  "..##."  "....."  ".....", /* t */
    "....."  "....."  "#...#"  "#...#"  "#...#"  "#..##"  ".##.#"  "....."  ".....", /* u */
    "....."  "....."  "#...#"  "#...#"  "#...#"  ".#.#."  "..#.."  "....."  ".....", /* v */
    "....."  "....."  "#...#"  "#...#"  "#.#.#"  "#.#.#"  ".#.#."  "....."  ".....", /* w */
    "....."  "....."  "#...#"  ".#.#."  "..#.."  ".#.#."  "#...#"  "....."  ".....", /* x */
    "....."  "....."  "#...#"  "#...#"  "#...#"  "#...#"  ".####"  "....#"  ".###.", /* y */
    "....."  "....."  "#####"  "...#."  "..#.."  ".#..."  "#####"  "....."  ".....", /* z */
    "...##"  "..#.."  "..#.."  ".#..."  "..#.."  "..#.."  "...##"  "....."  ".....", /* { */
    "..#.."  "..#.."  "..#.."  "..#.."  "..#.."  "..#.."  "..#.."  "..#.."  "..#..", /* | */
    "##..."  "..#.."  "..#.."  "...#."  "..#.."  "..#.."  "##..."  "....."  ".....", /* } */
    "....."  "....."  ".#..."  "#.#.#"  "...#."  "....."  "....."  "....."  ".....", /* ~ */
};

/* The characters of UTF-8 text as the font draws them: one per code
   point, '?' for what it has no glyph for. */
std::string drawable(const std::string &text)
{
    std::string out;
    for (unsigned char c : text) {
        if ((c & 0xC0) == 0x80)
            continue; /* a continuation byte: its code point is already a '?' */
        out += c >= 32 && c < 127 ? (char)c : '?';
    }
    return out;
}

class Canvas {
public:
    Canvas(int w, int h, Rgb fill) : width(w), height(h), pixels((size_t)w * (size_t)h * 3)
    {
        rect(0, 0, w, h, fill);
    }

    void put(int x, int y, Rgb c)
    {
        if (x < 0 || y < 0 || x >= width || y >= height)
            return;
        unsigned char *p = &pixels[((size_t)y * (size_t)width + (size_t)x) * 3];
        p[0] = c.r, p[1] = c.g, p[2] = c.b;
    }

    void rect(int x, int y, int w, int h, Rgb c)
    {
        for (int j = y; j < y + h; ++j)
            for (int i = x; i < x + w; ++i)
                put(i, j, c);
    }

    /* Draws text (already drawable) with its cell's top left at (x, y). */
    void text(int x, int y, const std::string &s, Rgb c)
    {
        for (size_t k = 0; k < s.size(); ++k) {
            const char *rows = font[(unsigned char)s[k] - 32];
            for (int j = 0; j < glyph_h; ++j)
                for (int i = 0; i < glyph_w; ++i)
                    if (rows[j * glyph_w + i] == '#')
                        rect(x + (int)k * advance + i * text_scale, y + j * text_scale, text_scale, text_scale, c);
        }
    }

    int width, height;
    std::vector<unsigned char> pixels; /* RGB, rows top to bottom */
};

/* Text cut to `columns` characters, "..." marking the cut. */
std::string fit(const std::string &s, size_t columns)
{
    if (s.size() <= columns)
        return s;
    return columns <= 3 ? s.substr(0, columns) : s.substr(0, columns - 3) + "...";
}

/* Text in lines of at most `columns` characters, broken at spaces (a
   longer word across lines). */
std::vector<std::string> wrap(const std::string &s, size_t columns)
{
    std::vector<std::string> lines;
    std::string line;
    size_t at = 0;
    columns = std::max<size_t>(columns, 8);
    while (at < s.size()) {
        size_t space = s.find(' ', at);
        std::string word = s.substr(at, space == std::string::npos ? std::string::npos : space - at);
        at = space == std::string::npos ? s.size() : space + 1;
        while (word.size() > columns) {
            if (!line.empty())
                lines.push_back(line), line.clear();
            lines.push_back(word.substr(0, columns));
            word = word.substr(columns);
        }
        if (!line.empty() && line.size() + 1 + word.size() > columns)
            lines.push_back(line), line.clear();
        line += (line.empty() ? "" : " ") + word;
    }
    if (!line.empty() || lines.empty())
        lines.push_back(line);
    return lines;
}

/* ---- geometry ---- */

struct Vec {
    double x, y, z;
};

Vec operator+(Vec a, Vec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec operator-(Vec a, Vec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec operator*(Vec a, double k) { return {a.x * k, a.y * k, a.z * k}; }
double dot(Vec a, Vec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec cross(Vec a, Vec b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
Vec unit(Vec a)
{
    double l = std::sqrt(dot(a, a));
    return l > 0.0 ? a * (1.0 / l) : Vec{0, 0, 0};
}

/* "+x", "-z", ... for a unit vector along an axis, else "". */
std::string axis_name(Vec a)
{
    const double c[3] = {a.x, a.y, a.z};
    for (int k = 0; k < 3; ++k)
        if (std::fabs(c[k]) == 1.0)
            return std::string(c[k] > 0 ? "+" : "-") + "xyz"[k];
    return "";
}

/* One face as written, in the picture's model space (the file's positions
   moved and scaled into [-0.5, 0.5]^3: every position within range of a
   double, whatever the file holds). */
struct Face {
    Vec p[3];
    Vec normal; /* unit, by the winding as written; zero when degenerate */
    Mark mark;
    bool turned; /* flipped by the repair: as read, its normal is the other way */
    Rgb kept;    /* its colour when kept */
};

/* The triangles of the file, with every corner finite, as Faces. */
class Model {
public:
    Model(const MeshFile &file, const std::vector<UnitResult> &results) : f(file), r(results)
    {
        double lo[3], hi[3];
        for (int k = 0; k < 3; ++k)
            lo[k] = std::numeric_limits<double>::infinity(), hi[k] = -lo[k];
        each_corner([&](const double *p) {
            for (int k = 0; k < 3; ++k)
                lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
        });
        half = 0.0;
        for (int k = 0; k < 3; ++k) {
            if (!(lo[k] <= hi[k]))
                lo[k] = hi[k] = 0.0; /* nothing to draw */
            mid[k] = 0.5 * lo[k] + 0.5 * hi[k];
            half = std::max(half, 0.5 * hi[k] - 0.5 * lo[k]);
        }
        if (!(half > 0.0))
            half = 1.0; /* a point, or nothing */
    }

    template <class F> void each_face(F &&use) const
    {
        for (size_t i = 0; i < f.units.size(); ++i) {
            const Unit &u = f.units[i];
            const UnitResult &res = r[i];
            for (size_t t = 0; t < u.indices.size() / 3; ++t) {
                const double *c[3];
                if (!corners(u, t, c))
                    continue;
                bool turned = written_flipped(u, res, t);
                Face face;
                for (int k = 0; k < 3; ++k)
                    face.p[k] = place(c[turned && k > 0 ? 3 - k : k]);
                face.normal = unit(cross(face.p[1] - face.p[0], face.p[2] - face.p[0]));
                face.mark = mark_of(u, res, t);
                face.turned = turned;
                face.kept = no_patch;
                if (face.mark == Mark::kept) {
                    unsigned char tint[3];
                    patch_tint(res.patch_ids[t], tint);
                    face.kept = {(unsigned char)((6 * grey + 4 * tint[0] + 5) / 10),
                                 (unsigned char)((6 * grey + 4 * tint[1] + 5) / 10),
                                 (unsigned char)((6 * grey + 4 * tint[2] + 5) / 10)};
                }
                use(face);
            }
        }
    }

    /* Where a file position is in model space; and back: o + s (p . axis)
       for p in model space is file_offset(o, s, axis) + file_scale(s) (p . axis)
       for p in the file's space. */
    Vec place(const double *p) const
    {
        return {(0.5 * p[0] - 0.5 * mid[0]) / half, (0.5 * p[1] - 0.5 * mid[1]) / half,
                (0.5 * p[2] - 0.5 * mid[2]) / half};
    }
    double file_scale(double s) const { return s * 0.5 / half; }
    double file_offset(double o, double s, Vec axis) const { return o - file_scale(s) * dot(centre(), axis); }
    Vec centre() const { return {mid[0], mid[1], mid[2]}; }

private:
    bool corners(const Unit &u, size_t t, const double *c[3]) const
    {
        for (int k = 0; k < 3; ++k) {
            size_t v = u.indices[3 * t + (size_t)k];
            if (v >= u.positions.size() / 3)
                return false;
            c[k] = &u.positions[3 * v];
            if (!std::isfinite(c[k][0]) || !std::isfinite(c[k][1]) || !std::isfinite(c[k][2]))
                return false;
        }
        return true;
    }

    template <class F> void each_corner(F &&use) const
    {
        for (const Unit &u : f.units)
            for (size_t t = 0; t < u.indices.size() / 3; ++t) {
                const double *c[3];
                if (corners(u, t, c))
                    for (int k = 0; k < 3; ++k)
                        use(c[k]);
            }
    }

    const MeshFile &f;
    const std::vector<UnitResult> &r;
    double mid[3], half;
};

/* ---- views ---- */

struct View {
    std::string name, label;
    bool before = false; /* the "before" row: the faces as read, those seen from behind culled */
    Vec toward, right, up; /* toward the camera; the screen's right and up */
    double lo_r = 0, hi_r = 0, lo_u = 0, hi_u = 0; /* the model's extent on right and up */
    int x = 0, y = 0, w = 0, h = 0;                /* the cell in the image */
    double scale = 1, ox = 0, oy = 0;              /* pixel = (ox + scale (p . right), oy - scale (p . up)) */
};

const int margin = 12, views_top = 126, gap = 10, pad = 14, label_h = 28, header_h = 30, block_gap = 24;
const int max_views_w = 1600, max_views_h = 1160, min_cell_w = 250, min_content_h = 80, min_width = 960;
const int samples = 2; /* per pixel along x and y */
const int legend_x[2] = {12, 560}, legend_y[3] = {40, 66, 92}, swatch = 18;

/* The four cameras for an up axis, each twice: the "after" views (front,
   back, top, oblique), then the same cameras for "before" (before_front,
   ...). The screen's right is +x (+y when up is along x); the front
   camera is on the side right x up: -y when z is up, +z when y is up
   (glTF's front), -z when x is up. The back camera is opposite, the top
   one above looking down (the front at the bottom of the view), the
   oblique one 35 degrees from the front to the right and 30 degrees up. */
std::vector<View> cameras(const float up_axis[3])
{
    Vec up = unit({up_axis[0], up_axis[1], up_axis[2]});
    if (dot(up, up) == 0.0)
        up = {0, 0, 1};
    /* right: +x, unless up is along x (then +y) */
    Vec right = std::fabs(up.x) > 0.9 ? Vec{0, 1, 0} : Vec{1, 0, 0};
    right = unit(right - up * dot(right, up));
    Vec toward = cross(right, up); /* z up: -y, the front camera at -y; y up: +z */
    std::vector<View> v(4);
    v[0].name = "front", v[0].toward = toward, v[0].right = right;
    v[1].name = "back", v[1].toward = toward * -1.0, v[1].right = right * -1.0;
    v[2].name = "top", v[2].toward = up, v[2].right = right;
    const double pi = 3.14159265358979323846, az = 35.0 * pi / 180.0, el = 30.0 * pi / 180.0;
    v[3].name = "oblique";
    v[3].toward = unit(toward * (std::cos(el) * std::cos(az)) + right * (std::cos(el) * std::sin(az)) + up * std::sin(el));
    v[3].right = unit(cross(up, v[3].toward));
    for (View &view : v) {
        view.up = cross(view.toward, view.right);
        std::string from = axis_name(view.toward);
        view.label = view.name + (from.empty() ? "" : " (from " + from + ")");
    }
    for (int k = 0; k < 4; ++k) {
        View before = v[(size_t)k];
        before.before = true;
        before.name = "before_" + before.name;
        v.push_back(before);
    }
    return v;
}

/* Where the views are: the image's width, the grid's height and each
   block's (before, after) top left corner and width. */
struct Layout {
    int width = 0, grid_h = 0;
    int block_x[2] = {0, 0}, block_y[2] = {0, 0}, block_w = 0;
};

/* Fits the views to the model and places them. Front, back and top share
   one scale (one drawing of the model, as on a plan); the oblique view is
   fitted to the same cell on its own. The views of each block, before and
   after, are a grid of 2 x 2, 4 x 1 or 1 x 4, the blocks stacked or side
   by side (before first), whichever draws the plan views largest (the
   oblique one counts a quarter): a row before above a row after unless
   another is clearly larger. */
Layout lay_out(std::vector<View> &views, const Model &model)
{
    const double inf = std::numeric_limits<double>::infinity();
    for (View &v : views)
        v.lo_r = v.lo_u = inf, v.hi_r = v.hi_u = -inf;
    model.each_face([&](const Face &f) {
        for (View &v : views)
            for (const Vec &p : f.p) {
                double a = dot(p, v.right), b = dot(p, v.up);
                v.lo_r = std::min(v.lo_r, a), v.hi_r = std::max(v.hi_r, a);
                v.lo_u = std::min(v.lo_u, b), v.hi_u = std::max(v.hi_u, b);
            }
    });
    double mw = 0, mh = 0, m = 1e-9; /* the largest extents of the three plan views */
    for (size_t i = 0; i < views.size(); ++i) {
        View &v = views[i];
        if (!(v.lo_r <= v.hi_r))
            v.lo_r = v.hi_r = v.lo_u = v.hi_u = 0.0; /* nothing to draw */
        m = std::max({m, v.hi_r - v.lo_r, v.hi_u - v.lo_u});
        if (i % 4 < 3)
            mw = std::max(mw, v.hi_r - v.lo_r), mh = std::max(mh, v.hi_u - v.lo_u);
    }
    const View &oblique = views[3];
    double ow = std::max(oblique.hi_r - oblique.lo_r, 1e-3 * m), oh = std::max(oblique.hi_u - oblique.lo_u, 1e-3 * m);
    mw = std::max(mw, 1e-3 * m), mh = std::max(mh, 1e-3 * m);
    /* columns and rows of a block, and whether the blocks are side by side */
    static const int arrangements[6][3] = {{4, 1, 0}, {2, 2, 1}, {2, 2, 0}, {1, 4, 1}, {4, 1, 1}, {1, 4, 0}};
    int cols = 4, rows = 1, side = 0, content_w = 0, content_h = 0;
    double plan = 0, best = 0;
    for (int g = 0; g < 6; ++g) {
        int c = arrangements[g][0], r = arrangements[g][1], sd = arrangements[g][2];
        int bw = sd ? (max_views_w - block_gap) / 2 : max_views_w;
        int bh = sd ? max_views_h - header_h : (max_views_h - block_gap) / 2 - header_h;
        double aw = (double)(bw - (c - 1) * gap) / c - 2 * pad;
        double ah = (double)(bh - (r - 1) * gap) / r - label_h - 2 * pad;
        double s = std::min(aw / mw, ah / mh);
        int cw = std::max((int)std::ceil(s * mw), min_cell_w - 2 * pad), ch = std::max((int)std::ceil(s * mh), min_content_h);
        double score = std::pow(s, 0.75) * std::pow(std::min(cw / ow, ch / oh), 0.25);
        if (g == 0 || score > 1.15 * best)
            cols = c, rows = r, side = sd, plan = s, best = score, content_w = cw, content_h = ch;
    }
    int cell_w = content_w + 2 * pad, cell_h = label_h + content_h + 2 * pad;
    int block_w = cols * cell_w + (cols - 1) * gap, block_h = header_h + rows * cell_h + (rows - 1) * gap;
    int grid_w = side ? 2 * block_w + block_gap : block_w;
    Layout out;
    out.width = std::max(min_width, grid_w + 2 * margin);
    out.grid_h = side ? block_h : 2 * block_h + block_gap;
    out.block_w = block_w;
    int x0 = (out.width - grid_w) / 2;
    for (int b = 0; b < 2; ++b) {
        out.block_x[b] = x0 + (side ? b * (block_w + block_gap) : 0);
        out.block_y[b] = views_top + (side ? 0 : b * (block_h + block_gap));
    }
    for (size_t i = 0; i < views.size(); ++i) {
        View &v = views[i];
        int b = v.before ? 0 : 1, k = (int)(i % 4);
        v.x = out.block_x[b] + (k % cols) * (cell_w + gap);
        v.y = out.block_y[b] + header_h + (k / cols) * (cell_h + gap);
        v.w = cell_w, v.h = cell_h;
        v.scale = i % 4 < 3 ? plan : std::min(content_w / ow, content_h / oh);
        double ew = v.scale * (v.hi_r - v.lo_r), eh = v.scale * (v.hi_u - v.lo_u);
        v.ox = v.x + pad + (content_w - ew) / 2 - v.scale * v.lo_r;
        v.oy = v.y + label_h + pad + (content_h - eh) / 2 + v.scale * v.hi_u;
    }
    return out;
}

Rgb shade(Rgb c, double light)
{
    return {(unsigned char)std::lround(c.r * light), (unsigned char)std::lround(c.g * light),
            (unsigned char)std::lround(c.b * light)};
}

bool is_marked(Mark m) { return m == Mark::flipped || m == Mark::doubtful; }

/* Draws one view into its cell of the canvas. An "after" view fills
   `marked` (when given) with a byte per sample, 1 where a flipped or
   doubtful face is what the sample shows. */
void draw_view(Canvas &canvas, const View &v, const Model &model, std::vector<unsigned char> *marked)
{
    const int sw = v.w * samples, sh = v.h * samples;
    const double none = -std::numeric_limits<double>::infinity();
    std::vector<double> depth((size_t)sw * (size_t)sh, none);
    std::vector<Rgb> colour((size_t)sw * (size_t)sh, panel);
    std::vector<unsigned char> shows_mark(marked != nullptr ? (size_t)sw * (size_t)sh : 0, 0);
    const Vec light = unit(v.right * -0.35 + v.up * 0.45 + v.toward * 0.82); /* from the upper left, near the camera */
    /* a sample: nearer than what is there (ties to the first drawn) */
    auto put = [&](int i, int j, double z, Rgb c, bool mark) {
        if (i < 0 || j < 0 || i >= sw || j >= sh)
            return;
        size_t at = (size_t)j * (size_t)sw + (size_t)i;
        if (z > depth[at]) {
            depth[at] = z, colour[at] = c;
            if (marked != nullptr)
                shows_mark[at] = mark;
        }
    };
    model.each_face([&](const Face &f) {
        if (dot(f.normal, f.normal) == 0.0)
            return; /* degenerate: no side to show */
        Vec normal = v.before && f.turned ? f.normal * -1.0 : f.normal; /* before: as read */
        double X[3], Y[3], Z[3];
        for (int k = 0; k < 3; ++k) {
            X[k] = (v.ox + v.scale * dot(f.p[k], v.right) - v.x) * samples;
            Y[k] = (v.oy - v.scale * dot(f.p[k], v.up) - v.y) * samples;
            Z[k] = dot(f.p[k], v.toward);
        }
        double area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
        double facing = dot(normal, v.toward);
        bool front = facing > -1e-6; /* edge-on counts as front */
        if (v.before && !front)
            return; /* culled, as a renderer culls back faces */
        double lit = 0.35 + 0.65 * std::max(0.0, dot(front ? normal : normal * -1.0, light));
        bool marked_face = !v.before && is_marked(f.mark);
        Rgb base = v.before ? Rgb{grey, grey, grey}
                            : !marked_face ? (front ? f.kept : back_blue) : f.mark == Mark::flipped ? red : amber;
        Rgb main = shade(base, lit), stripe = shade(back_blue, lit);
        bool striped = !front && marked_face;
        if (std::fabs(area) < 2.0) {
            /* edge-on, or smaller than a pixel: its edges, a pixel wide, so
               that a sheet seen from its side is a line and a dense mesh
               has no holes; behind the faces they border (an edge-on face
               of a solid is where its other faces are) */
            if (std::fabs(facing) < 0.05)
                main = shade(base, 0.6); /* lit from the side: neither bright nor dark */
            for (int e = 0; e < 3; ++e) {
                int a = e, b = (e + 1) % 3;
                int n = (int)std::ceil(std::max(std::fabs(X[b] - X[a]), std::fabs(Y[b] - Y[a])));
                for (int k = 0; k <= n; ++k) {
                    double t = n > 0 ? (double)k / n : 0.0;
                    double x = X[a] + t * (X[b] - X[a]), y = Y[a] + t * (Y[b] - Y[a]), z = Z[a] + t * (Z[b] - Z[a]);
                    for (int j = (int)std::ceil(y - 1.5); j <= (int)std::floor(y + 0.5); ++j)
                        for (int i = (int)std::ceil(x - 1.5); i <= (int)std::floor(x + 0.5); ++i)
                            put(i, j, z - 1e-4, main, marked_face);
                }
            }
            return;
        }
        int i0 = std::max(0, (int)std::floor(std::min({X[0], X[1], X[2]})));
        int i1 = std::min(sw - 1, (int)std::ceil(std::max({X[0], X[1], X[2]})));
        int j0 = std::max(0, (int)std::floor(std::min({Y[0], Y[1], Y[2]})));
        int j1 = std::min(sh - 1, (int)std::ceil(std::max({Y[0], Y[1], Y[2]})));
        double inv = 1.0 / area;
        for (int j = j0; j <= j1; ++j) {
            /* the row's span: where its centre line crosses the edges, a
               sample wider each side (the test below decides), so that a
               long sliver costs its length, not its bounding box */
            double py = j + 0.5, lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (int e = 0; e < 3; ++e) {
                int a = e, b = (e + 1) % 3;
                if ((Y[a] - py) * (Y[b] - py) > 0.0 || Y[a] == Y[b])
                    continue;
                double x = X[a] + (py - Y[a]) * (X[b] - X[a]) / (Y[b] - Y[a]);
                lo = std::min(lo, x), hi = std::max(hi, x);
            }
            if (!(lo <= hi))
                continue;
            int from = std::max(i0, (int)std::floor(lo) - 1), to = std::min(i1, (int)std::ceil(hi) + 1);
            for (int i = from; i <= to; ++i) {
                double px = i + 0.5;
                double b0 = ((X[1] - px) * (Y[2] - py) - (X[2] - px) * (Y[1] - py)) * inv;
                double b1 = ((X[2] - px) * (Y[0] - py) - (X[0] - px) * (Y[2] - py)) * inv;
                double b2 = 1.0 - b0 - b1;
                if (b0 < 0.0 || b1 < 0.0 || b2 < 0.0)
                    continue;
                put(i, j, b0 * Z[0] + b1 * Z[1] + b2 * Z[2],
                    striped && ((i + j) / (8 * samples)) % 2 == 1 ? stripe : main, marked_face);
            }
        }
    });
    /* outlines: a covered sample beside an empty one, or in front of one
       much farther away, darkened */
    const double step = 0.04;
    std::vector<Rgb> outlined = colour;
    for (int j = 0; j < sh; ++j)
        for (int i = 0; i < sw; ++i) {
            size_t at = (size_t)j * (size_t)sw + (size_t)i;
            if (depth[at] == none)
                continue;
            bool edge = false;
            static const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
            for (int k = 0; k < 4 && !edge; ++k) {
                int ni = i + di[k], nj = j + dj[k];
                if (ni >= 0 && nj >= 0 && ni < sw && nj < sh)
                    edge = depth[(size_t)nj * (size_t)sw + (size_t)ni] < depth[at] - step;
            }
            if (edge) {
                Rgb c = colour[at];
                outlined[at] = {(unsigned char)(c.r * 11 / 20), (unsigned char)(c.g * 11 / 20), (unsigned char)(c.b * 11 / 20)};
            }
        }
    for (int y = 0; y < v.h; ++y)
        for (int x = 0; x < v.w; ++x) {
            unsigned r = 0, g = 0, b = 0;
            for (int j = 0; j < samples; ++j)
                for (int i = 0; i < samples; ++i) {
                    const Rgb &c = outlined[(size_t)(y * samples + j) * (size_t)sw + (size_t)(x * samples + i)];
                    r += c.r, g += c.g, b += c.b;
                }
            const unsigned n = samples * samples;
            canvas.put(v.x + x, v.y + y, {(unsigned char)((r + n / 2) / n), (unsigned char)((g + n / 2) / n),
                                          (unsigned char)((b + n / 2) / n)});
        }
    canvas.text(v.x + 8, v.y + 6, fit(v.label, (size_t)(v.w - 16) / advance), muted);
    if (marked != nullptr)
        marked->swap(shows_mark);
}

/* ---- rings: marked faces too small to see ---- */

/* A ring, its centre relative to its view's cell (the same in the before
   view of that camera). */
struct Ring {
    double x, y, r;
    Rgb c;
};

const int spot_cell = 24;       /* pixels: marked faces whose centres are this close are one spot */
const int visible_enough = 100; /* pixels: a spot showing fewer marked ones is ringed */
const size_t most_rings = 24;   /* per view */

/* The spots of marked faces in an "after" view that show fewer than
   visible_enough marked pixels (hidden, edge-on or small), each as a ring
   around it: red when a face of it is flipped, else amber. A spot is the
   marked faces whose projected centres fall in touching 24-pixel squares;
   the first most_rings spots, in the order of their squares (top to
   bottom, left to right). */
std::vector<Ring> find_rings(const View &v, const Model &model, const std::vector<unsigned char> &marked)
{
    struct Square {
        double x0, y0, x1, y1; /* the projected extent of its faces, in the cell */
        bool flipped;
        int spot;
    };
    const double inf = std::numeric_limits<double>::infinity();
    std::map<std::pair<int, int>, Square> squares; /* (row, column) */
    model.each_face([&](const Face &f) {
        if (!is_marked(f.mark))
            return;
        double X[3], Y[3];
        for (int k = 0; k < 3; ++k)
            X[k] = v.ox + v.scale * dot(f.p[k], v.right) - v.x, Y[k] = v.oy - v.scale * dot(f.p[k], v.up) - v.y;
        double cx = (X[0] + X[1] + X[2]) / 3.0, cy = (Y[0] + Y[1] + Y[2]) / 3.0;
        std::pair<int, int> key((int)std::floor(cy / spot_cell), (int)std::floor(cx / spot_cell));
        Square &q = squares.emplace(key, Square{inf, inf, -inf, -inf, false, -1}).first->second;
        q.x0 = std::min({q.x0, X[0], X[1], X[2]}), q.x1 = std::max({q.x1, X[0], X[1], X[2]});
        q.y0 = std::min({q.y0, Y[0], Y[1], Y[2]}), q.y1 = std::max({q.y1, Y[0], Y[1], Y[2]});
        q.flipped |= f.mark == Mark::flipped;
    });
    std::vector<Ring> rings;
    int spots = 0;
    for (auto &start : squares) {
        if (start.second.spot >= 0)
            continue;
        /* the spot: the squares touching this one, and so on (8 neighbours) */
        Square spot = start.second;
        std::vector<std::pair<int, int>> todo{start.first};
        start.second.spot = spots;
        while (!todo.empty()) {
            std::pair<int, int> at = todo.back();
            todo.pop_back();
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    auto next = squares.find({at.first + dy, at.second + dx});
                    if (next == squares.end() || next->second.spot >= 0)
                        continue;
                    Square &q = next->second;
                    q.spot = spots;
                    spot.x0 = std::min(spot.x0, q.x0), spot.x1 = std::max(spot.x1, q.x1);
                    spot.y0 = std::min(spot.y0, q.y0), spot.y1 = std::max(spot.y1, q.y1);
                    spot.flipped |= q.flipped;
                    todo.push_back(next->first);
                }
        }
        ++spots;
        /* its marked pixels that show */
        int i0 = std::max(0, (int)std::floor(spot.x0 * samples)), i1 = std::min(v.w * samples - 1, (int)std::ceil(spot.x1 * samples));
        int j0 = std::max(0, (int)std::floor(spot.y0 * samples)), j1 = std::min(v.h * samples - 1, (int)std::ceil(spot.y1 * samples));
        long shown = 0;
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i)
                shown += marked[(size_t)j * (size_t)(v.w * samples) + (size_t)i];
        if (shown >= (long)visible_enough * samples * samples)
            continue;
        double w = spot.x1 - spot.x0, h = spot.y1 - spot.y0;
        double r = std::min(std::max(0.5 * std::sqrt(w * w + h * h) + 8.0, 14.0), std::min(v.w, v.h) / 3.0);
        rings.push_back({0.5 * (spot.x0 + spot.x1), 0.5 * (spot.y0 + spot.y1), r, spot.flipped ? red : amber});
        if (rings.size() == most_rings)
            break;
    }
    return rings;
}

/* A ring 3 pixels wide with a white pixel each side, within the rectangle
   (x, y, w, h) of the canvas. */
void draw_ring(Canvas &canvas, double cx, double cy, double r, Rgb c, int x, int y, int w, int h)
{
    int i0 = std::max(x, (int)std::floor(cx - r - 3)), i1 = std::min(x + w - 1, (int)std::ceil(cx + r + 3));
    int j0 = std::max(y, (int)std::floor(cy - r - 3)), j1 = std::min(y + h - 1, (int)std::ceil(cy + r + 3));
    for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
            double dx = i + 0.5 - cx, dy = j + 0.5 - cy, d = std::fabs(std::sqrt(dx * dx + dy * dy) - r);
            if (d <= 1.5)
                canvas.put(i, j, c);
            else if (d <= 2.5)
                canvas.put(i, j, white);
        }
}

std::string number(double x)
{
    if (x == 0.0)
        x = 0.0; /* not "-0" */
    char s[40];
    std::snprintf(s, sizeof(s), "%.9g", x);
    return s;
}

/* ---- PNG ---- */

struct PngSink {
    std::string bytes;
    std::string error;
};

#ifdef MESHFIX_TOOL_NO_PNG
bool encode_png(const Canvas &, const std::string &, PngSink &sink)
{
    sink.error = "this meshfix was built without PNG support (no libpng)";
    return false;
}
#else
void png_failed(png_structp png, png_const_charp message)
{
    PngSink *sink = (PngSink *)png_get_error_ptr(png);
    sink->error = message != nullptr ? message : "libpng failed";
    png_longjmp(png, 1);
}

void png_warned(png_structp, png_const_charp) {}

void png_append(png_structp png, png_bytep data, png_size_t size)
{
    PngSink *sink = (PngSink *)png_get_io_ptr(png);
    bool ok = true;
    try {
        sink->bytes.append((const char *)data, size);
    } catch (const std::exception &) {
        ok = false;
    }
    if (!ok)
        png_error(png, "out of memory");
}

void png_flush_nothing(png_structp) {}

/* The canvas as PNG bytes: 8-bit RGB, the views in a tEXt chunk, nothing
   that changes from run to run (no time chunk). libpng reports errors by
   longjmp: nothing here between setjmp and the calls has a destructor to
   skip (the vectors are made before). */
bool encode_png(const Canvas &canvas, const std::string &views, PngSink &sink)
{
    std::vector<png_bytep> rows((size_t)canvas.height);
    for (int y = 0; y < canvas.height; ++y)
        rows[(size_t)y] = (png_bytep)&canvas.pixels[(size_t)y * (size_t)canvas.width * 3];
    char key[] = "meshfix views";
    std::vector<char> text(views.begin(), views.end());
    text.push_back(0);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, png_failed, png_warned);
    if (png == nullptr) {
        sink.error = "cannot start libpng";
        return false;
    }
    png_infop info = png_create_info_struct(png);
    if (info == nullptr) {
        png_destroy_write_struct(&png, nullptr);
        sink.error = "out of memory";
        return false;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_set_write_fn(png, &sink, png_append, png_flush_nothing);
    png_set_IHDR(png, info, (png_uint_32)canvas.width, (png_uint_32)canvas.height, 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_compression_level(png, 9);
    png_text chunk;
    std::memset(&chunk, 0, sizeof(chunk));
    chunk.compression = PNG_TEXT_COMPRESSION_NONE;
    chunk.key = key;
    chunk.text = text.data();
    png_set_text(png, info, &chunk, 1);
    png_write_info(png, info);
    png_write_image(png, rows.data());
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return true;
}
#endif

} // namespace

namespace {

std::string triangles_word(size_t n) { return std::to_string(n) + (n == 1 ? " triangle" : " triangles"); }

/* The legend's words: what each colour covers, counted in triangles. */
std::vector<std::string> legend_words(const MeshFile &file, const std::vector<UnitResult> &results, bool inspect)
{
    size_t flipped = 0, doubtful = 0, doubtful_flipped = 0, kept = 0, none = 0;
    std::set<std::pair<size_t, unsigned int>> kept_patches;
    for (size_t i = 0; i < file.units.size(); ++i) {
        const Unit &u = file.units[i];
        const UnitResult &r = results[i];
        for (size_t t = 0; t < u.indices.size() / 3; ++t)
            switch (mark_of(u, r, t)) {
            case Mark::flipped:
                ++flipped;
                break;
            case Mark::doubtful:
                ++doubtful;
                doubtful_flipped += r.changes.face_flipped[u.triangle_face[t]]; /* flipped, or would be */
                break;
            case Mark::kept:
                ++kept;
                kept_patches.insert({i, r.patch_ids[t]});
                break;
            case Mark::none:
                ++none;
                break;
            }
    }
    size_t patches = kept_patches.size();
    return {(inspect ? "would flip: " : "flipped: ") + triangles_word(flipped),
            "doubtful: " + triangles_word(doubtful) +
                (doubtful != 0 ? ", " + std::to_string(doubtful_flipped) + (inspect ? " would flip" : " flipped") : ""),
            "kept: " + triangles_word(kept) + " in " + std::to_string(patches) + (patches == 1 ? " patch" : " patches") +
                (none != 0 ? " (" + std::to_string(none) + " in none)" : ""),
            "seen from behind (inside-out)", "ringed: too small to see"};
}

} // namespace

void picture_up(const MeshFile &file, float up[3], std::string &why)
{
    up[0] = up[1] = 0.0f, up[2] = 1.0f;
    std::string format = file.format();
    if (is_gltf_format(format) || format == "obj")
        up[1] = 1.0f, up[2] = 0.0f;
    why = format == "obj" ? "OBJ" : is_gltf_format(format) ? "glTF" : format == "stl" ? "STL" : format == "ply" ? "PLY" : "OFF";
    if (format != "obj")
        return;
    /* the mesh's extent, then its area and the level area at its lowest y and z */
    const double inf = std::numeric_limits<double>::infinity();
    double lo[3] = {inf, inf, inf}, hi[3] = {-inf, -inf, -inf};
    auto each_triangle = [&](auto &&use) {
        for (const Unit &u : file.units)
            for (size_t t = 0; t < u.indices.size() / 3; ++t) {
                const double *c[3];
                bool finite = true;
                for (int k = 0; k < 3; ++k) {
                    c[k] = &u.positions[3 * (size_t)u.indices[3 * t + (size_t)k]];
                    finite = finite && std::isfinite(c[k][0]) && std::isfinite(c[k][1]) && std::isfinite(c[k][2]);
                }
                if (finite)
                    use(c);
            }
    };
    each_triangle([&](const double *const *c) {
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a)
                lo[a] = std::min(lo[a], c[k][a]), hi[a] = std::max(hi[a], c[k][a]);
    });
    double size = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    if (!(size > 0.0) || !std::isfinite(size))
        return;
    if (std::fabs(lo[2]) <= 0.005 * size && std::fabs(lo[1]) > 0.05 * size) {
        up[1] = 0.0f, up[2] = 1.0f, why = "OBJ standing on z = 0";
        return;
    }
    double area = 0.0, base[3] = {0.0, 0.0, 0.0};
    const double level = std::cos(25.0 * 3.14159265358979323846 / 180.0);
    each_triangle([&](const double *const *c) {
        Vec a{c[0][0], c[0][1], c[0][2]}, b{c[1][0], c[1][1], c[1][2]}, d{c[2][0], c[2][1], c[2][2]};
        Vec n = cross(b - a, d - a);
        double twice = std::sqrt(dot(n, n));
        area += 0.5 * twice;
        for (int axis = 1; axis < 3; ++axis) {
            double along = axis == 1 ? n.y : n.z;
            double top = std::max({c[0][axis], c[1][axis], c[2][axis]});
            if (twice > 0.0 && std::fabs(along) >= level * twice && top <= lo[axis] + 0.01 * size)
                base[axis] += 0.5 * twice;
        }
    });
    if (base[2] >= 0.01 * area && base[2] >= 3.0 * base[1])
        up[1] = 0.0f, up[2] = 1.0f, why = "OBJ with a flat base at its lowest z";
}

bool write_picture(const std::string &path, const MeshFile &file, const std::vector<UnitResult> &results,
                   const float up[3], const PictureText &words, std::string &error)
{
    if (!png_supported()) {
        error = "cannot write '" + path + "': this meshfix was built without PNG support (no libpng)";
        return false;
    }
    Model model(file, results);
    std::vector<View> views = cameras(up);
    Layout layout = lay_out(views, model);
    const int width = layout.width;
    const size_t columns = (size_t)(width - 2 * margin) / advance;
    std::vector<std::string> summary = wrap(drawable(words.summary), columns);
    const int summary_y = views_top + layout.grid_h + 12;
    Canvas canvas(width, summary_y + (int)summary.size() * line_height + 6, white);
    canvas.text(margin, 10, fit(drawable(words.title), columns), ink);
    /* the legend: red, amber, grey in the first column; blue and the ring in the second */
    const std::vector<std::string> legend = legend_words(file, results, words.inspect);
    const Rgb swatches[4] = {red, amber, {grey, grey, grey}, back_blue};
    for (int k = 0; k < 5; ++k) {
        int x = legend_x[k / 3], y = legend_y[k % 3];
        canvas.rect(x - 1, y - 1, swatch + 2, swatch + 2, muted);
        if (k < 4)
            canvas.rect(x, y, swatch, swatch, swatches[k]);
        else
            draw_ring(canvas, x + swatch / 2.0, y + swatch / 2.0, 5.5, red, x, y, swatch, swatch);
        canvas.text(x + swatch + 8, y, fit(legend[(size_t)k], (size_t)(width - x - swatch - 8 - margin) / advance), ink);
    }
    const char *const headers[2] = {"before: the input as read, faces seen from behind culled (as a renderer draws it)",
                                    words.inspect ? "after: as a repair would write it, marked" : "after: as written, the repair marked"};
    for (int b = 0; b < 2; ++b)
        canvas.text(layout.block_x[b], layout.block_y[b] + 6, fit(headers[b], (size_t)layout.block_w / advance), ink);
    for (size_t k = 0; k < 4; ++k) {
        View &after = views[k], &before = views[k + 4];
        std::vector<unsigned char> marked;
        draw_view(canvas, after, model, &marked);
        draw_view(canvas, before, model, nullptr);
        for (const Ring &ring : find_rings(after, model, marked))
            for (const View *v : {&after, &before})
                draw_ring(canvas, v->x + ring.x, v->y + ring.y, ring.r, ring.c, v->x, v->y + label_h, v->w, v->h - label_h);
    }
    std::string chunk;
    for (const View &v : views) {
        double s = model.file_scale(v.scale);
        chunk += v.name + " " + std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.w) + " " +
                 std::to_string(v.h) + " " + number(model.file_offset(v.ox, v.scale, v.right)) + " " +
                 number(v.oy + s * dot(model.centre(), v.up)) + " " + number(s);
        for (Vec a : {v.right, v.up})
            chunk += " " + number(a.x) + " " + number(a.y) + " " + number(a.z);
        chunk += "\n";
    }
    for (size_t k = 0; k < summary.size(); ++k)
        canvas.text(margin, summary_y + (int)k * line_height, summary[k], ink);
    PngSink sink;
    if (!encode_png(canvas, chunk, sink)) {
        error = "cannot write '" + path + "': " + sink.error;
        return false;
    }
    return write_bytes(path, sink.bytes, error);
}

} // namespace tool
