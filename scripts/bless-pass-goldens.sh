#!/usr/bin/env bash
# Blesses per-pass goldens (golden/<scene>/lavapipe/<config>/passes/) for every lavapipe golden of
# the given configurations, rendered exactly as each frame golden's JSON says (size, frames,
# warm-up, knobs), without touching the frame goldens themselves: the bless runs into a scratch
# root and only its passes/ folder is moved into place.
#
#   scripts/bless-pass-goldens.sh [-b build/fgbench] [-r RENDERS] CONFIG...   e.g. default visbuffer
#
# A new render path's goldens (e.g. meshlet) get their per-pass goldens with the same one command
# once their frame goldens exist. Look at a few captured images before committing.
set -euo pipefail
fgbench=build/fgbench
renders=3
while getopts "b:r:" option; do
  case $option in
    b) fgbench=$OPTARG ;;
    r) renders=$OPTARG ;;
    *) echo "usage: $0 [-b FGBENCH] [-r RENDERS] CONFIG..." >&2; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
[[ $# -ge 1 ]] || { echo "usage: $0 [-b FGBENCH] [-r RENDERS] CONFIG..." >&2; exit 2; }
root=$(cd "$(dirname "$0")/.." && pwd)
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

for config in "$@"; do
  for golden in "$root"/golden/*/lavapipe/"$config".json; do
    [[ -f $golden ]] || continue
    scene=$(basename "$(dirname "$(dirname "$golden")")")
    [[ $scene == proof ]] && continue  # builtin:proof has no per-pass goldens
    # The frame golden's own configuration, as bless options (one per line).
    mapfile -t options < <(python3 - "$golden" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))["config"]
for key in ("width", "height", "frames", "warmup"):
    if c.get(key):
        print(f"--{key}"); print(c[key])
for key, value in sorted(c.get("knobs", {}).items()):
    print("--set"); print(f"{key}={value}")
PY
)
    echo "blessing per-pass goldens of $scene/$config"
    "$fgbench" bless "$root/scenes/$scene.json" --device lavapipe --renders "$renders" --passes --quiet \
      --golden-root "$scratch" --config "$config" "${options[@]}"
    target="$root/golden/$scene/lavapipe/$config"
    rm -rf "$target/passes"
    mkdir -p "$target"
    mv "$scratch/$scene/lavapipe/$config/passes" "$target/passes"
  done
done
du -sb "$root"/golden/*/lavapipe/*/passes 2>/dev/null | awk '{ total += $1 } END { printf "per-pass goldens: %d bytes\n", total }'
