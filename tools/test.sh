#!/usr/bin/env bash
# Builds and runs the whole test suite through ctest. GUI tests start their own Xvfb.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh
cd build
# Every test sets its own TIMEOUT; --timeout is the fallback for one that forgets, so a hang
# fails in minutes instead of at ctest's 25-minute default.
ctest --output-on-failure --timeout 600 -j"$(nproc)" "$@"
