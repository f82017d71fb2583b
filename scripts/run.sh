#!/usr/bin/env bash
# Installs what is missing, builds, and opens the workbench on a bundled
# sample. Without a display it runs the batch CLI on that sample instead and
# says where the output went.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
sample=samples/spot_control_mesh.obj
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  exec build/app/workbench/contour-workbench "$sample" "$@"
fi
out=out/run-$(date +%Y%m%d-%H%M%S)
mkdir -p "$out"
echo "run: no display (DISPLAY is not set): running the batch CLI on $sample instead"
# Under a virtual X server (setup.sh installs xvfb) the diagnostic snapshot
# also gets the workbench's two pictures.
xvfb=()
if command -v xvfb-run >/dev/null; then xvfb=(xvfb-run -a); fi
"${xvfb[@]}" build/app/batch/contour-batch --mesh "$sample" --method interpolated --surface auto \
  --svg "$out/spot_control_mesh.svg" --json "$out/spot_control_mesh.json" \
  --snapshot-dir "$out/snapshot" "$@"
echo "run: SVG written to $PWD/$out/spot_control_mesh.svg"
echo "run: JSON report written to $PWD/$out/spot_control_mesh.json"
echo "run: diagnostic snapshot (report, SVG, PLY, session, PNGs) written to $PWD/$out/snapshot/"
