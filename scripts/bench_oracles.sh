#!/usr/bin/env bash
# The C++ reference oracles (CGAL, Boost.Polygon) on the scenes of the issue 4 benchmark,
# to set beside `cargo run --release -p gvd --example bench_oracles -- SCENE_DIR`.
#
# usage: scripts/bench_oracles.sh ORACLE_BUILD_DIR SCENE_DIR [RUNS=3] [BIG_RUNS=1]
#
# ORACLE_BUILD_DIR holds oracle_points_cgal, oracle_segments_cgal and oracle_boost, built
# as ../shared/oracles/README.md says (copy the directory, `make`). Every *.json scene of
# SCENE_DIR is run with `--bench`: all points -> oracle_points_cgal and oracle_boost; any
# segment -> oracle_segments_cgal and oracle_boost. "seconds" is the oracle's own
# stats.seconds (construction only, JSON reading not included), best of RUNS runs
# (BIG_RUNS for n >= 10^6). "peak MB" is the largest maximum resident set size of the
# runs (/usr/bin/time %M): the whole process, including the nlohmann::json document of
# the scene, so it is an upper bound on the construction's memory.
set -euo pipefail
if [ $# -lt 2 ]; then
  sed -n '4,5p' "$0" | sed 's/^# //' >&2
  exit 2
fi
BUILD=$1
SCENES=$2
RUNS=${3:-3}
BIG_RUNS=${4:-1}
TIME=/usr/bin/time
[ -x "$TIME" ] || { echo "bench_oracles.sh: needs GNU time at $TIME (apt-get install time)" >&2; exit 2; }
for p in oracle_points_cgal oracle_segments_cgal oracle_boost; do
  [ -x "$BUILD/$p" ] || { echo "bench_oracles.sh: $BUILD/$p is missing (run make there)" >&2; exit 2; }
done
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

echo "| n | kind | program | seconds (best) | runs | peak MB (whole process) |"
echo "|---:|---|---|---:|---:|---:|"
shopt -s nullglob
for scene in "$SCENES"/*.json; do
  if grep -q '"kind" *: *"segment"' "$scene"; then
    kind=segments; progs="oracle_segments_cgal oracle_boost"
  else
    kind=points; progs="oracle_points_cgal oracle_boost"
  fi
  for prog in $progs; do
    best=""; peak=0; n="?"; done_runs=0; err=""
    runs=$RUNS
    for ((k = 0; k < runs; k++)); do
      if ! "$TIME" -f '%M' -o "$TMP/mem" "$BUILD/$prog" "$scene" --bench >"$TMP/out" 2>"$TMP/err"; then
        err=$(grep -v '^Command exited' "$TMP/err" | head -n 1); break
      fi
      read -r n secs < <(python3 -c 'import json,sys; s=json.load(open(sys.argv[1]))["stats"]; print(s["n"], s["seconds"])' "$TMP/out")
      if [ "$k" -eq 0 ] && [ "$n" -ge 1000000 ]; then runs=$BIG_RUNS; fi
      mem=$(tail -n 1 "$TMP/mem")
      [ "$mem" -gt "$peak" ] && peak=$mem
      if [ -z "$best" ] || awk -v a="$secs" -v b="$best" 'BEGIN { exit !(a < b) }'; then best=$secs; fi
      done_runs=$((k + 1))
    done
    if [ -n "$err" ]; then
      echo "| $n | $kind | $prog | failed: $err | $done_runs | — |"
    else
      awk -v n="$n" -v k="$kind" -v p="$prog" -v s="$best" -v r="$done_runs" -v m="$peak" \
        'BEGIN { printf "| %s | %s | %s | %.3f | %d | %.0f |\n", n, k, p, s, r, m / 1024 }'
    fi
  done
done
