#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test suite under one
# virtual X server. Extra arguments go to setup.sh (--asan, --debug).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh "$@"
build_dir=build
case "${1:-}" in --asan) build_dir=build-asan ;; --debug) build_dir=build-debug ;; esac
cd "$build_dir"
export QT_QPA_PLATFORM=xcb
if [ "$build_dir" = build-asan ]; then
  # Leaks from Mesa/Qt plug-ins are not ours; everything else aborts the test.
  export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
fi
xvfb-run -a -s "-screen 0 1600x1200x24" ctest --output-on-failure -j2
