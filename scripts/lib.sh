# Sourced by the report scripts (scripts/*.sh): strict mode, the source root, the
# build to use and a work folder removed when the script exits.
#   root   the source tree
#   build  RHEODDA_BUILD_DIR, default build/
#   work   a fresh temporary folder
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RHEODDA_BUILD_DIR:-$root/build}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# bench_slope: writes the benchmark's 744-block cohesionless slope (bench/scenes/
# jointed-slope-cohesionless.yaml scaled by rockmass_bench --creep 1000) into $work and sets
# slope_scene to its path (needs rockmass_bench built).
bench_slope() {
  "$build/bench/rockmass_bench" --no-generation --scene "$root/bench/scenes/jointed-slope-cohesionless.yaml" \
    --write-scenes "$work" --creep 1000 --max-wall 0 >/dev/null
  slope_scene="$work/jointed-slope-cohesionless-1000.yaml"
}

# scene_variant BASE OUT OLD=>NEW...: the scene file BASE with each OLD text replaced by NEW
# (once), written to OUT; a text not in BASE stops the script.
scene_variant() {
  /usr/bin/python3 - "$@" <<'EOF'
import sys
src = open(sys.argv[1]).read()
for sub in sys.argv[3:]:
    old, new = sub.split("=>")
    if old not in src:
        sys.exit(f"scene_variant: {old!r} not in {sys.argv[1]}")
    src = src.replace(old, new, 1)
open(sys.argv[2], "w").write(src)
EOF
}

# ensure_built TARGET...: configures and builds the CMake targets (Release) in $build
# unless each is there already (bench/TARGET or apps/TARGET).
ensure_built() {
  local t missing=()
  for t in "$@"; do
    [[ -x "$build/bench/$t" || -x "$build/apps/$t" ]] || missing+=("$t")
  done
  ((${#missing[@]} == 0)) && return 0
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$build" -j "$(nproc)" --target "${missing[@]}"
}

# prototype_build PATCH TARGET...: a temporary copy of the tree (its working changes
# included) with PATCH applied (bench/prototypes/, ideas tried and not adopted), the
# CMake targets built in the copy's own build folder; sets proto_build to that folder.
# The copy is removed when the script exits.
prototype_build() {
  local patch="$1"
  shift
  local copy="$work/prototype"
  git -C "$root" worktree add --detach "$copy" HEAD >/dev/null 2>&1
  trap 'git -C "$root" worktree remove --force "'"$copy"'" >/dev/null 2>&1; rm -rf "$work"' EXIT
  git -C "$root" diff HEAD | git -C "$copy" apply --allow-empty
  git -C "$copy" apply "$patch"
  cmake -S "$copy" -B "$copy/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$copy/build" -j "$(nproc)" --target "$@" >/dev/null
  proto_build="$copy/build"
}
