#!/usr/bin/env bash
# Builds (Release) and runs every benchmark in bench/; prints their figures.
# Usage: scripts/bench.sh            (build dir: $RHEODDA_BUILD_DIR or build/)
# Add a new benchmark to BENCHES below when you add it to bench/CMakeLists.txt.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RHEODDA_BUILD_DIR:-$root/build}"
BENCHES=(
  laws_bench
  contact_bench
  engine_bench
  fit_bench
  shear_creep_table1
  shear_creep_wall
  accuracy_bench
  stability_map
)
"$root/scripts/install-deps.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DRHEODDA_BUILD_BENCH=ON >/dev/null
cmake --build "$build" -j "$(nproc)" --target "${BENCHES[@]}" rheodda
# Run them all even if one fails; report the failures at the end.
failed=()
for b in "${BENCHES[@]}"; do
  echo "==== $b ===="
  "$build/bench/$b" || failed+=("$b")
  echo
done
# Scripts that benchmark whole commands (they build nothing themselves).
echo "==== bench/study-mpi.sh ===="
bash "$root/bench/study-mpi.sh" "$build" || failed+=("bench/study-mpi.sh")
echo
if ((${#failed[@]})); then
  echo "failed: ${failed[*]}" >&2
  exit 1
fi
