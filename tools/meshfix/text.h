/* meshfix command-line tool: text helpers for the lossless writers.
   A rewritten file is the input with a few byte ranges replaced, so
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
