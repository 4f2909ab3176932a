#!/usr/bin/env bash
# Lints and schema-checks deploy/'s YAML: the Kubernetes manifests and compose.yaml.
#   1. yamllint (strict, deploy/.yamllint.yaml);
#   2. schema/check.py: a vendored strict subset of the Kubernetes API and Compose spec
#      (unknown fields, types, required fields) plus cross-object consistency, and its
#      self-test proving every rule fires on a broken copy of the real manifests;
#   3. the full upstream Kubernetes schemas from the npm package kubernetes-models, when
#      npm is available (installed once into $ALIGNSET_CACHE_DIR/npm-k8s; pinned versions).
#      Set ALIGNSET_UPSTREAM_SCHEMA=require to fail when it cannot run, =skip to skip it.
# Needs: yamllint, /usr/bin/python3 with python3-yaml; optionally node and npm.
set -euo pipefail
DEPLOY="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
CACHE="${ALIGNSET_CACHE_DIR:-$HOME/.cache/alignset}"
UPSTREAM="${ALIGNSET_UPSTREAM_SCHEMA:-auto}"
cd "$DEPLOY"
mapfile -t FILES < <(find k8s -name '*.yaml' | sort; echo compose.yaml)

echo "== yamllint"
yamllint -s -c .yamllint.yaml .yamllint.yaml "${FILES[@]}"
echo "yamllint: ${#FILES[@]} files clean"

echo "== vendored schema and consistency"
/usr/bin/python3 schema/check.py "${FILES[@]}"
/usr/bin/python3 schema/check.py --self-test "${FILES[@]}"

echo "== upstream Kubernetes schemas (npm kubernetes-models)"
if [ "$UPSTREAM" = skip ]; then
  echo "skipped (ALIGNSET_UPSTREAM_SCHEMA=skip)"
  exit 0
fi
unavailable() {
  if [ "$UPSTREAM" = require ]; then echo "FAIL: $1" >&2; exit 1; fi
  echo "skipped: $1"; exit 0
}
command -v node >/dev/null && command -v npm >/dev/null || unavailable "node/npm not installed"
dir="$CACHE/npm-k8s"
mkdir -p "$dir"
cat > "$dir/package.json.new" <<'JSON'
{
  "name": "alignset-manifest-check",
  "private": true,
  "type": "module",
  "dependencies": { "kubernetes-models": "5.1.0", "js-yaml": "4.1.0" }
}
JSON
if ! cmp -s "$dir/package.json.new" "$dir/package.json" || [ ! -d "$dir/node_modules/kubernetes-models" ]; then
  mv "$dir/package.json.new" "$dir/package.json"
  (cd "$dir" && npm install --no-audit --no-fund --loglevel=error >/dev/null 2>&1) \
    || unavailable "npm install of kubernetes-models failed"
else
  rm -f "$dir/package.json.new"
fi
cp schema/upstream-check.mjs "$dir/"
abs=(); for f in "${FILES[@]}"; do [ "$f" = compose.yaml ] || abs+=("$DEPLOY/$f"); done
node "$dir/upstream-check.mjs" "${abs[@]}"
