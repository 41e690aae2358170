#!/usr/bin/env bash
# The views the open issues' GPU targets are judged on (issues 25 and 26), each as one
# bench/ab-frames.sh run over the same binaries, so old and new alternate in one session:
#   default    the atrium's still view (25: frame <= 0.80 ms)
#   far        camera.distance=64, camera.far=inf (25: <= 0.25 ms)
#   scale8     atrium.scale=8 (25: <= 1.15x default)
#   occlusion  render.occlusion=1 on the still view (26: <= default + 0.03 ms)
#   city-on    scenes/city-walk.json along its path, render.occlusion=1 (26: off / on >= 2x)
#   city-off   the same with render.occlusion=0
# All on render.path=visbuffer, at the issues' 1920x1080 unless -s says otherwise.
#
#   bench/ab-views.sh [-r ROUNDS] [-s WxH] [-v VIEW,...] BINARY... [-- EXTRA-RUN-ARGS...]
#   bench/ab-views.sh -r 3 old/fgbench-gpu build/fgbench-gpu -- --device gpu
#   bench/ab-views.sh -r 1 -s 320x180 -v default,far build/fgbench          (a lavapipe smoke run)
#
# Each view prints ab-frames.sh's per-round lines and its medians over rounds; pass --device gpu
# (after --) on a GPU machine. Bound it with `timeout` there: a call has a time limit.
set -euo pipefail
rounds=3
size=1920x1080
views=default,far,scale8,occlusion,city-on,city-off
while [[ ${1:-} == -r || ${1:-} == -s || ${1:-} == -v ]]; do
  [[ $# -ge 2 ]] || { echo "$0: $1 needs a value" >&2; exit 2; }
  case $1 in
    -r) rounds=$2 ;;
    -s) size=$2 ;;
    -v) views=$2 ;;
  esac
  shift 2
done
[[ $size =~ ^([0-9]+)x([0-9]+)$ ]] || { echo "$0: -s $size: expected WIDTHxHEIGHT, e.g. 1920x1080" >&2; exit 2; }
width=${BASH_REMATCH[1]}
height=${BASH_REMATCH[2]}
binaries=()
while [[ $# -gt 0 && $1 != -- ]]; do binaries+=("$1"); shift; done
[[ ${#binaries[@]} -gt 0 ]] || { echo "usage: $0 [-r ROUNDS] [-s WxH] [-v VIEW,...] BINARY... [-- EXTRA-RUN-ARGS...]" >&2; exit 2; }
[[ ${1:-} == -- ]] && shift
extra=("$@")

here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
common=(--width "$width" --height "$height" --frames 64 --set render.path=visbuffer --no-debug-views --no-isolate)
IFS=, read -r -a chosen <<< "$views"
for view in "${chosen[@]}"; do
  case $view in
    default) args=("$root/scenes/atrium.json") ;;
    far) args=("$root/scenes/atrium.json" --set camera.distance=64 --set camera.far=inf) ;;
    scale8) args=("$root/scenes/atrium.json" --set atrium.scale=8) ;;
    occlusion) args=("$root/scenes/atrium.json" --set render.occlusion=1) ;;
    city-on) args=("$root/scenes/city-walk.json" --set render.occlusion=1) ;;
    city-off) args=("$root/scenes/city-walk.json" --set render.occlusion=0) ;;
    *) echo "$0: -v $view: unknown view (default, far, scale8, occlusion, city-on, city-off)" >&2; exit 2 ;;
  esac
  echo "== $view"
  "$here/ab-frames.sh" -r "$rounds" "${binaries[@]}" -- "${args[@]}" "${common[@]}" "${extra[@]}"
done
