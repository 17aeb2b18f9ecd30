#!/usr/bin/env bash
# The main job: installs what is missing, builds Release, runs the default experiment suite
# (experiments/*.yaml, sized to finish in about ten minutes on two cores) and makes every
# figure into results/figures/.
#
#   ./scripts/run.sh            default suite
#   ./scripts/run.sh --paper    paper-scale versions (the configs' "paper" profiles; hours)
#   ./scripts/run.sh fig05b-convergence table1-statistics   only these experiments
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh

profile=()
experiments=()
for arg in "$@"; do
  case "$arg" in
    --paper) profile=(--profile paper) ;;
    -h|--help) sed -n '2,8p' "$0"; exit 0 ;;
    *) experiments+=("$arg") ;;
  esac
done
if [ ${#experiments[@]} -eq 0 ]; then
  experiments=(fig05b-convergence convergence-eq2 fig10-deformed-field fig14b-bumps fig15-asymmetry fig11-degradation
               table1-statistics table1-deformable table1-defo-defo deformable-cantilever continuity-models
               speed-vs-error compare-volume analytic-cases asymmetry-models tessellation hard-cases-medial-axis hard-cases-tube-peg hard-cases-tunnelling
               scale-points scale-resolution)
fi

failed=()
start=$(date +%s)
for name in "${experiments[@]}"; do
  config="experiments/$name.yaml"
  if [ ! -f "$config" ]; then
    echo "run: no experiment config $config" >&2
    failed+=("$name")
    continue
  fi
  echo "=== $name"
  if ! ./build/bin/contactlab run "$config" --out "results/$name" "${profile[@]}"; then
    failed+=("$name")
  fi
done
/usr/bin/python3 scripts/make_figures.py --results results
echo "run: $(( $(date +%s) - start )) s; results in results/<experiment>/ (cycles.csv, summary.csv, convergence.csv, meta.json), figures in results/figures/"
if [ ${#failed[@]} -gt 0 ]; then
  echo "run: these experiments failed: ${failed[*]}" >&2
  exit 1
fi
