#!/usr/bin/env python3
"""Checks that #include arrows point one way (README, "Layout").

Every quoted include of the form "folder/..." in a source file is looked up in
ALLOWED: a file in core/<idea>/ may include only the core folders listed for
<idea>, and a top-level folder only the folders listed for it. ALLOWED itself
must be acyclic, so no folder can include from a folder that depends on it.

  include_direction.py [ROOT]        check the tree at ROOT (default: repo root)
  include_direction.py --self-test   check that a planted bad include is caught

Exit status: 0 clean, 1 violations (one line each), 2 usage.
"""
import os
import re
import sys
import tempfile

# core/<idea> -> the core folders it may include (itself always allowed).
CORE_ALLOWED = {
    "util": [],
    "sampling": ["util"],
    "spectral": ["util"],
    "align": ["util"],
    "analysis": ["util", "sampling", "spectral"],
    "optimize": ["util", "sampling", "spectral", "analysis"],
}

# top-level folder -> the other top-level include roots it may use (itself
# always allowed). "alignset" and "grpc" are the generated headers of proto/.
TOP_ALLOWED = {
    "core": [],
    "storage": ["core"],
    "server": ["core", "storage", "alignset", "grpc"],
    "client": ["core", "storage", "alignset", "grpc"],
}

SOURCE_EXT = (".h", ".cc", ".cu", ".cuh")
INCLUDE_RE = re.compile(r'^\s*#\s*include\s+"([A-Za-z0-9_]+)/([^"]*)"')


def check_acyclic(graph):
    state = {}

    def visit(node, path):
        if state.get(node) == "done":
            return None
        if state.get(node) == "active":
            return path + [node]
        state[node] = "active"
        for nxt in graph.get(node, []):
            cycle = visit(nxt, path + [node])
            if cycle:
                return cycle
        state[node] = "done"
        return None

    for node in graph:
        cycle = visit(node, [])
        if cycle:
            return cycle
    return None


def scan(root):
    errors = []
    for name, graph in (("core folders", CORE_ALLOWED), ("top-level folders", TOP_ALLOWED)):
        cycle = check_acyclic(graph)
        if cycle:
            errors.append("ALLOWED table for %s has a cycle: %s" % (name, " -> ".join(cycle)))
    for top in TOP_ALLOWED:
        top_dir = os.path.join(root, top)
        if not os.path.isdir(top_dir):
            continue
        for dirpath, _, files in os.walk(top_dir):
            for f in files:
                if not f.endswith(SOURCE_EXT):
                    continue
                path = os.path.join(dirpath, f)
                rel = os.path.relpath(path, root)
                parts = rel.split(os.sep)
                idea = parts[1] if top == "core" and len(parts) > 2 else None
                if top == "core" and idea is None:
                    errors.append("%s: a core source outside every idea folder" % rel)
                    continue
                if idea is not None and idea not in CORE_ALLOWED:
                    errors.append("%s: core folder '%s' is not in the layout table" % (rel, idea))
                    continue
                with open(path, encoding="utf-8", errors="replace") as fh:
                    for lineno, line in enumerate(fh, 1):
                        m = INCLUDE_RE.match(line)
                        if not m:
                            continue
                        inc_top, inc_rest = m.group(1), m.group(2)
                        where = "%s:%d" % (rel, lineno)
                        if inc_top != top and inc_top not in TOP_ALLOWED[top]:
                            errors.append('%s: %s/ may not include "%s/%s"' % (where, top, inc_top, inc_rest))
                            continue
                        if idea is not None and inc_top == "core":
                            inc_idea = inc_rest.split("/", 1)[0]
                            if "/" not in inc_rest:
                                errors.append('%s: "core/%s" names no idea folder' % (where, inc_rest))
                            elif inc_idea != idea and inc_idea not in CORE_ALLOWED[idea]:
                                errors.append('%s: core/%s/ may not include "core/%s"' % (where, idea, inc_rest))
    return errors


def self_test():
    with tempfile.TemporaryDirectory() as tmp:
        def write(rel, text):
            path = os.path.join(tmp, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w") as fh:
                fh.write(text)
        write("core/util/status.h", "#pragma once\n")
        write("core/spectral/engine.h", '#include "core/util/status.h"\n')
        if scan(tmp):
            print("self-test: a clean tree was flagged: %s" % scan(tmp))
            return 1
        planted = {
            "core/util/bad.h": '#include "core/spectral/engine.h"\n',        # upward in core
            "core/align/bad.cc": '#include "core/optimize/optimizer.h"\n',   # sideways, not allowed
            "core/sampling/bad.cc": '#include "storage/set_cache.h"\n',       # core -> storage
            "storage/bad.cc": '#include "server/service.h"\n',              # storage -> server
            "core/loose.h": "#pragma once\n",                                # outside an idea folder
        }
        for rel, text in planted.items():
            write(rel, text)
        errors = scan(tmp)
        missed = [rel for rel in planted if not any(e.startswith(rel) for e in errors)]
        if missed:
            print("self-test: planted violations not caught: %s" % ", ".join(missed))
            return 1
    print("self-test: %d planted violations caught" % len(planted))
    return 0


def main(argv):
    if len(argv) > 2:
        print(__doc__)
        return 2
    if len(argv) == 2 and argv[1] == "--self-test":
        return self_test()
    root = argv[1] if len(argv) == 2 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    errors = scan(os.path.abspath(root))
    for e in errors:
        print(e)
    if errors:
        return 1
    print("include direction: clean")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
