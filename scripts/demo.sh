#!/usr/bin/env bash
# Installs the dependencies (Debian 12), builds surfcert and runs the main job on the default
# scene: certified topology reports for the seed example and degenerate pairs.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh build -DSURFCERT_BUILD_TESTS=OFF
./build/app/surfcert run data/scenes/default.json -o build/default_report.json
echo "JSON report written to build/default_report.json"
