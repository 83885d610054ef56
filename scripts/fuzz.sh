#!/usr/bin/env bash
# Fuzzes the two input readers (JSON, equation expressions) with libFuzzer + ASan + UBSan.
# Usage: scripts/fuzz.sh [SECONDS]   (default 60 seconds per target; needs clang)
# Builds build-fuzz (clang, -DSURFCERT_BUILD_FUZZ=ON: surfcert_core and the fuzz targets only),
# then runs each target for SECONDS on a copy of its seed corpus tests/fuzz/corpus/<name>
# (new inputs go to the copy, never into the repository). Exits non-zero on any crash, sanitizer
# report, timeout, out-of-memory or violated property; the crashing input is left in
# build-fuzz/artifacts/ (add it to the corpus and a unit test once fixed).
set -euo pipefail
cd "$(dirname "$0")/.."
secs="${1:-60}"
build=build-fuzz
command -v "${CXX:-clang++}" >/dev/null ||
  { echo "fuzz.sh: ${CXX:-clang++} not found (scripts/setup.sh installs clang)" >&2; exit 1; }
CC="${CC:-clang}" CXX="${CXX:-clang++}" \
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSURFCERT_BUILD_FUZZ=ON >/dev/null
cmake --build "$build" -j"$(nproc)" --target json_fuzz expression_fuzz
mkdir -p "$build/artifacts"
status=0
for name in json expression; do
  work="$build/corpus/$name"
  rm -rf "$work"
  mkdir -p "$work"
  cp tests/fuzz/corpus/"$name"/* "$work"/
  echo "== fuzzing ${name}_fuzz for ${secs}s (seed corpus: $(ls "$work" | wc -l) files)"
  if ! ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    "$build/tests/fuzz/${name}_fuzz" "$work" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$build/artifacts/${name}-" \
    2>"$build/${name}_fuzz.log"; then
    status=1
    tail -n 60 "$build/${name}_fuzz.log"
    echo "== ${name}_fuzz FAILED (log: $build/${name}_fuzz.log, input: $build/artifacts/)"
  else
    grep -E '^#[0-9]+.*(DONE|pulse)|stat::(number_of_executed_units|average_exec_per_sec|new_units_added|peak_rss_mb)' \
      "$build/${name}_fuzz.log" | tail -n 6
  fi
done
if [ "$status" -eq 0 ]; then
  echo "== fuzz: OK (json_fuzz and expression_fuzz, ${secs}s each, no crash)"
else
  echo "== fuzz: FAILED"
fi
exit "$status"
