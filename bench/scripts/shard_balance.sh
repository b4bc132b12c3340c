#!/bin/bash
# Benchmark of the shard plan (issue 14): runs bench/sweeps/bench_shard_balance.yaml as N shards (2 and
# 4), every shard one after the other on one thread, once dealt round robin (--balance index) and
# once by expected cost (--balance cost), and prints each shard's measured wall time next to the
# plan's expected seconds, and the makespan (the slowest shard: what a job array waits for),
# in wall time and in CPU time (user + system: a shard runs on one thread, so CPU time is its
# run time without the waits that other load on the machine causes).
# Usage: bench/scripts/shard_balance.sh [--csv OUT]   (build/asperity must be built; stores go to a
# temporary folder, removed at the end). Each shard timed whole by /usr/bin/time.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
exe="$root/build/asperity"
csv=""
if [ "${1:-}" = "--csv" ]; then csv=${2:?--csv needs a file}; shift 2; fi
[ -x "$exe" ] || { echo "shard_balance: build $exe first" >&2; exit 2; }
if [ -n "$csv" ] && [ -e "$csv" ]; then echo "shard_balance: $csv exists; not overwriting it" >&2; exit 2; fi
work=$(mktemp -d "${TMPDIR:-/tmp}/asperity-shard-balance.XXXXXX")
trap 'rm -rf "$work"' EXIT
campaign="$root/bench/sweeps/bench_shard_balance.yaml"
table="$work/table.csv"
echo "shards,balance,shard,points,expected_s,wall_s,cpu_s" > "$table"
for n in 2 4; do
  for balance in index cost; do
    for ((i = 0; i < n; i++)); do
      out="$work/$n-$balance-$i"
      /usr/bin/time -f "%e %U %S" -o "$work/time.txt" \
        "$exe" sweep "$campaign" --out "$out" --shard "$i/$n" --balance "$balance" -j1 2>"$work/err.txt" >/dev/null ||
        { cat "$work/err.txt" >&2; exit 1; }
      read -r wall user sys < "$work/time.txt"
      points=$(($(wc -l < "$out/points.csv") - 1))
      expected=$(sed -n 's/.*balanced by expected cost: this shard \([^ ]*\) s.*/\1/p' "$work/err.txt")
      echo "$n,$balance,$i,$points,${expected:-nan},$wall,$(awk -v u="$user" -v s="$sys" 'BEGIN{printf "%.2f", u + s}')" >> "$table"
    done
  done
done
echo "# load average at the end: $(cut -d' ' -f1-3 /proc/loadavg); $(nproc) hardware threads; each shard on one thread"
column -s, -t < "$table"
echo
awk -F, 'NR > 1 { k = $1 "," $2; if ($6 > wmax[k]) wmax[k] = $6; if ($7 > cmax[k]) cmax[k] = $7; csum[k] += $7 }
         END { for (n = 2; n <= 4; n += 2) {
                 i = n ",index"; c = n ",cost";
                 printf "%d shards: makespan in CPU time %.2f s round robin vs %.2f s by cost (%.2fx), in wall time %.2f vs %.2f s; total CPU %.2f vs %.2f s\n",
                        n, cmax[i], cmax[c], cmax[i] / cmax[c], wmax[i], wmax[c], csum[i], csum[c] } }' "$table"
if [ -n "$csv" ]; then mkdir -p "$(dirname "$csv")"; cp "$table" "$csv"; fi
