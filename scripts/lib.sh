# Sourced by the report scripts (scripts/*.sh): strict mode, the source root, the
# build to use and a work folder removed when the script exits.
#   root   the source tree
#   build  RHEODDA_BUILD_DIR, default build/
#   work   a fresh temporary folder
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RHEODDA_BUILD_DIR:-$root/build}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# ensure_built TARGET...: configures and builds the CMake targets (Release) in $build
# unless each is there already (bench/TARGET or apps/TARGET).
ensure_built() {
  local t missing=()
  for t in "$@"; do
    [[ -x "$build/bench/$t" || -x "$build/apps/$t" ]] || missing+=("$t")
  done
  ((${#missing[@]} == 0)) && return 0
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$build" -j "$(nproc)" --target "${missing[@]}"
}
