#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The README's viewer pictures: data/sessions/channel.json (a source on the ridge of the default
# terrain, SPH, 30 simulated seconds) replayed headless (EGL) at 1280x800, recorded every 5 s;
# three frames side by side (docs/images/viewer-channel.png) and the last with the erosion overlay
# (docs/images/viewer.png). Needs build/runnel-viewer and Debian's python3-pil.
set -euo pipefail
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
build/runnel-viewer --headless --replay data/sessions/channel.json --size 1280x800 \
  --record "$work/frames" --record-interval 5
build/runnel-viewer --headless --replay data/sessions/channel.json --size 1280x800 \
  --overlay erosion --screenshot "$work/erosion.png"
/usr/bin/python3 - "$work" <<'PY'
import sys
from PIL import Image
work = sys.argv[1]
box = (40, 40, 1240, 760)  # the terrain in the default view (framed with a margin)
frames = [Image.open(f"{work}/frames/frame_{k:06d}.png").crop(box).resize((640, 384)) for k in (0, 2, 5)]
strip = Image.new("RGB", (1920, 384))
for i, f in enumerate(frames):
    strip.paste(f, (640 * i, 0))
strip.save("docs/images/viewer-channel.png")
Image.open(f"{work}/erosion.png").crop(box).save("docs/images/viewer.png")
PY
echo "docs/images/viewer-channel.png docs/images/viewer.png"
