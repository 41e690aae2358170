#!/usr/bin/env bash
# fgbench set-up: installs the Debian packages fgbench needs (when missing), then configures and
# builds Release into build/. Idempotent: a second run with nothing changed only re-checks packages
# (no network) and lets the build system find nothing to do.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"

packages=(
  build-essential cmake ninja-build pkg-config git
  libvulkan-dev libvulkan-volk-dev vulkan-validationlayers vulkan-tools spirv-tools glslang-tools
  mesa-vulkan-drivers
  libglm-dev libassimp-dev assimp-testmodels
  libopenimageio-dev openimageio-tools libopenexr-dev
  libbenchmark-dev libgtest-dev libgmock-dev
  libspdlog-dev libfmt-dev libcli11-dev nlohmann-json3-dev
  graphviz libmeshoptimizer-dev libxxhash-dev libzstd-dev
  # Optional, run time only: the fast EXR reader dlopens libdeflate to inflate ZIP blocks 3-10x
  # faster than zlib; without it, EXRs are read through OpenEXR (slower, same pixels).
  libdeflate0
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }

# Mesa from bookworm-backports gives lavapipe with Vulkan 1.4 (descriptor indexing, mesh shaders).
backports_list=/etc/apt/sources.list.d/fgbench-backports.list
want_backports_mesa() {
  local v
  v=$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true)
  [ -z "$v" ] || dpkg --compare-versions "$v" lt 24
}

if [ ${#missing[@]} -gt 0 ] || want_backports_mesa; then
  export DEBIAN_FRONTEND=noninteractive
  if [ ! -f "$backports_list" ]; then
    echo "deb http://deb.debian.org/debian bookworm-backports main" | as_root tee "$backports_list" >/dev/null
  fi
  echo "setup: installing ${missing[*]:-(mesa from backports)}" >&2
  as_root apt-get update -qq || echo "setup: apt-get update had errors; continuing" >&2
  as_root apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  if as_root apt-get install -y -qq --no-install-recommends -t bookworm-backports \
      mesa-vulkan-drivers >/dev/null 2>&1; then
    echo "setup: mesa-vulkan-drivers from bookworm-backports" >&2
  else
    echo "setup: bookworm-backports unreachable; using stable mesa-vulkan-drivers" >&2
  fi
fi

jobs="$(nproc)"
build_type="${FGBENCH_BUILD_TYPE:-Release}"
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE="$build_type"
fi
cmake --build build --parallel "$jobs"

# The pure libraries' unit tests again under AddressSanitizer + UBSan; the main build's CTest runs
# them as the test "sanitizers.unit_tests". Skip with FGBENCH_SKIP_ASAN=1.
if [ "${FGBENCH_SKIP_ASAN:-0}" != 1 ]; then
  if [ ! -f build-asan/CMakeCache.txt ]; then
    cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFGBENCH_SANITIZE=ON \
      -DFGBENCH_UNIT_ONLY=ON >/dev/null
  fi
  cmake --build build-asan --parallel "$jobs"
fi
