#!/usr/bin/env bash
# Plots the Burgers creep curves of the seed's four Table 1 parameter sets
# (constant shear stress tau from t = 0, 200 h) with `rheodda law curve` and
# gnuplot into docs/img/table1-burgers.png.
# Usage: scripts/plot-table1.sh   (uses $RHEODDA_BUILD_DIR or build/; builds rheodda if missing)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # strict mode; root, build, work (removed at exit)
rheodda="$build/apps/rheodda"
ensure_built rheodda

# tau [MPa], E1 [MPa/mm], E2 [MPa/mm], eta1 [MPa h/mm], eta2 [MPa h/mm]
rows=(
  "0.232 26.87 192.43 34807.72 2141.23"
  "0.424 40.13 249.33 101760.29 3236.41"
  "0.439 29.45 260.76 52869.39 3771.63"
  "0.512 33.65 305.53 23051.02 5736.91"
)
plot="plot"
for i in "${!rows[@]}"; do
  read -r tau e1 e2 eta1 eta2 <<<"${rows[$i]}"
  "$rheodda" law curve burgers --param E1="$e1" --param E2="$e2" --param eta1="$eta1" \
    --param eta2="$eta2" --force "0:$tau" --t-end 200 --dt 1 --scheme lagged >"$work/row$i.csv"
  plot+=" '$work/row$i.csv' every ::1 using 1:3 with lines lw 2 title 'tau = $tau MPa',"
done

gnuplot <<GP
set terminal pngcairo size 900,560 font 'Sans,11'
set output '$root/docs/img/table1-burgers.png'
set datafile separator ','
set title 'Burgers shear creep of the seed''s Table 1 parameter sets (rheodda law curve)'
set xlabel 'time t [h]'
set ylabel 'shear displacement d [mm]'
set key left top
set grid
${plot%,}
GP
echo "wrote $root/docs/img/table1-burgers.png"
