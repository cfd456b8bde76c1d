#!/bin/sh
# Regenerates the synthetic creep curves of this folder from the seed's Table 1
# row 1 Burgers parameters (E1 26.87, E2 192.43 MPa/mm; eta1 34807.72,
# eta2 2141.23 MPa*h/mm) with `rheodda law curve` (exact column), plus Gaussian
# noise of 2e-5 mm (awk's generator seeded with 42, Box-Muller), rounded to 1e-7 mm.
#   table1-row1.csv      shear stress 0.232 MPa for 200 h, every 0.5 h (t, displacement)
#   steps-unloading.csv  0.232 MPa, 0.424 MPa from 100 h, unloaded at 200 h; every 1 h to
#                        300 h (t, tau, displacement: tau is the stage column)
# Usage: sh examples/creep-data/make-examples.sh path/to/rheodda
set -e
RHEODDA=${1:-rheodda}
DIR=$(dirname "$0")
PARAMS="--param E1=26.87 --param E2=192.43 --param eta1=34807.72 --param eta2=2141.23"
noisy() {  # $1: 1 to keep the force column as tau
  awk -F, -v tau="$1" 'BEGIN { srand(42); print (tau ? "t,tau,displacement" : "t,displacement") }
    NR > 1 { u1 = rand(); u2 = rand(); if (u1 < 1e-300) u1 = 1e-300
             z = sqrt(-2 * log(u1)) * cos(6.283185307179586 * u2)
             if (tau) printf "%g,%g,%.7f\n", $1, $2, $4 + 2e-5 * z
             else printf "%g,%.7f\n", $1, $4 + 2e-5 * z }'
}
{
  echo "# synthetic creep test: seed Table 1 row 1 (Burgers), shear stress 0.232 MPa; noise 2e-5 mm"
  echo "# units: MPa, mm, h; made by examples/creep-data/make-examples.sh"
  "$RHEODDA" law curve burgers $PARAMS --force 0:0.232 --t-end 200 --dt 0.5 | noisy 0
} > "$DIR/table1-row1.csv"
{
  echo "# synthetic multi-stage creep test: seed Table 1 row 1 (Burgers), tau 0.232 -> 0.424 MPa"
  echo "# at 100 h, unloaded at 200 h; noise 2e-5 mm; units: MPa, mm, h; made by make-examples.sh"
  "$RHEODDA" law curve burgers $PARAMS --force 0:0.232,100:0.424,200:0 --t-end 300 --dt 1 | noisy 1
} > "$DIR/steps-unloading.csv"
