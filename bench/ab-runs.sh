#!/usr/bin/env bash
# Interleaved repetitions of two fgbench configurations, then `fgbench compare-runs` on them
# (issue 27): separate processes, alternating A B A B ..., so drift in load and clocks hits both
# alike and the comparison has runs, not frames, as its samples. Each run writes OUT/A/rN or
# OUT/B/rN (a normal `fgbench run --out`); the end compares OUT/A with OUT/B and exits as
# compare-runs does: 0 no slowdown (also "unknown: add runs"), 1 B is slower, 2 bad input.
#
#   bench/ab-runs.sh [-r ROUNDS] [-o OUT] [-A BINARY] [-B BINARY] [-a ARG]... [-b ARG]... [-c ARG]...
#                    -- RUN-ARGS...
#
# -A/-B: each side's binary (default build/fgbench); -a/-b: one more run argument for that side
# only (repeatable, kept whole: spaces are fine); RUN-ARGS: what both sides get; -c: one more
# compare-runs argument (repeatable: -c --json). Default: 5 rounds into out/ab.
#   bench/ab-runs.sh -r 5 -A old/fgbench -B build/fgbench -- scenes/atrium.json --width 320 --height 180
#   bench/ab-runs.sh -r 5 -b --set -b render.occlusion=1 -- scenes/atrium.json --set render.path=visbuffer
set -euo pipefail
rounds=5
out=out/ab
a=build/fgbench
b=build/fgbench
a_args=()
b_args=()
compare_args=()
usage() {
  sed -n '8,9p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
}
while [[ $# -gt 0 && $1 != -- ]]; do
  [[ $# -ge 2 ]] || usage
  case $1 in
    -r) rounds=$2 ;;
    -o) out=$2 ;;
    -A) a=$2 ;;
    -B) b=$2 ;;
    -a) a_args+=("$2") ;;
    -b) b_args+=("$2") ;;
    -c) compare_args+=("$2") ;;
    *) echo "$0: unknown option $1" >&2; usage ;;
  esac
  shift 2
done
[[ ${1:-} == -- ]] || usage
shift
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "$0: -r $rounds: expected a positive integer" >&2; exit 2; }
for bin in "$a" "$b"; do [[ -x $bin ]] || { echo "$0: $bin: not an executable" >&2; exit 2; }; done

rm -rf "$out/A" "$out/B"
mkdir -p "$out/A" "$out/B"
for ((r = 1; r <= rounds; ++r)); do
  echo "round $r/$rounds: A" >&2
  "$a" run "$@" ${a_args[@]+"${a_args[@]}"} --out "$out/A/r$r" --quiet > /dev/null
  echo "round $r/$rounds: B" >&2
  "$b" run "$@" ${b_args[@]+"${b_args[@]}"} --out "$out/B/r$r" --quiet > /dev/null
done
exec "$b" compare-runs "$out/A" "$out/B" ${compare_args[@]+"${compare_args[@]}"}
