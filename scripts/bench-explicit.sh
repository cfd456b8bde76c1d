#!/usr/bin/env bash
# The explicit step against the implicit one and against the open-source peer on the
# running-bond brick wall (docs/notes/explicit-step.md, "The brick wall"): CPU seconds per
# simulated millisecond over 50 ms of a dynamic run (dt 1 ms), one thread, and the explicit
# step's wall time on two threads; the wall's largest displacement at 50 ms by each step,
# and by the explicit one with its safety factor halved (its convergence in the cycle).
#
#   scripts/bench-explicit.sh [SIZES]     # SIZES: contact_bench's --sizes, default 20,40,80
#   NTDDA_MIRROR=<git dir of doolin/ntdda> scripts/bench-explicit.sh   # with the peer's column
#
# The peer (shared/peers/ntdda) is built by its own build.sh when NTDDA_MIRROR is set; its
# figure is its analysis clock over the same wall (penalty 50 E, nu 0.25, friction 30 deg).
# About 10 minutes with the three sizes and the peer.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
sizes="${1:-20,40,80}"
ensure_built contact_bench
bench="$build/bench/contact_bench"
common=(--duration 0.05 --penalty 50 --poisson 0.25)

peer=""
if [[ -n "${NTDDA_MIRROR:-}" ]]; then
  peers="$root/../shared/peers/ntdda"
  peer="$(NTDDA_DIR="${NTDDA_DIR:-/tmp/ntdda}" bash "$peers/build.sh" | tail -n 1)"
fi

# value KEY FILE: the figure contact_bench prints after KEY on its summary lines.
value() { grep -o "$1 [0-9.e+-]*" "$2" | head -n 1 | awk '{print $NF}'; }
cpu_per_ms() { grep -o '[0-9.e+-]* CPU s per simulated ms' "$1" | awk '{print $1}'; }
wall_per_ms() { grep -o '[0-9.e+-]* wall s per simulated ms' "$1" | awk '{print $1}'; }
max_disp() { awk '!/^#/ && NF > 10 && $1 ~ /^[0-9]/ {print $NF}' "$1"; }

printf '| blocks | peer: CPU s per ms | implicit: CPU s per ms | explicit, 1 thread: CPU s per ms | explicit, 2 threads: wall s per ms | explicit vs peer (CPU, 1 thread) | cycles per step | ns per contact update | largest displacement implicit / explicit / explicit at half safety [m] |\n'
printf '|---:|---:|---:|---:|---:|---:|---:|---:|---|\n'
IFS=',' read -r -a list <<<"$sizes"
for n in "${list[@]}"; do
  "$bench" --sizes "$n" "${common[@]}" --integrator implicit --iterate-tol 0 >"$work/imp.txt"
  "$bench" --sizes "$n" "${common[@]}" --integrator explicit --threads 1 >"$work/exp1.txt"
  "$bench" --sizes "$n" "${common[@]}" --integrator explicit --threads 2 >"$work/exp2.txt"
  # Half the default safety factor (Settings::explicit_safety 0.8), on one thread (the same
  # bits as on two).
  "$bench" --sizes "$n" "${common[@]}" --integrator explicit --threads 1 --safety 0.4 >"$work/half.txt"
  blocks=$(awk '!/^#/ && $1 ~ /^[0-9]/ {print $1; exit}' "$work/exp1.txt")
  peer_cpu="–"
  if [[ -n "$peer" ]]; then
    python3 "$root/../shared/peers/ntdda/ntdda_gen_wall.py" gen "$n" "$n" "$work/peer$n" --steps 50 \
      --type dynamic --dt 0.001 --w 0.2 --h 0.1 >/dev/null
    geo=$(ls "$work/peer$n"/*.geo | head -n 1)
    ana=$(ls "$work/peer$n"/*.ana | head -n 1)
    "$peer" "$geo" "$ana" >"$work/peer.txt" 2>&1 || true
    s=$(grep -o 'CPU run time: [0-9.e+-]*' "$work/peer.txt" | awk '{print $NF}' | tail -n 1)
    [[ -n "$s" ]] && peer_cpu=$(awk -v s="$s" 'BEGIN {printf "%.4g", s / 50}')
  fi
  e1=$(cpu_per_ms "$work/exp1.txt")
  ratio="–"
  [[ "$peer_cpu" != "–" ]] && ratio=$(awk -v p="$peer_cpu" -v e="$e1" 'BEGIN {printf "%.1f x less", p / e}')
  cycles=$(grep -o '[0-9.]* cycles per step' "$work/exp1.txt" | awk '{print $1}')
  ns=$(grep -o '[0-9.]* ns CPU' "$work/exp1.txt" | awk '{print $1}')
  printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s / %s / %s |\n' "$blocks" "$peer_cpu" \
    "$(cpu_per_ms "$work/imp.txt")" "$e1" "$(wall_per_ms "$work/exp2.txt")" "$ratio" "$cycles" "$ns" \
    "$(max_disp "$work/imp.txt")" "$(max_disp "$work/exp1.txt")" "$(max_disp "$work/half.txt")"
done
