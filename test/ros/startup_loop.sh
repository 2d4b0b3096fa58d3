#!/usr/bin/env bash
# Start-up without races: the runtime starts with the demo graph (BagReader opening
# its bag while the image nodes set up image_transport on other thread groups, all
# through pluginlib) and is stopped again, N times in a row (default 50); each
# start must reach its first overlay frame and exit 0. Writes a JUnit result.
#   startup_loop.sh RESULT_XML BAG [N]   (with the devel space sourced)
set -u
source "$(dirname "$0")/junit.sh"
source "$(dirname "$0")/master.sh"
out=$1 bag=$2 rounds=${3:-50}
export ROS_HOME=${ROS_HOME:-$(mktemp -d)}
graph=$(rospack find apex)/graphs/paper_pipeline.yaml
failure=""
# why LOG: the line of a log that tells why the runtime stopped (a crash's own line), else its last
why() { grep -m1 -E 'terminate|Segmentation|Assertion|Aborted|free\(\)|unload|No plugins' "$1" || tail -n 1 "$1"; }

start_master "$ROS_HOME/roscore.log" || failure=$master_failure
rosparam set /apex/graph "$graph"
rosparam set /apex/overrides "{bag: {file: '$bag', loop: true, rate: 0.0}}"

for ((i = 1; i <= rounds && ${#failure} == 0; i++)); do
  log="$ROS_HOME/startup_$i.log"
  rosrun apex apex_runtime_node >"$log" 2>&1 &
  node=$!
  if ! timeout 30 rostopic echo -n 1 --noarr /apex_demo/overlay >/dev/null 2>&1; then
    failure="start $i: no overlay frame within 30 s ($(why "$log"))"
  fi
  kill -INT "$node" 2>/dev/null
  timeout 10 tail --pid="$node" -s 0.02 -f /dev/null
  if kill -0 "$node" 2>/dev/null; then
    [ -n "$failure" ] || failure="start $i: still running 10 s after SIGINT"
    kill -9 "$node"
  fi
  wait "$node"; rc=$?
  [ -n "$failure" ] || [ "$rc" -eq 0 ] || failure="start $i: exited with $rc ($(why "$log"))"
done
kill -TERM "$core" 2>/dev/null
wait "$core" 2>/dev/null

junit_result "$out" startup_loop Startup "TheDemoGraphStarts${rounds}TimesWithoutACrash" "$failure"
[ -z "$failure" ] && echo "startup loop: $rounds starts, ok" || { echo "startup loop: $failure"; exit 1; }
