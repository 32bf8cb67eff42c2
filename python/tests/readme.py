"""The READMEs' Python parts, for python/test.sh (not a pytest file):

    readme.py install README.md python/README.md
        prints the install block (the ```sh block after the "<!-- install:"
        line) of the first file; exits 1 unless every file has it, the same
    readme.py run FILE...
        runs each file's ```python blocks in order, one namespace per file;
        a line `print(...)  # TEXT` checks that the line printed is TEXT
        (or starts with TEXT before a closing "..."); exits 1 on a failure,
        or when a file has no such line
"""
import re
import sys

MARK = "<!-- install:"
PRINT = re.compile(r"^(\s*)print\((.*)\)\s+#\s?(.*)$")


def blocks(text, language):
    """The ```language blocks of a Markdown text, in order."""
    return re.findall(r"^```%s[ \t]*\n(.*?)^```[ \t]*$" % re.escape(language), text, re.M | re.S)


def install_block(text, path):
    if MARK not in text:
        sys.exit("%s: no %s line" % (path, MARK))
    after = text[text.index(MARK):]
    found = blocks(after, "sh")
    if not found:
        sys.exit("%s: no ```sh block after %s" % (path, MARK))
    return found[0]


def install(paths):
    texts = {p: install_block(open(p, encoding="utf-8").read(), p) for p in paths}
    first = texts[paths[0]]
    for p, block in texts.items():
        if block != first:
            sys.exit("%s's install block differs from %s's:\n%s\n---\n%s" % (p, paths[0], block, first))
    sys.stdout.write(first)


def expect(expected, *values):
    got = " ".join(str(v) for v in values)
    if expected.endswith("..."):
        ok = got.startswith(expected[:-3].rstrip())
    else:
        ok = got == expected
    if not ok:
        raise AssertionError("printed %r, the README says %r" % (got, expected))
    print(got)


def run(path):
    code, checked = [], 0
    for block in blocks(open(path, encoding="utf-8").read(), "python"):
        for line in block.splitlines():
            m = PRINT.match(line)
            if m:
                line = "%s__expect(%r, %s)" % (m.group(1), m.group(3).rstrip(), m.group(2))
                checked += 1
            code.append(line)
    if not checked:
        raise AssertionError("%s: no print(...)  # TEXT line in its python blocks" % path)
    exec(compile("\n".join(code) + "\n", path + " (python blocks)", "exec"), {"__expect": expect})
    return checked


def main():
    if len(sys.argv) >= 3 and sys.argv[1] == "install":
        install(sys.argv[2:])
    elif len(sys.argv) >= 3 and sys.argv[1] == "run":
        for path in sys.argv[2:]:
            print("%s: %d printed lines as its python blocks say" % (path, run(path)))
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
