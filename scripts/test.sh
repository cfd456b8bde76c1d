#!/usr/bin/env bash
# The test command: installs what is missing, builds, and runs every test through ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
build="${RHEODDA_BUILD_DIR:-$root/build}"
cd "$build"
ctest --output-on-failure -j "$(nproc)"
# The scene-file fuzz test again under AddressSanitizer and UBSan, built alone in its own tree.
asan="${RHEODDA_ASAN_BUILD_DIR:-$root/build-asan}"
cmake -S "$root" -B "$asan" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRHEODDA_SANITIZE=ON \
  -DRHEODDA_BUILD_BENCH=OFF >/dev/null
cmake --build "$asan" -j "$(nproc)" --target scene_fuzz_test
"$asan/tests/apps/scene_fuzz_test" --report_level=short
