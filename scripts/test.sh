#!/usr/bin/env bash
# Installs what is missing, builds, and runs the test suites under one
# virtual X server. --fast leaves out the suites labelled slow (ctest -LE
# slow); the other arguments go to setup.sh (--asan, --debug).
set -euo pipefail
cd "$(dirname "$0")/.."
setup_args=()
ctest_args=()
for arg in "$@"; do
  case "$arg" in
    --fast) ctest_args+=(-LE slow) ;;
    *) setup_args+=("$arg") ;;
  esac
done
scripts/setup.sh "${setup_args[@]+"${setup_args[@]}"}"
build_dir=build
for arg in "${setup_args[@]+"${setup_args[@]}"}"; do
  case "$arg" in --asan) build_dir=build-asan ;; --debug) build_dir=build-debug ;; esac
done
cd "$build_dir"
export QT_QPA_PLATFORM=xcb
if [ "$build_dir" = build-asan ]; then
  # Leaks from Mesa/Qt plug-ins are not ours; everything else aborts the test.
  export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
fi
xvfb-run -a -s "-screen 0 1600x1200x24" ctest --output-on-failure -j2 "${ctest_args[@]+"${ctest_args[@]}"}"
