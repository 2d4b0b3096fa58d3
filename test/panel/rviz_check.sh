#!/usr/bin/env bash
# The real rviz, under Xvfb, opens an rviz config (launch/apex_panel.rviz) against a
# runtime playing a graph (graphs/demo.yaml) on a bag: the panel plugin loads
# without errors, shows the graph and the runtime's timing. Writes a JUnit result
# and a screenshot.
#   rviz_check.sh RESULT_XML SCREENSHOT_PNG BAG [GRAPH CONFIG [NAME]]
# Needs the devel space sourced; starts (and stops) its own X server and master.
set -uo pipefail
result=$1 shot=$2 bag=$3
root=$(cd "$(dirname "$0")/../.." && pwd)
graph=${4:-$root/graphs/demo.yaml} config=${5:-$root/launch/apex_panel.rviz} name=${6:-PanelLoadsAndShowsTheDemoGraph}
work=$(mktemp -d)
pids=()
failure=""

cleanup() {
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill -INT "${pids[i]}" 2>/dev/null; done
  for p in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$p" 2>/dev/null
  done
}
trap cleanup EXIT

# Waits until a command succeeds (every 0.2 s), at most $1 seconds.
wait_for() {
  local limit=$1; shift
  local end=$((SECONDS + limit))
  until "$@" >/dev/null 2>&1; do
    [ $SECONDS -lt $end ] || return 1
    sleep 0.2
  done
}

# A display and a master port nobody uses.
display=$((90 + $$ % 100))
while [ -e "/tmp/.X11-unix/X$display" ]; do display=$((display + 1)); done
port=$((12000 + $$ % 1000))
export DISPLAY=":$display" LIBGL_ALWAYS_SOFTWARE=1 ROS_MASTER_URI="http://localhost:$port"
export XDG_RUNTIME_DIR="$work" ROSCONSOLE_STDOUT_LINE_BUFFERED=1

Xvfb "$DISPLAY" -screen 0 1700x1000x24 -nolisten tcp >"$work/xvfb.log" 2>&1 &
pids+=($!)
roscore -p "$port" >"$work/roscore.log" 2>&1 &
pids+=($!)
if ! wait_for 30 test -e "/tmp/.X11-unix/X$display"; then failure="Xvfb did not start: $(tail -3 "$work/xvfb.log")"
elif ! wait_for 60 rosparam get /rosdistro; then failure="the ROS master did not start"
else
  rosparam set /apex/overrides "{bag: {file: '$bag', loop: true}}"
  rosrun apex apex_runtime_node __name:=apex _graph:="$graph" >"$work/runtime.log" 2>&1 &
  pids+=($!)
  rosrun rviz rviz -d "$config" >"$work/rviz.log" 2>&1 &
  pids+=($!)
  if ! wait_for 120 grep -q "GraphPanel: showing the graph of /apex" "$work/rviz.log"; then
    failure="the panel did not show the graph of /apex"
  elif ! wait_for 30 grep -q "GraphPanel: timing shown" "$work/rviz.log"; then
    failure="the panel did not show the runtime's status"
  fi
  sleep 1  # one more frame drawn by the X server before the picture (nothing to wait on)
  import -display "$DISPLAY" -window root "$shot" 2>"$work/import.log" || failure="${failure:-no screenshot: $(cat "$work/import.log")}"
fi
errors=$(grep -E "ERROR|PluginlibFactory|failed to load|Failed to load" "$work/rviz.log" | grep -v "media_export" | head -5)
[ -z "$failure" ] && [ -n "$errors" ] && failure="rviz reported errors: $errors"

cleanup
trap - EXIT
esc() { sed -e 's/&/\&amp;/g' -e 's/</\&lt;/g' -e 's/>/\&gt;/g' -e 's/"/\&quot;/g'; }
mkdir -p "$(dirname "$result")"
if [ -z "$failure" ]; then
  echo "rviz check: ok (screenshot $shot)"
  printf '<testsuite name="rviz" tests="1" failures="0"><testcase classname="Rviz" name="%s"/></testsuite>\n' "$name" >"$result"
else
  echo "rviz check: FAILED: $failure"
  tail -20 "$work/rviz.log"
  msg=$(printf '%s' "$failure" | esc)
  printf '<testsuite name="rviz" tests="1" failures="1"><testcase classname="Rviz" name="%s"><failure message="%s"/></testcase></testsuite>\n' "$name" "$msg" >"$result"
fi
rm -rf "$work"
[ -z "$failure" ]
