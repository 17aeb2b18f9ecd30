#!/usr/bin/env bash
# Installs ContactLab's build, test and figure dependencies from Debian 12 packages (Highway
# for the vectorised field lookups, src/sdf/batch_distance; Bullet's extras for its convex
# decomposition, baselines/bullet/; with
# slurm-wlm and munge for the single-node Slurm cluster test, tests/slurm/; clang with its
# runtime libraries, which hold libFuzzer, for the fuzz targets, tests/fuzz/; cpp-httplib, three.js
# and Chromium for the 3D viewer and its browser tests, src/view/; OpenVDB for the reference
# field that cross-checks our field builder, baselines/reference/, and its benchmark; pybind11, pytest
# and pandas for the Python module, python/, and Hypothesis for its generated-argument tests;
# MkDocs with the Material theme for the documentation site, mkdocs.yml and docs/, built by the
# test Docs.MkdocsStrict). Does nothing when everything is present; uses sudo when not root.
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config git
  libeigen3-dev libtbb-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev zlib1g-dev
  libfcl-dev liboctomap-dev libccd-dev
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libbullet-dev libbullet-extras-dev
  libspectra-dev libnanoflann-dev libspnav-dev
  libhwy-dev libopenvdb-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  clang libclang-rt-14-dev
  python3 python3-numpy python3-matplotlib python3-yaml
  pybind11-dev python3-pybind11 python3-pytest python3-pandas python3-hypothesis
  libcpp-httplib-dev libjs-three chromium
  slurm-wlm munge
  mkdocs mkdocs-material
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
