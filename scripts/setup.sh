#!/usr/bin/env bash
# Installs the Debian packages TetLOD needs (only those missing; apt-get update
# first) and builds it (Release) into build/. Safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake pkg-config libeigen3-dev libtet1.5-dev libgtest-dev
  libbenchmark-dev zlib1g-dev)
# Renderer: GL headers, GLFW (window backend), stb (PNG, text), OSMesa and EGL
# (offscreen backends, loaded at run time), Xvfb for the window-backend test.
packages+=(libgl-dev libglfw3-dev libstb-dev libosmesa6 libegl1 libegl-mesa0 libgl1-mesa-dri xvfb
  xauth)
# Viewer: Dear ImGui with its GLFW and OpenGL 3 backends; XTest for the tests that
# drag the mouse over the window under Xvfb; DejaVu Sans for the Greek, Cyrillic and
# Latin Extended letters of names (ImGui's own font has Latin-1 only).
packages+=(libimgui-dev libxtst-dev fonts-dejavu-core)
# Extra packages a caller needs (scripts/test.sh adds gmsh for the interoperability test).
read -r -a extra <<<"${TETLOD_EXTRA_PACKAGES:-}"
packages+=("${extra[@]}")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "setup: installing ${missing[*]}"
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
fi

werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DTETLOD_WERROR=$werror
cmake --build build -j"$(nproc)"
