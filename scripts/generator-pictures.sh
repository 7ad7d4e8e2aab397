#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The picture of every generator and of the two example graphs in docs/generators.md: each at
# 129 x 129 vertices (cell 2 m, seed 1, default parameters), hillshaded by `runnel generate
# --picture`, then laid out with titles in docs/images/generators.png. Needs a built runnel (build/).
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
names=$(build/runnel generate --help | sed -n 's/^  \([a-z-]*\): .*/\1/p')
for g in $names; do
  build/runnel generate "$g" --size 129 --cell 2 --seed 1 -o "$tmp/$g.npy" --picture "$tmp/$g.png" 2>/dev/null
done
for graph in data/graphs/*.toml; do
  g=$(basename "$graph" .toml)
  build/runnel generate --graph "$graph" -o "$tmp/$g.npy" --picture "$tmp/graph:$g.png" 2>/dev/null
done
/usr/bin/python3 - "$tmp" docs/images/generators.png <<'PY'
import os, sys
from PIL import Image, ImageDraw
folder, out = sys.argv[1], sys.argv[2]
files = sorted(f for f in os.listdir(folder) if f.endswith('.png') and not f.startswith('graph:'))
files += sorted(f for f in os.listdir(folder) if f.startswith('graph:'))
tile, title, columns = 220, 18, 6
rows = (len(files) + columns - 1) // columns
sheet = Image.new('RGB', (columns * tile, rows * (tile + title)), 'white')
draw = ImageDraw.Draw(sheet)
for k, f in enumerate(files):
    x, y = (k % columns) * tile, (k // columns) * (tile + title)
    sheet.paste(Image.open(os.path.join(folder, f)).resize((tile - 6, tile - 6)), (x + 3, y + title))
    draw.text((x + 4, y + 3), f[:-4].replace('graph:', 'graph: '), fill='black')
sheet.save(out, optimize=True)
PY
echo "wrote docs/images/generators.png"
