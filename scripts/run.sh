#!/usr/bin/env bash
# Set-up plus the main job on the bundled default model.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
./build/app/tetlod stats assets/motor.mesh
# A picture of it (offscreen, no display needed): the air hidden, cut in half,
# coloured by stretch, the worst tets highlighted.
./build/app/tetlod render assets/motor.mesh --hide 1 --cut y=0 --highlight-below 0.2 \
  -o build/motor.png
