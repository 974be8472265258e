#!/usr/bin/env bash
# Runs every hostile-input reproducer (issue 15) through the gvd binary with a time and
# memory limit, and prints one line per run: exit code, seconds, output size, message.
#
#   scripts/hostile_reproducers.sh FUZZ_DIR [GVD_BINARY]
#
# FUZZ_DIR holds the reproducers (e.g. ../shared/corpus/hard/fuzz). Exit 0 with an output
# file or exit 2 with a message and no output file is a pass; a timeout (124), a signal
# (>128), a panic ("panicked" on stderr), a refusal that leaves an output, or a success
# without one is a FAIL. A diagram written is then checked by `gvd verify` (last column:
# PASS, FAIL, or "-" when the check does not end within the time limit); a FAIL there
# is reported as WRONG. The script exits 1 when any run fails or is wrong.
set -uo pipefail
DIR="${1:?usage: $0 FUZZ_DIR [GVD_BINARY]}"
GVD="${2:-target/release/gvd}"
LIMIT_S="${LIMIT_S:-10}"
LIMIT_KB="${LIMIT_KB:-4000000}"
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
failed=0

run() { # label success-writes-output(yes|no) args...
  local label="$1" wants_output="$2"
  shift 2
  rm -f "$OUT/out.json"
  local t0 t1 rc
  t0=$(date +%s.%N)
  (ulimit -v "$LIMIT_KB"; exec timeout -s KILL "$LIMIT_S" "$GVD" "$@" >"$OUT/stdout" 2>"$OUT/stderr") 2>/dev/null
  rc=$?
  t1=$(date +%s.%N)
  local size="-"
  [ -e "$OUT/out.json" ] && size=$(stat -c %s "$OUT/out.json")
  local edges="-"
  [ -s "$OUT/out.json" ] && edges=$(python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["edges"]))' "$OUT/out.json" 2>/dev/null)
  local msg verdict=ok
  msg=$(cat "$OUT/stderr" "$OUT/stdout" | tr '\n' ' ' | cut -c1-150)
  if grep -q panicked "$OUT/stderr"; then verdict=FAIL; fi
  case "$rc" in
    0) [ "$wants_output" = yes ] && [ "$size" = "-" ] && verdict=FAIL ;;
    1) [ "$wants_output" = yes ] && verdict=FAIL ;; # verify's "failed" verdict is a verdict
    2) [ "$size" != "-" ] && verdict=FAIL ;;
    *) verdict=FAIL ;;
  esac
  [ ${#msg} -ge 150 ] && [ "$(wc -c <"$OUT/stderr")" -gt 2000 ] && verdict=FAIL
  local check="-"
  if [ "$rc" = 0 ] && [ "$size" != "-" ] && [ "$1" = compute ]; then
    check=$( (ulimit -v "$LIMIT_KB"; timeout -s KILL "$LIMIT_S" "$GVD" verify "$2" "$OUT/out.json" 2>/dev/null) | tail -n 1 | awk '{print $NF}')
    [ "$check" = FAIL ] && [ "$verdict" = ok ] && verdict=WRONG
    [ -z "$check" ] && check="-"
  fi
  [ "$verdict" != ok ] && failed=1
  printf '%-5s %-46s rc=%-3s %5.1fs %9s B %6s edges %-4s  %s\n' "$verdict" "$label" "$rc" \
    "$(echo "$t1 - $t0" | bc)" "$size" "$edges" "$check" "$msg"
}

for f in "$DIR"/*.json; do
  name=$(basename "$f" .json)
  case "$name" in
    V01_diagram | V03_*_diagram) ;;
    V01_scene)
      for g in 18446744073709551615 4294967296 100000; do
        run "$name --grid $g" no verify "$f" "$DIR/V01_diagram.json" --grid "$g"
      done
      run "$name (default grid)" no verify "$f" "$DIR/V01_diagram.json"
      ;;
    V03_*_scene)
      run "$name" no verify "$f" "${f%_scene.json}_diagram.json"
      ;;
    H11_*)
      for m in 0 1e-6 -1 NaN; do
        run "$name --max-box=$m" yes compute "$f" --json "$OUT/out.json" "--max-box=$m"
      done
      ;;
    H12_*)
      run "$name --threads 100000" yes compute "$f" --json "$OUT/out.json" --threads 100000
      run "$name --threads 2" yes compute "$f" --json "$OUT/out.json" --threads 2
      ;;
    *)
      run "$name" yes compute "$f" --json "$OUT/out.json"
      ;;
  esac
done
exit $failed
