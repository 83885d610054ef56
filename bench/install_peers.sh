#!/bin/sh
# Benchmark peers only (bench/trace_bench, bench/distance_peers_bench, bench/float_atlas); the
# library and the tests never need them.
# Open CASCADE 7.6.3 (Debian 12): Geom, GeomConvert, GeomAPI_IntSS, GeomAPI_ExtremaSurfaceSurface.
# FCL 0.7.0 (Debian 12 libfcl-dev; pulls libccd-dev, libeigen3-dev, liboctomap-dev).
set -e
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO=sudo
$SUDO apt-get update
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends \
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev \
  libfcl-dev
