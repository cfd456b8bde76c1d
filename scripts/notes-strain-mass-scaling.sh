#!/usr/bin/env bash
# Selective mass scaling of the strain unknowns, tried on the running-bond brick wall and not
# adopted (docs/notes/explicit-step.md, "Selective mass scaling of the strain unknowns"): builds
# contact_bench from the current sources with bench/prototypes/strain-mass-scaling.patch applied
# (in a temporary copy of the tree and build folder), runs the wall's explicit step over 50 ms
# with and without the prototype (RHEODDA_STRAIN_MASS_SCALING), and prints the cycles per step,
# the CPU per simulated millisecond and the largest displacement at 50 ms, and the highest
# frequency of one brick's rigid motion and of all its unknowns.
#
#   scripts/notes-strain-mass-scaling.sh [SIZES]    # contact_bench's --sizes, default 20,40
#
# A build of the copy takes as long as a build of the tree (minutes with ccache).
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
sizes="${1:-20,40}"
prototype_build "$root/bench/prototypes/strain-mass-scaling.patch" contact_bench
bench="$proto_build/bench/contact_bench"
common=(--duration 0.05 --penalty 50 --poisson 0.25 --integrator explicit --threads 1)

printf '| blocks | strain inertia | cycles per 1 ms step | CPU s per simulated ms | largest displacement at 50 ms [m] |\n'
printf '|---:|---|---:|---:|---:|\n'
IFS=',' read -r -a list <<<"$sizes"
for n in "${list[@]}"; do
  for scaled in 0 1; do
    if ((scaled)); then
      RHEODDA_STRAIN_MASS_SCALING=1 RHEODDA_STRAIN_MASS_SCALING_PRINT=1 "$bench" --sizes "$n" "${common[@]}" \
        >"$work/out.txt" 2>"$work/err.txt"
      what="scaled"
    else
      "$bench" --sizes "$n" "${common[@]}" >"$work/out.txt" 2>"$work/err.txt"
      what="as is"
    fi
    cycles="$(grep -o '[0-9.]* cycles per step' "$work/out.txt" | head -n 1 | awk '{print $1}')"
    cpu="$(grep -o '[0-9.e+-]* CPU s per simulated ms' "$work/out.txt" | awk '{print $1}')"
    largest="$(grep -o 'largest [0-9.e+-]* m' "$work/out.txt" | head -n 1 | awk '{print $2}')"
    printf '| %s | %s | %s | %s | %s |\n' "$n x $n" "$what" "$cycles" "$cpu" "$largest"
    [[ -s "$work/err.txt" ]] && sed -n 1p "$work/err.txt" | sed 's/^/    # /'
  done
done
