#!/usr/bin/env bash
# The ROS master restarted while the demo loops (roscore stopped and started again on its port, as
# on a robot): after the new master (in ~1-2 s; printed, and bounded by 60 s) the runtime answers get_graph, ~graph is latched
# again, a new subscriber gets the overlay, dynparam reads a node's parameters and rosparam its
# values; and a subscriber from before the restart kept getting overlays while no master ran.
# Once with the runtime as a node and roscore restarted; once as a nodelet in a manager and a bare
# rosmaster in its place (no run id: the runtime sees its registration lost). Writes a JUnit result.
#   master_restart.sh RESULT_XML BAG   (with the devel space sourced)
set -u
source "$(dirname "$0")/junit.sh"  # xml_text
source "$(dirname "$0")/master.sh"
export PATH=/usr/bin:/bin:$PATH  # dynparam needs Debian's python3
out=$1 bag=$2
port=$(free_port)
export ROS_MASTER_URI=http://localhost:$port ROS_HOME=${ROS_HOME:-$(mktemp -d)}
work=$(mktemp -d)
cases=() failures=()
pids=()

stop_all() {
  for p in "${pids[@]}"; do kill -INT "$p" 2>/dev/null; done
  for p in "${pids[@]}"; do timeout 15 tail --pid="$p" -f /dev/null; kill -9 "$p" 2>/dev/null; done
  pids=()
}
trap stop_all EXIT

master_on_port() {  # [bare]: roscore (or a bare rosmaster: no /run_id, no rosout) on $port; fails if not up within 30 s
  if [ "${1:-}" = bare ]; then
    rosmaster --core -p "$port" >>"$work/roscore.log" 2>&1 &
  else
    roscore -p "$port" >>"$work/roscore.log" 2>&1 &
  fi
  core=$!
  pids+=("$core")
  timeout 30 bash -c 'until rosparam list >/dev/null 2>&1; do sleep 0.1; done'
}

# Milliseconds until a command succeeds (tried every 0.1 s), at most $1 seconds; fails if it never did.
ms_until() {
  local limit=$1 start=$(date +%s%N)
  shift
  timeout "$limit" bash -c "until $* >/dev/null 2>&1; do sleep 0.1; done" || return 1
  echo $(( ($(date +%s%N) - start) / 1000000 ))
}

# check NAME MASTER [MANAGER]: the demo in a runtime (in MANAGER's nodelet manager if given), the
# master restarted as MASTER (roscore, or bare: a rosmaster without the run id roscore sets).
check() {
  local name=$1 restart=$2 manager=${3:-} failure="" log="$work/$1.log"
  cases+=("$name")
  master_on_port || failure="the first master did not come up"
  if [ -n "$manager" ]; then
    rosrun apex apex_nodelet_manager __name:="$manager" >"$work/$name.manager.log" 2>&1 &
    pids+=($!)
  fi
  roslaunch apex runtime.launch graph:="$(rospack find apex)/graphs/demo.yaml" bag:="$bag" loop:=true \
    manager:="$manager" >"$log" 2>&1 &
  pids+=($!)
  ms_until 60 rosservice call /apex/get_graph >/dev/null || failure="the runtime never answered get_graph"
  local before="$work/$name.before"
  PYTHONUNBUFFERED=1 rostopic echo -p /apex_demo/overlay/header/seq >"$before" 2>/dev/null &  # (unbuffered: counted as they come)
  pids+=($!)
  ms_until 30 "[ \$(wc -l <'$before') -gt 2 ]" >/dev/null || failure="${failure:-no overlay before the restart}"

  kill -INT "$core"  # the master goes, and with it every registration
  timeout 15 tail --pid="$core" -f /dev/null || kill -9 "$core"
  local gone=$(wc -l <"$before")
  ms_until 60 "[ \$(wc -l <'$before') -gt $((gone + 5)) ]" >/dev/null ||
    failure="${failure:-no overlay reached the subscriber while no master ran}"

  master_on_port "$restart" || failure="${failure:-the new master did not come up}"
  local took
  # (deadlines that only bound a hang: the times are printed; a loaded machine takes longer)
  took=$(ms_until 60 rosservice call /apex/get_graph) || failure="${failure:-get_graph unanswered 60 s after the new master}"
  timeout 60 rostopic echo -n 1 /apex/graph/revision >/dev/null 2>&1 || failure="${failure:-~graph is not latched again}"
  timeout 60 rostopic echo -n 1 /apex_demo/overlay/header >/dev/null 2>&1 || failure="${failure:-a new subscriber got no overlay}"
  timeout 60 rosrun dynamic_reconfigure dynparam get /apex/camera_detector/threshold 2>&1 | grep -q block_size ||
    failure="${failure:-dynparam cannot read camera_detector/threshold}"
  ms_until 60 rosparam get /apex/nodes/camera_detector/threshold/c >/dev/null ||
    failure="${failure:-the parameter values are not on the server of the new master}"
  grep -q "a new ROS master" "$log" "$work/$name.manager.log" 2>/dev/null || failure="${failure:-the runtime did not say it registered again}"
  echo "$name: get_graph answered ${took:-never} ms after the new master was up; ${failure:-OK}"
  failures+=("$failure")
  stop_all
}

check node roscore
check nodelet bare apex_manager

{
  echo '<?xml version="1.0" encoding="UTF-8"?>'
  n=0; for f in "${failures[@]}"; do [ -z "$f" ] || n=$((n + 1)); done
  echo "<testsuite name=\"master_restart\" tests=\"${#cases[@]}\" failures=\"$n\">"
  for i in "${!cases[@]}"; do
    echo "  <testcase classname=\"MasterRestart\" name=\"${cases[i]}\">"
    [ -z "${failures[i]}" ] || echo "    <failure message=\"$(xml_text "${failures[i]}")\"/>"
    echo "  </testcase>"
  done
  echo '</testsuite>'
} >"$out"
for f in "${failures[@]}"; do [ -z "$f" ] || exit 1; done
