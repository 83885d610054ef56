#!/usr/bin/env bash
# Installs the dependencies (Debian 12), builds surfcert with its tests and runs the whole
# suite with CTest. This is the README's test command and what CI (.ci/run) calls.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh build -DSURFCERT_BUILD_TESTS=ON -DSURFCERT_WERROR=${SURFCERT_WERROR:-OFF}
ctest --test-dir build --output-on-failure -j"$(nproc)"
