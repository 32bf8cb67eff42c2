/* meshfix command-line tool: text helpers for the readers and the
   lossless writers. The text formats (OBJ, OFF, ASCII STL, the PLY header)
   are read with one idea of a line and a word: a line ends at LF, CRLF or
   a lone CR (files from old Macs, or with their line ends mixed), and a
   UTF-8 byte-order mark before the first word is no part of it. A
   rewritten file is the input with a few byte ranges replaced, so
   everything the tool does not touch passes through as it was. */
#ifndef MESHFIX_TOOL_TEXT_H
#define MESHFIX_TOOL_TEXT_H

#include <cstddef>
#include <string>
#include <vector>

namespace tool {

struct Span {
    size_t begin, end; /* bytes [begin, end) of the file */
};

/* Replace `length` bytes at `offset` with `text`. */
struct Edit {
    size_t offset, length;
    std::string text;
};

/* Spaces between tokens (a NUL byte is not one: it is part of a token). */
inline bool is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

/* 3 when the data starts with a UTF-8 byte-order mark (an editor's mark,
   not text: left as it is, read past), else 0. */
size_t byte_order_mark(const std::string &data);

/* The length of the line break at `at`: 2 for CRLF, 1 for LF or a lone
   CR, 0 when none starts there. */
size_t line_break(const std::string &data, size_t at);

/* Where the line holding `at` ends: its line break, or the data's end. */
size_t line_end(const std::string &data, size_t at);

/* Words across lines, a '#' that starts a word commenting out the rest
   of its line (OFF, ASCII STL). A word is compared whole: a NUL byte is
   part of it. */
struct WordScanner {
    explicit WordScanner(const std::string &d) : data(d), at(byte_order_mark(d)) {}

    /* The next word; false at the end of the data. */
    bool word(Span &s);
    /* Past the rest of the line (not its line break). */
    void skip_line() { at = line_end(data, at); }
    std::string text(const Span &s) const { return data.substr(s.begin, s.end - s.begin); }
    bool is(const Span &s, const char *w) const;

    const std::string &data;
    size_t at;
};

/* The data with every edit applied; edits must not overlap. */
std::string splice(const std::string &data, std::vector<Edit> edits);

/* The corners of a face in reverse order, the first kept first (the
   library's flip of (a, b, c) is (a, c, b)): the position each corner
   moves to. */
inline size_t reversed_corner(size_t i, size_t n) { return i == 0 ? 0 : n - i; }

/* Edits that write the face's corner tokens in reverse order (first kept),
   leaving the space between them as it was. */
void reverse_tokens(const std::string &data, const std::vector<Span> &corners, std::vector<Edit> &edits);

/* The text of a number negated without reformatting it: "-0.5" becomes
   "0.5", "1e3" becomes "-1e3"; a zero stays as it is. */
std::string negated_number(const std::string &token);

/* A number token as a double; false when it is not one. */
bool parse_double(const std::string &token, double &value);

} // namespace tool

#endif
