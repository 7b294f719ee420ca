#!/usr/bin/env bash
# Installs everything the build, the tool and the tests need, from Debian packages (and the
# Khronos glTF validator, three.js and three-vrm from npm for the export tests). Safe to re-run.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  cmake g++ make pkg-config git
  libeigen3-dev liblbfgspp-dev catch2 nlohmann-json3-dev
  libzip-dev libtinygltf-dev libstb-dev libglm-dev
  libglfw3-dev libimgui-dev libepoxy-dev libegl-dev libegl-mesa0 libgl-dev libgl1-mesa-dri
  mesa-utils xvfb xauth xdotool imagemagick
  python3-numpy nodejs npm
)

# The fuzz smoke run (tools/fuzz.sh, part of the test suite) needs clang and its libFuzzer /
# sanitizer runtimes.
if [ "${1:-}" = "--test" ]; then
  packages+=(clang libclang-rt-14-dev)
fi

missing=()
for p in "${packages[@]}"; do
  # NodeSource's nodejs bundles npm and conflicts with Debian's npm package.
  [ "$p" = npm ] && command -v npm >/dev/null && continue
  [[ "$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null)" == *"install ok installed"* ]] || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  echo "setup: installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}"
fi

# The glTF validator (test tool only) lives in tests/validator/node_modules (git-ignored).
if [ "${1:-}" = "--test" ] && [ ! -d tests/validator/node_modules/gltf-validator ]; then
  echo "setup: installing the Khronos glTF validator from npm"
  npm install --silent --no-audit --no-fund --prefix tests/validator gltf-validator >/dev/null
fi
# three.js and three-vrm (test tools only: exports loaded as a web app would) live in
# tests/threejs/node_modules (git-ignored), pinned by tests/threejs/package-lock.json.
if [ "${1:-}" = "--test" ] && { [ ! -d tests/threejs/node_modules/three ] ||
                                [ ! -d tests/threejs/node_modules/@pixiv/three-vrm ]; }; then
  echo "setup: installing three and @pixiv/three-vrm from npm"
  npm ci --silent --no-audit --no-fund --prefix tests/threejs >/dev/null
fi
echo "setup: ok"
