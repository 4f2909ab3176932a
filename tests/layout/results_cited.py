#!/usr/bin/env python3
"""Checks that bench/ holds benchmarks and the results the documents cite.

1. Every file under bench/results/ is cited by a document: README.md,
   docs/*.md, deploy/README.md, core/README.md, bench/README.md, or a
   bench/results/*.md that is itself cited (followed transitively). A file is
   cited where a document names its path, relative to the document or to the
   repository root; a name with a glob (*, ?) or a brace list ({a,b}) cites
   every file it matches. A folder's name alone cites nothing inside it.
2. Every other file under bench/ (the benchmarks and their scripts) is named
   in bench/README.md, the index that gives each its one command.

  results_cited.py [ROOT]        check the tree at ROOT (default: repo root)
  results_cited.py --self-test   check that planted uncited files are caught

Exit status: 0 clean, 1 uncited files (one line each), 2 usage.
"""
import fnmatch
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import checker_main  # noqa: E402

RESULTS = os.path.join("bench", "results")
TOKEN_RE = re.compile(r"[A-Za-z0-9_.\-/{},*?]+")
# Files of bench/ that are no benchmark: the build file and the index itself.
NOT_BENCHMARKS = {os.path.join("bench", "CMakeLists.txt"), os.path.join("bench", "README.md"),
                  os.path.join("bench", "render", "CMakeLists.txt")}


def files_under(root, rel):
    out = set()
    for dirpath, dirnames, files in os.walk(os.path.join(root, rel)):
        dirnames[:] = [d for d in dirnames if d != "__pycache__"]
        for f in files:
            out.add(os.path.relpath(os.path.join(dirpath, f), root))
    return out


def expand_braces(token):
    m = re.search(r"\{([^{}]*)\}", token)
    if not m:
        return [token]
    out = []
    for part in m.group(1).split(","):
        out += expand_braces(token[:m.start()] + part + token[m.end():])
    return out


def cited_by(root, doc, candidates):
    """The candidates (paths relative to root) that the document names."""
    with open(os.path.join(root, doc), encoding="utf-8", errors="replace") as fh:
        text = fh.read()
    base = os.path.dirname(doc)
    found = set()
    for token in set(TOKEN_RE.findall(text)):
        token = token.rstrip(".,;:")
        for name in expand_braces(token):
            for origin in (base, ""):
                path = os.path.normpath(os.path.join(origin, name))
                if any(c in name for c in "*?"):
                    # A glob names files: its last part has more than wildcards
                    # (Markdown's ** for bold is no citation).
                    if not re.search(r"[A-Za-z0-9]", os.path.basename(name)):
                        continue
                    found.update(c for c in candidates if fnmatch.fnmatchcase(c, path))
                elif path in candidates:
                    found.add(path)
    return found


def check(root):
    errors = []
    results = files_under(root, RESULTS)
    roots = ["README.md", os.path.join("deploy", "README.md"), os.path.join("core", "README.md"),
             os.path.join("bench", "README.md")]
    docs_dir = os.path.join(root, "docs")
    if os.path.isdir(docs_dir):
        roots += [os.path.join("docs", f) for f in sorted(os.listdir(docs_dir)) if f.endswith(".md")]
    queue = [d for d in roots if os.path.isfile(os.path.join(root, d))]
    seen, cited = set(), set()
    while queue:
        doc = queue.pop()
        if doc in seen:
            continue
        seen.add(doc)
        for f in cited_by(root, doc, results):
            cited.add(f)
            if f.endswith(".md"):
                queue.append(f)
    for f in sorted(results - cited):
        errors.append("%s: cited by no document (cite it where its figures are used, or remove it: "
                      "git keeps it)" % f)

    index = os.path.join("bench", "README.md")
    benchmarks = files_under(root, "bench") - results - NOT_BENCHMARKS
    named = cited_by(root, index, benchmarks) if os.path.isfile(os.path.join(root, index)) else set()
    for f in sorted(benchmarks - named):
        errors.append("%s: not in bench/README.md (every benchmark has its one command there)" % f)
    return errors


def self_test():
    with tempfile.TemporaryDirectory() as tmp:
        def write(rel, text=""):
            path = os.path.join(tmp, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w") as fh:
                fh.write(text)
        write("README.md", "See [the table](bench/results/table.md) and bench/results/fig_{a,b}.png.\n")
        write("docs/results.md", "Data: [tsv](../bench/results/data.tsv); runs in `bench/results/runs/*.tsv`.\n")
        write("bench/results/table.md", "From [raw](raw.txt) and sub/inner.tsv.\n")
        for f in ("raw.txt", "sub/inner.tsv", "fig_a.png", "fig_b.png", "data.tsv", "runs/1.tsv", "runs/2.tsv"):
            write("bench/results/" + f)
        write("bench/bench_x.cc")
        write("bench/render/run.sh")
        write("bench/README.md", "| `bash bench/render/run.sh` | ... |\n| `build/bench/bench_x` (bench/bench_x.cc) | ... |\n")
        clean = check(tmp)
        if clean:
            print("self-test: a clean tree was flagged: %s" % clean)
            return 1
        planted = {
            "bench/results/orphan.tsv": "",                # named nowhere
            "bench/results/runs/3.txt": "",                # beside a glob that does not match it
            "bench/results/unlinked/inner.md": "",         # only its folder could be meant
            "bench/results/uncited.md": "[x](raw2.txt)",   # cites, but is itself uncited
            "bench/results/raw2.txt": "",                  # cited only by an uncited document
            "bench/screen.py": "",                         # a script with no command in the index
        }
        for rel, text in planted.items():
            write(rel, text)
        write("docs/more.md", "The folder bench/results/unlinked holds a screen, **in bold**; runs/* and *.\n")
        errors = check(tmp)
        missed = [rel for rel in planted if not any(e.startswith(rel + ":") for e in errors)]
        if missed or len(errors) != len(planted):
            print("self-test: planted %s, got %s" % (sorted(planted), errors))
            return 1
    print("self-test: %d planted uncited files caught" % len(planted))
    return 0


def main(argv):
    return checker_main.run(argv, __doc__, check, self_test, lambda root: "bench results: every file cited, every benchmark indexed")


if __name__ == "__main__":
    sys.exit(main(sys.argv))
