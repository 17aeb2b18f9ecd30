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
               speed-vs-error compare-volume baseline-settings analytic-cases asymmetry-models tessellation hard-cases-medial-axis hard-cases-tube-peg hard-cases-tunnelling
               scale-points scale-resolution closed-loop-rate fig03-hoses)
fi

# One progress line per experiment on stderr: its share of the suite and the time left, both from
# measured wall times (scripts/suite-progress.sh says why not from the configs' sizes), kept per
# profile in results/.suite-times.tsv (written after each experiment that succeeds).
source scripts/suite-progress.sh
suite_progress_begin results/.suite-times.tsv "${profile[1]:-default}" "${experiments[@]}"

failed=()
start=$(date +%s)
index=0
for name in "${experiments[@]}"; do
  index=$(( index + 1 ))
  config="experiments/$name.yaml"
  if [ ! -f "$config" ]; then
    echo "run: no experiment config $config" >&2
    failed+=("$name")
    continue
  fi
  suite_progress_line "$index" $(( $(date +%s) - start )) >&2
  began=$(date +%s)
  if ./build/bin/contactlab run "$config" --out "results/$name" "${profile[@]}"; then
    suite_progress_record "$index" $(( $(date +%s) - began ))
    suite_progress_save  # now, so that an interrupted suite keeps the times it measured
  else
    failed+=("$name")
  fi
done
/usr/bin/python3 scripts/make_figures.py --results results
echo "run: $(( $(date +%s) - start )) s; results in results/<experiment>/ (cycles.csv, summary.csv, convergence.csv, meta.json), figures in results/figures/"
if [ ${#failed[@]} -gt 0 ]; then
  echo "run: these experiments failed: ${failed[*]}" >&2
  exit 1
fi
