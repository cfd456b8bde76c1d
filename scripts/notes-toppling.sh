#!/usr/bin/env bash
# The measurements of docs/notes/explicit-step.md, "Toppling: the Goodman–Bray slope":
# bench/toppling_probe on the slope of tests/contact/engine/toppling_test.cpp
# (goodman_bray.hpp, goodman_bray_dda.hpp), largest block displacement [m] at the times
# given, friction angle phi_LE + dphi:
#  1. the limit-equilibrium analysis: phi_LE, the forces block by block at 38.15 deg, and
#     the analysis before its correction (goodman_bray.hpp of commit 9810239^, compiled alone);
#  2. the explicit step and the implicit step (Shi's stick rule, the test's; and
#     stick_keeps_force) at 5 ms steps, around phi_LE;
#  3. the explicit step with each of its controls and the model's stiffnesses changed;
#  4. the implicit step at 5, 2, 1 and 0.5 ms, each stick rule.
# Prints the measurements; about 25 min on 2 loaded cores (the explicit runs).
# Usage: scripts/notes-toppling.sh   (uses $RHEODDA_BUILD_DIR or build/)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # strict mode; root, build, work (removed at exit)
cmake --build "$build" --target toppling_probe -j2 >/dev/null
P="$build/bench/toppling_probe"

echo "== 1. limit equilibrium"
"$P" le 38.15
git -C "$root" show 9810239^:tests/contact/engine/goodman_bray.hpp >"$work/goodman_bray.hpp"
cat >"$work/before.cpp" <<'CPP'
#include <cstdio>
#include "goodman_bray.hpp"
int main() {
  const rheodda::testing::goodman_bray::Slope s;
  std::printf("before the correction (9810239^): phi_LE = %.4f deg\n",
              rheodda::testing::goodman_bray::critical_friction_angle(s));
}
CPP
g++ -std=c++20 -O2 -I"$work" "$work/before.cpp" -o "$work/before" && "$work/before"

echo "== 2. both steps at 5 ms around phi_LE"
"$P" dda --integrator explicit --dphi -0.5 -0.1 0 0.1 0.5 --times 6 10 20
"$P" dda --integrator implicit --dphi -0.5 -0.1 0 0.1 0.5 1 2 5 --times 6 10 20 40
"$P" dda --integrator implicit --stick-keeps-force --dphi -0.5 -0.1 0 0.05 0.1 0.5 1 2 5 --times 6 10 20 40

echo "== 3. the explicit step's controls and the model's stiffnesses"
for args in "--safety 0.4" "--dt 0.001" "--damping 0.8" "--young 1e11" "--penalty 10" "--penalty 200"; do
  # shellcheck disable=SC2086
  "$P" dda --integrator explicit $args --dphi 0 0.1 0.5 --times 6 10
done
"$P" dda --integrator explicit --damping 0 --dphi 0.5 2 5 --times 6 10

echo "== 4. the implicit step's step"
for dt in 0.002 0.001 0.0005; do
  "$P" dda --integrator implicit --dt "$dt" --dphi 0.5 1 2 5 --times 6 10 20
  "$P" dda --integrator implicit --stick-keeps-force --dt "$dt" --dphi 0.5 1 2 5 --times 6 10 20
done
