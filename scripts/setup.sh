#!/usr/bin/env bash
# Installs the Debian packages that are missing, configures with Ninja and
# builds. Idempotent and quiet when nothing is missing.
#   scripts/setup.sh            Release build in build/
#   scripts/setup.sh --asan     Debug build with AddressSanitizer + UBSan in build-asan/
#   scripts/setup.sh --debug    Debug build (phase invariants checked) in build-debug/
set -euo pipefail
cd "$(dirname "$0")/.."

build_type=Release
build_dir=build
sanitize=OFF
for arg in "$@"; do
  case "$arg" in
    --debug) build_type=Debug; build_dir=build-debug ;;
    --asan) build_type=Debug; build_dir=build-asan; sanitize=ON ;;
    *) echo "setup.sh: unknown option '$arg' (use --debug or --asan)" >&2; exit 2 ;;
  esac
done

packages=(cmake g++ ninja-build pkg-config
  qt6-base-dev qt6-base-dev-tools libqt6opengl6-dev qt6-svg-dev libvtk9-dev libosd-dev
  libcgal-dev libembree-dev libeigen3-dev libtbb-dev libcli11-dev nlohmann-json3-dev
  libsuitesparse-dev xvfb xauth libgl1-mesa-dri qt6-qpa-plugins fonts-dejavu-core)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing missing Debian packages: ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null; then sudo=sudo; else
      echo "setup: error: not root and no sudo; install as root: apt-get install ${missing[*]}" >&2; exit 1
    fi
  fi
  log=$(mktemp)
  if ! { $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq \
        --no-install-recommends "${missing[@]}"; } >"$log" 2>&1; then
    echo "setup: error: apt-get failed to install: ${missing[*]}" >&2
    tail -n 20 "$log" >&2
    echo "setup: (full apt log: $log)" >&2
    exit 1
  fi
  rm -f "$log"
fi

if [ ! -f "$build_dir/build.ninja" ]; then
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE="$build_type" \
    -DCONTOUR_SANITIZE="$sanitize" >"$build_dir.configure.log" 2>&1 || {
    echo "setup: error: cmake configure failed, see $build_dir.configure.log" >&2
    tail -n 30 "$build_dir.configure.log" >&2; exit 1; }
fi
# Two jobs: CGAL and VTK translation units need about 1.5 GiB each.
cmake --build "$build_dir" -- -j"$(nproc)" >"$build_dir.build.log" 2>&1 || {
  echo "setup: error: build failed, see $build_dir.build.log" >&2
  grep -E 'error|FAILED' "$build_dir.build.log" | head -n 30 >&2; exit 1; }
echo "setup: built $build_type in $build_dir/"
