#!/usr/bin/env bash
# The runtime as a nodelet, interrupted at random moments: N rounds of a manager, a `nodelet load`
# of apex/Runtime with the demo graph, and SIGINT (what roslaunch sends) to the loader or to the
# manager after 0 to 2 s (while the runtime loads, runs, or unloads). Counts what a robot's
# operator would see: an abort (SIGABRT or SIGSEGV, a core), a process alive 14 s after its SIGINT (roslaunch kills at 15)
# (or after its manager went), a manager that no longer answers after a loader was stopped.
# TOOLS: `apex` (the default: apex_nodelet_manager and apex_nodelet_load, as runtime.launch and
# docs/ros.md use them) or `nodelet` (Debian's `nodelet manager` and `nodelet load`: the manager crashes
# when stopped with a loader attached, whatever the nodelet, and a loader outlives its manager).
# Then CYCLES loads and unloads of the runtime with the demo graph in one manager: each load
# answers get_graph, each unload ends its loader, and the manager answers at the end.
#   nodelet_interrupts.sh RESULT_XML BAG [ROUNDS] [TOOLS] [CYCLES]   (with the devel space sourced)
set -u
source "$(dirname "$0")/junit.sh"  # xml_text
source "$(dirname "$0")/master.sh"
export PATH=/usr/bin:/bin:$PATH
out=$1 bag=$2 rounds=${3:-100} tools=${4:-apex} cycles=${5:-50}
if [ "$tools" = apex ]; then
  manager_command=(apex apex_nodelet_manager) load_command=(apex apex_nodelet_load)
else
  manager_command=(nodelet nodelet manager) load_command=(nodelet nodelet load)
fi
export ROS_HOME=${ROS_HOME:-$(mktemp -d)} ROSCONSOLE_STDOUT_LINE_BUFFERED=1
work=$(mktemp -d)
start_master "$work/roscore.log" || rounds=0 cycles=0  # (both cases fail with $master_failure)
all=()  # every process started: a timeout from outside must leave none behind (job control gives each its own group)
trap 'for p in "${all[@]}"; do kill -9 "$p" 2>/dev/null; done; kill -INT $core; wait $core 2>/dev/null' EXIT
rosparam set /apex/graph "$(rospack find apex)/graphs/demo.yaml"
rosparam set /apex/overrides "{bag: {file: '$bag', loop: true}}"

aborts=0 lingering=0 deaf=0 rounds_done=0
notes=()
# Starts a process that takes SIGINT as from a terminal or roslaunch (job control on: a background
# job of a script would ignore it); its pid in $started.
set -m
start() { local log=$1; shift; "$@" >"$log" 2>&1 & started=$!; all+=("$started"); }
# Whether process $1 is gone within $2 seconds; its exit status in $status.
gone_within() {
  local pid=$1 limit=$2
  timeout "$limit" tail --pid="$pid" -f /dev/null 2>/dev/null
  if kill -0 "$pid" 2>/dev/null; then return 1; fi
  wait "$pid" 2>/dev/null; status=$?
  return 0
}
crashed() { [ "$1" -eq 134 ] || [ "$1" -eq 139 ] || [ "$1" -eq 136 ]; }  # SIGABRT, SIGSEGV, SIGFPE
# expect_gone PID WHO WHEN: PID ends within 14 s (else counted, and killed: roslaunch would kill it
# after 15), and not by a crash. (It takes well under 2 s on a quiet machine; a hang never ends.)
expect_gone() {
  if ! gone_within "$1" 14; then
    lingering=$((lingering + 1)); notes+=("round $r: $2 lived on 14 s ($3)")
    kill -9 "$1"; wait "$1" 2>/dev/null
  elif crashed "$status"; then
    aborts=$((aborts + 1)); notes+=("round $r: $2 died with $status ($3)")
  fi
}

for ((r = 0; r < rounds; r++)); do
  start /dev/null rosrun "${manager_command[@]}" __name:=mgr
  manager=$started

  timeout 60 bash -c 'until rosservice list 2>/dev/null | grep -q /mgr/load_nodelet; do sleep 0.05; done'
  loader_log="$work/loader_$r.log"
  start "$loader_log" rosrun "${load_command[@]}" apex/Runtime mgr __name:=apex
  loader=$started
  delay=$(awk -v s="$RANDOM" 'BEGIN { srand(s); printf "%.2f", rand() * 2 }')
  sleep "$delay"
  stopped=$([ $((r % 2)) -eq 0 ] && echo loader || echo manager)
  if [ "$stopped" = loader ]; then  # the loader stopped: the runtime unloads, the manager stays
    kill -INT "$loader"
    expect_gone "$loader" "the loader" "SIGINT to it at $delay s"
    if ! timeout 30 rosnode ping -c 1 /mgr >/dev/null 2>&1; then  # (its XML-RPC answers; a Python tool: slow to start when loaded)
      deaf=$((deaf + 1)); notes+=("round $r: the manager did not answer after the loader went (SIGINT at $delay s)")
    fi
  fi
  kill -INT "$manager"  # the manager stopped: after its loader, or while the runtime loads or runs
  expect_gone "$manager" "the manager" "SIGINT to the $stopped at $delay s"
  if kill -0 "$loader" 2>/dev/null; then
    # A loader stopped before it reached the manager waits for one, as ROS's loaders do (launch
    # order is free): a SIGINT then ends it, at once.
    if [ "$tools" = apex ] && ! grep -q "loading nodelet" "$loader_log"; then
      sleep 0.5
      kill -INT "$loader"
    fi
    expect_gone "$loader" "the loader" "after its manager; SIGINT to the $stopped at $delay s"
  fi
  rounds_done=$((rounds_done + 1))
done

# One manager, the runtime loaded and unloaded again and again
start /dev/null rosrun "${manager_command[@]}" __name:=mgr
manager=$started
timeout 20 bash -c 'until rosservice list 2>/dev/null | grep -q /mgr/load_nodelet; do sleep 0.05; done'
cycles_done=0 cycle_failure=$master_failure
for ((c = 0; c < cycles; c++)); do
  [ -z "$cycle_failure" ] || break
  start "$work/cycle.log" rosrun "${load_command[@]}" apex/Runtime mgr __name:=apex
  loader=$started
  timeout 30 bash -c 'until rosservice call /apex/get_graph >/dev/null 2>&1; do sleep 0.1; done' ||
    cycle_failure="cycle $c: the runtime never answered get_graph"
  kill -INT "$loader"
  gone_within "$loader" 14 || { cycle_failure="${cycle_failure:-cycle $c: the loader lived on 14 s after SIGINT}"; kill -9 "$loader"; }
  timeout 30 bash -c 'while rosservice list 2>/dev/null | grep -q /apex/get_graph; do sleep 0.1; done' ||
    cycle_failure="${cycle_failure:-cycle $c: the runtime was not unloaded}"
  cycles_done=$((cycles_done + 1))
done
timeout 30 rosnode ping -c 1 /mgr >/dev/null 2>&1 || cycle_failure="${cycle_failure:-the manager did not answer after $cycles_done cycles}"
kill -INT "$manager"
if ! gone_within "$manager" 14; then
  cycle_failure="${cycle_failure:-the manager lived on 14 s after SIGINT}"; kill -9 "$manager"
elif crashed "$status"; then
  cycle_failure="${cycle_failure:-the manager died with $status after $cycles_done cycles}"
fi
echo "$cycles_done loads and unloads in one manager: ${cycle_failure:-OK}"

summary="$rounds_done rounds with ${tools}'s manager and loader: $aborts aborts, $lingering processes alive 14 s after they should have gone, $deaf managers deaf"
echo "$summary"
for n in "${notes[@]+"${notes[@]}"}"; do echo "  $n"; done
failure=$master_failure
[ $((aborts + lingering + deaf)) -eq 0 ] || failure="$summary; ${notes[*]:0:5}"
cases="  <testcase classname=\"NodeletInterrupts\" name=\"LoaderAndManagerInterruptedAtRandomMomentsExitCleanly\">"
cases+=$([ -z "$failure" ] || echo "<failure message=\"$(xml_text "$failure")\"/>")"</testcase>"
cases+=$'\n'"  <testcase classname=\"NodeletInterrupts\" name=\"TheRuntimeLoadedAndUnloadedManyTimesInOneManager\">"
cases+=$([ -z "$cycle_failure" ] || echo "<failure message=\"$(xml_text "$cycle_failure")\"/>")"</testcase>"
fails=$(( $([ -z "$failure" ] && echo 0 || echo 1) + $([ -z "$cycle_failure" ] && echo 0 || echo 1) ))
printf '<?xml version="1.0" encoding="UTF-8"?>\n<testsuite name="nodelet_interrupts" tests="2" failures="%d">\n%s\n</testsuite>\n' \
  "$fails" "$cases" >"$out"
[ -z "$failure" ] && [ -z "$cycle_failure" ]
