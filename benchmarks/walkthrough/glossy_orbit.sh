#!/usr/bin/env bash
# Issue 42's second walkthrough: CornellBox-Glossy (its sphere and short box radiance-cached, HSH records) seen from
# inside the box by a camera that swings 180 degrees around the objects, from the left wall past the open front to the
# right wall, 120 frames at 512 x 384: radiance records reused as the view turns. The same measurements as
# sponza_walk.sh (it runs them).
#   benchmarks/walkthrough/glossy_orbit.sh OUT_DIR [render|analyse|all]
here="$(cd "$(dirname "$0")/../.." && pwd)"
SCENE="$here/../shared/scenes/cornell_box_mcguire/CornellBox-Glossy.gltf" \
  CAMERA_PATH="--orbit 5 --orbit-degrees 180 --eye=-0.85,1.25,0 --target 0,0.4,0 --fov 70" \
  TITLE="CornellBox-Glossy orbit inside the box, 512 x 384" \
  exec bash "$here/benchmarks/walkthrough/sponza_walk.sh" "$@"
