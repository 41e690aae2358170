#!/usr/bin/env bash
# Writes a CTest resource specification listing this machine's GPUs, from `fgbench devices --json`,
# so GPU tests (RESOURCE_GROUPS "gpus:1") get one device each:
#   scripts/gpu-resources.sh [OUT.json]          (default: build/gpu-resources.json)
#   ctest --test-dir build -L gpu --resource-spec-file build/gpu-resources.json
# CPU implementations (lavapipe) are not GPUs and are left out unless FGBENCH_RESOURCE_CPU=1.
# Environment: FGBENCH (the binary, default build/fgbench).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$here/build/gpu-resources.json}"
fgbench="${FGBENCH:-$here/build/fgbench}"
include_cpu="${FGBENCH_RESOURCE_CPU:-0}"

if [ ! -x "$fgbench" ]; then
  echo "gpu-resources: $fgbench not found; build first (scripts/setup.sh) or set FGBENCH" >&2
  exit 2
fi
devices_json="$("$fgbench" devices --json)" || { echo "gpu-resources: 'fgbench devices --json' failed" >&2; exit 3; }

# `devices --json` prints one key per line; pair each device's "index" with its "type" without
# needing jq or Python on a fresh machine.
ids="$(printf '%s\n' "$devices_json" | awk -v cpu="$include_cpu" '
  /"index":/ { gsub(/[^0-9]/, "", $2); index_value = $2 }
  /"type":/  { t = $2; gsub(/[",]/, "", t); type_value = t }
  /^ *}/     { if (index_value != "" && (type_value != "cpu" || cpu == "1")) print index_value; index_value = ""; type_value = "" }
')"

entries=""
for id in $ids; do
  entries="${entries:+$entries, }{\"id\": \"$id\", \"slots\": 1}"
done
mkdir -p "$(dirname "$out")"
tmp="$out.tmp.$$"
printf '{\n  "version": {"major": 1, "minor": 0},\n  "local": [\n    {"gpus": [%s]}\n  ]\n}\n' "$entries" > "$tmp"
mv "$tmp" "$out"
echo "gpu-resources: $(printf '%s\n' $ids | grep -c . || true) GPU(s) -> $out" >&2
