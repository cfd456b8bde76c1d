#!/usr/bin/env bash
# Regenerates the pictures of the README's tour (docs/img/tour-*.png; docs/guide/getting-started.md) from the
# shipped examples, as a user makes them: `rheodda run` then `rheodda plot`.
# Usage: scripts/readme-pictures.sh   (build: $RHEODDA_BUILD_DIR or build/)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
B="${RHEODDA_BUILD_DIR:-$root/build}/apps/rheodda"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$B" run "$root/examples/goodman-toppling.yaml" -o "$work/goodman" >/dev/null
"$B" plot "$work/goodman" >/dev/null
last="$(ls "$work/goodman/plots"/blocks_*.png | sort | tail -1)"   # the frame at 100 d
cp "$last" "$root/docs/img/tour-goodman-blocks.png"
frame="$(basename "$last" .png)"; frame="${frame#blocks_}"
cp "$work/goodman/plots/contacts_$frame.png" "$root/docs/img/tour-goodman-contacts.png"
cp "$work/goodman/plots/strength_$frame.png" "$root/docs/img/tour-goodman-strength.png"
"$B" run "$root/examples/shear-creep-test.yaml" -o "$work/shear" >/dev/null
"$B" plot "$work/shear" >/dev/null
cp "$work/shear/plots/history.png" "$root/docs/img/tour-shear-creep-history.png"
echo "readme-pictures: docs/img/tour-goodman-{blocks,contacts,strength}.png, docs/img/tour-shear-creep-history.png"
