#!/usr/bin/env python3
"""Checks that #include arrows point one way (README, "Layout").

Every include of a project header is mapped to the node that owns it and
looked up in ALLOWED:
  - a quoted include "folder/..." belongs to the top-level folder;
  - the generated headers of proto/ ("alignset/v1/...", "grpc/...", quoted or
    in angle brackets) belong to "proto";
  - the public API of the client library, <alignset/X.h> (the headers in
    client/include/alignset/ and the core headers installed beside them),
    is its own node, "alignset-public": a renderer may include the public
    API without depending on the client's internals.
A file in core/<idea>/ may include only the core folders listed for <idea>,
and a top-level folder only the nodes listed for it. Every top-level folder
that holds sources must have an entry, and ALLOWED itself must be acyclic,
so no folder can include from a folder that depends on it.

  include_direction.py [ROOT]        check the tree at ROOT (default: repo root)
  include_direction.py --self-test   check that planted bad includes are caught

Exit status: 0 clean, 1 violations (one line each), 2 usage.
"""
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import checker_main  # noqa: E402

# core/<idea> -> the core folders it may include (itself always allowed).
CORE_ALLOWED = {
    "util": [],
    "sampling": ["util"],
    "spectral": ["util"],
    "align": ["util"],
    "analysis": ["util", "sampling", "spectral"],
    "optimize": ["util", "sampling", "spectral", "analysis"],
}

PUBLIC = "alignset-public"
PRODUCT = ["proto", "core", "storage", "server", "client", "sampler", "render", "cli", PUBLIC]

# node -> the other nodes it may include (itself always allowed). Top-level
# folders are nodes; so are the public API (PUBLIC) and the generated proto
# headers ("proto"). bench/ and tests/ may use every product folder, but no
# product folder may include them.
TOP_ALLOWED = {
    "proto": [],
    "core": [],
    "storage": ["core"],
    "server": ["core", "storage", "proto"],
    # The sampler library a renderer links: core and the public headers only.
    "sampler": ["core", PUBLIC],
    # The installed headers: client.h, npy.h, set_table.h, set_choice.h, ... and core's
    # status.h, point_set.h, directions.h (installed under <alignset/>).
    PUBLIC: ["core"],
    # The renderer uses the public API as a user's renderer would: never the
    # client's internals, the server or storage.
    "render": ["core", PUBLIC],
    # The client library a renderer links: never the renderer or the command
    # line above it.
    "client": ["core", "proto", PUBLIC],
    # The `alignset` command line sits on top of every library it drives
    # (`alignset render` runs render/, `alignset cache` storage/).
    "cli": ["core", "storage", "client", "sampler", "render", PUBLIC],
    # alignset inside other renderers (integrations/pbrt-v4): the installed
    # API only, as a renderer author's own checkout would use it.
    "integrations": [PUBLIC],
    "bench": PRODUCT,
    # The fuzzers drive each parser where it lives (fuzz/README.md).
    "fuzz": PRODUCT,
    "tests": PRODUCT + ["bench"],
    "deploy": ["proto"],
    "scripts": [],
}

# Top-level folders that hold no C++ of the project.
NOT_SOURCE = {"build", "docs", "shared"}

SOURCE_EXT = (".h", ".cc", ".cpp", ".cu", ".cuh")
QUOTED_RE = re.compile(r'^\s*#\s*include\s+"([A-Za-z0-9_.-]+)/([^"]*)"')
ANGLE_RE = re.compile(r'^\s*#\s*include\s+<(alignset)/([^>]*)>')


def owner_of_file(rel):
    """The node a source file belongs to."""
    parts = rel.split(os.sep)
    if parts[:3] in (["client", "include", "alignset"], ["sampler", "include", "alignset"]):
        return PUBLIC
    return parts[0]


def owner_of_include(first, rest, quoted, top_dirs):
    """The node an include names, or None for a header outside the project."""
    if first == "alignset":
        return "proto" if rest.startswith("v1/") else PUBLIC
    if first == "grpc":
        # "grpc/health/v1/..." is generated from proto/; <grpc/...> is gRPC's own.
        return "proto" if quoted else None
    if quoted and (first in TOP_ALLOWED or first in top_dirs):
        return first
    return None


def public_home(root, first, rest):
    """The library whose public headers hold <alignset/REST>: "sampler", "client"
    (version.h is generated for the client), or None for core's installed headers."""
    for lib in ("sampler", "client"):
        if os.path.exists(os.path.join(root, lib, "include", first, rest)):
            return lib
    return "client" if rest == "version.h" else None


def has_sources(path):
    for _, _, files in os.walk(path):
        if any(f.endswith(SOURCE_EXT) for f in files):
            return True
    return False


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
    top_dirs = sorted(d for d in os.listdir(root)
                      if os.path.isdir(os.path.join(root, d)) and not d.startswith(".")
                      and d not in NOT_SOURCE and not d.startswith("build"))
    for top in top_dirs:
        top_dir = os.path.join(root, top)
        if top not in TOP_ALLOWED:
            if has_sources(top_dir):
                errors.append("%s/: top-level folder '%s' holds sources but has no entry in the "
                              "layout table" % (top, top))
            continue
        for dirpath, _, files in os.walk(top_dir):
            for f in sorted(files):
                if not f.endswith(SOURCE_EXT):
                    continue
                path = os.path.join(dirpath, f)
                rel = os.path.relpath(path, root)
                parts = rel.split(os.sep)
                node = owner_of_file(rel)
                idea = parts[1] if top == "core" and len(parts) > 2 else None
                if top == "core" and idea is None:
                    errors.append("%s: a core source outside every idea folder" % rel)
                    continue
                if idea is not None and idea not in CORE_ALLOWED:
                    errors.append("%s: core folder '%s' is not in the layout table" % (rel, idea))
                    continue
                with open(path, encoding="utf-8", errors="replace") as fh:
                    for lineno, line in enumerate(fh, 1):
                        m = QUOTED_RE.match(line)
                        quoted = m is not None
                        if not m:
                            m = ANGLE_RE.match(line)
                        if not m:
                            continue
                        inc_first, inc_rest = m.group(1), m.group(2)
                        inc_node = owner_of_include(inc_first, inc_rest, quoted, top_dirs)
                        if inc_node is None:
                            continue
                        where = "%s:%d" % (rel, lineno)
                        shown = ('"%s/%s"' if quoted else "<%s/%s>") % (inc_first, inc_rest)
                        if inc_node not in TOP_ALLOWED:
                            errors.append("%s: %s names folder '%s', which has no entry in the "
                                          "layout table" % (where, shown, inc_node))
                            continue
                        if inc_node != node and inc_node not in TOP_ALLOWED[node]:
                            errors.append("%s: %s may not include %s" % (where, node, shown))
                            continue
                        # The two libraries' public headers stand apart: sampler/ (its
                        # sources and headers) includes nothing of client/'s, nor the reverse.
                        home = public_home(root, inc_first, inc_rest) if inc_node == PUBLIC else None
                        if home is not None and top in ("sampler", "client") and home != top:
                            errors.append("%s: %s/ may not include %s, a header of %s/" % (where, top, shown, home))
                            continue
                        if idea is not None and inc_node == "core":
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
        write("render/scene.h", '#include "core/util/status.h"\n#include <alignset/client.h>\n')
        write("client/include/alignset/client.h", "#include <alignset/status.h>\n")
        write("sampler/include/alignset/set_table.h", "#include <alignset/status.h>\n")
        write("cli/cmd_render.cc", '#include "render/scene.h"\n#include "cli/progress.h"\n')
        write("bench/render/main.cc", '#include "render/scene.h"\n#include "server/service.h"\n')
        if scan(tmp):
            print("self-test: a clean tree was flagged: %s" % scan(tmp))
            return 1
        planted = {
            "core/util/bad.h": '#include "core/spectral/engine.h"\n',        # upward in core
            "core/align/bad.cc": '#include "core/optimize/optimizer.h"\n',   # sideways, not allowed
            "core/sampling/bad.cc": '#include "storage/set_cache.h"\n',       # core -> storage
            "storage/bad.cc": '#include "server/service.h"\n',              # storage -> server
            "core/loose.h": "#pragma once\n",                                # outside an idea folder
            "render/bad_server.cc": '#include "server/service.h"\n',        # render -> server
            "render/bad_storage.cc": '#include "storage/set_cache.h"\n',    # render -> storage
            "render/bad_client.cc": '#include "client/service_client.h"\n', # render -> client internals
            "render/bad_proto.h": "#include <alignset/v1/alignset.pb.h>\n",  # render -> generated proto
            "core/util/bad_render.h": '#include "render/scene.h"\n',        # core -> render
            "client/include/alignset/bad.h": '#include "client/service_client.h"\n',  # public API -> internals
            "server/bad_bench.cc": '#include "bench/render/x.h"\n',         # product -> bench
            "client/bad_tests.cc": '#include "tests/cli/cli_runner.h"\n',  # product -> tests
            "client/bad_render.cc": '#include "render/scene.h"\n',        # client -> render (an arrow back up)
            "client/bad_cli.cc": '#include "cli/progress.h"\n',           # client -> the command line
            "render/bad_cli.cc": '#include "cli/progress.h"\n',           # render -> the command line
            "sampler/bad_client.cc": '#include "client/service_client.h"\n',  # sampler -> the client's internals
            "sampler/bad_storage.cc": '#include "storage/set_cache.h"\n',     # sampler -> SQLite
            "sampler/bad_client_api.cc": "#include <alignset/client.h>\n",     # sampler -> the client's API
            "sampler/include/alignset/bad.h": "#include <alignset/client.h>\n",  # its public header too
            "client/bad_sampler_api.cc": "#include <alignset/set_table.h>\n",  # client -> the sampler's API
            "newfolder/x.cc": "",                                            # a folder without an entry
        }
        for rel, text in planted.items():
            write(rel, text)
        errors = scan(tmp)
        def caught(rel):  # a line for the file, or for its folder ("newfolder/: ...")
            return any(e.startswith(rel) or e.startswith(rel.split("/", 1)[0] + "/:") for e in errors)
        missed = [rel for rel in planted if not caught(rel)]
        if missed:
            print("self-test: planted violations not caught: %s" % ", ".join(missed))
            return 1
    print("self-test: %d planted violations caught" % len(planted))
    return 0


def main(argv):
    return checker_main.run(argv, __doc__, scan, self_test, lambda root: "include direction: clean")


if __name__ == "__main__":
    sys.exit(main(sys.argv))
