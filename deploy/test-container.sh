#!/usr/bin/env bash
# Builds the real deploy/Dockerfile without a Docker daemon and tests the image:
#   1. a Debian 12 base image made here with debootstrap from the mirror apt uses on this
#      machine, imported with podman as "debian:bookworm" (what the Dockerfile's FROM names);
#      the rootfs tarball is cached under $ALIGNSET_CACHE_DIR (default ~/.cache/alignset);
#   2. buildah bud --isolation chroot of deploy/Dockerfile (layers cached between runs);
#   3. checks of the image config (non-root user, port, volume, health check, OCI labels);
#   4. the server started from the image (buildah run, host network, loopback port), health
#      SERVING asked from the host and with the image's own HEALTHCHECK command, an aligned
#      set requested with the host CLI, the SQLite cache found on the volume, clean stop.
# Needs root and the Debian packages buildah, podman, debootstrap (scripts/install-deps.sh).
#
# Environment:
#   ALIGNSET_CACHE_DIR       cache root (rootfs tarball, container storage)
#   ALIGNSET_STORAGE_DRIVER  overlay (default when the kernel has it) or vfs
#   ALIGNSET_ROOTFS_MAX_DAYS rebuild the cached rootfs after this many days (default 14)
#   ALIGNSET_HOST_CLI        host alignset binary (default build/cli/alignset, built if absent)
#   ALIGNSET_BUILD_JOBS      compile jobs inside the image build (default 2)
#   ALIGNSET_TEST_ITERATIONS optimizer iterations of the set the test requests (default 300)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
CACHE="${ALIGNSET_CACHE_DIR:-$HOME/.cache/alignset}"
MAX_DAYS="${ALIGNSET_ROOTFS_MAX_DAYS:-14}"
JOBS="${ALIGNSET_BUILD_JOBS:-2}"
ITERS="${ALIGNSET_TEST_ITERATIONS:-300}"   # the served set's optimizer budget: a smoke test
IMAGE="localhost/alignset:test"
BASE="debian:bookworm"
SUITE="bookworm"
PY=/usr/bin/python3
START=$(date +%s)

log() { printf '[test-container %4ds] %s\n' "$(( $(date +%s) - START ))" "$*"; }
die() { log "FAIL: $*"; exit 1; }

[ "$(id -u)" -eq 0 ] || die "must run as root (buildah chroot isolation, debootstrap)"
for tool in buildah podman debootstrap; do
  command -v "$tool" >/dev/null || die "$tool missing: run scripts/install-deps.sh"
done

DRIVER="${ALIGNSET_STORAGE_DRIVER:-}"
if [ -z "$DRIVER" ]; then
  if grep -qw overlay /proc/filesystems; then DRIVER=overlay; else DRIVER=vfs; fi
fi
STORE="$CACHE/containers/storage-$DRIVER"
mkdir -p "$STORE" "$CACHE/containers/run" "$CACHE/rootfs"
# A private store: nothing here touches the machine's default container storage.
CFLAGS=(--root "$STORE" --runroot "$CACHE/containers/run" --storage-driver "$DRIVER")
bah() { buildah "${CFLAGS[@]}" "$@"; }
pod() { podman "${CFLAGS[@]}" "$@"; }

# --- 1. base image --------------------------------------------------------------------
# The Debian entries of this machine's apt sources (both the one-line and the deb822
# format), written as one deb822 file for the image: host and image see the same archive.
SOURCES="$("$PY" - "$SUITE" <<'PYEOF'
import glob, sys
suite = sys.argv[1]
wanted = {suite, suite + "-updates", suite + "-security"}
entries = []  # (uri, suite, components)
def add(uris, suites, comps):
    for u in uris:
        for s in suites:
            if s in wanted and (u, s) not in [(e[0], e[1]) for e in entries]:
                entries.append((u, s, comps))
files = sorted(glob.glob("/etc/apt/sources.list")) + sorted(glob.glob("/etc/apt/sources.list.d/*.list"))
for path in files:
    for line in open(path, encoding="utf-8", errors="replace"):
        parts = line.split("#", 1)[0].split()
        if not parts or parts[0] != "deb":
            continue
        parts = parts[1:]
        if parts and parts[0].startswith("["):
            while parts and not parts[0].endswith("]"):
                parts = parts[1:]
            parts = parts[1:]
        if len(parts) >= 3:
            add([parts[0]], [parts[1]], parts[2:])
for path in sorted(glob.glob("/etc/apt/sources.list.d/*.sources")):
    for stanza in open(path, encoding="utf-8", errors="replace").read().split("\n\n"):
        fields = {}
        for line in stanza.splitlines():
            if line.startswith("#") or ":" not in line or line[0].isspace():
                continue
            k, v = line.split(":", 1)
            fields[k.strip().lower()] = v.split()
        if "deb" in fields.get("types", []) and fields.get("enabled", ["yes"]) != ["no"]:
            add(fields.get("uris", []), fields.get("suites", []), fields.get("components", ["main"]))
if not any(s == suite for _, s, _ in entries):
    sys.exit("no apt source for suite %s found in /etc/apt" % suite)
for uri, s, comps in sorted(entries, key=lambda e: e[1] != suite):
    print("Types: deb\nURIs: %s\nSuites: %s\nComponents: %s\n"
          "Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg\n" % (uri, s, " ".join(comps)))
PYEOF
)" || die "could not read the apt sources of this machine"
MIRROR="$(printf '%s\n' "$SOURCES" | awk '/^URIs:/ {print $2; exit}')"
KEY="$(printf '%s' "$SOURCES" | sha256sum | cut -c1-12)"
TARBALL="$CACHE/rootfs/debian-$SUITE-minbase-$KEY.tar"
log "mirror $MIRROR, storage driver $DRIVER, cache $CACHE"

if [ -f "$TARBALL" ] && [ -z "$(find "$TARBALL" -mtime +"$MAX_DAYS")" ]; then
  log "reusing cached rootfs $TARBALL"
else
  log "debootstrap $SUITE (minbase) from $MIRROR"
  work="$(mktemp -d "$CACHE/rootfs/debootstrap.XXXXXX")"
  trap 'rm -rf "$work"' EXIT
  include=()
  case "$MIRROR" in https:*) include=(--include=ca-certificates) ;; esac
  nice -n 10 debootstrap --variant=minbase "${include[@]}" "$SUITE" "$work/root" "$MIRROR" \
    > "$work/debootstrap.log" 2>&1 || { tail -20 "$work/debootstrap.log"; die "debootstrap failed"; }
  rm -f "$work/root/etc/apt/sources.list"
  printf '%s\n' "$SOURCES" > "$work/root/etc/apt/sources.list.d/debian.sources"
  rm -rf "$work/root/var/cache/apt/archives/"*.deb "$work/root/var/lib/apt/lists/"*
  tar --numeric-owner -C "$work/root" -cf "$TARBALL.tmp" .
  mv "$TARBALL.tmp" "$TARBALL"
  rm -f "$TARBALL".imported.*
  rm -rf "$work"; trap - EXIT
fi
stamp="$TARBALL.imported.$DRIVER"
if [ ! -f "$stamp" ] || ! pod image exists "$BASE"; then
  log "importing the rootfs as $BASE"
  pod import --quiet "$TARBALL" "$BASE" >/dev/null
  touch "$stamp"
fi

# --- 2. image build ---------------------------------------------------------------------
# Bounded cache: wipe the private store when it outgrows its budget.
if [ "$(du -sm "$STORE" | cut -f1)" -gt 20000 ]; then
  log "container store over 20 GB: removing all images"
  bah rmi --all --force >/dev/null || true
  pod import --quiet "$TARBALL" "$BASE" >/dev/null
fi
log "building $IMAGE from deploy/Dockerfile (-j$JOBS; log: $CACHE/last-image-build.log)"
build_log="$CACHE/last-image-build.log"
if ! nice -n 10 buildah "${CFLAGS[@]}" bud --isolation chroot --network host --pull=never \
      --layers --format docker -f "$ROOT/deploy/Dockerfile" \
      --build-arg BUILD_JOBS="$JOBS" \
      -t "$IMAGE" "$ROOT" > "$build_log" 2>&1; then
  tail -40 "$build_log"
  die "image build failed (full log: $build_log)"
fi
log "image built: $(pod image inspect --format '{{.Size}}' "$IMAGE" | awk '{printf "%.0f MB", $1/1e6}')"

# --- 3. image configuration -------------------------------------------------------------
VERSION="$(sed -n 's/^project(alignset VERSION \([0-9.]*\).*/\1/p' "$ROOT/CMakeLists.txt")"
hc_cmd="$(bah inspect --type image "$IMAGE" | "$PY" -c '
import json, sys
cfg = json.load(sys.stdin)["Docker"]["config"]
errors = []
user = cfg.get("User", "")
if not user or user.split(":")[0] in ("", "0", "root"):
    errors.append("runs as root (User=%r)" % user)
if "50051/tcp" not in (cfg.get("ExposedPorts") or {}):
    errors.append("port 50051 not exposed")
if "/var/lib/alignset" not in (cfg.get("Volumes") or {}):
    errors.append("no volume at /var/lib/alignset")
labels = cfg.get("Labels") or {}
oci = "org.opencontainers.image."
for key in ("title", "description", "version", "source", "licenses"):
    if oci + key not in labels:
        errors.append("no %s%s label" % (oci, key))
if labels.get(oci + "version") != sys.argv[1]:
    errors.append("version label %r, project version %r" % (labels.get(oci + "version"), sys.argv[1]))
if labels.get(oci + "licenses") != "Apache-2.0":
    errors.append("licenses label %r" % labels.get(oci + "licenses"))
hc = (cfg.get("Healthcheck") or {}).get("Test") or []
if "health" not in " ".join(hc):
    errors.append("no gRPC health check (Healthcheck=%r)" % hc)
if errors:
    sys.exit("image config: " + "; ".join(errors))
print(hc[1] if hc[0] == "CMD-SHELL" else " ".join(hc[1:]))
' "$VERSION")" || die "image configuration check failed"
log "image config ok (user non-root, 50051 exposed, volume, HEALTHCHECK, OCI labels of $VERSION)"

# --- 4. run the image -------------------------------------------------------------------
ctr="$(bah from --pull=never "$IMAGE")"
# The working container drops the image's VOLUME declaration (the image keeps it, checked
# above): with it, buildah 1.28's `run --isolation chroot` now and then mounts a fresh
# directory over /var/lib/alignset instead of the --volume given for that path.
bah config --volume /var/lib/alignset- "$ctr"
tmp="$(mktemp -d)"
server_pid=""   # the host's `buildah run`
inner_pid=""    # alignset-server itself: chroot isolation shares the host's PID namespace
cleanup() {
  local p
  for p in "$inner_pid" "$server_pid"; do
    if [ -n "$p" ] && kill -0 "$p" 2>/dev/null; then
      kill -TERM "$p" 2>/dev/null || true; sleep 2; kill -KILL "$p" 2>/dev/null || true
    fi
  done
  bah rm "$ctr" >/dev/null 2>&1 || true
  rm -rf "$tmp"
}
trap cleanup EXIT
crun() { bah run --isolation chroot --network host "$@"; }
# First descendant of process $1 whose command name is $2.
descendant() {
  local kid
  for kid in $(ps -o pid= --ppid "$1"); do
    if [ "$(cat "/proc/$kid/comm" 2>/dev/null)" = "$2" ]; then echo "$kid"; return 0; fi
    descendant "$kid" "$2" && return 0
  done
  return 1
}

whoami_in="$(crun "$ctr" -- id -u)"
[ "$whoami_in" = 10001 ] || die "container user is uid $whoami_in, expected 10001"
crun "$ctr" -- alignset --help > "$tmp/help.txt" 2>&1 || true
grep -qi "usage\|alignset" "$tmp/help.txt" || { cat "$tmp/help.txt"; die "alignset --help gave no usage"; }
log "alignset runs in the image as uid 10001"

for bin in alignset-server alignset-health-probe; do
  crun "$ctr" -- sh -c "command -v $bin" >/dev/null || die "$bin is not in the image"
done

# Host side: the project's CLI and the health probe, built here if CI has not built them.
HOST_CLI="${ALIGNSET_HOST_CLI:-$ROOT/build/cli/alignset}"
if [ ! -x "$HOST_CLI" ]; then
  log "building the host CLI ($HOST_CLI)"
  [ -f "$ROOT/build/build.ninja" ] || cmake -S "$ROOT" -B "$ROOT/build" -G Ninja >/dev/null
  nice -n 10 ninja -C "$ROOT/build" -j"$JOBS" alignset >/dev/null
fi
PROBE="$ROOT/build/health-probe/alignset-health-probe"
if [ ! -x "$PROBE" ] || [ "$ROOT/deploy/health-probe/health_probe.cc" -nt "$PROBE" ]; then
  log "building the host health probe"
  cmake -S "$ROOT/deploy/health-probe" -B "$ROOT/build/health-probe" -G Ninja >/dev/null
  nice -n 10 ninja -C "$ROOT/build/health-probe" >/dev/null
fi

port="$("$PY" -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')"
addr="127.0.0.1:$port"
data="$tmp/data"; mkdir -p "$data"; chown 10001:10001 "$data"
log "starting alignset-server from the image on $addr (volume $data)"
# Loopback only: the chroot isolation shares the host's network namespace.
crun --env ALIGNSET_LISTEN="$addr" --volume "$data:/var/lib/alignset" "$ctr" -- \
  alignset-server --workers 1 --threads-per-worker 1 --max-iterations "$ITERS" > "$tmp/server.log" 2>&1 &
server_pid=$!
for _ in $(seq 1 40); do inner_pid="$(descendant "$server_pid" alignset-server)" && break; sleep 0.25; done
[ -n "$inner_pid" ] || { cat "$tmp/server.log"; die "alignset-server process not found"; }

state=""
for _ in $(seq 1 60); do
  kill -0 "$server_pid" 2>/dev/null || { cat "$tmp/server.log"; die "server exited early"; }
  if state="$("$PROBE" --server "$addr" --timeout 2 2>&1)" && [ "$state" = SERVING ]; then
    break
  fi
  sleep 0.5
done
[ "$state" = SERVING ] || { cat "$tmp/server.log"; die "health never SERVING: $state"; }
log "health from the host: $state"

# The image's own HEALTHCHECK command, run inside the container against the live server.
crun --env ALIGNSET_LISTEN="$addr" "$ctr" -- /bin/sh -c "$hc_cmd" > "$tmp/hc.txt" 2>&1 \
  || { cat "$tmp/hc.txt"; die "image HEALTHCHECK failed against the running server"; }
log "image HEALTHCHECK passes"

n=64
t0=$(date +%s%N)
"$HOST_CLI" get --n "$n" --dir 30 --out "$tmp/set.txt" --server "$addr" > "$tmp/get.txt" 2>&1 \
  || { cat "$tmp/get.txt" "$tmp/server.log"; die "alignset get failed"; }
t1=$(date +%s%N)
"$PY" - "$tmp/set.txt" "$n" <<'PYEOF' || die "the returned set is not $n points in [0,1)^2"
import sys
pts = [l.split() for l in open(sys.argv[1]) if l.strip() and not l.startswith("#")]
n = int(sys.argv[2])
assert len(pts) == n, "%d points, expected %d" % (len(pts), n)
for p in pts:
    x, y = float(p[0]), float(p[1])
    assert 0.0 <= x < 1.0 and 0.0 <= y < 1.0, p
assert len({tuple(p) for p in pts}) == n, "duplicate points"
PYEOF
log "got $n points aligned at 30 deg in $(( (t1 - t0) / 1000000 )) ms"

db="$data/alignset.sqlite"
[ -s "$db" ] || { ls -la "$data"; die "no SQLite cache on the volume ($db)"; }
[ "$(stat -c %u "$db")" = 10001 ] || die "cache file not owned by uid 10001"
log "SQLite cache on the volume: $(stat -c %s "$db") bytes, owner uid 10001"

# `buildah run` answers SIGTERM by killing its child outright, so the signal goes to the
# server itself, as `docker stop` or the kubelet would deliver it.
log "stopping the server (SIGTERM to pid $inner_pid)"
kill -TERM "$inner_pid"
for _ in $(seq 1 40); do kill -0 "$server_pid" 2>/dev/null || break; sleep 0.25; done
if kill -0 "$server_pid" 2>/dev/null; then
  cat "$tmp/server.log"; die "server did not stop within 10 s of SIGTERM"
fi
rc=0; wait "$server_pid" || rc=$?
server_pid=""; inner_pid=""
[ "$rc" -eq 0 ] || { cat "$tmp/server.log"; die "server exited with status $rc after SIGTERM"; }
log "server stopped cleanly"

# --- 5. the Kubernetes precompute scripts, run in the image -----------------------------
# The shard and merge scripts of k8s/precompute/scripts.yaml as the Indexed Job's pods run
# them: 2 shards of the one-direction space at N=16, then the merge into the data volume
# that already holds the set served above.
mkdir -p "$tmp/scripts" "$tmp/shards" "$tmp/work0" "$tmp/work1"
"$PY" - "$ROOT/deploy/k8s/precompute/scripts.yaml" "$tmp/scripts" <<'PYEOF'
import sys, yaml
doc = yaml.safe_load(open(sys.argv[1]))
for name, text in doc["data"].items():
    open("%s/%s" % (sys.argv[2], name), "w").write(text)
PYEOF
chown -R 10001:10001 "$tmp/shards" "$tmp/work0" "$tmp/work1"
# The totals line of `alignset cache list`: "K sets (A one-direction, B two-direction)".
totals() { grep -oE '[0-9]+ sets \([0-9]+ one-direction, [0-9]+ two-direction\)' "$1" | tail -n 1; }
shard_port="$("$PY" -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')"
job_env=(--env ALIGNSET_SHARDS=2 --env ALIGNSET_PRECOMPUTE_N=16 --env ALIGNSET_PRECOMPUTE_SPACE=1dir
         --env ALIGNSET_THREADS=1 --env ALIGNSET_MAX_ITERATIONS="$ITERS"
         --env ALIGNSET_SHARD_LISTEN="127.0.0.1:$shard_port"
         --volume "$tmp/scripts:/scripts:ro" --volume "$tmp/shards:/shards")
for i in 0 1; do
  crun "${job_env[@]}" --env JOB_COMPLETION_INDEX="$i" --volume "$tmp/work$i:/work" "$ctr" -- \
    /bin/sh /scripts/shard.sh > "$tmp/shard$i.log" 2>&1 \
    || { cat "$tmp/shard$i.log"; die "shard.sh failed for index $i"; }
  [ -s "$tmp/shards/shard-000$i-of-0002.sqlite" ] || die "shard $i wrote no file"
done
# Each shard alone: 23 of the 46 keys (the canonical order split in two).
for i in 0 1; do
  crun --volume "$tmp/shards:/shards" "$ctr" -- alignset cache list \
    --db "/shards/shard-000$i-of-0002.sqlite" > "$tmp/list$i.txt" 2>&1 \
    || { cat "$tmp/list$i.txt" "$tmp/shard$i.log"; die "cache list of shard $i failed"; }
  shard_total="$(totals "$tmp/list$i.txt")"
  [ "$shard_total" = "23 sets (23 one-direction, 0 two-direction)" ] \
    || { cat "$tmp/list$i.txt" "$tmp/shard$i.log"; die "shard $i holds: $shard_total"; }
done
log "shard.sh wrote shards 0/2 and 1/2 (N=16, 1dir), 23 sets each"
crun --volume "$data:/var/lib/alignset" "${job_env[@]}" --env ALIGNSET_PUBLISH_DIR=/shards/published \
  "$ctr" -- /bin/sh /scripts/merge.sh \
  > "$tmp/merge.log" 2>&1 || { cat "$tmp/merge.log"; die "merge.sh failed"; }
crun --volume "$data:/var/lib/alignset" "$ctr" -- \
  alignset cache list --db /var/lib/alignset/alignset.sqlite > "$tmp/list.txt" 2>&1 \
  || { cat "$tmp/list.txt"; die "cache list failed"; }
merged_total="$(totals "$tmp/list.txt")"
# 46 canonical one-direction sets at N=16 from the shards, plus the N=64 set served above.
[ "$merged_total" = "47 sets (47 one-direction, 0 two-direction)" ] \
  || { cat "$tmp/merge.log" "$tmp/list.txt"; die "merged cache holds: $merged_total"; }
crun --volume "$data:/var/lib/alignset" "$ctr" -- \
  alignset cache verify --db /var/lib/alignset/alignset.sqlite > "$tmp/verify.txt" 2>&1 \
  || { cat "$tmp/verify.txt"; die "cache verify failed after the merge"; }
# Every set the merge took from a shard is that shard's, bit for bit.
for i in 0 1; do
  crun --volume "$data:/var/lib/alignset" --volume "$tmp/shards:/shards" "$ctr" -- \
    alignset cache diff --shared-only /var/lib/alignset/alignset.sqlite \
    "/shards/shard-000$i-of-0002.sqlite" > "$tmp/diff$i.txt" 2>&1 \
    || { cat "$tmp/diff$i.txt"; die "cache diff: the merged cache and shard $i differ"; }
  grep -q "^compared 23 shared sets: 23 the same, 0 differ, 0 damaged;" "$tmp/diff$i.txt" \
    || { cat "$tmp/diff$i.txt"; die "cache diff of shard $i: unexpected summary"; }
done
log "merge.sh: $merged_total; cache verify ok; cache diff: each shard's 23 sets the same"

# --- 6. two read-only replicas over the published file (deploy/k8s/replicas) -------------
# As the replica Deployment runs them: ALIGNSET_READ_ONLY=1, the published merged file on a
# read-only mount. Both must serve every key with identical bytes, refuse a miss with
# NOT_FOUND naming the key, and leave the file (and its directory) exactly as they found it.
pub="$tmp/shards/published"
[ -s "$pub/alignset.sqlite" ] || { cat "$tmp/merge.log"; die "merge.sh published no file for the replicas"; }
sum_before="$(sha256sum "$pub/alignset.sqlite" | cut -d' ' -f1)"
ls_before="$(ls -la --time-style=full-iso "$pub")"
replica_pids=(); replica_inner=(); replica_addr=()
for r in 0 1; do
  rport="$("$PY" -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')"
  replica_addr[$r]="127.0.0.1:$rport"
  crun --env ALIGNSET_LISTEN="127.0.0.1:$rport" --env ALIGNSET_READ_ONLY=1 \
    --env ALIGNSET_DB=/var/lib/alignset-shipped/alignset.sqlite \
    --volume "$pub:/var/lib/alignset-shipped:ro" "$ctr" -- \
    alignset-server --workers 1 --threads-per-worker 1 --max-iterations "$ITERS" > "$tmp/replica$r.log" 2>&1 &
  replica_pids[$r]=$!
done
stop_replicas() {
  local r p
  for r in 0 1; do
    p="${replica_inner[$r]:-}"
    if [ -n "$p" ]; then kill -TERM "$p" 2>/dev/null || true; fi
  done
  for r in 0 1; do
    p="${replica_pids[$r]:-}"
    if [ -n "$p" ]; then wait "$p" 2>/dev/null || true; fi
  done
  replica_pids=(); replica_inner=()
}
trap 'stop_replicas; cleanup' EXIT
for r in 0 1; do
  for _ in $(seq 1 40); do replica_inner[$r]="$(descendant "${replica_pids[$r]}" alignset-server)" && break; sleep 0.25; done
  [ -n "${replica_inner[$r]}" ] || { cat "$tmp/replica$r.log"; die "replica $r process not found"; }
  state=""
  for _ in $(seq 1 60); do
    kill -0 "${replica_pids[$r]}" 2>/dev/null || { cat "$tmp/replica$r.log"; die "replica $r exited early"; }
    if state="$("$PROBE" --server "${replica_addr[$r]}" --timeout 2 2>&1)" && [ "$state" = SERVING ]; then break; fi
    sleep 0.5
  done
  [ "$state" = SERVING ] || { cat "$tmp/replica$r.log"; die "replica $r never SERVING: $state"; }
done
log "two read-only replicas SERVING on ${replica_addr[0]} and ${replica_addr[1]}"
# Every key: the 46 one-direction sets at N=16 as one array, the N=64 set, and a mirrored one.
for r in 0 1; do
  "$HOST_CLI" get --n 16 --space 1dir --out "$tmp/space$r.npy" --server "${replica_addr[$r]}" > "$tmp/rget$r.txt" 2>&1 \
    || { cat "$tmp/rget$r.txt" "$tmp/replica$r.log"; die "replica $r: get --space 1dir failed"; }
  for d in 30 120; do
    "$HOST_CLI" get --n 64 --dir "$d" --out "$tmp/set$d-$r.npy" --server "${replica_addr[$r]}" >> "$tmp/rget$r.txt" 2>&1 \
      || { cat "$tmp/rget$r.txt"; die "replica $r: get --n 64 --dir $d failed"; }
  done
done
for f in space set30- set120-; do
  cmp "$tmp/${f}0.npy" "$tmp/${f}1.npy" || die "the replicas served different bytes ($f)"
done
"$PY" - "$tmp/space0.npy" <<'PYEOF' || die "the replica's space is not 46 sets of 16 points"
import sys, numpy as np
a = np.load(sys.argv[1])
assert a.shape == (46, 16, 2), a.shape
assert ((a >= 0) & (a < 1)).all()
PYEOF
log "both replicas served the 46 + 1 keys with identical bytes"
set +e
"$HOST_CLI" get --n 256 --dir 30 --out "$tmp/miss.txt" --server "${replica_addr[0]}" > "$tmp/miss.log" 2>&1
miss_rc=$?
set -e
[ "$miss_rc" -ne 0 ] && grep -q "NOT_FOUND" "$tmp/miss.log" && grep -q "n=256" "$tmp/miss.log" \
  || { cat "$tmp/miss.log"; die "a replica's miss was not NOT_FOUND naming the key (exit $miss_rc)"; }
log "a miss on a replica: $(head -n 1 "$tmp/miss.log")"
stop_replicas
[ "$(sha256sum "$pub/alignset.sqlite" | cut -d' ' -f1)" = "$sum_before" ] || die "a replica changed the shipped file"
[ "$(ls -la --time-style=full-iso "$pub")" = "$ls_before" ] || die "a replica left files beside the shipped one"
log "the shipped file is unchanged (sha256 $sum_before), nothing added beside it"
log "PASS in $(( $(date +%s) - START )) s"
