#!/usr/bin/env bash
# scripts/suite-progress.sh, the progress lines of scripts/run.sh: the share and the estimate
# with no times recorded (by count; no estimate before the first finishes, then from elapsed
# time), with the last run's times (shares by time, the estimate scaled by this run's pace), an
# experiment never timed, and the times file written back without losing other profiles' lines.
# Usage: suite_progress_test.sh SCRIPTS_DIR WORKDIR
set -euo pipefail
scripts=$1; work=$2
rm -rf "$work" && mkdir -p "$work"
source "$scripts/suite-progress.sh"

status=0
expect() {  # expect WHAT ACTUAL EXPECTED
  if [ "$2" != "$3" ]; then
    echo "FAILED: $1"; echo "  got:      $2"; echo "  expected: $3"; status=1
  else
    echo "ok: $2"
  fi
}

times=$work/times.tsv

# No times recorded: shares by count, no estimate before the first experiment finishes, then
# elapsed per finished experiment times those left.
suite_progress_begin "$times" default a b c d
expect "first line, no times" "$(suite_progress_line 1 0)" \
  "[1/4] a (25% of the suite by count) ... no estimate before the first experiment finishes"
expect "second line, no times" "$(suite_progress_line 2 120)" "[2/4] b (25% of the suite by count) ... est. 6 min left"
suite_progress_record 1 120
suite_progress_record 2 60
suite_progress_record 4 20   # c failed: not recorded
suite_progress_save
expect "times written" "$(cat "$times")" "$(printf 'default\ta\t120\ndefault\tb\t60\ndefault\td\t20')"

# The next run: shares by the recorded times (c never timed weighs their mean, 67 s), the first
# estimate the last run's times as they are, later ones scaled by this run's pace (here twice as
# fast: a took 60 s against 120).
printf 'paper\ta\t5000\n' >> "$times"
suite_progress_begin "$times" default a b c d
expect "first line, timed" "$(suite_progress_line 1 0)" "[1/4] a (45% of the suite) ... est. 4 min left (last run's times)"
expect "second line, timed" "$(suite_progress_line 2 60)" "[2/4] b (22% of the suite) ... est. 1 min left"
expect "third line, timed" "$(suite_progress_line 3 90)" "[3/4] c (25% of the suite) ... est. 44 s left"
# Another profile's times are its own; long estimates read in hours.
suite_progress_begin "$times" paper a b
expect "paper profile" "$(suite_progress_line 1 0)" "[1/2] a (50% of the suite) ... est. 2 h 47 min left (last run's times)"
suite_progress_record 2 7
suite_progress_save
expect "other lines kept" "$(sort "$times" | tr '\t' ' ' | tr '\n' ';')" \
  "default a 120;default b 60;default d 20;paper a 5000;paper b 7;"

# Under `set -euo pipefail`, as scripts/run.sh runs them, none of the functions fails (a new
# shell: `set -e` is off inside a subshell that is part of a || list).
sete=$(bash -euo pipefail -c 'source "$1/suite-progress.sh"; suite_progress_begin "$2/none.tsv" default x y
  suite_progress_line 1 0 > /dev/null; suite_progress_record 1 3; suite_progress_line 2 3 > /dev/null
  suite_progress_save; echo fine' sete "$scripts" "$work" 2>&1 || true)
expect "set -e" "$(echo "$sete" | tail -1)" "fine"
exit $status
