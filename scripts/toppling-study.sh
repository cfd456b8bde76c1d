#!/usr/bin/env bash
# Regenerates the figures of docs/guide/toppling-study.md (the seed's section 5):
#   bash scripts/toppling-study.sh            # after scripts/build.sh
# Runs examples/studies/toppling-phi.yaml and toppling-laws.yaml with `rheodda study`
# into out/toppling-study/, then draws with gnuplot and copies the pictures to
# docs/img/toppling-*.png, and splices the tables of docs/guide/toppling-study.md
# (toppling-phi, toppling-creep-history, toppling-laws markers). Environment: RHEODDA (the binary, default
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

# The joints' shear displacement with Burgers creep (the seed discusses it, section 5):
# per joint set, the mean over its shear-carrying contacts of |shear displacement|
# (history.csv's JOINTSET.shear_displacement_magnitude, docs/reference/outputs.md).
awk -F, '/^#/ { next }
  $1 == "time" { for (i = 1; i <= NF; ++i) col[$i] = i; next }
  { print $1, $col["base.shear_displacement_magnitude"], $col["anti_toppling.shear_displacement_magnitude"] }' \
  "$OUT/laws/cases/burgers/history.csv" > "$OUT/joint-shear.dat"
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
set output 'docs/img/toppling-joint-shear.png'
set title 'Goodman slope, Burgers joints, phi = 50 deg: mean |shear displacement| of the joints'
set xlabel 'time [d]'
set ylabel 'mean |shear displacement| over the joint set [m]'
set key bottom right
plot '$OUT/joint-shear.dat' using 1:2 with lines lw 2 title 'base (slip surface)', \
     '' using 1:3 with lines lw 2 title 'anti-toppling planes'
GP

# Figure 12: the deformed slope at several times (rheodda plot of the Burgers case).
rm -rf "$OUT/laws/cases/burgers/plots"
"$B" plot "$OUT/laws/cases/burgers" --times 0,5,50,100 --scale 1
i=0
for f in "$OUT"/laws/cases/burgers/plots/blocks_*.png; do
  cp "$f" "docs/img/toppling-blocks-$i.png"; i=$((i + 1))
done
# Figure 10: the slope settled without creep at several base friction angles (20 s).
for phi in 33 35 45 55; do
  rm -rf "$OUT/phi/cases/phi$phi/plots"
  "$B" plot "$OUT/phi/cases/phi$phi" --times 2.3148148e-4 --scale 1
  cp "$OUT"/phi/cases/phi$phi/plots/blocks_*.png "docs/img/toppling-phi-blocks-$phi.png"
done
# The four laws on the anti-toppling planes: block 10's displacement against time.
cp "$OUT/laws/study.png" docs/img/toppling-laws.png
ls docs/img/toppling-*.png

# The tables of docs/guide/toppling-study.md from the laws study (its study.csv):
# the Burgers case's displacements at 1, 10, 50 and 100 d, and per law.
/usr/bin/python3 - "$OUT/laws/study.csv" "$OUT/history.md" "$OUT/laws.md" <<'PY'
import csv, sys
rows = {r["case"]: r for r in csv.DictReader(open(sys.argv[1]))}
def v(r, block, t):
    return float(r[f"{block}_top.displacement@{t}"])
b = rows["burgers"]
with open(sys.argv[2], "w") as f:
    print("| time [d] | 1 | 10 | 50 | 60 | 100 |", file=f)
    print("|---|---|---|---|---|---|", file=f)
    for block, name in (("block1", "block 1"), ("block10", "block 10")):
        print(f"| {name} displacement [m] | " + " | ".join(f"{v(b, block, t):.3g}" for t in (1, 10, 50, 60, 100)) + " |", file=f)
    print("", file=f)
    print("Rate over the last 50 days: block 10 " + f"{(v(b, 'block10', 100) - v(b, 'block10', 50)) / 50:.3f} m/d, block 1 "
          + f"{(v(b, 'block1', 100) - v(b, 'block1', 50)) / 50:.3f} m/d.", file=f)
with open(sys.argv[3], "w") as f:
    print("| law | block 10 at 1 d [m] | at 100 d [m] | block 1 at 100 d [m] |", file=f)
    print("|---|---|---|---|", file=f)
    for law in ("burgers", "maxwell", "kelvin", "nishihara"):
        r = rows[law]
        if r["status"] != "completed":
            print(f"| {law} | {r['status']} | | |", file=f)
            continue
        print(f"| {law} | {v(r, 'block10', 1):.2f} | {v(r, 'block10', 100):.2f} | {v(r, 'block1', 100):.2f} |", file=f)
PY
scripts/splice-doc.sh docs/guide/toppling-study.md toppling-creep-history "$OUT/history.md"
scripts/splice-doc.sh docs/guide/toppling-study.md toppling-laws "$OUT/laws.md"
# The phi sweep's table (phi.dat: phi, block 1, block 10 at 20 s).
awk 'BEGIN { h = "| φ [deg] |"; s = "|---|"; a = "| block 1 |"; b = "| block 10 |" }
     { h = h " " $1 " |"; s = s "---|"; a = a sprintf(" %#.3g |", $2); b = b sprintf(" %#.3g |", $3) }
     END { print h; print s; print a; print b }' "$OUT/phi.dat" >"$OUT/phi.md"
scripts/splice-doc.sh docs/guide/toppling-study.md toppling-phi "$OUT/phi.md"
# The joints' mean |shear displacement| of the Burgers case at 1, 10, 50 and 100 d.
awk 'function near(t,   d) { d = $1 - t; return d < 0 ? -d : d }
     BEGIN { n = split("1 10 50 100", T, " ") }
     { for (k = 1; k <= n; ++k) if (!(k in best) || near(T[k]) < best[k]) { best[k] = near(T[k]); b[k] = $2; a[k] = $3 } }
     END { h = "| time [d] |"; s = "|---|"; x = "| base: mean \\|shear displacement\\| [m] |"; y = "| anti-toppling planes [m] |"
           for (k = 1; k <= n; ++k) { h = h " " T[k] " |"; s = s "---|"; x = x sprintf(" %.3f |", b[k]); y = y sprintf(" %.3f |", a[k]) }
           print h; print s; print x; print y }' "$OUT/joint-shear.dat" >"$OUT/joint-shear.md"
scripts/splice-doc.sh docs/guide/toppling-study.md toppling-joint-shear "$OUT/joint-shear.md"
