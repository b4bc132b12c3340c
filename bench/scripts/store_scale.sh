#!/bin/bash
# Scale benchmark of the campaign store (issue 14): for each size POINTS (default 100000 and
# 1000000) a cheap campaign (P0.98N stand-in, 294 junctions, 1 ms of simulated time per point;
# model.eta x model.epsilon x model.c_min = POINTS/10^4 x 100 x 100; alpha_b or p as an axis costs
# ~8 times more per point, eta, epsilon and c_min do not) is
#   sweep     run from scratch on one thread (points/s per thread, peak RSS),
#   resume    rerun on the complete store: with inputs.txt (stored hashes trusted), and without it
#             (every stored point rebuilt and re-hashed),
#   shards    run again as 16 shards (--shard I/16, one after the other, one thread each),
#   merge     `asperity merge` of the 16 shards (checked equal to the unsharded store, wall_s aside),
#   copy      beside it, disk speed: `cat` of the 16 journals through `tee` into two files and a
#             `sync` of both (the least I/O a merge does: read each row once, write the journal and
#             points.csv, flushed),
#   plot      a 100 x 100 heat map slice (--where model.eta=0) of the merged store,
# each under /usr/bin/time -v (wall seconds, maximum resident set). With two sizes or more, each
# figure is extrapolated to 10^7 points along the line through the two largest sizes (a figure
# that did not grow between them is not extrapolated downwards). Prints a
# table and writes it as CSV to OUT (default: not written).
# Usage: bench/scripts/store_scale.sh [--csv OUT] [POINTS...]   (build/asperity must be built; stores go
# to a temporary folder under $TMPDIR, removed at the end: ~700 bytes of disk per point and size)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
exe="$root/build/asperity"
csv=""
if [ "${1:-}" = "--csv" ]; then csv=${2:?--csv needs a file}; shift 2; fi
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(100000 1000000)
[ -x "$exe" ] || { echo "store_scale: build $exe first" >&2; exit 2; }
if [ -n "$csv" ] && [ -e "$csv" ]; then echo "store_scale: $csv exists; not overwriting it" >&2; exit 2; fi
for n in "${sizes[@]}"; do
  if ! [[ "$n" =~ ^[1-9][0-9]*0000$ ]]; then echo "store_scale: POINTS must be a multiple of 10000, got '$n'" >&2; exit 2; fi
done
work=$(mktemp -d "${TMPDIR:-/tmp}/asperity-store-scale.XXXXXX")
trap 'rm -rf "$work"' EXIT
results="$work/results.txt"  # size step wall_s rss_mb

measure() {  # measure SIZE STEP COMMAND...: runs it under /usr/bin/time -v, records wall and RSS
  local size=$1 step=$2
  shift 2
  if ! /usr/bin/time -v -o "$work/time.txt" "$@" >"$work/out.txt" 2>"$work/err.txt"; then
    echo "store_scale: $step failed:" >&2; cat "$work/err.txt" "$work/time.txt" >&2; exit 1
  fi
  awk -v size="$size" -v step="$step" '
    /Elapsed \(wall clock\)/ { n = split($NF, p, ":"); w = 0; for (i = 1; i <= n; ++i) w = w * 60 + p[i] }
    /Maximum resident set size/ { r = $NF / 1024 }
    END { printf "%s %s %.2f %.1f\n", size, step, w, r }' "$work/time.txt" >>"$results"
}

for n in "${sizes[@]}"; do
  d="$work/$n"
  mkdir -p "$d"
  cat >"$d/scale.yaml" <<YAML
name: store_scale
scenes: ["$root/scenes/paper/P0.98N.yaml"]
set: {stop.time: 1e-3, output.series: []}
axes:
  model.eta: {linspace: [0, 250, $((n / 10000))]}
  model.epsilon: {linspace: [0.5, 0.99, 100]}
  model.c_min: {logspace: [1e-5, 1e-2, 100]}
YAML
  echo "store_scale: $n points: sweep (load $(cut -d' ' -f1 /proc/loadavg))" >&2
  measure "$n" sweep "$exe" sweep "$d/scale.yaml" -j1 --out "$d/full"
  grep -q "0 failed" "$work/err.txt" || { cat "$work/err.txt" >&2; exit 1; }
  measure "$n" resume_trusted "$exe" sweep "$d/scale.yaml" -j1 --out "$d/full"
  grep -q "stored hashes trusted" "$work/err.txt" ||
    echo "store_scale: note: hashes not trusted on resume (a -dirty or unknown build?): $(tail -1 "$work/err.txt")" >&2
  grep -q " 0 run now" "$work/err.txt" || { cat "$work/err.txt" >&2; exit 1; }
  rm "$d/full/inputs.txt"
  measure "$n" resume_rehash "$exe" sweep "$d/scale.yaml" -j1 --out "$d/full"
  grep -q " 0 run now" "$work/err.txt" || { cat "$work/err.txt" >&2; exit 1; }
  echo "store_scale: $n points: 16 shards (load $(cut -d' ' -f1 /proc/loadavg))" >&2
  for i in $(seq 0 15); do
    measure "$n" "shard$i" "$exe" sweep "$d/scale.yaml" -j1 --quiet --shard "$i/16" --out "$d/shard$i"
  done
  measure "$n" merge16 "$exe" merge "$d"/shard{0..15} --out "$d/merged"
  # Disk speed, side by side: the bytes merge must move at least (read the 16 journals once, write
  # a journal and a points.csv of their size, flushed to disk as merge flushes its files).
  mkdir -p "$d/copy"
  measure "$n" copy16 sh -c 'cat "$@" | tee "$0/journal.csv" > "$0/points.csv" && sync "$0/journal.csv" "$0/points.csv"' \
    "$d/copy" "$d"/shard{0..15}/journal.csv
  rm -rf "$d/copy"
  strip() { sed 's/,[^,]*$//' "$1/points.csv"; }
  cmp -s <(strip "$d/full") <(strip "$d/merged") || { echo "store_scale: merged store differs from the unsharded one" >&2; exit 1; }
  measure "$n" plot "$exe" plot "$d/merged" --x model.epsilon --y model.c_min --z force_evals --where model.eta=0 \
    --out "$d/map.png"
  echo "$n journal_mb $(( $(stat -c %s "$d/full/journal.csv") / 1000000 )) 0" >>"$results"
  rm -rf "$d"  # disk: the next size starts clean
done

# Table: the 16 shards summed (wall) and maxed (RSS); points/s per thread of the sweep.
awk -v now="$(date -u +%Y-%m-%dT%H:%MZ)" -v load="$(cut -d' ' -f1-3 /proc/loadavg)" -v csv="$csv" '
  {
    size = $1; step = $2
    if (step == "journal_mb") { jm[size] = $3; next }
    if (step ~ /^shard/) { step = "shards16" ; w[size, step] += $3; if ($4 > r[size, step]) r[size, step] = $4 }
    else { w[size, step] = $3; r[size, step] = $4 }
    if (!(size in seen)) { seen[size] = 1; sizes[++ns] = size }
  }
  END {
    split("sweep resume_trusted resume_rehash shards16 merge16 copy16 plot", steps, " ")
    printf "store scale benchmark, %s, load %s (one thread per sweep; resume_rehash re-hashes every stored point)\n", now, load
    hdr = sprintf("%-16s", "step"); for (k = 1; k <= ns; ++k) hdr = hdr sprintf(" | %9s pts: wall s, RSS MB", sizes[k])
    if (ns >= 2) hdr = hdr " | 1e7 extrapolated: wall s, RSS MB"
    print hdr
    if (csv != "") print "step,points,wall_s,rss_mb,extrapolated" > csv
    a = sizes[ns - 1]; b = sizes[ns]
    for (s = 1; s <= 7; ++s) {
      st = steps[s]; line = sprintf("%-16s", st)
      for (k = 1; k <= ns; ++k) {
        line = line sprintf(" | %22.2f %8.1f", w[sizes[k], st], r[sizes[k], st])
        if (csv != "") printf "%s,%s,%.2f,%.1f,no\n", st, sizes[k], w[sizes[k], st], r[sizes[k], st] > csv
      }
      if (ns >= 2) {
        # A step that did not grow between the two sizes (the plot reads a fixed slice) is not
        # extrapolated downwards: its larger figure stands.
        sw = (w[b, st] - w[a, st]) / (b - a); if (sw < 0) sw = 0
        sr = (r[b, st] - r[a, st]) / (b - a); if (sr < 0) sr = 0
        ew = (w[b, st] > w[a, st] ? w[b, st] : w[a, st]) + sw * (1e7 - b)
        er = (r[b, st] > r[a, st] ? r[b, st] : r[a, st]) + sr * (1e7 - b)
        line = line sprintf(" | %22.1f %8.1f", ew, er)
        if (csv != "") printf "%s,10000000,%.1f,%.1f,yes\n", st, ew, er > csv
      }
      print line
    }
    for (k = 1; k <= ns; ++k) {
      printf "sweep at %s points: %.0f points/s per thread; journal.csv %s MB\n", sizes[k], sizes[k] / w[sizes[k], "sweep"], jm[sizes[k]]
      if (w[sizes[k], "copy16"] > 0)
        printf "merge at %s points: %.0f MB/s of journal vs %.0f MB/s for cat | tee + sync of the same bytes (merge takes %.2fx the copy)\n",
               sizes[k], jm[sizes[k]] / w[sizes[k], "merge16"], jm[sizes[k]] / w[sizes[k], "copy16"], w[sizes[k], "merge16"] / w[sizes[k], "copy16"]
    }
  }' "$results"
