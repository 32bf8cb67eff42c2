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
    Rgb kept; /* its colour when kept */
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
    Vec toward, right, up; /* toward the camera; the screen's right and up */
    double lo_r = 0, hi_r = 0, lo_u = 0, hi_u = 0; /* the model's extent on right and up */
    int x = 0, y = 0, w = 0, h = 0;                /* the cell in the image */
    double scale = 1, ox = 0, oy = 0;              /* pixel = (ox + scale (p . right), oy - scale (p . up)) */
};

const int margin = 12, views_top = 100, gap = 10, pad = 14, label_h = 28;
const int max_views_w = 1240, max_views_h = 960, min_cell_w = 250, min_content_h = 80, min_width = 740;
const int samples = 2; /* per pixel along x and y */
const int legend_x[2] = {12, 330}, legend_y[2] = {40, 66}, swatch = 18;

/* The four cameras for an up axis. The screen's right is +x (+y when up
   is along x); the front camera is on the side right x up: -y when z is
   up, +z when y is up (glTF's front), -z when x is up. The back camera is
   opposite, the top one above looking down (the front at the bottom of
   the view), the oblique one 35 degrees from the front to the right and
   30 degrees up. */
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
    return v;
}

/* Where the views are: the image's width and the grid's height. */
struct Layout {
    int width = 0, grid_h = 0;
};

/* Fits the views to the model and places them. Front, back and top share
   one scale (one drawing of the model, as on a plan); the oblique view is
   fitted to the same cell on its own. */
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
        if (i < 3)
            mw = std::max(mw, v.hi_r - v.lo_r), mh = std::max(mh, v.hi_u - v.lo_u);
    }
    const View &oblique = views[3];
    double ow = std::max(oblique.hi_r - oblique.lo_r, 1e-3 * m), oh = std::max(oblique.hi_u - oblique.lo_u, 1e-3 * m);
    mw = std::max(mw, 1e-3 * m), mh = std::max(mh, 1e-3 * m);
    /* the grid that draws the plan views largest (the oblique one counts a
       quarter), the square one unless another is clearly larger */
    static const int grids[3][2] = {{2, 2}, {4, 1}, {1, 4}};
    int cols = 2, rows = 2, content_w = 0, content_h = 0;
    double plan = 0, best = 0;
    for (int g = 0; g < 3; ++g) {
        int c = grids[g][0], r = grids[g][1];
        double aw = (double)(max_views_w - (c - 1) * gap) / c - 2 * pad;
        double ah = (double)(max_views_h - (r - 1) * gap) / r - label_h - 2 * pad;
        double s = std::min(aw / mw, ah / mh);
        int cw = std::max((int)std::ceil(s * mw), min_cell_w - 2 * pad), ch = std::max((int)std::ceil(s * mh), min_content_h);
        double score = std::pow(s, 0.75) * std::pow(std::min(cw / ow, ch / oh), 0.25);
        if (g == 0 || score > 1.15 * best)
            cols = c, rows = r, plan = s, best = score, content_w = cw, content_h = ch;
    }
    int cell_w = content_w + 2 * pad, cell_h = label_h + content_h + 2 * pad;
    int grid_w = cols * cell_w + (cols - 1) * gap;
    Layout out;
    out.width = std::max(min_width, grid_w + 2 * margin);
    out.grid_h = rows * cell_h + (rows - 1) * gap;
    int x0 = (out.width - grid_w) / 2;
    for (size_t i = 0; i < views.size(); ++i) {
        View &v = views[i];
        v.x = x0 + (int)(i % (size_t)cols) * (cell_w + gap);
        v.y = views_top + (int)(i / (size_t)cols) * (cell_h + gap);
        v.w = cell_w, v.h = cell_h;
        v.scale = i < 3 ? plan : std::min(content_w / ow, content_h / oh);
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

/* Draws one view into its cell of the canvas. */
void draw_view(Canvas &canvas, const View &v, const Model &model)
{
    const int sw = v.w * samples, sh = v.h * samples;
    const double none = -std::numeric_limits<double>::infinity();
    std::vector<double> depth((size_t)sw * (size_t)sh, none);
    std::vector<Rgb> colour((size_t)sw * (size_t)sh, panel);
    const Vec light = unit(v.right * -0.35 + v.up * 0.45 + v.toward * 0.82); /* from the upper left, near the camera */
    /* a sample: nearer than what is there (ties to the first drawn) */
    auto put = [&](int i, int j, double z, Rgb c) {
        if (i < 0 || j < 0 || i >= sw || j >= sh)
            return;
        size_t at = (size_t)j * (size_t)sw + (size_t)i;
        if (z > depth[at])
            depth[at] = z, colour[at] = c;
    };
    model.each_face([&](const Face &f) {
        if (dot(f.normal, f.normal) == 0.0)
            return; /* degenerate: no side to show */
        double X[3], Y[3], Z[3];
        for (int k = 0; k < 3; ++k) {
            X[k] = (v.ox + v.scale * dot(f.p[k], v.right) - v.x) * samples;
            Y[k] = (v.oy - v.scale * dot(f.p[k], v.up) - v.y) * samples;
            Z[k] = dot(f.p[k], v.toward);
        }
        double area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
        double facing = dot(f.normal, v.toward);
        bool front = facing > -1e-6; /* edge-on counts as front */
        double lit = 0.35 + 0.65 * std::max(0.0, dot(front ? f.normal : f.normal * -1.0, light));
        bool marked = f.mark == Mark::flipped || f.mark == Mark::doubtful;
        Rgb base = !marked ? (front ? f.kept : back_blue) : f.mark == Mark::flipped ? red : amber;
        Rgb main = shade(base, lit), stripe = shade(back_blue, lit);
        bool striped = !front && marked;
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
                            put(i, j, z - 1e-4, main);
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
                    striped && ((i + j) / (8 * samples)) % 2 == 1 ? stripe : main);
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
    const Rgb swatches[4] = {red, amber, back_blue, {grey, grey, grey}};
    const char *const legend[4] = {words.inspect ? "would be flipped" : "flipped by the repair", "doubtful patch",
                                   "back face (renders inside-out)", "kept (tinted by patch)"};
    for (int k = 0; k < 4; ++k) {
        int x = legend_x[k / 2], y = legend_y[k % 2];
        canvas.rect(x - 1, y - 1, swatch + 2, swatch + 2, muted);
        canvas.rect(x, y, swatch, swatch, swatches[k]);
        canvas.text(x + swatch + 8, y, legend[k], ink);
    }
    std::string chunk;
    for (const View &v : views) {
        draw_view(canvas, v, model);
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
