#!/usr/bin/env bash
# fgbench set-up. Idempotent: a second run with nothing changed only re-checks packages (no network)
# and lets the build system find nothing to do.
#   scripts/setup.sh           installs the Debian packages fgbench needs (when missing) and builds
#                              what running needs: build/fgbench (Release) and what it loads.
#   scripts/setup.sh --tests   also what the test suite needs: the test packages (chromium for the
#                              report's browser test), every target of build/ (tests, benchmarks,
#                              fgbench-gpu) and build-asan/ (the pure libraries' unit tests under
#                              AddressSanitizer + UBSan; FGBENCH_SKIP_ASAN=1 skips it).
#   scripts/setup.sh --backports-entry   prints the backports entry it would add (see below), only.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"

tests=0
print_backports=0
for arg in "$@"; do
  case "$arg" in
    --tests) tests=1 ;;
    --backports-entry) print_backports=1 ;;
    -h | --help) sed -n '2,10p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "setup: unknown option '$arg' (expected --tests or --backports-entry)" >&2; exit 2 ;;
  esac
done

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
# Only the test suite needs these: headless Chromium renders report.html in the browser test.
test_packages=(chromium)
[ "$tests" = 1 ] && packages+=("${test_packages[@]}")

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }

# Mesa from backports gives lavapipe with Vulkan 1.4 (descriptor indexing, mesh shaders).
apt_etc="${FGBENCH_APT_ETC:-/etc/apt}"  # another root only for testing the derivation below
codename="${FGBENCH_DEBIAN_CODENAME:-$(. /etc/os-release 2>/dev/null && echo "${VERSION_CODENAME:-bookworm}" || echo bookworm)}"
backports="$codename-backports"
backports_list="$apt_etc/sources.list.d/fgbench-backports.list"

want_backports_mesa() {
  local v
  v=$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true)
  [ -z "$v" ] || dpkg --compare-versions "$v" lt 24
}

# The machine's enabled Debian entries, one per line as "SUITE URI [OPTIONS]", from one-line
# sources (sources.list, sources.list.d/*.list) and deb822 stanzas (sources.list.d/*.sources).
# Our own backports file is left out: it is derived from the others.
configured_sources() {
  local f
  for f in "$apt_etc/sources.list" "$apt_etc"/sources.list.d/*.list; do
    [ -f "$f" ] && [ "$f" != "$backports_list" ] || continue
    awk '$1 == "deb" {
           opts = ""; i = 2
           if ($2 ~ /^\[/) { while (i <= NF && $i !~ /\]$/) { opts = opts " " $i; i++ } opts = opts " " $i; i++ }
           gsub(/^ *\[ *| *\] *$/, "", opts)
           print $(i + 1), $i, opts
         }' "$f"
  done
  for f in "$apt_etc"/sources.list.d/*.sources; do
    [ -f "$f" ] || continue
    awk 'function flush(  n, m, u, s, us, ss) {
           if (types ~ /(^| )deb( |$)/ && enabled != "no") {
             n = split(uris, us, " "); m = split(suites, ss, " ")
             for (u = 1; u <= n; u++) for (s = 1; s <= m; s++) print ss[s], us[u], (key != "" ? "signed-by=" key : "")
           }
           types = uris = suites = key = enabled = ""
         }
         /^[ \t]*#/ { next }
         /^[ \t]*$/ { flush(); next }
         { field = tolower($1); sub(/^[^:]*:[ \t]*/, "") }
         field == "types:" { types = $0 } field == "uris:" { uris = $0 } field == "suites:" { suites = $0 }
         field == "signed-by:" { key = $0 } field == "enabled:" { enabled = tolower($0) }
         END { flush() }' "$f"
  done
}

# Writes the backports entry from the first configured source of the release itself (same mirror,
# proxy and key), unless the machine already lists backports. Prints one line if it cannot.
add_backports_entry() {
  local sources suite uri opts
  sources="$(configured_sources)"
  if awk -v want="$backports" '$1 == want { found = 1 } END { exit !found }' <<<"$sources"; then
    [ "$print_backports" = 0 ] || echo "(already configured: $(awk -v want="$backports" '$1 == want { print $2; exit }' <<<"$sources"))"
    return 0
  fi
  read -r suite uri opts < <(awk -v want="$codename" '$1 == want' <<<"$sources" | head -n 1) || true
  if [ -z "${uri:-}" ]; then
    echo "setup: no '$codename' entry in $apt_etc/sources.list{,.d}, nothing to derive $backports from: using stable mesa-vulkan-drivers" >&2
    return 1
  fi
  local entry="deb ${opts:+[$opts] }$uri $backports main"
  if [ "$print_backports" = 1 ]; then echo "$entry"; return 0; fi
  if [ "$(cat "$backports_list" 2>/dev/null)" != "$entry" ]; then
    echo "$entry" | as_root tee "$backports_list" >/dev/null
  fi
}

if [ "$print_backports" = 1 ]; then
  add_backports_entry || true
  exit 0
fi

if [ ${#missing[@]} -gt 0 ] || want_backports_mesa; then
  export DEBIAN_FRONTEND=noninteractive
  have_backports=0
  add_backports_entry && have_backports=1
  echo "setup: installing ${missing[*]:-(mesa from backports)}" >&2
  as_root apt-get update -qq || echo "setup: apt-get update had errors; continuing" >&2
  [ ${#missing[@]} -eq 0 ] || as_root apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  if [ "$have_backports" = 1 ]; then
    if as_root apt-get install -y -qq --no-install-recommends -t "$backports" mesa-vulkan-drivers >/dev/null 2>&1; then
      echo "setup: mesa-vulkan-drivers from $backports" >&2
    else
      echo "setup: $backports unreachable through the configured sources ($(cat "$backports_list" 2>/dev/null || echo "already listed")); using stable mesa-vulkan-drivers" >&2
    fi
  fi
fi

jobs="$(nproc)"
build_type="${FGBENCH_BUILD_TYPE:-Release}"
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE="$build_type"
elif [ "$tests" = 1 ]; then
  # Configure again (seconds): a build/ made by the plain set-up, before the test packages were
  # installed, has Chromium cached as not found, and only a configure run searches again.
  cmake -S . -B build >/dev/null
fi
if [ "$tests" = 0 ]; then
  # Running needs build/fgbench and what it builds with it (shaders, the model-import module).
  cmake --build build --parallel "$jobs" --target fgbench
  exit 0
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
