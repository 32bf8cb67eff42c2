/* meshfix command-line tool: a JSON document edited as text (glTF).

   A changed glTF is written as its own JSON text with only the members the
   repair changes replaced or added, so every other byte stays as it was:
   numbers as written (a 64-bit integer, 1e400, -0), nulls in arrays, empty
   arrays and objects, unknown members and extensions, escapes, member
   order and white space. A reader of the document (nlohmann json, as in
   tinygltf, or a browser) takes the last of two members with one name, so
   the last is the one read and edited here. */
#ifndef MESHFIX_TOOL_JSON_EDIT_H
#define MESHFIX_TOOL_JSON_EDIT_H

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace tool {

struct JsonMember;

/* A value in the text: where it is and, for the objects and arrays that
   can be edited (those not inside "extras" or "extensions", to a depth of
   five), what is inside. */
struct JsonValue {
    char kind = 0;            /* '{', '[', '"', '0' (number), 't', 'f' or 'n' */
    size_t begin = 0, end = 0; /* its text: [begin, end) */
    std::string string;       /* a string's value, decoded */
    std::vector<JsonMember> members; /* an object's, in order */
    std::vector<JsonValue> items; /* an array's */
    bool children = false;        /* members and items were kept */

    /* The last member named `key`, or nullptr. */
    const JsonValue *member(const std::string &key) const;
};

struct JsonMember {
    std::string key;
    size_t key_begin = 0; /* its opening quote */
    JsonValue value;
};

/* Parses JSON text (RFC 8259; white space, and the NULs some writers pad
   a GLB chunk with, may follow the value). false when it is not JSON. */
bool parse_json(const std::string &text, JsonValue &root);

/* The text of a JSON string holding `value` (quotes included). */
std::string json_quote(const std::string &value);

/* Changes to a document's text, applied all at once: each replaces a span
   of the original, so spans must not overlap. */
class JsonEdits {
public:
    explicit JsonEdits(const std::string &source) : text(source) {}
    /* Sets the object's member to the value's text: its last value
       replaced, or the member added at the end. */
    void set(const JsonValue &object, const std::string &key, const std::string &value_text);
    /* Writes the object again with its members changed: each (key, value
       text) replaces the last member of that name (others of the name
       dropped) or is added at the end; an empty value text removes the
       member. The other members keep their text. Nothing inside the object
       may be edited too. */
    void update(const JsonValue &object, const std::vector<std::pair<std::string, std::string>> &changes);
    /* Appends items (their texts) to the array. */
    void append(const JsonValue &array, const std::vector<std::string> &item_texts);
    /* The document with every change. */
    std::string result() const;

private:
    void splice(size_t begin, size_t end, const std::string &with);
    const std::string &text;
    std::vector<std::pair<std::pair<size_t, size_t>, std::string>> splices;
};

} // namespace tool

#endif
