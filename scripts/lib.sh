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
