#!/usr/bin/python3
"""Strict schema and consistency check of deploy/'s Kubernetes manifests and compose file.

Kubernetes validates manifests only when they reach a cluster; this catches the same class of
mistakes offline: unknown or misspelt fields, wrong types, missing required fields (against
the vendored subset in manifests.schema.json), and cross-references that no schema sees
(selectors, probe ports, ConfigMap names and keys, $(VAR) expansions, shard counts).

  check.py DIR...          check every *.yaml under the given directories / files
  check.py --self-test     prove that each rule fires on a broken copy of the real manifests
"""
import copy
import glob
import json
import os
import re
import sys

import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
SCHEMA = json.load(open(os.path.join(HERE, "manifests.schema.json"), encoding="utf-8"))
DEFS = SCHEMA["definitions"]
TYPES = {
    "object": lambda v: isinstance(v, dict),
    "array": lambda v: isinstance(v, list),
    "string": lambda v: isinstance(v, str),
    "integer": lambda v: isinstance(v, int) and not isinstance(v, bool),
    "number": lambda v: isinstance(v, (int, float)) and not isinstance(v, bool),
    "boolean": lambda v: isinstance(v, bool),
    "null": lambda v: v is None,
}
KIND_DEFS = {
    ("v1", "ConfigMap"), ("v1", "Service"), ("v1", "PersistentVolumeClaim"),
    ("apps/v1", "StatefulSet"), ("apps/v1", "Deployment"), ("batch/v1", "Job"),
    ("kustomize.config.k8s.io/v1beta1", "Kustomization"),
}


def validate(value, schema, path, errors):
    """A JSON-Schema subset; objects are closed unless additionalProperties says otherwise."""
    if "$ref" in schema:
        return validate(value, DEFS[schema["$ref"]], path, errors)
    if "enum" in schema:
        if value not in schema["enum"]:
            errors.append("%s: %r is not one of %s" % (path, value, schema["enum"]))
        return
    types = schema.get("type")
    if types is not None:
        types = types if isinstance(types, list) else [types]
        if not any(TYPES[t](value) for t in types):
            errors.append("%s: expected %s, got %s" % (path, "/".join(types), type(value).__name__))
            return
    if isinstance(value, str):
        if "pattern" in schema and not re.search(schema["pattern"], value):
            errors.append("%s: %r does not match %s" % (path, value, schema["pattern"]))
        if "maxLength" in schema and len(value) > schema["maxLength"]:
            errors.append("%s: %r longer than %d" % (path, value, schema["maxLength"]))
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        if "minimum" in schema and value < schema["minimum"]:
            errors.append("%s: %r below %r" % (path, value, schema["minimum"]))
        if "maximum" in schema and value > schema["maximum"]:
            errors.append("%s: %r above %r" % (path, value, schema["maximum"]))
    if isinstance(value, list):
        if len(value) < schema.get("minItems", 0):
            errors.append("%s: needs at least %d items" % (path, schema["minItems"]))
        if "items" in schema:
            for i, item in enumerate(value):
                validate(item, schema["items"], "%s[%d]" % (path, i), errors)
    if isinstance(value, dict):
        props = schema.get("properties", {})
        extra = schema.get("additionalProperties", False if props else True)
        if len(value) < schema.get("minProperties", 0):
            errors.append("%s: needs at least %d entries" % (path, schema["minProperties"]))
        for req in schema.get("required", []):
            if req not in value:
                errors.append("%s: missing required field %r" % (path, req))
        for key, item in value.items():
            sub = "%s.%s" % (path, key)
            if key in props:
                validate(item, props[key], sub, errors)
            elif extra is False:
                errors.append("%s: unknown field" % sub)
            elif isinstance(extra, dict):
                validate(item, extra, sub, errors)


def quantity(q):
    """Kubernetes quantity to a float (cpu in cores, memory in bytes)."""
    m = re.fullmatch(r"([0-9.]+)(m|Ki|Mi|Gi|Ti|k|M|G|T)?", str(q))
    if not m:
        raise ValueError("bad quantity %r" % q)
    scale = {None: 1, "m": 1e-3, "k": 1e3, "M": 1e6, "G": 1e9, "T": 1e12,
             "Ki": 2**10, "Mi": 2**20, "Gi": 2**30, "Ti": 2**40}[m.group(2)]
    return float(m.group(1)) * scale


def pod_specs(doc):
    kind = doc.get("kind")
    if kind in ("StatefulSet", "Deployment", "Job"):
        return [doc.get("spec", {}).get("template", {})]
    return []


def consistency(docs, errors):
    """Cross-object rules. docs: list of (file, document)."""
    configmaps = {d["metadata"]["name"]: d.get("data", {}) or {}
                  for _, d in docs if d.get("kind") == "ConfigMap"}
    claims = {d["metadata"]["name"] for _, d in docs if d.get("kind") == "PersistentVolumeClaim"}
    # A StatefulSet's claim templates become claims named <template>-<statefulset>-<ordinal>.
    for _, d in docs:
        if d.get("kind") == "StatefulSet":
            claims |= {"%s-%s-%d" % (t["metadata"]["name"], d["metadata"]["name"], i)
                       for t in d["spec"].get("volumeClaimTemplates", [])
                       for i in range(d["spec"].get("replicas", 1) or 1)}
    for f, d in docs:
        where = "%s %s/%s" % (f, d.get("kind"), d.get("metadata", {}).get("name"))
        kind = d.get("kind")
        if kind == "StatefulSet":
            # The design: one writer of the SQLite file (deploy/README.md).
            if d["spec"].get("replicas", 1) != 1:
                errors.append("%s: replicas must be 1 (single SQLite writer)" % where)
        if kind in ("StatefulSet", "Deployment"):
            sel = d["spec"]["selector"]["matchLabels"]
            labels = d["spec"]["template"].get("metadata", {}).get("labels", {})
            if any(labels.get(k) != v for k, v in sel.items()):
                errors.append("%s: selector %s does not match template labels %s" % (where, sel, labels))
        if kind == "Job":
            spec = d["spec"]
            if spec["template"]["spec"].get("restartPolicy") not in ("Never", "OnFailure"):
                errors.append("%s: a Job's pods need restartPolicy Never or OnFailure" % where)
            if spec.get("completionMode") == "Indexed":
                if "completions" not in spec:
                    errors.append("%s: an Indexed Job needs completions" % where)
                for c in spec["template"]["spec"]["containers"]:
                    for ef in c.get("envFrom", []):
                        data = configmaps.get(ef.get("configMapRef", {}).get("name"), {})
                        if "ALIGNSET_SHARDS" in data and str(spec.get("completions")) != data["ALIGNSET_SHARDS"]:
                            errors.append("%s: completions %s != ALIGNSET_SHARDS %s" % (
                                where, spec.get("completions"), data["ALIGNSET_SHARDS"]))
        if kind == "Service":
            sel = d["spec"].get("selector", {})
            targets = [(f2, d2) for f2, d2 in docs if d2.get("kind") in ("StatefulSet", "Deployment") and all(
                d2["spec"]["template"].get("metadata", {}).get("labels", {}).get(k) == v for k, v in sel.items())]
            if not targets:
                errors.append("%s: selector %s matches no workload" % (where, sel))
            for p in d["spec"]["ports"]:
                tp = p.get("targetPort", p["port"])
                ok = False
                for _, w in targets:
                    for c in w["spec"]["template"]["spec"]["containers"]:
                        for cp in c.get("ports", []):
                            ok |= tp in (cp.get("name"), cp["containerPort"])
                if targets and not ok:
                    errors.append("%s: targetPort %r is no container port of the workload" % (where, tp))
        for tmpl in pod_specs(d):
            spec = tmpl["spec"]
            psc = spec.get("securityContext", {})
            volumes = {v["name"]: v for v in spec.get("volumes", [])}
            vct = {t["metadata"]["name"] for t in d["spec"].get("volumeClaimTemplates", [])}
            for v in volumes.values():
                if "configMap" in v and v["configMap"]["name"] not in configmaps:
                    errors.append("%s: volume %s names unknown ConfigMap %s" % (where, v["name"], v["configMap"]["name"]))
                pvc = v.get("persistentVolumeClaim", {}).get("claimName")
                if pvc and pvc not in claims:
                    errors.append("%s: volume %s names unknown claim %s" % (where, v["name"], pvc))
            for c in spec["containers"]:
                cw = "%s container %s" % (where, c["name"])
                csc = c.get("securityContext", {})
                if not (csc.get("runAsNonRoot", psc.get("runAsNonRoot")) is True and
                        csc.get("runAsUser", psc.get("runAsUser", 0)) != 0):
                    errors.append("%s: must run as a non-root numeric user" % cw)
                if csc.get("allowPrivilegeEscalation", True) is not False:
                    errors.append("%s: allowPrivilegeEscalation must be false" % cw)
                res = c.get("resources", {})
                for key in ("cpu", "memory"):
                    req = res.get("requests", {}).get(key)
                    lim = res.get("limits", {}).get(key)
                    if req is None or lim is None:
                        errors.append("%s: needs requests and limits for %s" % (cw, key))
                    elif quantity(req) > quantity(lim):
                        errors.append("%s: %s request %s above limit %s" % (cw, key, req, lim))
                ports = {p["containerPort"] for p in c.get("ports", [])}
                for probe in ("startupProbe", "readinessProbe", "livenessProbe"):
                    g = c.get(probe, {}).get("grpc")
                    if g and g["port"] not in ports:
                        errors.append("%s: %s port %s is not a container port" % (cw, probe, g["port"]))
                if kind in ("StatefulSet", "Deployment") and not all(
                        "grpc" in c.get(p, {}) for p in ("readinessProbe", "livenessProbe")):
                    errors.append("%s: the server needs gRPC readiness and liveness probes" % cw)
                if kind == "Deployment":
                    # Several pods, so no writer: each serves the shipped file read-only
                    # (--read-only), from a volume mounted read-only (deploy/README.md).
                    values = {}
                    for ef in c.get("envFrom", []):
                        values.update(configmaps.get(ef.get("configMapRef", {}).get("name"), {}))
                    values.update({e["name"]: e.get("value") for e in c.get("env", [])})
                    if str(values.get("ALIGNSET_READ_ONLY")) not in ("1", "true"):
                        errors.append("%s: a Deployment's server must be a read-only replica "
                                      "(ALIGNSET_READ_ONLY: \"1\"): only one pod may write SQLite" % cw)
                    for vm in c.get("volumeMounts", []):
                        v = volumes.get(vm["name"], {})
                        if "persistentVolumeClaim" in v and not (
                                vm.get("readOnly") is True and v["persistentVolumeClaim"].get("readOnly") is True):
                            errors.append("%s: the cache volume %s of a replica must be mounted read-only "
                                          "(volumeMount and claim readOnly: true)" % (cw, vm["name"]))
                env = {e["name"] for e in c.get("env", [])}
                for ef in c.get("envFrom", []):
                    name = ef.get("configMapRef", {}).get("name")
                    if name is not None:
                        if name not in configmaps:
                            errors.append("%s: envFrom names unknown ConfigMap %s" % (cw, name))
                        env |= set(configmaps.get(name, {}))
                for arg in c.get("args", []) + c.get("command", []):
                    for var in re.findall(r"\$\(([A-Za-z_][A-Za-z0-9_]*)\)", arg):
                        if var not in env:
                            errors.append("%s: $(%s) is not set in the container's environment" % (cw, var))
                for vm in c.get("volumeMounts", []):
                    if vm["name"] not in volumes and vm["name"] not in vct:
                        errors.append("%s: mount of undeclared volume %s" % (cw, vm["name"]))
                # Scripts run from a ConfigMap volume must exist as keys of that ConfigMap.
                for arg in c.get("command", []) + c.get("args", []):
                    for vm in c.get("volumeMounts", []):
                        prefix = vm["mountPath"].rstrip("/") + "/"
                        v = volumes.get(vm["name"], {})
                        if arg.startswith(prefix) and "configMap" in v:
                            key = arg[len(prefix):]
                            if key not in configmaps.get(v["configMap"]["name"], {}):
                                errors.append("%s: %s is no key of ConfigMap %s" % (cw, arg, v["configMap"]["name"]))


def check_compose(f, doc, errors):
    validate(doc, {"$ref": "Compose"}, f, errors)
    if errors:
        return
    volumes = set(doc.get("volumes") or {})
    services = doc["services"]
    for name, s in services.items():
        for v in s.get("volumes", []):
            src = v.split(":")[0]
            if not src.startswith((".", "/")) and src not in volumes:
                errors.append("%s: service %s mounts undeclared volume %s" % (f, name, src))
        for dep, cond in s.get("depends_on", {}).items():
            if dep not in services:
                errors.append("%s: service %s depends on unknown service %s" % (f, name, dep))
            elif cond["condition"] == "service_healthy" and "healthcheck" not in services[dep]:
                errors.append("%s: %s waits for %s to be healthy, which has no healthcheck" % (f, name, dep))
        hc = s.get("healthcheck", {}).get("test", [])
        if hc and "alignset-health-probe" not in hc:
            errors.append("%s: service %s health check does not use alignset-health-probe" % (f, name))


def load(paths):
    files = []
    for p in paths:
        if os.path.isdir(p):
            files += sorted(glob.glob(os.path.join(p, "**", "*.yaml"), recursive=True))
        else:
            files.append(p)
    out = []
    for f in files:
        if os.path.basename(f).startswith("."):
            continue
        for doc in yaml.safe_load_all(open(f, encoding="utf-8")):
            if doc is not None:
                out.append((os.path.relpath(f), doc))
    return out


def check(docs):
    errors = []
    k8s = []
    for f, d in docs:
        if "services" in d and "kind" not in d:
            check_compose(f, d, errors)
            continue
        key = (d.get("apiVersion"), d.get("kind"))
        if key not in KIND_DEFS:
            errors.append("%s: unknown apiVersion/kind %s" % (f, key))
            continue
        n = len(errors)
        validate(d, {"$ref": d["kind"]}, "%s %s" % (f, d["kind"]), errors)
        if len(errors) == n and d["kind"] != "Kustomization":
            k8s.append((f, d))
        if d["kind"] == "Kustomization":
            base = os.path.dirname(f)
            for r in d.get("resources", []):
                if not os.path.exists(os.path.join(base, r)):
                    errors.append("%s: resource %s does not exist" % (f, r))
    if not errors:
        consistency(k8s, errors)
    return errors


def self_test(paths):
    """Each mutation of the real manifests must be caught; the originals must pass."""
    docs = load(paths)
    base = check(docs)
    assert not base, "the manifests themselves fail: %s" % base

    def find(kind, name=None):
        for i, (_, d) in enumerate(docs):
            if d.get("kind") == kind and (name is None or d["metadata"]["name"] == name):
                return i
        raise LookupError(kind)

    def sts(d): return d["spec"]["template"]["spec"]["containers"][0]
    cases = {
        "misspelt field": ("StatefulSet", lambda d: sts(d).__setitem__("resource", sts(d).pop("resources"))),
        "string replicas": ("StatefulSet", lambda d: d["spec"].__setitem__("replicas", "1")),
        "two replicas": ("StatefulSet", lambda d: d["spec"].__setitem__("replicas", 2)),
        "probe on wrong port": ("StatefulSet", lambda d: sts(d)["readinessProbe"]["grpc"].__setitem__("port", 8080)),
        "no liveness probe": ("StatefulSet", lambda d: sts(d).pop("livenessProbe")),
        "root user": ("StatefulSet", lambda d: d["spec"]["template"]["spec"]["securityContext"].__setitem__("runAsUser", 0)),
        "selector mismatch": ("StatefulSet", lambda d: d["spec"]["selector"]["matchLabels"].__setitem__("app.kubernetes.io/name", "x")),
        "request above limit": ("StatefulSet", lambda d: sts(d)["resources"]["requests"].__setitem__("memory", "3Gi")),
        "unset $(VAR)": ("StatefulSet", lambda d: sts(d).setdefault("args", []).append("$(ALIGNSET_NOPE)")),
        "replica not read-only": ("Deployment", lambda d: sts(d).setdefault("env", []).append(
            {"name": "ALIGNSET_READ_ONLY", "value": "0"})),
        "replica writable mount": ("Deployment", lambda d: [vm.__setitem__("readOnly", False)
                                                            for vm in sts(d)["volumeMounts"]]),
        "replica without liveness probe": ("Deployment", lambda d: sts(d).pop("livenessProbe")),
        "service port name": ("Service", lambda d: d["spec"]["ports"][0].__setitem__("targetPort", "http")),
        "bad enum": ("Service", lambda d: d["spec"].__setitem__("type", "Internal")),
        "shard count mismatch": ("Job", lambda d: d["spec"].__setitem__("completions", 63)
                                 if d["spec"].get("completionMode") == "Indexed" else
                                 d["spec"]["template"]["spec"].__setitem__("restartPolicy", "Always")),
        "missing script key": ("Job", lambda d: d["spec"]["template"]["spec"]["containers"][0].__setitem__(
            "command", ["/bin/sh", "/scripts/nope.sh"])),
        "unknown claim": ("Job", lambda d: [v["persistentVolumeClaim"].__setitem__("claimName", "nope")
                                            for v in d["spec"]["template"]["spec"]["volumes"] if "persistentVolumeClaim" in v]),
    }
    cases.update({
        "compose misspelt field": ("compose", lambda d: d["services"]["server"].__setitem__(
            "healthchek", d["services"]["server"].pop("healthcheck"))),
        "compose undeclared volume": ("compose", lambda d: d.__setitem__("volumes", {})),
        "compose bad condition": ("compose", lambda d: d["services"]["precompute"]["depends_on"]["server"]
                                  .__setitem__("condition", "service_ready")),
    })
    failed = []
    for label, (kind, mutate) in cases.items():
        for idx in [i for i, (_, d) in enumerate(docs)
                    if d.get("kind") == kind or (kind == "compose" and "services" in d)]:
            broken = copy.deepcopy(docs)
            mutate(broken[idx][1])
            if not check(broken):
                failed.append("%s (%s)" % (label, docs[idx][0]))
    if failed:
        print("self-test: mutations NOT caught: %s" % ", ".join(failed))
        return 1
    print("self-test: all %d kinds of mutation caught" % len(cases))
    return 0


def main(argv):
    if argv and argv[0] == "--self-test":
        return self_test(argv[1:])
    docs = load(argv)
    errors = check(docs)
    for e in errors:
        print("error: " + e)
    print("%d documents in %d files checked, %d errors" % (
        len(docs), len({f for f, _ in docs}), len(errors)))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
