#!/usr/bin/env bash
# Rock masses at scale (docs/guide/rockmass.md, "Performance"): two persistent joint sets at right
# angles cut a 100 x 100 m square at spacings 1, 0.5, 0.33 and 0.25 m (10 000 to 160 000
# blocks). For each: the estimate made before cutting (rockmass::estimate_cut: crossings and
# blocks, as `rheodda check` prints them), the blocks cut, the wall time and peak resident
# memory of `rheodda check` (/usr/bin/time), its memory per crossing above the program's
# 20 MB (the figure behind estimate_cut's 2.1 kB), and the wall times of `rheodda generate`
# and of `rheodda check` on the explicit scene it writes.
# Usage: scripts/rockmass-scaling.sh [--write]   (build: $RHEODDA_BUILD_DIR or build/;
#        --write splices the table into docs/guide/rockmass.md between <!-- rockmass-scaling:begin/end -->)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="${RHEODDA_BUILD_DIR:-$root/build}/apps/rheodda"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
table="$work/table.md"
{
  echo "| spacing [m] | estimated crossings | estimated blocks | blocks | check [s] | check peak [MB] | kB a crossing | generate [s] | check of the explicit scene [s] | its peak [MB] |"
  echo "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
} >"$table"
timed() {  # timed OUT CMD...: wall seconds and peak kB into OUT
  /usr/bin/time -f '%e %M' -o "$1" "${@:2}" >"$work/log" 2>&1
}
for s in 1.0 0.5 0.33 0.25; do
  cat >"$work/s.yaml" <<YAML
title: two persistent sets at spacing $s m
units: {length: m, force: N, time: d}
analysis: {type: static, duration: 1, dt: 0.5, gravity: [0, -7.32313e10]}
materials: {rock: {density: 3.41384e-7, young_modulus: 1.0e10, poisson_ratio: 0.25}}
joint_sets: {bedding: {friction_angle: 35}, joints: {friction_angle: 35}, frame: {friction_angle: 40}}
rock_mass:
  region: [[0, 0], [100, 0], [100, 100], [0, 100]]
  boundary_joint_set: frame
  seed: 3
  joint_sets:
    - {joint_set: bedding, dip: 20, dip_direction: left, spacing: $s}
    - {joint_set: joints, dip: 70, spacing: $s}
YAML
  timed "$work/check" "$bin" check "$work/s.yaml"
  est=$(grep -o 'estimated before cutting: [^,]*, up to [^ ]* blocks' "$work/log")
  crossings=$(awk '{print $4}' <<<"$est")
  pieces=$(awk '{print $9}' <<<"$est")
  blocks=$(grep -o "rock mass 'rock': [0-9]* blocks" "$work/log" | awk '{print $4}')
  timed "$work/generate" "$bin" generate "$work/s.yaml" -o "$work/explicit.yaml"
  timed "$work/explicit" "$bin" check "$work/explicit.yaml"
  read -r check_s check_kb <"$work/check"
  read -r generate_s _ <"$work/generate"
  read -r explicit_s explicit_kb <"$work/explicit"
  awk -v s="$s" -v c="$crossings" -v p="$pieces" -v b="$blocks" -v cs="$check_s" -v ck="$check_kb" \
      -v gs="$generate_s" -v es="$explicit_s" -v ek="$explicit_kb" 'BEGIN {
    printf "| %s | %.3g | %.3g | %s | %.2f | %.0f | %.2f | %.2f | %.2f | %.0f |\n",
           s, c, p, b, cs, ck * 1024 / 1e6, (ck * 1024 - 20e6) / c / 1e3, gs, es, ek * 1024 / 1e6 }' >>"$table"
done
if [ "${1:-}" = "--write" ]; then
  bash "$root/scripts/splice-doc.sh" "$root/docs/guide/rockmass.md" rockmass-scaling "$table"
fi
cat "$table"
