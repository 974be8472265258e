#!/usr/bin/env bash
# Diffs the JSON output of two gvd binaries over every scene given (directories or
# files), ignoring the timing figures in `stats` (keys naming "seconds").
# Each scene is run with the default engine and, where it applies, with
# `--engine subdivision` and `--bisectors`. Exit 1 on any difference.
#
# usage: scripts/diff_outputs.sh OLD_GVD NEW_GVD SCENE_OR_DIR...
set -uo pipefail
if [ $# -lt 3 ]; then sed -n '6p' "$0" | sed 's/^# //' >&2; exit 2; fi
OLD=$1 NEW=$2; shift 2
TMP=$(mktemp -d); trap 'rm -rf "$TMP"' EXIT
normalize() { # strips stats timings, prints canonical JSON
  python3 - "$1" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
def strip(s):
    if isinstance(s, dict):
        return {k: strip(v) for k, v in s.items() if "seconds" not in k}
    return s
if "stats" in d: d["stats"] = strip(d["stats"])
print(json.dumps(d, sort_keys=True, indent=0))
PY
}
scenes=()
for a in "$@"; do
  if [ -d "$a" ]; then while IFS= read -r f; do scenes+=("$f"); done < <(find "$a" -name '*.json' -not -path '*/bad/*' -not -path '*/fuzz/*' -not -name '*_diagram.json' | sort)
  else scenes+=("$a"); fi
done
same=0 differ=0 refused=0
for s in "${scenes[@]}"; do
  for flags in "" "--engine subdivision" "--bisectors"; do
    o="$TMP/old.json" n="$TMP/new.json"; rm -f "$o" "$n"
    timeout 120 "$OLD" compute "$s" $flags --json "$o" >/dev/null 2>"$TMP/old.err"; ro=$?
    timeout 120 "$NEW" compute "$s" $flags --json "$n" >/dev/null 2>"$TMP/new.err"; rn=$?
    if [ $ro -ne 0 ] || [ $rn -ne 0 ]; then
      if [ $ro -ne $rn ]; then echo "DIFF $s [$flags]: exit $ro vs $rn"; differ=$((differ+1))
      elif ! diff -q <(sed 's/[0-9.]* s$//' "$TMP/old.err") <(sed 's/[0-9.]* s$//' "$TMP/new.err") >/dev/null; then
        echo "DIFF $s [$flags]: messages differ"; diff "$TMP/old.err" "$TMP/new.err" | head -4; differ=$((differ+1))
      else refused=$((refused+1)); fi
      continue
    fi
    normalize "$o" > "$TMP/old.norm"; normalize "$n" > "$TMP/new.norm"
    if cmp -s "$TMP/old.norm" "$TMP/new.norm"; then same=$((same+1))
    else echo "DIFF $s [$flags]"; differ=$((differ+1)); fi
  done
done
echo "diff_outputs: $same identical, $refused refused alike, $differ different"
[ $differ -eq 0 ]
