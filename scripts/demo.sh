#!/usr/bin/env bash
# Installs the dependencies (Debian 12), builds surfcert and runs the main job on the default
# scene: certified topology reports for the seed example and degenerate pairs.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh build -DSURFCERT_BUILD_TESTS=OFF
./build/app/surfcert run data/scenes/default.json -o build/default_report.json
echo "JSON report written to build/default_report.json"
# The Python module (built when pybind11 is found) is made importable by Debian's python3: a .pth
# file naming build/python, so `python3 -c "import surfcert"` works without PYTHONPATH.
if [ -d build/python/surfcert ] && [ -x /usr/bin/python3 ] && [ "$(id -u)" = 0 ]; then
  site=$(/usr/bin/python3 -c 'import site; print(site.getsitepackages()[0])')
  mkdir -p "$site" && echo "$(pwd)/build/python" > "$site/surfcert-build.pth"
  echo "Python: /usr/bin/python3 imports surfcert from $(pwd)/build/python ($site/surfcert-build.pth)"
fi
