#!/usr/bin/env python3
"""Checks that the places which state a deployment setting say the same thing.

  settings_agree.py ROOT SERVER_BINARY              check the tree at ROOT
  settings_agree.py --self-test ROOT SERVER_BINARY  plant drifts in a copy; each must be caught

What must agree:
  - every ALIGNSET_* variable set both in deploy/k8s/configmap.yaml and in the server's
    environment in deploy/compose.yaml (compose's "${VAR:-default}" counts as its default);
  - ALIGNSET_MAX_N: the ConfigMap, compose, the server's compiled default (its --help),
    deploy/README.md's settings table and the server's flag list (docs/operations.md, or
    README.md in a tree without docs/);
  - the image version: the default of ARG ALIGNSET_VERSION in deploy/Dockerfile and
    deploy/Dockerfile.cuda, and the CMake project version; both images carry the OCI labels
    (title, description, version, source, licenses = Apache-2.0, the LICENSE file's).

Exit status: 0 they agree, 1 a drift (one line each), 2 usage.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

import yaml

OCI = ("title", "description", "version", "source", "licenses")


def read(root, rel):
    with open(os.path.join(root, rel), encoding="utf-8") as f:
        return f.read()


def compose_env(root):
    doc = yaml.safe_load(read(root, "deploy/compose.yaml"))
    env = doc["services"]["server"].get("environment") or {}
    out = {}
    for k, v in env.items():
        m = re.fullmatch(r"\$\{\w+:-(.*)\}", str(v))
        out[k] = m.group(1) if m else str(v)
    return out


def configmap_env(root):
    return {k: str(v) for k, v in yaml.safe_load(read(root, "deploy/k8s/configmap.yaml"))["data"].items()}


def server_default_max_n(server):
    text = subprocess.run([server, "--help"], capture_output=True, text=True, check=False).stdout
    m = re.search(r"--max-n\b.*?\(default (\d+)\)", text)
    return m.group(1) if m else None


def check(root, server):
    errors = []
    cm, comp = configmap_env(root), compose_env(root)
    for k in sorted(set(cm) & set(comp)):
        if cm[k] != comp[k]:
            errors.append("%s: configmap.yaml says %r, compose.yaml %r" % (k, cm[k], comp[k]))

    max_n = {
        "deploy/k8s/configmap.yaml": cm.get("ALIGNSET_MAX_N"),
        "deploy/compose.yaml": comp.get("ALIGNSET_MAX_N"),
        "alignset-server --help": server_default_max_n(server),
    }
    m = re.search(r"\|\s*`ALIGNSET_MAX_N`\s*\|\s*(\d+)\s*\|", read(root, "deploy/README.md"))
    max_n["deploy/README.md"] = m.group(1) if m else None
    # The server's flag list: docs/operations.md since the README was split into docs/.
    flags_doc = "docs/operations.md" if os.path.exists(os.path.join(root, "docs/operations.md")) else "README.md"
    m = re.search(r"`--max-n` \((\d+)\)", read(root, flags_doc))
    max_n[flags_doc] = m.group(1) if m else None
    if len(set(max_n.values())) != 1 or None in max_n.values():
        errors.append("ALIGNSET_MAX_N differs: " + ", ".join("%s %s" % kv for kv in max_n.items()))

    m = re.search(r"project\(alignset VERSION ([0-9.]+)", read(root, "CMakeLists.txt"))
    version = m.group(1) if m else None
    for dockerfile in ("deploy/Dockerfile", "deploy/Dockerfile.cuda"):
        text = read(root, dockerfile)
        m = re.search(r"^ARG ALIGNSET_VERSION=(\S+)$", text, re.M)
        if not m or m.group(1) != version:
            errors.append("%s: ARG ALIGNSET_VERSION=%s, CMake project version %s"
                          % (dockerfile, m.group(1) if m else "(none)", version))
        for key in OCI:
            if not re.search(r"org\.opencontainers\.image\.%s=\"[^\"]*\"" % key, text):
                errors.append("%s: no org.opencontainers.image.%s label" % (dockerfile, key))
        if 'org.opencontainers.image.licenses="Apache-2.0"' not in text:
            errors.append("%s: licenses label is not Apache-2.0" % dockerfile)
    if "Apache License" not in read(root, "LICENSE") or "Version 2.0" not in read(root, "LICENSE"):
        errors.append("LICENSE is not the Apache License 2.0")
    return errors


def self_test(root, server):
    drifts = [
        ("deploy/k8s/configmap.yaml", 'ALIGNSET_MAX_N: "65536"', 'ALIGNSET_MAX_N: "16384"'),
        ("deploy/compose.yaml", "${ALIGNSET_WORKERS:-1}", "${ALIGNSET_WORKERS:-3}"),
        ("deploy/README.md", "| `ALIGNSET_MAX_N` | 65536 |", "| `ALIGNSET_MAX_N` | 32768 |"),
        ("deploy/Dockerfile", "ARG ALIGNSET_VERSION=", "ARG ALIGNSET_VERSION=9"),
        ("docs/operations.md", "`--max-n` (65536)", "`--max-n` (4096)"),
        ("deploy/Dockerfile.cuda", 'licenses="Apache-2.0"', 'licenses="MIT"'),
    ]
    failures = 0
    for rel, old, new in drifts:
        with tempfile.TemporaryDirectory() as tmp:
            for f in ("CMakeLists.txt", "README.md", "LICENSE"):
                shutil.copy(os.path.join(root, f), tmp)
            shutil.copytree(os.path.join(root, "deploy"), os.path.join(tmp, "deploy"))
            if os.path.isdir(os.path.join(root, "docs")):
                shutil.copytree(os.path.join(root, "docs"), os.path.join(tmp, "docs"))
            text = read(tmp, rel)
            if old not in text:
                print("self-test: %r not found in %s" % (old, rel))
                failures += 1
                continue
            with open(os.path.join(tmp, rel), "w", encoding="utf-8") as f:
                f.write(text.replace(old, new, 1))
            if not check(tmp, server):
                print("self-test: a drift in %s (%s) went unnoticed" % (rel, new))
                failures += 1
    if failures == 0:
        print("self-test: all %d planted drifts caught" % len(drifts))
    return failures


def main(argv):
    args = [a for a in argv[1:] if a != "--self-test"]
    if len(args) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    root, server = args
    if "--self-test" in argv:
        return 1 if self_test(root, server) else 0
    errors = check(root, server)
    for e in errors:
        print(e)
    if not errors:
        print("deployment settings agree")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
