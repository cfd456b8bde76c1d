#!/usr/bin/env bash
# Plots the seed's two-block shear creep test run by the DDA engine (Burgers
# joints of Table 1, default scheme, dt = 2 h) against the closed form (the
# seed's eqs. 20-21) into docs/img/rheology-table1-dda.png.
# Usage: scripts/plot-shear-creep.sh   (uses $RHEODDA_BUILD_DIR or build/; builds the bench if missing)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # strict mode; root, build, work (removed at exit)
bench="$build/bench/shear_creep_table1"
ensure_built shear_creep_table1
"$bench" --csv "$work"
taus=(0.232 0.424 0.439 0.512)
plot="plot"
for i in 0 1 2 3; do
  plot+=" '$work/closed$i.csv' using 1:2 with lines lw 2 lc $((i + 1)) title 'tau = ${taus[$i]} MPa',"
  plot+=" '$work/row$i.csv' every 5 using 1:2 with points pt 7 ps 0.9 lc $((i + 1)) notitle,"
done
plot+=" NaN with lines lw 2 lc 'black' title 'closed form (eqs. 20-21)',"
plot+=" NaN with points pt 7 lc 'black' title 'DDA, dt = 2 h (every 5th step)',"
gnuplot <<GP
set terminal pngcairo size 900,560 font 'Sans,11'
set output '$root/docs/img/rheology-table1-dda.png'
set datafile separator ','
set title 'Two-block shear creep test in DDA (Burgers joints of the seed''s Table 1) vs closed form'
set xlabel 'time t [h]'
set ylabel 'joint shear displacement d [mm]'
set key right bottom
set yrange [0:0.024]
set grid
${plot%,}
GP
echo "wrote $root/docs/img/rheology-table1-dda.png"
