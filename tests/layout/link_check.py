#!/usr/bin/env python3
"""Checks that every relative link in the project's documentation resolves.

Scans README.md, every docs/*.md, deploy/, core/ and bench/README.md for Markdown links and
images, [text](target) and ![alt](target). A target with a scheme (http:,
https:, mailto:) is skipped; any other target must name an existing file or
folder relative to the document, and a #fragment must match a heading of the
target document under GitHub's anchor rules (lower case, punctuation other
than '-' and '_' dropped, spaces to '-', a -N suffix for repeats). Links inside
code spans and fenced code blocks are not links.

  link_check.py [ROOT]        check the documents under ROOT (default: repo root)
  link_check.py --self-test   check that a planted broken link and anchor are caught

Exit status: 0 clean, 1 broken links (one line each), 2 usage.
"""
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import checker_main  # noqa: E402

LINK_RE = re.compile(r"!?\[(?:[^\]\\]|\\.)*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
HEADING_RE = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
CODE_SPAN_RE = re.compile(r"`+[^`]*`+")


def documents(root):
    docs = [os.path.join(root, "README.md"), os.path.join(root, "deploy", "README.md"),
            os.path.join(root, "bench", "README.md"), os.path.join(root, "core", "README.md")]
    docs_dir = os.path.join(root, "docs")
    if os.path.isdir(docs_dir):
        docs += [os.path.join(docs_dir, f) for f in sorted(os.listdir(docs_dir)) if f.endswith(".md")]
    return [d for d in docs if os.path.isfile(d)]


def prose_lines(text, keep_code_spans=False):
    """The lines outside fenced code blocks, with code spans removed (kept
    for headings: GitHub's anchor keeps the text of a heading's code span)."""
    fenced = False
    for number, line in enumerate(text.split("\n"), 1):
        if line.lstrip().startswith(("```", "~~~")):
            fenced = not fenced
            continue
        if not fenced:
            yield number, line if keep_code_spans else CODE_SPAN_RE.sub("", line)


def slug(heading):
    s = heading.strip().lower()
    s = re.sub(r"[^\w\- ]", "", s, flags=re.UNICODE)
    return s.replace(" ", "-")


def anchors(path):
    seen, out = {}, set()
    with open(path, encoding="utf-8") as fh:
        for _, line in prose_lines(fh.read(), keep_code_spans=True):
            m = HEADING_RE.match(line)
            if not m:
                continue
            base = slug(re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", m.group(2)))
            n = seen.get(base, 0)
            out.add(base if n == 0 else "%s-%d" % (base, n))
            seen[base] = n + 1
    return out


def check(root):
    errors = []
    for doc in documents(root):
        rel_doc = os.path.relpath(doc, root)
        with open(doc, encoding="utf-8") as fh:
            text = fh.read()
        for number, line in prose_lines(text):
            for m in LINK_RE.finditer(line):
                target = m.group(1)
                if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target):
                    continue
                path, _, fragment = target.partition("#")
                resolved = os.path.normpath(os.path.join(os.path.dirname(doc), path)) if path else doc
                where = "%s:%d: %s" % (rel_doc, number, target)
                if not os.path.exists(resolved):
                    errors.append("%s: no such file" % where)
                    continue
                if fragment and resolved.endswith(".md") and fragment not in anchors(resolved):
                    errors.append("%s: no heading with anchor #%s" % (where, fragment))
    return errors


def self_test():
    with tempfile.TemporaryDirectory() as tmp:
        os.makedirs(os.path.join(tmp, "docs"))
        with open(os.path.join(tmp, "docs", "a.md"), "w") as fh:
            fh.write("# Title\n\n## Where it helps (measured)\n\n## The `alignset render` command\n\n"
                     "## Where it helps (measured)\n")
        good = ("# R\n\n[a](docs/a.md) [b](docs/a.md#where-it-helps-measured) [web](https://x.org/y)\n"
                "[c](docs/a.md#the-alignset-render-command) [d](docs/a.md#where-it-helps-measured-1)\n"
                "![e](docs/a.md) [f](#r)\n"
                "`[not](a/link)`\n```\n[not](either)\n```\n")
        with open(os.path.join(tmp, "README.md"), "w") as fh:
            fh.write(good)
        if check(tmp):
            print("self-test: a clean tree was flagged: %s" % check(tmp))
            return 1
        with open(os.path.join(tmp, "README.md"), "w") as fh:
            fh.write(good + "[gone](docs/missing.md)\n[bad anchor](docs/a.md#nowhere)\n")
        errors = check(tmp)
        caught = [any("docs/missing.md" in e for e in errors), any("#nowhere" in e for e in errors)]
        if not all(caught) or len(errors) != 2:
            print("self-test: expected exactly the two planted links, got: %s" % errors)
            return 1
    print("self-test: a broken link and a broken anchor caught")
    return 0


def main(argv):
    return checker_main.run(argv, __doc__, check, self_test, lambda root: "links: clean (%d documents)" % len(documents(root)))


if __name__ == "__main__":
    sys.exit(main(sys.argv))
