#!/usr/bin/env bash
# Makes the README's pictures from recordings, drawn by viewer/ in headless
# Chromium (tools/viewer_picture.mjs): runs the examples that write them,
# then renders one frame of each into docs/images/.
#   tools/readme_pictures.sh [build dir, default build/native: the quick start's]
# Needs the examples built, `apt-get install chromium` and `npm ci --prefix viewer`.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/native}
mkdir -p docs/images
"$build/examples/rube_goldberg" >/dev/null
"$build/examples/particles_plume" >/dev/null
node tools/viewer_picture.mjs out/rube_goldberg.glb docs/images/rube_goldberg.png --time 3.8 --contacts \
  --camera=1.5,5.5,11 --target=-0.2,1.8,0
node tools/viewer_picture.mjs out/particles_plume.ipr docs/images/particles_plume.png --time 9 \
  --camera=4,3.5,5 --target=0,1,0
