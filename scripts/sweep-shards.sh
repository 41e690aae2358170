#!/usr/bin/env bash
# A sweep spread over every GPU of a machine, with CTest as the scheduler: N shards
# (`fgbench sweep --shard K/N`, cut along reference groups) run as N CTest tests that each take one
# GPU (RESOURCE_GROUPS "gpus:1", from scripts/gpu-resources.sh), then `fgbench sweep-merge` joins
# them into OUT/merged (sweep.json/.csv/.md/.html, one front).
#
#   scripts/sweep-shards.sh [-n N] [-o OUT] [-d DEVICE] [-b FGBENCH] -- SCENE [sweep options]
#   scripts/sweep-shards.sh -n 2 -o out/atrium-shards -- scenes/atrium.json --width 1920 --height 1080 \
#       --vary msaa=1,2,4,8 --vary render.ssaa=1,2
#
# N defaults to the GPUs in the resource specification (build/gpu-resources.json, written by
# scripts/gpu-resources.sh if missing). Without GPUs (or with -d DEVICE) every shard runs on DEVICE
# (lavapipe in CI), N at a time. Leave --device and --out out of the sweep options: each shard's
# device is the GPU CTest gives it, its output OUT/shard-K. OUT/CTestTestfile.cmake stays behind,
# so `ctest --test-dir OUT --resource-spec-file build/gpu-resources.json -j N` runs it again.
# The same shards as a Slurm array job: see README.md ("Sweeps over several GPUs").
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
self="$here/scripts/sweep-shards.sh"

usage() { sed -n '2,17p' "$self" | sed 's/^# \{0,1\}//' >&2; exit 2; }

# Inner mode, run by each CTest test: one shard on the GPU CTest allocated (or DEVICE).
if [[ ${1:-} == --run-shard ]]; then
  shard=$2 out=$3 device=$4 fgbench=$5
  shift 5
  [[ ${1:-} == -- ]] && shift
  allocation="${CTEST_RESOURCE_GROUP_0_GPUS:-}"
  if [[ -n $allocation ]]; then
    device="${allocation#id:}"
    device="${device%%,*}"
  fi
  scene=$1
  shift
  exec "$fgbench" sweep "$scene" "$@" --device "$device" --shard "$shard" --out "$out" --quiet
fi

shards="" out="" device="" fgbench="$here/build/fgbench"
while [[ $# -gt 0 && $1 != -- ]]; do
  case "$1" in
    -n) shards=$2; shift 2 ;;
    -o) out=$2; shift 2 ;;
    -d) device=$2; shift 2 ;;
    -b) fgbench=$2; shift 2 ;;
    -h | --help) usage ;;
    *) echo "sweep-shards: unknown option '$1' (expected -n, -o, -d, -b, then -- SCENE ...)" >&2; exit 2 ;;
  esac
done
[[ ${1:-} == -- ]] || usage
shift
[[ $# -ge 1 ]] || { echo "sweep-shards: no scene given after --" >&2; exit 2; }
for arg in "$@"; do
  case "$arg" in
    --device | --device=* | --out | --out=* | --shard | --shard=*)
      echo "sweep-shards: $arg is set per shard; leave it out of the sweep options" >&2
      exit 2
      ;;
  esac
done
[[ -x $fgbench ]] || { echo "sweep-shards: $fgbench not found; build first (scripts/setup.sh) or give -b" >&2; exit 2; }

spec=""
if [[ -z $device ]]; then
  spec="$here/build/gpu-resources.json"
  mkdir -p "$(dirname "$spec")"
  [[ -f $spec ]] || FGBENCH="$fgbench" "$here/scripts/gpu-resources.sh" "$spec" >/dev/null
  gpus=$(grep -o '"id"' "$spec" | wc -l)
  if [[ $gpus -eq 0 ]]; then
    echo "sweep-shards: no GPU in $spec; running the shards on lavapipe" >&2
    spec="" device=lavapipe
  fi
  [[ -n $shards ]] || shards=$gpus
fi
[[ -n $shards ]] || shards=2
[[ $shards =~ ^[1-9][0-9]*$ ]] || { echo "sweep-shards: -n $shards: expected a positive count" >&2; exit 2; }
[[ -n $out ]] || out="out/$(basename "${1%.json}")-shards"
mkdir -p "$out"
out="$(cd "$out" && pwd)"

quote() { printf '[==[%s]==] ' "$@"; }
{
  echo "# Written by scripts/sweep-shards.sh: $shards shard(s) of a sweep, then the merge."
  dirs=""
  for ((k = 1; k <= shards; ++k)); do
    echo "add_test(shard-$k $(quote "$self" --run-shard "$k/$shards" "$out/shard-$k" "${device:-auto}" "$fgbench" -- "$@"))"
    echo "set_tests_properties(shard-$k PROPERTIES RESOURCE_GROUPS gpus:1 FIXTURES_SETUP shards TIMEOUT 86400" \
      "WORKING_DIRECTORY $(quote "$PWD"))"
    dirs="$dirs $(quote "$out/shard-$k")"
  done
  echo "add_test(merge $(quote "$fgbench" sweep-merge)$dirs $(quote --out "$out/merged"))"
  echo "set_tests_properties(merge PROPERTIES FIXTURES_REQUIRED shards)"
} >"$out/CTestTestfile.cmake"

echo "sweep-shards: $shards shard(s) into $out (ctest --test-dir $out${spec:+ --resource-spec-file $spec} -j $shards)" >&2
ctest --test-dir "$out" --output-on-failure -j "$shards" ${spec:+--resource-spec-file "$spec"}
echo "sweep-shards: merged sweep in $out/merged (sweep.html, sweep.json, sweep.csv, sweep.md)" >&2
