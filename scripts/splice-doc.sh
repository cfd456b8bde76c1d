#!/usr/bin/env bash
# Replaces the text between the lines <!-- NAME:begin --> and <!-- NAME:end -->
# of a Markdown file by the contents of another file: how the report scripts
# (accuracy-report.sh, refinement-*.sh) put generated tables into docs/.
# Usage: scripts/splice-doc.sh DOC NAME FILE
set -euo pipefail
doc="$1" name="$2" file="$3"
grep -qxF "<!-- $name:begin -->" "$doc" || { echo "splice-doc: no <!-- $name:begin --> in $doc" >&2; exit 1; }
tmp="$(mktemp)"
awk -v b="<!-- $name:begin -->" -v e="<!-- $name:end -->" -v f="$file" '
  $0 == b { print; while ((getline line < f) > 0) print line; skip = 1; next }
  $0 == e { skip = 0 }
  !skip { print }' "$doc" >"$tmp"
cat "$tmp" >"$doc"
rm -f "$tmp"
