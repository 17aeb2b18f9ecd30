#!/usr/bin/env bash
# Regenerates data/meshes/*.gz from the full meshes of a source folder (default ../shared/data/meshes
# beside the checkout; see data/meshes/SOURCES.md). Most meshes are copied whole, gzip -9 without
# a timestamp (so the output is byte-for-byte reproducible); armadillo and stanford-bunny are
# first decimated with CGAL (scripts/data/decimate_mesh.cc, boundary edges kept).
#
#   ./scripts/make-mesh-data.sh [SOURCE_MESH_FOLDER]
set -euo pipefail
cd "$(dirname "$0")/.."
src=${1:-../shared/data/meshes}
out=data/meshes
if [ ! -d "$src" ]; then
  echo "make-mesh-data: no source folder $src" >&2
  exit 1
fi
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

whole=(dragon.obj bunny-watertight.obj bumpy-cube.obj knight.off screwdriver.off rocker-arm.obj fandisk.obj
       block.obj joint.obj spot.obj teapot.obj suzanne.obj)
for name in "${whole[@]}"; do
  gzip -9 -n -c "$src/$name" > "$tmp/$name.gz"
  mv "$tmp/$name.gz" "$out/$name.gz"
done

# name, target edge count: ~20,000 triangles (armadillo, closed) and ~16,000 (stanford-bunny, open).
g++ -O2 -std=c++17 -o "$tmp/decimate_mesh" scripts/data/decimate_mesh.cc -lgmp -lmpfr
decimated=("armadillo.obj 30000" "stanford-bunny.obj 24000")
for entry in "${decimated[@]}"; do
  read -r name edges <<<"$entry"
  "$tmp/decimate_mesh" "$src/$name" "$tmp/$name" "$edges"
  gzip -9 -n -c "$tmp/$name" > "$tmp/$name.gz"
  mv "$tmp/$name.gz" "$out/$name.gz"
done
du -cb "$out"/*.gz | tail -1
