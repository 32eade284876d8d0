# Step timing for .ci/run (sourced): `step NAME` ends the step before and starts NAME; jobs
# started with `background NAME CMD...` run beside the steps and are joined with `join NAME`.
# On exit, for any reason, a table of every step's and job's wall time is printed, so the next
# change that slows CI shows where.

ci_t0=$(date +%s)
ci_logs=$(mktemp -d)
ci_rows=()
ci_step=""
ci_step_t0=$ci_t0

# ci_cpu: "busy total" jiffies of all cores from /proc/stat, so each step's row can show how
# busy the cores were: a step well under 100% leaves a core for work that could run beside it.
ci_cpu() {
  local _cpu user nice system idle iowait rest
  read -r _cpu user nice system idle iowait rest </proc/stat
  local irq softirq steal
  read -r irq softirq steal _ <<<"$rest"
  local busy=$((user + nice + system + irq + softirq + steal))
  echo "$busy $((busy + idle + iowait))"
}
ci_step_cpu=$(ci_cpu)
declare -A ci_job_pid ci_job_t0

ci_close_step() {
  local now cpu busy b0 t0 b1 t1
  now=$(date +%s)
  cpu=$(ci_cpu)
  read -r b0 t0 <<<"$ci_step_cpu"
  read -r b1 t1 <<<"$cpu"
  busy=$(( t1 > t0 ? 100 * (b1 - b0) / (t1 - t0) : 0 ))
  [ -n "$ci_step" ] && ci_rows+=("$ci_step|$((now - ci_step_t0))|${busy}%")
  ci_step=""
  ci_step_t0=$now
  ci_step_cpu=$cpu
}

step() {
  ci_close_step
  ci_step="$1"
  echo "== $1"
}

# background NAME COMMAND...: runs COMMAND with its output in a log of its own; `join NAME`
# waits for it, prints that log, and fails the run if the job failed.
background() {
  local name=$1
  shift
  ci_job_t0[$name]=$(date +%s)
  # The job notes its own end, so the table shows how long it ran, not when it was joined.
  ( rc=0; "$@" || rc=$?; date +%s >"$ci_logs/$name.end"; exit "$rc" ) >"$ci_logs/$name.log" 2>&1 &
  ci_job_pid[$name]=$!
  echo "== started in the background: $name"
}

join() {
  local name=$1 rc=0 t0 waited
  t0=$(date +%s)
  wait "${ci_job_pid[$name]}" || rc=$?
  waited=$(($(date +%s) - t0))
  ci_rows+=("  $name (background; waited ${waited} s)|$(($(cat "$ci_logs/$name.end") - ci_job_t0[$name]))|")
  echo "== $name (background job, exit $rc):"
  sed 's/^/   | /' "$ci_logs/$name.log" | tail -n 40
  [ "$rc" -eq 0 ] || { echo "background job $name failed"; return "$rc"; }
}

# ci_table [EXIT_STATUS]: the table, ending with the run's exit status (the last command's if
# none is given); returns that status.
ci_table() {
  local rc=${1:-$?}
  ci_close_step
  local total=$(($(date +%s) - ci_t0)) row
  echo
  echo "== CI step times (wall clock, $(nproc) cores; busy: the share of all cores in use)"
  printf '%-60s %8s %6s\n' "step" "seconds" "busy"
  local name secs busy
  for row in "${ci_rows[@]}"; do
    IFS='|' read -r name secs busy <<<"$row"
    printf '%-60s %8s %6s\n' "$name" "$secs" "$busy"
  done
  printf '%-60s %8s  (%d min %02d s, exit %d)\n' "total" "$total" $((total / 60)) $((total % 60)) "$rc"
  [ -d target ] && echo "target/: $(du -sh target 2>/dev/null | cut -f1)"
  rm -rf "$ci_logs"
  return "$rc"
}
