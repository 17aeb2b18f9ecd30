# Progress of a suite of experiments (sourced by scripts/run.sh): one line per experiment with
# its share of the suite and an estimate of the time left, e.g.
#   [3/9] continuity-models (12% of the suite) ... est. 4 min left
# Plain lines, no cursor movement or colour, so a log or a pipe reads the same as a terminal.
#
# Where the numbers come from, and why: the configs' declared sizes (sweep points, models,
# cycles) do not tell what an experiment costs -- a 65536-point pointshell cycle costs hundreds of
# 256-point ones, the dense reference dwarfs the models it checks, and a cold cache adds field and
# pointshell builds -- so neither the shares nor the estimate are taken from them. Both come from
# measured wall time only:
#   - each experiment's weight is its wall time in the last run that finished it with the same
#     profile (TIMES file); one never timed weighs the mean of those that were, and with none
#     timed at all every experiment weighs the same (the share is then one of the count);
#   - the time left is the weight still to run, scaled by how this run's finished experiments
#     compared with their weights (elapsed / their weight); before any has finished it is the
#     last run's times as they are, and with no times at all there is no estimate yet.
#
# Use: suite_progress_begin TIMES PROFILE NAME...; then per experiment I (1-based)
# suite_progress_line I ELAPSED (ELAPSED: seconds since the suite began), and when it succeeded
# suite_progress_record I SECONDS; suite_progress_save writes the times (after each, or at the end).

# "45 s", "12 min", "2 h 05 min".
suite_progress_duration() {
  local s=$1 m=$(( ($1 + 30) / 60 ))
  if [ "$s" -lt 60 ]; then echo "$s s"
  elif [ "$m" -lt 60 ]; then echo "$m min"
  else printf '%d h %02d min\n' $(( m / 60 )) $(( m % 60 )); fi
}

# suite_progress_begin TIMES PROFILE NAME...: reads the last run's times of PROFILE from TIMES
# (lines "PROFILE<TAB>NAME<TAB>SECONDS"; a missing file is no times) and weighs the experiments.
suite_progress_begin() {
  _sp_times_file=$1; _sp_profile=$2; shift 2
  _sp_names=("$@")
  _sp_weights=()
  _sp_recorded=()      # seconds this run, for suite_progress_save; empty: not finished
  _sp_timed=0          # experiments with a time from the last run
  local name sum=0 known=() i
  for name in "${_sp_names[@]}"; do
    local t=""
    if [ -f "$_sp_times_file" ]; then
      t=$(awk -F'\t' -v p="$_sp_profile" -v n="$name" '$1 == p && $2 == n && $3 ~ /^[0-9]+$/ { t = $3 } END { print t }' \
          "$_sp_times_file")
    fi
    known+=("$t")
    if [ -n "$t" ]; then sum=$(( sum + (t > 0 ? t : 1) )); _sp_timed=$(( _sp_timed + 1 )); fi
  done
  local mean=1
  if [ "$_sp_timed" -gt 0 ]; then mean=$(( (sum + _sp_timed / 2) / _sp_timed )); fi
  if [ "$mean" -le 0 ]; then mean=1; fi
  for i in "${!_sp_names[@]}"; do
    local w=${known[$i]}
    if [ -z "$w" ]; then w=$mean; fi
    if [ "$w" -le 0 ]; then w=1; fi
    _sp_weights+=("$w")
    _sp_recorded+=("")
  done
}

# suite_progress_line I ELAPSED: the line for experiment I (1-based) about to run, ELAPSED
# seconds after the suite began (the experiments before I have run, each finished or failed).
suite_progress_line() {
  local i=$1 elapsed=$2 n=${#_sp_names[@]} total=0 done_weight=0 left_weight=0 k
  for k in "${!_sp_weights[@]}"; do
    total=$(( total + _sp_weights[k] ))
    if [ "$k" -lt $(( i - 1 )) ]; then done_weight=$(( done_weight + _sp_weights[k] ))
    else left_weight=$(( left_weight + _sp_weights[k] )); fi
  done
  local share=$(( (100 * _sp_weights[i - 1] + total / 2) / total ))
  local what="% of the suite"
  if [ "$_sp_timed" -eq 0 ]; then what="% of the suite by count"; fi
  local est
  if [ "$i" -gt 1 ] && [ "$done_weight" -gt 0 ] && [ "$elapsed" -gt 0 ]; then
    est="est. $(suite_progress_duration $(( (elapsed * left_weight + done_weight / 2) / done_weight ))) left"
  elif [ "$_sp_timed" -gt 0 ]; then
    est="est. $(suite_progress_duration "$left_weight") left (last run's times)"
  else
    est="no estimate before the first experiment finishes"
  fi
  echo "[$i/$n] ${_sp_names[i - 1]} ($share$what) ... $est"
}

# suite_progress_record I SECONDS: experiment I finished in SECONDS.
suite_progress_record() { _sp_recorded[$(( $1 - 1 ))]=$2; }

# suite_progress_save: writes this run's times into TIMES, keeping every other line.
suite_progress_save() {
  local tmp="$_sp_times_file.tmp.$$" i finished=""
  for i in "${!_sp_names[@]}"; do
    if [ -n "${_sp_recorded[i]}" ]; then finished+="${_sp_names[i]} "; fi
  done
  mkdir -p "$(dirname "$_sp_times_file")"
  {
    if [ -f "$_sp_times_file" ]; then
      awk -F'\t' -v p="$_sp_profile" -v names="$finished" '
        BEGIN { n = split(names, a, " "); for (k = 1; k <= n; ++k) skip[a[k]] = 1 }
        !($1 == p && ($2 in skip))' "$_sp_times_file"
    fi
    for i in "${!_sp_names[@]}"; do
      if [ -n "${_sp_recorded[i]}" ]; then printf '%s\t%s\t%s\n' "$_sp_profile" "${_sp_names[i]}" "${_sp_recorded[i]}"; fi
    done
  } > "$tmp"
  mv "$tmp" "$_sp_times_file"
}
