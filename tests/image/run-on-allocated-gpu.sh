#!/usr/bin/env bash
# Runs `fgbench run` on the GPU CTest allocated to this test (RESOURCE_GROUPS "gpus:1"):
# CTEST_RESOURCE_GROUP_0_GPUS is "id:<device index>,slots:1". Usage: $0 FGBENCH SCENE [run options]
set -euo pipefail
fgbench="$1"; shift
scene="$1"; shift
allocation="${CTEST_RESOURCE_GROUP_0_GPUS:-}"
if [ -z "$allocation" ]; then
  echo "run-on-allocated-gpu: no GPU allocated; run ctest with --resource-spec-file (scripts/gpu-resources.sh)" >&2
  exit 2
fi
device="${allocation#id:}"
device="${device%%,*}"
exec "$fgbench" run "$scene" --device "$device" "$@"
