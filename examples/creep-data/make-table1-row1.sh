#!/bin/sh
# Regenerates table1-row1.csv: the seed's Table 1 row 1 Burgers curve
# (tau = 0.232 MPa; E1 26.87, E2 192.43 MPa/mm; eta1 34807.72, eta2 2141.23 MPa*h/mm)
# sampled every 0.5 h for 200 h, plus Gaussian noise of 2e-5 mm (awk's
# generator seeded with 42, Box-Muller), rounded to 1e-7 mm.
# Usage: sh examples/creep-data/make-table1-row1.sh path/to/rheodda > examples/creep-data/table1-row1.csv
set -e
RHEODDA=${1:-rheodda}
echo "# synthetic creep test: seed Table 1 row 1 (Burgers), shear stress 0.232 MPa; noise 2e-5 mm"
echo "# units: MPa, mm, h; made by examples/creep-data/make-table1-row1.sh"
"$RHEODDA" law curve burgers --param E1=26.87 --param E2=192.43 --param eta1=34807.72 \
    --param eta2=2141.23 --force 0:0.232 --t-end 200 --dt 0.5 |
  awk -F, 'BEGIN { srand(42); print "t,displacement" }
           NR > 1 { u1 = rand(); u2 = rand(); if (u1 < 1e-300) u1 = 1e-300;
                    z = sqrt(-2 * log(u1)) * cos(6.283185307179586 * u2);
                    printf "%g,%.7f\n", $1, $4 + 2e-5 * z }'
