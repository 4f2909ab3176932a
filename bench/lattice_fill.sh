#!/usr/bin/env bash
# How long `alignset precompute --construction lattice` fills a space with
# and without the server's shared lattice terms (--lattice-terms-mb, default
# 128; 0 turns them off: every key searches alone, as before they existed).
# A real server on loopback, a fresh cache for each run, the server's
# defaults otherwise (one worker with every core). Whole spaces, not
# samples: the terms are shared between the keys of a space, so a sample of
# scattered keys would share less than the space does. The run without the
# terms samples the two-direction space at N = 4096 (shard 0 of 20, every
# 20th key, extrapolated to 4141; a key alone costs the same wherever it is).
# Each row also checks that both runs stored the same bytes for every key
# they share.
#
#   bash bench/lattice_fill.sh [OUT.md]          # default bench/results/lattice_fill.md
#   LARGE=1 ...: also the one-direction spaces at N = 16384 and 65536 (whose
#   keys share no direction: the terms cannot help, the rows show what they
#   cost) and the two-direction space at 16384 (10 minutes with the terms;
#   without them one key, extrapolated). The two-direction space at 65536 is
#   left out: its first 294 keys took 553 s with the terms (1.9 s a key).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${BUILD_DIR:-build}"
OUT="${1:-bench/results/lattice_fill.md}"
cmake --build "$BUILD_DIR" --target alignset-server alignset >/dev/null
WORK=$(mktemp -d)
. scripts/lib/loopback_server.sh
trap 'stop_loopback_server; rm -rf "$WORK"' EXIT
CLI="$BUILD_DIR/cli/alignset"

declare -A seconds
# fill TAG TERMS_MB ARGS...: one fresh server, one precompute; its seconds.
fill() {
  local tag=$1 mb=$2
  shift 2
  rm -f "$WORK/$tag.sqlite"
  start_loopback_server 30 "$WORK/server.log" "$BUILD_DIR/server/alignset-server" \
    --db "$WORK/$tag.sqlite" --log-level warn --lattice-terms-mb "$mb"
  local t0 t1
  t0=$(date +%s.%N)
  "$CLI" precompute --server "$ADDR" --construction lattice "$@" >"$WORK/last.log" 2>&1 || {
    echo "lattice_fill: precompute $* failed:" >&2
    tail -5 "$WORK/last.log" >&2
    exit 1
  }
  t1=$(date +%s.%N)
  stop_loopback_server
  seconds[$tag]=$(/usr/bin/python3 -c "import sys; print('%.2f' % (float(sys.argv[2]) - float(sys.argv[1])))" "$t0" "$t1")
  echo "lattice_fill: $tag $* ${seconds[$tag]} s" >&2
}
# same A B: how many keys both files hold and how many of them differ
# (`alignset cache diff`: the points, bit for bit).
same() {
  local summary
  summary=$("$CLI" cache diff --shared-only "$WORK/$1.sqlite" "$WORK/$2.sqlite" | tail -1) || true
  [[ $summary =~ ^compared\ ([0-9]+)\ shared\ sets:\ [0-9]+\ the\ same,\ ([0-9]+)\ differ,\ ([0-9]+)\ damaged ]] || {
    echo "lattice_fill: cache diff said: $summary" >&2
    echo "not compared"
    return
  }
  echo "${BASH_REMATCH[1]} keys, $((BASH_REMATCH[2] + BASH_REMATCH[3])) differ"
}

rows=()
row() {  # label items_before items_after before_tag after_tag
  local label=$1 nb=$2 na=$3 b=$4 a=$5
  rows+=("$(/usr/bin/python3 -c "
import sys
label, nb, na, tb, ta, same = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5]), sys.argv[6]
whole_b = tb / nb * na
print('| %s | %d | %.1f s | %.1f s | %.1fx | %s |' % (label, na, whole_b, ta, whole_b / ta, same))
" "$label" "$nb" "$na" "${seconds[$b]}" "${seconds[$a]}" "$(same "$b" "$a")")")
  echo "${rows[-1]}" >&2
}

fill one4096_alone 0 -n 4096 --space 1dir -m 8
fill one4096_terms 128 -n 4096 --space 1dir -m 8
row "1 dir, N = 4096, 46 keys x 8 realizations" 368 368 one4096_alone one4096_terms
fill two1024_alone 0 -n 1024 --space 2dir
fill two1024_terms 128 -n 1024 --space 2dir
row "2 dir, N = 1024, 4141 keys" 4141 4141 two1024_alone two1024_terms
fill two4096_alone 0 -n 4096 --space 2dir --shard 0/20
fill two4096_terms 128 -n 4096 --space 2dir
row "2 dir, N = 4096, 4141 keys (without the terms: 208 keys, extrapolated)" 208 4141 two4096_alone two4096_terms
if [[ -n ${LARGE:-} ]]; then
  for n in 16384 65536; do
    fill "one${n}_alone" 0 -n "$n" --space 1dir
    fill "one${n}_terms" 128 -n "$n" --space 1dir
    row "1 dir, N = $n, 46 keys" 46 46 "one${n}_alone" "one${n}_terms"
  done
  fill two16384_alone 0 -n 16384 --space keys --key 30,75
  fill two16384_terms 128 -n 16384 --space 2dir
  row "2 dir, N = 16384, 4141 keys (without the terms: one key, 30 and 75 deg, extrapolated)" 1 4141 two16384_alone two16384_terms
fi

{
  echo "# Filling the lattice spaces with the shared search terms: \`bash bench/lattice_fill.sh\`"
  echo
  echo "$(nproc) cores, load average at the end: $(cut -d' ' -f1-3 /proc/loadavg); one worker with every core; a fresh cache per run; $(date -u +%Y-%m-%d). Wall-clock seconds of one \`alignset precompute --construction lattice\` call; *alone*: \`--lattice-terms-mb 0\`, every key searched on its own; *shared*: the default 128 MB of terms. The last column compares the sets both runs stored, byte for byte."
  echo
  echo "| space | items | alone | shared | speed-up | same sets |"
  echo "|---|---:|---:|---:|---:|---|"
  printf '%s\n' "${rows[@]}"
} >"$OUT"
echo "lattice_fill: wrote $OUT" >&2
