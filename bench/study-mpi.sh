#!/usr/bin/env bash
# Scaling of `rheodda study` over MPI ranks (docs/notes/performance.md, "Studies: dispatch and MPI scaling").
# Prints figures; asserts nothing.
#
# Usage: bench/study-mpi.sh [BUILD_DIR] [MAX_RANKS]     (default build/, 64)
#
# 1. Dispatch overhead per case: cases whose program (--case-program) does nothing but
#    write a history.csv and a summary.json; the study's wall time per case, minus the
#    stand-in's own time per call (measured alone in a shell loop), is what the study adds
#    (spawning the case process, dispatching to a rank, collecting, study.csv).
# 2. Speed-up on this machine's cores: real short cases (the sliding block over 2 s),
#    with 1 and 2 worker ranks (mpirun -np 2 and 3), and locally with -j 1 and -j 2.
# 3. Dispatch with many ranks, simulated: oversubscribed ranks (up to MAX_RANKS workers)
#    whose cases sleep 1 s without using a core; the ideal wall time is
#    ceil(cases / workers) s, and efficiency = ideal / measured (from the study's
#    own wall time, which leaves out MPI start-up).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
max_ranks="${2:-64}"
rheodda="$build/apps/rheodda"
[ -x "$rheodda" ] || { echo "no $rheodda: build first (scripts/build.sh)" >&2; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1   # the build containers run as root
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# A study of N cases of the sliding block (the case program may stand in for rheodda).
make_study() {  # make_study FILE N DURATION
  {
    echo "scene: $root/examples/sliding-block.yaml"
    echo "set: {analysis.duration: $3, analysis.output_interval: $3}"
    echo "outputs: [centre.u]"
    echo "times: [0]"
    echo "sweep:"
    echo "  method: random"
    echo "  samples: $2"
    echo "  parameters: [{name: phi, key: joint_sets.slope.friction_angle, unit: deg, range: [26, 29]}]"
  } > "$1"
}

# A stand-in case program: sleeps $1 s, then writes what a completed run writes.
make_stand_in() {  # make_stand_in FILE SLEEP
  cat > "$1" <<EOF
#!/bin/sh
# called as: PROGRAM run SCENE -o DIR [--resume]
[ "$2" = 0 ] || sleep $2
printf 'time,step,centre.u\n0,0,0\n' > "\$4/history.csv"
printf '{"status": "completed", "steps": 0, "wall_seconds": 0}\n' > "\$4/summary.json"
EOF
  chmod +x "$1"
}

# The study's own wall time, from its last line ("... wall time X s").
study_wall() { sed -n 's/.*wall time \([0-9.]*\) s.*/\1/p' | tail -1; }

echo "== 1. dispatch overhead per case (stand-in cases that do nothing)"
make_stand_in "$work/noop.sh" 0
make_study "$work/noop.yaml" 400 0.001
for i in $(seq 400); do mkdir -p "$work/loop/$i"; done
t0=$(date +%s.%N)
for i in $(seq 400); do "$work/noop.sh" run x -o "$work/loop/$i"; done
t1=$(date +%s.%N)
alone=$(echo "($t1 - $t0) / 400 * 1000" | bc -l)
printf "stand-in alone: %.2f ms per call\n" "$alone"
w=$("$rheodda" study "$work/noop.yaml" -o "$work/noop-local" -j 1 --no-plot --case-program "$work/noop.sh" 2>/dev/null | study_wall)
printf "local -j 1:            %.2f ms per case, of which the study adds %.2f ms\n" \
  "$(echo "$w / 400 * 1000" | bc -l)" "$(echo "$w / 400 * 1000 - $alone" | bc -l)"
w=$(mpirun --oversubscribe -np 2 "$rheodda" study "$work/noop.yaml" -o "$work/noop-mpi" --no-plot \
      --case-program "$work/noop.sh" 2>/dev/null | study_wall)
printf "mpirun -np 2 (1 worker): %.2f ms per case, of which the study adds %.2f ms\n" \
  "$(echo "$w / 400 * 1000" | bc -l)" "$(echo "$w / 400 * 1000 - $alone" | bc -l)"

echo "== 2. speed-up on $(nproc) cores (16 sliding-block cases of 2 s, dt 1 ms: 2000 steps each)"
make_study "$work/real.yaml" 16 2
for j in 1 2; do
  w=$("$rheodda" study "$work/real.yaml" -o "$work/real-j$j" -j $j --no-plot 2>/dev/null | study_wall)
  printf "local -j %d:                 %6.2f s\n" $j "$w"
done
for np in 2 3; do
  w=$(mpirun --oversubscribe -np $np "$rheodda" study "$work/real.yaml" -o "$work/real-np$np" --no-plot 2>/dev/null | study_wall)
  printf "mpirun -np %d (%d workers):  %6.2f s\n" $np $((np - 1)) "$w"
done

echo "== 3. many ranks, simulated (cases sleep 1 s; 4 cases per worker)"
make_stand_in "$work/sleep.sh" 1
printf "%8s %6s %10s %10s %10s\n" workers cases "ideal [s]" "study [s]" efficiency
r=2
while [ "$r" -le "$max_ranks" ]; do
  n=$((4 * r))
  make_study "$work/sleep-$r.yaml" $n 0.001
  w=$(mpirun --oversubscribe -np $((r + 1)) "$rheodda" study "$work/sleep-$r.yaml" -o "$work/sleep-$r" --no-plot \
        --case-program "$work/sleep.sh" 2>/dev/null | study_wall)
  printf "%8d %6d %10.2f %10.2f %10.3f\n" $r $n 4 "$w" "$(echo "4 / $w" | bc -l)"
  r=$((r * 2))
done
