#!/usr/bin/env bash
# Builds and runs the whole test suite through ctest. GUI tests start their own Xvfb.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh
cd build
ctest --output-on-failure -j"$(nproc)" "$@"
