#!/usr/bin/env bash
# Every bundled scene (data/scenes/*.json and data/scenes/hard/*.json; sphere_grid_1m last)
# through `shadowcert diff` of the robust volume methods at each given size, one JSON and log per
# run in OUT, then a table of hard errors, pixels compared and open volumes per size and method
# (docs/campaign.md#issue-27-pertris-reversed-pairs). Exit 1 when any run failed a check.
#
#   tools/scene_sweep.sh SHADOWCERT OUT [SIZE ...]       sizes default: 1024x768 1920x1080
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 2 ] || { echo "usage: tools/scene_sweep.sh SHADOWCERT OUT [SIZE ...]" >&2; exit 2; }
cli=$1 out=$2
shift 2
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(1024x768 1920x1080)
mkdir -p "$out"
scenes=$(ls data/scenes/*.json data/scenes/hard/*.json | grep -v sphere_grid_1m; echo data/scenes/sphere_grid_1m.json)
status=0
for size in "${sizes[@]}"; do
  for scene in $scenes; do
    name=$(echo "$scene" | sed 's|data/scenes/||; s|/|_|g; s|\.json$||')
    if "$cli" diff "$scene" --methods cpu,cs,gs,ts,pertri --size "$size" --json "$out/${name}_$size.json" \
         > "$out/${name}_$size.log" 2>&1; then
      echo "$size $name ok"
    else
      echo "$size $name FAILED (exit $?): $out/${name}_$size.log"
      status=1
    fi
  done
done
python3 - "$out" "${sizes[@]}" <<'PY'
import glob, json, sys
out, sizes = sys.argv[1], sys.argv[2:]
for size in sizes:
    runs = [json.load(open(f)) for f in sorted(glob.glob(f"{out}/*_{size}.json"))]
    print(f"{size}: {len(runs)} scenes")
    for method in ("cpu", "cs", "gs", "ts", "pertri"):
        rows = [r["methods"][method] for r in runs if method in r["methods"]]
        hard = sum(r["hard_errors"] for r in rows)
        pixels = sum(r["hard_errors"] + r["agree"] + r["ambiguous"] for r in rows)
        ambiguous = sum(r["ambiguous"] for r in rows)
        open_volumes = sum(not r["closed"] for r in rows)
        print(f"  {method:7s} hard errors {hard:>8,}  pixels {pixels:>12,}  ambiguous {ambiguous:>11,}  open volumes {open_volumes}")
PY
exit $status
