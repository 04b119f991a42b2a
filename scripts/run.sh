#!/usr/bin/env bash
# Set-up plus the main job on the bundled default model.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
./build/app/tetlod stats assets/motor.mesh
