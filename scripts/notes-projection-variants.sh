#!/usr/bin/env bash
# The commit's projection onto the Mohr-Coulomb envelope, by variant (docs/notes/step-controls.md,
# "The seed's slope itself, refined"): the seed's slope on its own steps
# (bench/scenes/goodman-toppling-seed-steps.yaml) over 20 d at level L4 of
# scripts/refinement-goodman-creep.sh (max_displacement_ratio 6.25e-5, dt 1/32 d), run by a copy
# of the tree with bench/prototypes/projection-variants.patch: no projection, opening only, the
# return mapping only, beyond the strength committed sliding, and the code as it is. Prints each
# run's last line (steps and cuts).
#
#   scripts/notes-projection-variants.sh [VARIANT...]   # default: none tension shear sliding adopted
#
# A build of the copy and about 12 minutes on one core (no projection alone about 5).
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
variants=("$@")
((${#variants[@]})) || variants=(none tension shear sliding adopted)
prototype_build "$root/bench/prototypes/projection-variants.patch" rheodda
sed -e 's/^  duration: 60 .*$/  duration: 20/' -e 's/^  dt: 0.5 .*$/  dt: 0.03125\n  max_displacement_ratio: 6.25e-5/' \
  "$root/bench/scenes/goodman-toppling-seed-steps.yaml" >"$work/l4.yaml"
grep -q '^  max_displacement_ratio: 6.25e-5$' "$work/l4.yaml" || { echo "the scene's analysis block changed" >&2; exit 1; }
for v in "${variants[@]}"; do
  [[ "$v" == adopted ]] && v=""
  echo "# RHEODDA_PROJECTION=${v:-(unset: as adopted)}"
  RHEODDA_PROJECTION="$v" "$proto_build/apps/rheodda" run "$work/l4.yaml" -o "$work/out-${v:-adopted}" 2>&1 |
    grep -o 'completed at .*'
done
