#!/usr/bin/env bash
# The measurements of docs/notes/bolts.md: the bolt tests of tests/core
# (bolt_swing_test.cpp, bolt_test.cpp) run with their messages, on this tree and,
# with the same test files, on an earlier commit (default: the parent of the
# commit that made the bolts' force act along the end-of-step axis), built in a
# temporary worktree; and examples/rockmass/tunnel-stages.yaml run by both
# (steps, cuts, the crown's and walls' displacement at 100 d). Prints both;
# about 15 min on 2 cores.
# Usage: scripts/notes-bolts.sh [commit]   (uses $RHEODDA_BUILD_DIR or build/)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RHEODDA_BUILD_DIR:-$root/build}"
before="${1:-$(git -C "$root" log --format=%H -1 --grep='end-of-step axis' -- core/src/bolt_step.cpp)^}"
suites='bolts,bolt_swing'
run() {  # $1: build directory
  cmake --build "$1" --target core_test rheodda -j2 >/dev/null
  "$1/tests/core/core_test" --run_test="$suites" --log_level=message 2>&1 |
    sed -n 's/\x1b\[[0-9;]*m//g; /: .*steps\|pendulum\|relaxation\|_tolerance/p' | grep -v 'error:\|^ ' || true
  local out
  out="$(mktemp -d)"
  "$1/apps/rheodda" run "$root/examples/rockmass/tunnel-stages.yaml" -o "$out" 2>&1 | grep -o 'completed.*cuts of dt)'
  /usr/bin/python3 - "$out/history.csv" <<'PY'
import csv, math, sys
rows = [r for r in csv.reader(l for l in open(sys.argv[1]) if not l.startswith("#"))]
v = dict(zip(rows[0], rows[-1]))
print("  at", v["time"], "d:", ", ".join(f"{p} {math.hypot(float(v[p + '.u']), float(v[p + '.v'])):.6g} m"
                                        for p in ("crown", "left_wall", "right_wall")))
PY
  rm -rf "$out"
}
echo "== this tree ($(git -C "$root" rev-parse --short HEAD))"
run "$build"
work="$(mktemp -d)"
trap 'git -C "$root" worktree remove --force "$work/src" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT
git -C "$root" worktree add --detach "$work/src" "$before" >/dev/null 2>&1
cp "$root/tests/core/bolt_swing_test.cpp" "$root/tests/core/bolt_test.cpp" "$work/src/tests/core/"
grep -q bolt_swing_test.cpp "$work/src/tests/core/CMakeLists.txt" ||
  sed -i 's|    bolt_test.cpp|    bolt_test.cpp\n    bolt_swing_test.cpp|' "$work/src/tests/core/CMakeLists.txt"
cmake -S "$work/src" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
echo "== before ($(git -C "$root" rev-parse --short "$before"), the same tests)"
run "$work/build"
