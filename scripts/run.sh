#!/usr/bin/env bash
# The main job: installs what is missing, builds Release, and builds the signed distance
# field of a real mesh, printing its summary and where the field went.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
out=${OUT:-results/run}
mkdir -p "$out"
mesh=${MESH:-dragon.obj}
resolution=${RESOLUTION:-128}
./build/bin/contactlab mesh-info "$mesh"
./build/bin/contactlab sdf "$mesh" --resolution "$resolution" --out "$out/field.sdf"
echo "run: the distance field of $mesh is in $out/field.sdf"
