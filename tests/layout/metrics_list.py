#!/usr/bin/env python3
"""Checks that every server metric reaches every place that shows it.

The one list of metrics is the proto's MetricsResponse message
(proto/alignset/v1/alignset.proto): adding a metric starts there. Each of
its fields must then be
  - filled by the server (server/service_info.cc: set_FIELD),
  - described for Prometheus (server/prometheus_text.cc: "FIELD"),
  - a field of the client library's ServiceMetrics
    (client/include/alignset/client.h) and copied into it
    (client/service_client.cc: FIELD()),
  - printed by `alignset stats` (cli/cmd_stats.cc: m.FIELD),
  - named in docs/operations.md.
A place that forgets one is a finding, one line each.

  metrics_list.py [ROOT]        check the tree at ROOT (default: repo root)
  metrics_list.py --self-test   check that a planted forgotten place is caught

Exit status: 0 clean, 1 findings, 2 usage.
"""
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import checker_main  # noqa: E402

PROTO = os.path.join("proto", "alignset", "v1", "alignset.proto")
# (file, the pattern a field must match there, what the place is)
PLACES = [
    (os.path.join("server", "service_info.cc"), r"\bset_{f}\(", "the server fills it"),
    (os.path.join("server", "prometheus_text.cc"), r'"{f}"', "Prometheus describes it"),
    (os.path.join("client", "include", "alignset", "client.h"), r"\b{f}\b", "ServiceMetrics has it"),
    (os.path.join("client", "service_client.cc"), r"\b{f}\(\)", "the client copies it"),
    (os.path.join("cli", "cmd_stats.cc"), r"\bm\.{f}\b", "alignset stats prints it"),
    (os.path.join("docs", "operations.md"), r"\b{f}\b", "docs/operations.md names it"),
]


def metric_fields(root):
    with open(os.path.join(root, PROTO), encoding="utf-8") as fh:
        text = fh.read()
    m = re.search(r"message MetricsResponse \{(.*?)\n\}", text, re.S)
    if not m:
        return None
    body = re.sub(r"//[^\n]*", "", m.group(1))
    return re.findall(r"^\s*(?:repeated\s+)?\w+\s+(\w+)\s*=\s*\d+\s*;", body, re.M)


def check(root):
    fields = metric_fields(root)
    if not fields:
        return [PROTO + ": no MetricsResponse message with fields"]
    findings = []
    for rel, pattern, what in PLACES:
        path = os.path.join(root, rel)
        if not os.path.exists(path):
            findings.append(rel + ": missing (" + what + ")")
            continue
        with open(path, encoding="utf-8", errors="replace") as fh:
            text = fh.read()
        for f in fields:
            if not re.search(pattern.format(f=re.escape(f)), text):
                findings.append("%s: metric %s is missing (%s)" % (rel, f, what))
    return findings


def self_test():
    with tempfile.TemporaryDirectory() as tmp:
        def write(rel, text):
            path = os.path.join(tmp, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w") as fh:
                fh.write(text)
        write(PROTO, "message MetricsResponse {\n  uint64 hits = 1;  // a comment\n  string name = 2;\n}\n")
        write("server/service_info.cc", "out->set_hits(1); out->set_name(x);")
        write("server/prometheus_text.cc", '{"hits", ...}, {"name", ...}')
        write("client/include/alignset/client.h", "uint64_t hits; std::string name;")
        write("client/service_client.cc", "m.hits = r.hits(); m.name = r.name();")
        write("cli/cmd_stats.cc", "print(m.hits, m.name)")
        write("docs/operations.md", "`hits` and `name`")
        if check(tmp):
            print("self-test: a complete tree was flagged: %s" % check(tmp))
            return 1
        write("cli/cmd_stats.cc", "print(m.hits)")
        found = check(tmp)
        if found != ["cli/cmd_stats.cc: metric name is missing (alignset stats prints it)"]:
            print("self-test: a metric left out of `alignset stats` was not caught: %s" % found)
            return 1
        write(PROTO, "message MetricsResponse {\n  uint64 hits = 1;\n  uint64 misses = 3;\n  string name = 2;\n}\n")
        write("cli/cmd_stats.cc", "print(m.hits, m.name)")
        if len(check(tmp)) != len(PLACES):
            print("self-test: a metric added to the proto alone was not caught everywhere: %s" % check(tmp))
            return 1
    print("self-test: the forgotten places were caught")
    return 0


if __name__ == "__main__":
    sys.exit(checker_main.run(sys.argv, __doc__, check, self_test,
                              lambda root: "every metric of MetricsResponse reaches the server, Prometheus, "
                                           "the client, alignset stats and docs/operations.md"))
