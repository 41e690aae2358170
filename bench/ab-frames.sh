#!/usr/bin/env bash
# A/B frame timing of fgbench binaries on one configuration, the way the notes measure renderer
# costs (e.g. #17's stability fixes): the binaries run in turn, ROUNDS times, so drift in clocks or
# load hits all of them alike; each run prints its frame median (p5..p95 over the measured frames)
# and the median of every pass above 0.01 ms, and the end prints each binary's median over rounds
# (the frame, the slowest pass, and with -p PASS that pass too).
#
#   bench/ab-frames.sh [-r ROUNDS] [-p PASS] BINARY... -- RUN-ARGS...
#   bench/ab-frames.sh -r 4 old/fgbench build/fgbench -- scenes/atrium.json --device gpu \
#       --width 1920 --height 1080 --frames 64
set -euo pipefail
rounds=3
pass=""
while [[ ${1:-} == -r || ${1:-} == -p ]]; do
  [[ $# -ge 2 ]] || { echo "$0: $1 needs a value" >&2; exit 2; }
  if [[ $1 == -r ]]; then rounds=$2; else pass=$2; fi
  shift 2
done
binaries=()
while [[ $# -gt 0 && $1 != -- ]]; do binaries+=("$1"); shift; done
[[ $# -gt 0 ]] || { echo "usage: $0 [-r ROUNDS] [-p PASS] BINARY... -- RUN-ARGS..." >&2; exit 2; }
shift
[[ ${#binaries[@]} -gt 0 ]] || { echo "$0: no binary given" >&2; exit 2; }
for b in "${binaries[@]}"; do [[ -x $b ]] || { echo "$0: $b: not an executable" >&2; exit 2; }; done

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for ((r = 1; r <= rounds; ++r)); do
  for i in "${!binaries[@]}"; do
    "${binaries[$i]}" run "$@" --out "$out/run" --quiet --json > "$out/r$r-b$i.json"
    python3 - "$out/r$r-b$i.json" "r$r ${binaries[$i]}" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); f = d["frame_gpu_ms"]
passes = " ".join(f'{p["name"]}={p["gpu_ms"]["median"]:.3f}' for p in d["passes"] if p["gpu_ms"]["median"] >= 0.01)
print(f'{sys.argv[2]}: frame {f["median"]:.3f} (p5 {f.get("p5", 0):.3f} p95 {f.get("p95", 0):.3f}) | {passes}')
PY
  done
done
python3 - "$out" "$rounds" "$pass" "${binaries[@]}" <<'PY'
import json, statistics, sys
out, rounds, chosen, binaries = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4:]
print("median over rounds (min..max):")
for i, b in enumerate(binaries):
    runs = [json.load(open(f"{out}/r{r}-b{i}.json")) for r in range(1, rounds + 1)]
    frames = [d["frame_gpu_ms"]["median"] for d in runs]
    names = [p["name"] for p in runs[0]["passes"]]
    top = max(names, key=lambda n: runs[0]["passes"][names.index(n)]["gpu_ms"]["median"])
    line = f"  {b}: frame {statistics.median(frames):.3f} ({min(frames):.3f}..{max(frames):.3f})"
    for name in dict.fromkeys([top, chosen]):
        if not name:
            continue
        times = [next((p["gpu_ms"]["median"] for p in d["passes"] if p["name"] == name), None) for d in runs]
        if None in times:
            line += f"; {name}: not in every run"
            continue
        line += f"; {name} {statistics.median(times):.3f} ({min(times):.3f}..{max(times):.3f})"
    print(line)
PY
