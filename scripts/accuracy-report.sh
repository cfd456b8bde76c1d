#!/usr/bin/env bash
# Regenerates the speed-accuracy report: runs bench/accuracy_bench (also its
# --toppling comparison on examples/goodman-toppling-creep.yaml) and
# bench/stability_map (the law-level map, and with --dda its DDA spot-check),
# puts their tables into docs/notes/step-controls.md (between the "generated"
# markers) and draws docs/img/accuracy-error-vs-time.png and
# docs/img/stability-map.png and docs/img/toppling-error-vs-time.png with gnuplot.
# Usage: scripts/accuracy-report.sh   (uses $RHEODDA_BUILD_DIR or build/; builds the benches if missing)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # strict mode; root, build, work (removed at exit)
ensure_built accuracy_bench stability_map
"$build/bench/accuracy_bench" --csv "$work/accuracy.csv" >"$work/accuracy.md"
"$build/bench/stability_map" --csv "$work/stability.csv" >"$work/stability.md"
"$build/bench/stability_map" --dda >"$work/stability-dda.md"
"$build/bench/stability_map" --power >"$work/stability-power.md"
"$build/bench/accuracy_bench" --toppling "$root/examples/goodman-toppling-creep.yaml" 100 |
  sed "s|$root/||" >"$work/toppling.md"

# Tables between the <!-- NAME:begin/end --> markers of docs/notes/step-controls.md.
splice() { "$root/scripts/splice-doc.sh" "$root/docs/notes/step-controls.md" "$1" "$2"; }
splice accuracy-table "$work/accuracy.md"
splice stability-table "$work/stability.md"
splice stability-dda "$work/stability-dda.md"
splice stability-power "$work/stability-power.md"
splice toppling-table "$work/toppling.md"

# Error vs wall time, one panel per case, one line per scheme (fixed steps).
for c in creep staged relaxation; do
  for s in lagged implicit exponential-linear default; do
    awk -F, -v c="$c" -v s="$s" 'NR > 1 && $1 == c && $2 == s && $7 != "inf" { print $6, $7, $3 }' \
      "$work/accuracy.csv" | sort -g >"$work/$c-$s.dat"
  done
done
awk -F, 'NR > 1 && $1 == "adaptive" && $7 != "inf" { print $6, $7, $4 }' "$work/accuracy.csv" |
  sort -g >"$work/adaptive.dat"
panel() {
  local c="$1" extra="${2:-}" plot="plot"
  for s in lagged implicit exponential-linear default; do
    [[ -s "$work/$c-$s.dat" ]] &&
      plot+=" '$work/$c-$s.dat' using 1:2 with linespoints lw 2 pt 7 title '$s',"
  done
  echo "${plot%,}$extra"
}
gnuplot <<GP
set terminal pngcairo size 1500,520 font 'Sans,11'
set output '$root/docs/img/accuracy-error-vs-time.png'
set multiplot layout 1,3 title 'Error against the closed form vs wall time (Table 1 Burgers joints, 4 rows, 0-200 h; dt from 0.002 to 20 h)'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set xlabel 'wall time, 4 rows [s]'
set ylabel 'largest error / peak [-]'
set key bottom left
set title 'two-block creep test, DDA (constant load)'
$(panel creep)
set title 'staged load (tau; ramp to 2 tau at 80-85.5 h; to 0 at 140-143.3 h), DDA'
set key top right
$(panel staged ", '$work/adaptive.dat' using 1:2 with linespoints lw 2 pt 5 dt 2 lc 'black' title 'adaptive, creep tolerance 1e-9..1e-5 mm'")
set key bottom left
set title 'relaxation, law in series with E1'
$(panel relaxation)
unset multiplot
GP
echo "wrote $root/docs/img/accuracy-error-vs-time.png"

# Stability map: growth factor per scheme over (dt E2/eta2, k/E2).
gnuplot <<GP
set terminal pngcairo size 1500,480 font 'Sans,11'
set output '$root/docs/img/stability-map.png'
set datafile separator ','
set multiplot layout 1,3 title 'Stability map: largest |force| after 200 steps / first force (relaxation of a spring k in series with a Kelvin element E2, eta2)'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set xlabel 'dt E2 / eta2 [-]'
set ylabel 'k / E2 [-]'
set cbrange [0:2]
set cblabel 'growth: green <= 1 (stable), red > 1'
set palette defined (0 '#4caf50', 1 '#4caf50', 1.0001 '#d32f2f', 2 '#d32f2f')
set key off
do for [s in "lagged implicit exponential-linear"] {
  set title s
  plot '$work/stability.csv' using (strcol(1) eq s ? \$2 : NaN):3:(\$4 > 2 ? 2 : \$4) with points pt 5 ps 2.2 palette, \
       (s eq "lagged" ? 2.0 / (1.0 - exp(-x)) - 1.0 : NaN) with lines lw 2 lc 'black'
}
unset multiplot
GP
echo "wrote $root/docs/img/stability-map.png"

# Toppling comparison: error vs wall time, fixed steps (both schemes) and
# adaptive stepping (creep_tolerance) and step doubling (step_tolerance), from
# the generated table's rows.
awk -F'|' '/^\| fixed dt = / && !/exponential/ { print $7, $6 }' "$work/toppling.md" >"$work/top-fixed.dat"
awk -F'|' '/^\| fixed dt = / && /exponential/ { print $7, $6 }' "$work/toppling.md" >"$work/top-el.dat"
awk -F'|' '/^\| [0-9.e-]+ \| no \|/ { print $8, $7, $2 }' "$work/toppling.md" >"$work/top-adaptive.dat"
awk -F'|' '/^\| [0-9.e-]+ \| on \|/ { print $9, $8, $2 }' "$work/toppling.md" >"$work/top-doubling.dat"
awk -F'|' '/^\| [0-9.e-]+ \| off \|/ { print $9, $8, $2 }' "$work/toppling.md" >"$work/top-doubling-off.dat"
gnuplot <<GP
set terminal pngcairo size 800,560 font 'Sans,11'
set output '$root/docs/img/toppling-error-vs-time.png'
set title 'Toppling slope (base 70 deg, planes 85 deg), creep 0-100 d: error vs wall time'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set xlabel 'wall time [ms]'
set ylabel 'largest |u - u_{ref}| / u_{ref} at 100 d [-]'
set key bottom left
plot '$work/top-fixed.dat' using 1:2 with linespoints lw 2 pt 7 title 'fixed dt, 8 d to 1/256 d (implicit)', \
     '$work/top-el.dat' using 1:2 with points pt 9 ps 1.5 title 'fixed dt, exponential-linear', \
     '$work/top-adaptive.dat' using 1:2 with linespoints lw 2 pt 5 dt 2 lc 'black' title 'adaptive, creep tolerance 1e-3..1e-8 m', \
     '$work/top-doubling.dat' using 1:2 with linespoints lw 2 pt 13 ps 1.4 lc 'red' title 'step doubling, extrapolated, step tolerance 1e-2..1e-7 m', \
     '$work/top-doubling-off.dat' using 1:2 with linespoints lw 1 pt 12 ps 1.2 dt 3 lc 'red' title 'step doubling, not extrapolated'
GP
echo "wrote $root/docs/img/toppling-error-vs-time.png"
