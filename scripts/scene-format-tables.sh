#!/usr/bin/env bash
# Regenerates the key tables of docs/reference/scene-format.md from the keys' declarations
# (scene/src/keys*.cpp) through `rheodda keys --markdown MAP`, between each pair of
# <!-- keys-MAP:begin/end --> markers the doc holds, and the table of the engine's settings
# in docs/reference/engine.md from their declarations (core/src/settings.cpp) through
# `rheodda keys --markdown settings`, between <!-- settings:begin/end -->, and the table of
# history.csv's columns in docs/reference/outputs.md from their declarations
# (scene/src/history_columns.cpp) through `rheodda keys --markdown history`, between
# <!-- history:begin/end -->.
# tests/scene/schema_test.cpp checks that the docs hold what this writes.
# Usage: scripts/scene-format-tables.sh     (RHEODDA_BUILD_DIR: the build to use, default build/)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RHEODDA_BUILD_DIR:-$root/build}"
doc="$root/docs/reference/scene-format.md"
tmp="$(mktemp)"
trap 'rm -f "$tmp"' EXIT
for map in $(sed -n 's/^<!-- keys-\(.*\):begin -->$/\1/p' "$doc"); do
  "$build/apps/rheodda" keys --markdown "$map" >"$tmp"
  "$root/scripts/splice-doc.sh" "$doc" "keys-$map" "$tmp"
done
"$build/apps/rheodda" keys --markdown settings >"$tmp"
"$root/scripts/splice-doc.sh" "$root/docs/reference/engine.md" settings "$tmp"
"$build/apps/rheodda" keys --markdown history >"$tmp"
"$root/scripts/splice-doc.sh" "$root/docs/reference/outputs.md" history "$tmp"
echo "scene-format-tables: docs/reference/scene-format.md key tables and engine.md's settings regenerated"
