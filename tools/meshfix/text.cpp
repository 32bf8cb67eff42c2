/* meshfix command-line tool: text helpers for the readers and the
   lossless writers. */
#include "text.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>

namespace tool {

size_t byte_order_mark(const std::string &data) { return data.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0; }

size_t line_break(const std::string &data, size_t at)
{
    if (at >= data.size())
        return 0;
    if (data[at] == '\n')
        return 1;
    if (data[at] != '\r')
        return 0;
    return at + 1 < data.size() && data[at + 1] == '\n' ? 2 : 1;
}

size_t line_end(const std::string &data, size_t at)
{
    while (at < data.size() && data[at] != '\n' && data[at] != '\r')
        ++at;
    return at;
}

bool WordScanner::word(Span &s)
{
    for (;;) {
        while (at < data.size() && is_space(data[at]))
            ++at;
        if (at < data.size() && data[at] == '#') {
            skip_line();
            continue;
        }
        break;
    }
    s.begin = at;
    while (at < data.size() && !is_space(data[at]))
        ++at;
    s.end = at;
    return s.end > s.begin;
}

bool WordScanner::is(const Span &s, const char *w) const
{
    return s.end - s.begin == std::strlen(w) && data.compare(s.begin, s.end - s.begin, w) == 0;
}

std::string splice(const std::string &data, std::vector<Edit> edits)
{
    std::sort(edits.begin(), edits.end(), [](const Edit &a, const Edit &b) { return a.offset < b.offset; });
    std::string out;
    out.reserve(data.size() + 16 * edits.size());
    size_t at = 0;
    for (const Edit &e : edits) {
        out.append(data, at, e.offset - at);
        out += e.text;
        at = e.offset + e.length;
    }
    out.append(data, at, std::string::npos);
    return out;
}

void reverse_tokens(const std::string &data, const std::vector<Span> &corners, std::vector<Edit> &edits)
{
    size_t n = corners.size();
    for (size_t i = 1; i < n; ++i) {
        const Span &to = corners[reversed_corner(i, n)];
        const Span &from = corners[i];
        edits.push_back({to.begin, to.end - to.begin, data.substr(from.begin, from.end - from.begin)});
    }
}

bool parse_double(const std::string &token, double &value)
{
    char *end = nullptr;
    errno = 0;
    value = std::strtod(token.c_str(), &end);
    return !token.empty() && end == token.c_str() + token.size();
}

std::string negated_number(const std::string &token)
{
    double value;
    if (!parse_double(token, value) || value == 0.0)
        return token; /* -0 for 0 would change the bytes and nothing else */
    if (token[0] == '-')
        return token.substr(1);
    if (token[0] == '+')
        return "-" + token.substr(1);
    return "-" + token;
}

} // namespace tool
