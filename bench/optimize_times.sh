#!/bin/bash
# Wall time of `alignset optimize` for two builds, interleaved on one engine
# thread (a change to the engine measured end to end, set-up included), and
# whether their sets are byte for byte the same.
#   bench/optimize_times.sh BEFORE_ALIGNSET AFTER_ALIGNSET [REPS]
# Prints "N before|after MS" lines and "N bytes identical|differ".
set -euo pipefail
before=$1 after=$2 reps=${3:-5}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for spec in 1024:0 4096:0 16384:300 65536:150; do
  n=${spec%%:*} it=${spec##*:}
  extra=()
  [[ $it != 0 ]] && extra=(--max-iterations "$it")
  for _ in $(seq "$reps"); do
    for label in before after; do
      bin=$before
      [[ $label == after ]] && bin=$after
      s=$(date +%s%N)
      "$bin" optimize -n "$n" --dir 30 "${extra[@]}" --threads 1 -o "$tmp/$label.npy" > /dev/null 2>&1
      e=$(date +%s%N)
      echo "$n $label $(((e - s) / 1000000))"
    done
  done
  if cmp -s "$tmp/before.npy" "$tmp/after.npy"; then echo "$n bytes identical"; else echo "$n bytes differ"; fi
done
