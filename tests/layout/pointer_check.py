#!/usr/bin/env python3
"""Checks that comments and messages which point at a document's section
point at one that exists, as link_check.py does for Markdown links.

A pointer is a document's name followed by a quoted section, in any source
file of the project (C++, Python, shell, CMake, proto, YAML, Dockerfiles):
  (docs/method.md, "The low-frequency floor")      README, "Layout"
  docs/results.md's "Direction estimation" tables  (deploy/README.md, "Read-only replicas")
Comment markers between lines are ignored, so a pointer may wrap. The
section must be a heading of that document, or the start of one (up to a
':', ' (' or the end): "Filling the space" names "Filling the space: the key
lineage". A document named without a section (docs/results.md) must exist.

  pointer_check.py [ROOT]        check the tree at ROOT (default: repo root)
  pointer_check.py --self-test   check that planted stale pointers are caught

Exit status: 0 clean, 1 stale pointers (one line each), 2 usage.
"""
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import checker_main  # noqa: E402
from link_check import HEADING_RE, prose_lines  # noqa: E402

DOC = r"(?:(?:deploy|core|bench)/README\.md|README(?:\.md)?|docs/[a-z_]+\.md)"
POINTER_RE = re.compile(r"(?<![\w/])(" + DOC + r")(?:'s\s*|,\s*|\s+)(?:section\s+)?\\?[\"“]([^\"”\\]{2,120})\\?[\"”]")
DOC_NAME_RE = re.compile(r"(?<![\w/.])(docs/[a-z_]+\.md|(?:deploy|core|bench)/README\.md)\b")
SOURCE_EXT = (".h", ".cc", ".cu", ".cuh", ".py", ".sh", ".proto", ".yaml", ".yml", ".in", ".cmake")
SKIP_DIRS = {".git", "shared", "third_party", "__pycache__"}
COMMENT_LEAD = re.compile(r"^\s*(?://+|#+|\*+|\"\"\"|--)?\s?")


def sources(root):
    for dirpath, dirnames, files in os.walk(root):
        rel_dir = os.path.relpath(dirpath, root)
        dirnames[:] = sorted(d for d in dirnames if d not in SKIP_DIRS and not d.startswith("build")
                             and os.path.join(rel_dir, d) not in (os.path.join("bench", "results"),
                                                                  os.path.join(".", "bench", "results")))
        for f in sorted(files):
            if f.endswith(SOURCE_EXT) or f == "CMakeLists.txt" or f.startswith("Dockerfile"):
                yield os.path.normpath(os.path.join(rel_dir, f))


def headings(path):
    out = []
    with open(path, encoding="utf-8") as fh:
        for _, line in prose_lines(fh.read(), keep_code_spans=True):
            m = HEADING_RE.match(line)
            if m:
                text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", m.group(2)).replace("`", "")
                out.append(text.strip().lower())
    return out


def names_heading(section, titles):
    s = section.strip().lower()
    return any(t == s or (t.startswith(s) and t[len(s):len(s) + 2] in (":", ": ", " (")) for t in titles)


def joined(text):
    """The file's lines without their comment markers, joined, with where
    each character came from (for line numbers)."""
    parts, starts = [], []
    pos = 0
    for number, line in enumerate(text.split("\n"), 1):
        body = COMMENT_LEAD.sub("", line, count=1)
        starts.append((pos, number))
        parts.append(body)
        pos += len(body) + 1
    return " ".join(parts), starts


def line_of(starts, offset):
    number = 1
    for pos, n in starts:
        if pos > offset:
            break
        number = n
    return number


def check(root):
    errors = []
    cache = {}
    for rel in sources(root):
        if rel.startswith(os.path.join("tests", "layout") + os.sep):
            continue  # the checkers' own examples
        with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as fh:
            text, starts = joined(fh.read())
        for m in POINTER_RE.finditer(text):
            doc, section = m.group(1), " ".join(m.group(2).split())
            if doc in ("README", "README.md"):
                doc = "README.md"
            where = "%s:%d" % (rel, line_of(starts, m.start()))
            path = os.path.join(root, doc)
            if not os.path.isfile(path):
                errors.append('%s: %s, "%s": no such document' % (where, doc, section))
                continue
            if doc not in cache:
                cache[doc] = headings(path)
            if not names_heading(section, cache[doc]):
                errors.append('%s: %s has no section "%s"' % (where, doc, section))
        for m in DOC_NAME_RE.finditer(text):
            if not os.path.isfile(os.path.join(root, m.group(1))):
                errors.append("%s: %s: no such document" % ("%s:%d" % (rel, line_of(starts, m.start())), m.group(1)))
    return errors


def self_test():
    with tempfile.TemporaryDirectory() as tmp:
        def write(rel, text):
            path = os.path.join(tmp, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w") as fh:
                fh.write(text)
        write("README.md", "# alignset\n\n## Layout\n")
        write("docs/method.md", "# Method\n\n### Filling the space: the key lineage\n\n## The `alignset` floor (measured)\n")
        write("core/a.h", '// Why (README, "Layout"); and (docs/method.md, "Filling the\n// space").\n')
        write("server/b.cc", 'Log("repair it (docs/method.md, \\"The alignset floor\\")");\n')
        write("bench/c.py", '"""The tables of docs/method.md\'s "Filling the space: the key lineage"."""\n')
        clean = check(tmp)
        if clean:
            print("self-test: a clean tree was flagged: %s" % clean)
            return 1
        planted = {
            "core/old.h": '// (README, "Choices")\n',                                # a section that left
            "server/msg.cc": 'Log("see (README, \\"Operations\\")");\n',             # in a message
            "core/wrapped.h": '// (docs/method.md, "Filling the\n// gaps")\n',       # wrapped, wrong
            "bench/gone.sh": '# see docs/usage.md for more\n',                       # a document that left
            "core/prefix.h": '// (docs/method.md, "Filling")\n',                     # not a whole heading start
        }
        for rel, text in planted.items():
            write(rel, text)
        errors = check(tmp)
        missed = [rel for rel in planted if not any(e.startswith(rel + ":") for e in errors)]
        if missed or len(errors) != len(planted):
            print("self-test: planted %s, got %s" % (sorted(planted), errors))
            return 1
    print("self-test: %d stale pointers caught" % len(planted))
    return 0


def main(argv):
    return checker_main.run(argv, __doc__, check, self_test, lambda root: "pointers: clean")


if __name__ == "__main__":
    sys.exit(main(sys.argv))
