#!/usr/bin/env bash
# `rheodda check --refine=3` on the tunnel and reservoir examples
# (examples/rockmass/tunnel-stages.yaml, reservoir-slope.yaml; docs/guide/tunnels-and-slopes.md):
# each at its own step controls (L0) and with every step control halved twice,
# and puts each refinement table, as `check` prints it, into
# docs/notes/engineering-examples.md between its refinement-NAME markers.
# About 10 min on 2 cores (the reservoir's finest level is 4 runs of a minute).
# Usage: scripts/refinement-engineering.sh   (uses $RHEODDA_BUILD_DIR or build/)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # strict mode; root, build, work (removed at exit)
splice() { "$root/scripts/splice-doc.sh" "$root/docs/notes/engineering-examples.md" "$1" "$2"; }
# refine NAME: `check --refine=3` of examples/rockmass/NAME.yaml, its table as Markdown in $work/NAME.md
refine() {
  # exit 3: the verdict is not "fine"; the table says what did not converge
  "$build/apps/rheodda" check "$root/examples/rockmass/$1.yaml" --refine=3 -j "$(nproc)" -o "$work/$1" \
    >/dev/null 2>&1 || [[ $? -eq 3 ]]
  { echo '```'; cat "$work/$1/refinement.txt"; echo '```'; } >"$work/$1.md"
  echo "refinement-engineering: $1: $(grep "^step controls:" "$work/$1/refinement.txt")"
}
refine tunnel-stages
splice refinement-tunnel-stages "$work/tunnel-stages.md"
refine reservoir-slope
splice refinement-reservoir-slope "$work/reservoir-slope.md"
