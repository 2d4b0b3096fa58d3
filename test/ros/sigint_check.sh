#!/usr/bin/env bash
# Clean shutdown on SIGINT and on SIGTERM (what roslaunch, systemd and docker send):
# the runtime, with a graph running in two thread groups, exits 0 within 2 s,
# unregistered from the master. Writes a JUnit result with one case per signal.
#   sigint_check.sh RESULT_XML   (with the devel space sourced)
set -u
out=$1
port=$((20000 + RANDOM % 20000))
export ROS_MASTER_URI=http://localhost:$port ROS_HOME=${ROS_HOME:-$(mktemp -d)}
here=$(cd "$(dirname "$0")" && pwd)
declare -A failure

roscore -p "$port" >/dev/null 2>&1 &
core=$!

for sig in INT TERM; do
  failure[$sig]=""
  rosrun apex apex_runtime_node _graph:="$here/../data/clock_chain.yaml" >/dev/null 2>&1 &
  node=$!
  # (--wait gives up at once while the master itself is still starting: retry until answered)
  timeout 30 bash -c 'until rosservice call --wait /apex/get_graph >/dev/null 2>&1; do sleep 0.2; done' ||
    failure[$sig]="the runtime never answered /apex/get_graph"
  if [ -z "${failure[$sig]}" ]; then
    start=$(date +%s%N)
    kill -"$sig" "$node"
    timeout 10 tail --pid="$node" -s 0.02 -f /dev/null  # waits for the exit (checked every 20 ms), at most 10 s
    took_ms=$(( ($(date +%s%N) - start) / 1000000 ))
    if kill -0 "$node" 2>/dev/null; then
      failure[$sig]="still running 10 s after SIG$sig"
      kill -9 "$node"
    else
      wait "$node"; rc=$?
      if [ "$rc" -ne 0 ]; then
        failure[$sig]="exited with $rc after SIG$sig"
      elif [ "$took_ms" -gt 2000 ]; then
        failure[$sig]="took $took_ms ms to exit after SIG$sig (limit 2 s)"
      elif rosnode list 2>/dev/null | grep -qx /apex; then
        failure[$sig]="/apex is still registered with the master after SIG$sig"
      fi
    fi
    echo "SIG$sig: exited in $took_ms ms"
  fi
  kill -9 "$node" 2>/dev/null
  wait "$node" 2>/dev/null
done
kill -TERM "$core" 2>/dev/null  # a background roscore ignores SIGINT in a script
wait "$core" 2>/dev/null

failed=0
for sig in INT TERM; do [ -z "${failure[$sig]}" ] || failed=$((failed + 1)); done
mkdir -p "$(dirname "$out")"
{
  echo '<?xml version="1.0" encoding="UTF-8"?>'
  echo "<testsuite name=\"shutdown\" tests=\"2\" failures=\"$failed\">"
  for sig in INT TERM; do
    echo "  <testcase classname=\"Shutdown\" name=\"Sig${sig}StopsEveryThreadGroupAndExitsZeroWithin2s\">"
    [ -z "${failure[$sig]}" ] || echo "    <failure message=\"${failure[$sig]}\"/>"
    echo '  </testcase>'
  done
  echo '</testsuite>'
} >"$out"
[ "$failed" -eq 0 ] && echo "shutdown check: ok" || { echo "shutdown check: ${failure[INT]} ${failure[TERM]}"; exit 1; }
