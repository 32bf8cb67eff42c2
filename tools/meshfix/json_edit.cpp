/* meshfix command-line tool: a JSON document edited as text (json_edit.h). */
#include "json_edit.h"

#include <algorithm>
#include <cstdint>

namespace tool {
namespace {

/* The objects and arrays whose insides are kept: the root and four levels
   below it reach a glTF primitive's members (meshes[i].primitives[j]). */
const int kept_depth = 4;
/* Deeper than any glTF the tool reads (it refuses more than 128 levels
   before parsing): the recursion stops here. */
const int deepest = 512;

struct Parser {
    const std::string &text;
    size_t at = 0;

    void skip_space()
    {
        while (at < text.size() && (text[at] == ' ' || text[at] == '\t' || text[at] == '\n' || text[at] == '\r'))
            ++at;
    }

    static int hex(char c)
    {
        return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
    }

    bool hex4(unsigned &code)
    {
        code = 0;
        for (int k = 0; k < 4; ++k) {
            if (at >= text.size() || hex(text[at]) < 0)
                return false;
            code = code * 16 + (unsigned)hex(text[at++]);
        }
        return true;
    }

    static void put_utf8(std::string &out, unsigned code)
    {
        if (code < 0x80) {
            out += (char)code;
        } else if (code < 0x800) {
            out += (char)(0xC0 | code >> 6);
            out += (char)(0x80 | (code & 0x3F));
        } else if (code < 0x10000) {
            out += (char)(0xE0 | code >> 12);
            out += (char)(0x80 | (code >> 6 & 0x3F));
            out += (char)(0x80 | (code & 0x3F));
        } else {
            out += (char)(0xF0 | code >> 18);
            out += (char)(0x80 | (code >> 12 & 0x3F));
            out += (char)(0x80 | (code >> 6 & 0x3F));
            out += (char)(0x80 | (code & 0x3F));
        }
    }

    /* A string from its opening quote, decoded into `out`. */
    bool string(std::string &out)
    {
        ++at;
        while (at < text.size() && text[at] != '"') {
            unsigned char c = (unsigned char)text[at];
            if (c < 0x20)
                return false;
            if (c != '\\') {
                out += (char)c;
                ++at;
                continue;
            }
            if (++at >= text.size())
                return false;
            char e = text[at++];
            unsigned code;
            switch (e) {
            case '"': out += '"'; break;
            case '\\': out += '\\'; break;
            case '/': out += '/'; break;
            case 'b': out += '\b'; break;
            case 'f': out += '\f'; break;
            case 'n': out += '\n'; break;
            case 'r': out += '\r'; break;
            case 't': out += '\t'; break;
            case 'u':
                if (!hex4(code))
                    return false;
                /* a high surrogate with its low one is one code point */
                if (code >= 0xD800 && code < 0xDC00 && at + 1 < text.size() && text[at] == '\\' && text[at + 1] == 'u') {
                    size_t back = at;
                    unsigned low;
                    at += 2;
                    if (hex4(low) && low >= 0xDC00 && low < 0xE000)
                        code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
                    else
                        at = back;
                }
                put_utf8(out, code);
                break;
            default: return false;
            }
        }
        if (at >= text.size())
            return false;
        ++at;
        return true;
    }

    bool digits()
    {
        size_t start = at;
        while (at < text.size() && text[at] >= '0' && text[at] <= '9')
            ++at;
        return at > start;
    }

    bool number()
    {
        if (text[at] == '-')
            ++at;
        if (at < text.size() && text[at] == '0')
            ++at;
        else if (!digits())
            return false;
        if (at < text.size() && text[at] == '.' && (++at, !digits()))
            return false;
        if (at < text.size() && (text[at] == 'e' || text[at] == 'E')) {
            ++at;
            if (at < text.size() && (text[at] == '+' || text[at] == '-'))
                ++at;
            if (!digits())
                return false;
        }
        return true;
    }

    bool literal(const char *word)
    {
        size_t n = std::char_traits<char>::length(word);
        if (text.compare(at, n, word) != 0)
            return false;
        at += n;
        return true;
    }

    /* The value at `at`; its insides kept when `keep`. */
    bool value(JsonValue &v, int depth, bool keep)
    {
        skip_space();
        if (at >= text.size() || depth > deepest)
            return false;
        v.begin = at;
        char c = text[at];
        bool ok;
        if (c == '{')
            ok = object(v, depth, keep);
        else if (c == '[')
            ok = array(v, depth, keep);
        else if (c == '"')
            v.kind = '"', ok = string(v.string);
        else if (c == 't' || c == 'f' || c == 'n')
            v.kind = c, ok = literal(c == 't' ? "true" : c == 'f' ? "false" : "null");
        else
            v.kind = '0', ok = number();
        v.end = at;
        return ok;
    }

    bool object(JsonValue &v, int depth, bool keep)
    {
        v.kind = '{';
        v.children = keep;
        ++at;
        skip_space();
        if (at < text.size() && text[at] == '}')
            return ++at, true;
        for (;;) {
            skip_space();
            JsonMember m;
            m.key_begin = at;
            if (at >= text.size() || text[at] != '"' || !string(m.key))
                return false;
            skip_space();
            if (at >= text.size() || text[at++] != ':')
                return false;
            bool inner = keep && depth < kept_depth && m.key != "extras" && m.key != "extensions";
            if (!value(m.value, depth + 1, inner))
                return false;
            if (keep)
                v.members.push_back(std::move(m));
            skip_space();
            if (at < text.size() && text[at] == ',') {
                ++at;
                continue;
            }
            return at < text.size() && text[at++] == '}';
        }
    }

    bool array(JsonValue &v, int depth, bool keep)
    {
        v.kind = '[';
        v.children = keep;
        ++at;
        skip_space();
        if (at < text.size() && text[at] == ']')
            return ++at, true;
        for (;;) {
            JsonValue item;
            if (!value(item, depth + 1, keep && depth < kept_depth))
                return false;
            if (keep)
                v.items.push_back(std::move(item));
            skip_space();
            if (at < text.size() && text[at] == ',') {
                ++at;
                continue;
            }
            return at < text.size() && text[at++] == ']';
        }
    }
};

} // namespace

const JsonValue *JsonValue::member(const std::string &key) const
{
    for (size_t i = members.size(); i-- > 0;)
        if (members[i].key == key)
            return &members[i].value;
    return nullptr;
}

bool parse_json(const std::string &text, JsonValue &root)
{
    Parser p{text};
    root = JsonValue();
    if (text.compare(0, 3, "\xEF\xBB\xBF") == 0)
        p.at = 3; /* a byte-order mark, as nlohmann json (tinygltf's reader) skips it */
    if (!p.value(root, 0, true))
        return false;
    while (p.at < text.size() && (text[p.at] == ' ' || text[p.at] == '\t' || text[p.at] == '\n' || text[p.at] == '\r' ||
                                  text[p.at] == '\0'))
        ++p.at;
    return p.at == text.size();
}

std::string json_quote(const std::string &value)
{
    static const char digits[] = "0123456789abcdef";
    std::string out = "\"";
    for (char ch : value) {
        unsigned char c = (unsigned char)ch;
        if (c == '"' || c == '\\')
            out += '\\', out += (char)c;
        else if (c < 0x20)
            out += "\\u00", out += digits[c >> 4], out += digits[c & 15];
        else
            out += (char)c;
    }
    return out + "\"";
}

void JsonEdits::splice(size_t begin, size_t end, const std::string &with) { splices.push_back({{begin, end}, with}); }

void JsonEdits::set(const JsonValue &object, const std::string &key, const std::string &value_text)
{
    const JsonValue *old = object.member(key);
    if (old != nullptr)
        splice(old->begin, old->end, value_text);
    else /* before the closing brace */
        splice(object.end - 1, object.end - 1, (object.members.empty() ? "" : ",") + json_quote(key) + ":" + value_text);
}

void JsonEdits::update(const JsonValue &object, const std::vector<std::pair<std::string, std::string>> &changes)
{
    auto change = [&](const std::string &key) -> const std::string * {
        for (const auto &c : changes)
            if (c.first == key)
                return &c.second;
        return nullptr;
    };
    std::string members;
    auto add = [&](const std::string &member) { members += (members.empty() ? "" : ",") + member; };
    for (const JsonMember &m : object.members) {
        const std::string *to = change(m.key);
        if (to == nullptr)
            add(text.substr(m.key_begin, m.value.end - m.key_begin));
        else if (!to->empty() && object.member(m.key) == &m.value)
            add(json_quote(m.key) + ":" + *to); /* the last of its name: the one read */
    }
    for (const auto &c : changes)
        if (object.member(c.first) == nullptr && !c.second.empty())
            add(json_quote(c.first) + ":" + c.second);
    splice(object.begin, object.end, "{" + members + "}");
}

void JsonEdits::append(const JsonValue &array, const std::vector<std::string> &item_texts)
{
    std::string added;
    for (const std::string &t : item_texts)
        added += (added.empty() && array.items.empty() ? "" : ",") + t;
    splice(array.end - 1, array.end - 1, added);
}

std::string JsonEdits::result() const
{
    std::vector<std::pair<std::pair<size_t, size_t>, std::string>> sorted = splices;
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const auto &a, const auto &b) { return a.first.first < b.first.first; });
    std::string out;
    size_t at = 0;
    for (const auto &s : sorted) {
        out.append(text, at, s.first.first - at);
        out += s.second;
        at = s.first.second;
    }
    out.append(text, at, std::string::npos);
    return out;
}

} // namespace tool
