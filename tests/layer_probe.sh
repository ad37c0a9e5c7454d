#!/usr/bin/env bash
# Builds the layer probes of tests/CMakeLists.txt: the include of sim/renderer.hpp must compile
# where sewer3d_sim is linked and fail, for want of the header, in io and triangulate.
set -uo pipefail
build=$1
log=$(mktemp)
trap 'rm -f "$log"' EXIT
if ! cmake --build "$build" --target layer_probe_sim >"$log" 2>&1; then
  cat "$log"
  echo "FAILED: the probe does not compile even where sewer3d_sim is linked"
  exit 1
fi
echo "ok: sim/renderer.hpp compiles in a target linking sewer3d_sim"
for module in io triangulate; do
  if cmake --build "$build" --target "layer_probe_$module" >"$log" 2>&1; then
    echo "FAILED: sim/renderer.hpp compiles in a target linking sewer3d_$module"
    exit 1
  fi
  if ! grep -q "sewer3d/sim/renderer.hpp: No such file" "$log"; then
    cat "$log"
    echo "FAILED: layer_probe_$module failed for another reason than the missing header"
    exit 1
  fi
  echo "ok: sewer3d_$module cannot include sim/renderer.hpp (the build stops: no such file)"
done
