#!/usr/bin/env bash
# Regenerates the figures of docs/toppling-study.md (the seed's section 5):
#   bash scripts/toppling-study.sh            # after scripts/build.sh
# Runs examples/studies/toppling-phi.yaml and toppling-laws.yaml with `rheodda study`
# into out/toppling-study/, then draws with gnuplot and copies the pictures to
# docs/img/toppling-*.png. Environment: RHEODDA (the binary, default
# build/apps/rheodda), OUT (default out/toppling-study), JOBS (default 2).
set -euo pipefail
cd "$(dirname "$0")/.."
B=${RHEODDA:-build/apps/rheodda}
OUT=${OUT:-out/toppling-study}
JOBS=${JOBS:-2}
mkdir -p "$OUT" docs/img

"$B" study examples/studies/toppling-phi.yaml  -o "$OUT/phi"  -j "$JOBS" || true   # a failed case is reported in study.csv
"$B" study examples/studies/toppling-laws.yaml -o "$OUT/laws" -j "$JOBS" || true

# Figures 9-10 of the seed: displacement at 20 s (settled dynamically) against the base friction angle, no creep.
awk -F, 'NR > 1 && $2 == "completed" { sub(/^phi/, "", $1); print $1, $4, $6 }' "$OUT/phi/study.csv" > "$OUT/phi.dat"
# Figure 11: displacement histories of blocks 1 and 10 with Burgers creep, phi = 50 deg, 100 d.
awk -F, '/^#/ || $1 == "time" { next } { print $1, sqrt($6*$6 + $7*$7), sqrt($8*$8 + $9*$9) }' \
  "$OUT/laws/cases/burgers/history.csv" > "$OUT/creep.dat"

gnuplot <<GP
set terminal pngcairo size 900,560 noenhanced
set grid
set output 'docs/img/toppling-phi.png'
set title 'Goodman slope without creep, settled dynamically: displacement at 20 s against base friction angle'
set xlabel 'base friction angle phi [deg]'
set ylabel 'displacement [m]'
set logscale y
set key top right
plot '$OUT/phi.dat' using 1:2 with linespoints lw 2 pt 7 title 'block 1 (top centre)', \
     '' using 1:3 with linespoints lw 2 pt 5 title 'block 10 (top centre)'
unset logscale y
set output 'docs/img/toppling-creep-history.png'
set title 'Goodman slope, Burgers joints (Table 3), phi = 50 deg: displacement histories'
set xlabel 'time [d]'
set key bottom right
plot '$OUT/creep.dat' using 1:2 with lines lw 2 title 'block 1 (top centre)', \
     '' using 1:3 with lines lw 2 title 'block 10 (top centre)'
GP

# Figure 12: the deformed slope at several times (rheodda plot of the Burgers case).
rm -rf "$OUT/laws/cases/burgers/plots"
"$B" plot "$OUT/laws/cases/burgers" --times 0,5,50,100 --scale 1
i=0
for f in "$OUT"/laws/cases/burgers/plots/blocks_*.png; do
  cp "$f" "docs/img/toppling-blocks-$i.png"; i=$((i + 1))
done
# The four laws on the anti-toppling planes: block 10's displacement against time.
cp "$OUT/laws/study.png" docs/img/toppling-laws.png
ls docs/img/toppling-*.png
