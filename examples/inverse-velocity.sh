#!/usr/bin/env bash
# Inverse-velocity forecast of the failure time (Fukuzono 1985) on the run of
# examples/damage-creep-test.yaml (damage-burgers, docs/reference/laws.md).
#
# Sample run:
#   examples/inverse-velocity.sh [RHEODDA] [OUTDIR]
#     RHEODDA: the rheodda binary (default: build/apps/rheodda)
#     OUTDIR:  where the run goes (default: out/damage-creep)
# What it does: runs the example, takes the joint's creep velocity
# v = d(plane.shear_displacement)/dt from history.csv (finite differences over
# each output interval), fits a straight line to 1/v over 100-140 h and prints
# where it reaches zero - the forecast failure time - next to Kachanov's t_f of
# the law at the mean applied stress (149.9 h) and the time the first contact
# fails (its creep stops). Draws docs/img/damage-inverse-velocity.png
# with gnuplot.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="${1:-$root/build/apps/rheodda}"
out="${2:-$root/out/damage-creep}"
"$bin" run "$root/examples/damage-creep-test.yaml" -o "$out" >/dev/null
data="$out/inverse-velocity.dat"
# time [h], 1/v [h/mm] at the interval midpoints, up to the first failure: there
# the failed contact stops creeping and 1/v jumps up (more than 2x after 50 h).
awk -F, '/^#/ { next } !c { for (i = 1; i <= NF; i++) if ($i == "plane.shear_displacement") c = i; next }
  { t = $1; d = -$c
    if (n++) { iv = (d > d0) ? (t - t0) / (d - d0) : 1e300
               if (t > 50 && iv > 2 * last) exit
               printf "%.6f %.9g\n", 0.5 * (t + t0), iv; last = iv }
    t0 = t; d0 = d }' "$out/history.csv" >"$data"
# Least-squares line 1/v = a + b t over 100-140 h; its zero is the forecast.
forecast=$(awk '$1 >= 100 && $1 <= 140 { n++; sx += $1; sy += $2; sxx += $1 * $1; sxy += $1 * $2 }
  END { b = (n * sxy - sx * sy) / (n * sxx - sx * sx); a = (sy - b * sx) / n; printf "%.2f", -a / b }' "$data")
failed=$(awk '{ t = $1 } END { printf "%.2f", t }' "$data")
echo "inverse-velocity forecast from 100-140 h: failure at $forecast h (law: t_f = 149.9 h at tau = 0.232 MPa; the first contact fails by $failed h)"
gnuplot <<GP
set terminal pngcairo size 800,560
set output '$root/docs/img/damage-inverse-velocity.png'
set title 'Inverse velocity of the joint creep, damage-burgers (examples/damage-creep-test.yaml)'
set xlabel 'time [h]'
set ylabel '1 / creep velocity [h/mm]'
set xrange [0:160]
set yrange [0:*]
set key outside below
set arrow from $forecast, graph 0 to $forecast, graph 1 nohead dt 2 lc rgb 'gray'
f(x) = a + b * x
a = 1; b = -1
set fit quiet
set fit logfile '/dev/null'
fit [100:140] f(x) '$data' using 1:2 via a, b
plot '$data' using 1:2 with points pt 7 ps 0.5 title '1/v from history.csv', \
     [60:$forecast] f(x) with lines lw 2 title sprintf('line fitted over 100-140 h: zero at %.1f h', $forecast)
GP
echo "wrote $root/docs/img/damage-inverse-velocity.png"
