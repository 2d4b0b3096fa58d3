#!/usr/bin/env bash
# Clean shutdown on SIGINT: the runtime, with a graph running in two thread
# groups, exits 0 within 10 s and leaves nothing running. Writes a JUnit result.
#   sigint_check.sh RESULT_XML   (with the devel space sourced)
set -u
out=$1
port=$((20000 + RANDOM % 20000))
export ROS_MASTER_URI=http://localhost:$port ROS_HOME=${ROS_HOME:-$(mktemp -d)}
here=$(cd "$(dirname "$0")" && pwd)
failure=""

roscore -p "$port" >/dev/null 2>&1 &
core=$!
rosrun apex apex_runtime_node _graph:="$here/../data/clock_chain.yaml" >/dev/null 2>&1 &
node=$!
# (--wait gives up at once while the master itself is still starting: retry until answered)
timeout 30 bash -c 'until rosservice call --wait /apex/get_graph >/dev/null 2>&1; do sleep 0.2; done' ||
  failure="the runtime never answered /apex/get_graph"

if [ -z "$failure" ]; then
  kill -INT "$node"
  timeout 10 tail --pid="$node" -f /dev/null  # waits for the exit, at most 10 s
  if kill -0 "$node" 2>/dev/null; then
    failure="still running 10 s after SIGINT"
    kill -9 "$node"
  else
    wait "$node"; rc=$?
    [ "$rc" -eq 0 ] || failure="exited with $rc after SIGINT"
  fi
fi
kill -9 "$node" 2>/dev/null
kill -TERM "$core" 2>/dev/null  # a background roscore ignores SIGINT in a script
wait "$core" 2>/dev/null

mkdir -p "$(dirname "$out")"
{
  echo '<?xml version="1.0" encoding="UTF-8"?>'
  echo "<testsuite name=\"sigint\" tests=\"1\" failures=\"$([ -z "$failure" ] && echo 0 || echo 1)\">"
  echo '  <testcase classname="Shutdown" name="SigintStopsEveryThreadGroupAndExitsZero">'
  [ -z "$failure" ] || echo "    <failure message=\"$failure\"/>"
  echo '  </testcase>'
  echo '</testsuite>'
} >"$out"
[ -z "$failure" ] && echo "sigint check: ok" || { echo "sigint check: $failure"; exit 1; }
