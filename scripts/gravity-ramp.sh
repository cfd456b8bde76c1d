#!/usr/bin/env bash
# The settling stage of examples/rockmass/jointed-slope.yaml with gravity at
# once and with its gravity ramp (docs/reference/engine.md, "Gravity ramp"): the stage
# alone (26 s: the 20 s stage and one static step), refined by `rheodda check
# --refine=5` (the stage's dt halved from 1 ms down to 62.5 us, its g2 halved
# with it or held). Puts the four refinement tables into docs/reference/engine.md between
# the gravity-ramp markers. About 30 min on 2 cores.
# Usage: scripts/gravity-ramp.sh   (uses $RHEODDA_BUILD_DIR or build/)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RHEODDA_BUILD_DIR:-$root/build}"
work="$(mktemp -d)"
ramped="$root/examples/rockmass/.gravity-ramp.yaml" at_once="$root/examples/rockmass/.gravity-at-once.yaml"
trap 'rm -rf "$work" "$ramped" "$at_once"' EXIT
# The stage only: 3e-4 d (26 s), one static step of 5e-5 d after it; and the
# same with gravity at once (the ramp removed).
/usr/bin/python3 - "$root/examples/rockmass/jointed-slope.yaml" "$ramped" "$at_once" <<'PY'
import re, sys
s = open(sys.argv[1]).read()
def sub(pattern, repl, text):
    text, n = re.subn(pattern, repl, text, count=1, flags=re.M)
    assert n == 1, pattern
    return text
s = sub(r"^  duration: .*$", "  duration: 3.0e-4        # d", s)
s = sub(r"^  dt: .*$", "  dt: 5.0e-5             # d", s)
s = sub(r"^  output_interval: .*$", "  output_interval: 5.0e-5 # d", s)
open(sys.argv[2], "w").write(s)
open(sys.argv[3], "w").write(sub(r",\s*gravity_ramp: [^,}]*", "", s))
PY
# Each with the stage's g2 halved with its dt (as `check --refine` does) and held
# at the example's 0.00025 (`--hold settle.max_displacement_ratio`).
cases=(
  "$ramped||gravity ramped up over 10 s (the example), the stage's dt and g2 halved together"
  "$ramped|--hold settle.max_displacement_ratio|gravity ramped up over 10 s (the example), the stage's dt halved, its g2 held"
  "$at_once||gravity at once, the stage's dt and g2 halved together"
  "$at_once|--hold settle.max_displacement_ratio|gravity at once, the stage's dt halved, its g2 held"
)
{
  k=0
  for case in "${cases[@]}"; do
    IFS='|' read -r file hold name <<<"$case"
    k=$((k + 1))
    # shellcheck disable=SC2086  # hold is empty or two words
    "$build/apps/rheodda" check "$file" --refine=5 $hold -j "$(nproc)" -o "$work/$k" >/dev/null 2>&1 || true
    echo "$name:"
    echo
    echo '```'
    sed -e '/^  the table:/d' -e '/^$/N;/^\n$/D' "$work/$k/refinement.txt"
    echo '```'
    echo
  done
} >"$work/table.md"
cat "$work/table.md"
"$root/scripts/splice-doc.sh" "$root/docs/notes/dynamic-stages.md" gravity-ramp "$work/table.md"
