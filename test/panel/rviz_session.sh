# Sourced by the rviz checks (rviz_check.sh, rviz_show_check.sh): an X server and a ROS master of
# their own, stopped on exit, a wait on conditions, and their JUnit testcases. Sets work (a temporary
# directory), pids (the processes to stop, in start order), DISPLAY, ROS_MASTER_URI and ROS_HOME.
work=$(mktemp -d)
pids=()
# A ROS home of their own: a runtime killed elsewhere leaves a recovery copy in the shared one,
# which the panel would offer here (a bar above the graph: another layout).
export ROS_HOME="$work/ros_home"

# Stops what was started, the last first: an interrupt, then a kill after 5 s.
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

# Starts Xvfb and roscore on a display and a master port nobody uses; fails, with why in `failure`,
# if either does not come up.
start_x_and_master() {
  local display=$((90 + $$ % 100)) port=$((12000 + $$ % 1000))
  while [ -e "/tmp/.X11-unix/X$display" ]; do display=$((display + 1)); done
  export DISPLAY=":$display" LIBGL_ALWAYS_SOFTWARE=1 ROS_MASTER_URI="http://localhost:$port"
  export XDG_RUNTIME_DIR="$work" ROSCONSOLE_STDOUT_LINE_BUFFERED=1
  Xvfb "$DISPLAY" -screen 0 1700x1000x24 -nolisten tcp >"$work/xvfb.log" 2>&1 &
  pids+=($!)
  roscore -p "$port" >"$work/roscore.log" 2>&1 &
  pids+=($!)
  if ! wait_for 30 test -e "/tmp/.X11-unix/X$display"; then failure="Xvfb did not start: $(tail -3 "$work/xvfb.log")"; return 1; fi
  wait_for 60 rosparam get /rosdistro || { failure="the ROS master did not start"; return 1; }
}

# What rviz (its log: $1) reported as errors, at most 5 lines.
rviz_errors() {
  grep -E "ERROR|PluginlibFactory|failed to load|Failed to load" "$1" 2>/dev/null | grep -v "media_export" | head -5
}

esc() { sed -e 's/&/\&amp;/g' -e 's/</\&lt;/g' -e 's/>/\&gt;/g' -e 's/"/\&quot;/g'; }
testcase() {  # NAME FAILURE-OR-EMPTY
  if [ -z "$2" ]; then printf '<testcase classname="Rviz" name="%s"/>' "$1"
  else printf '<testcase classname="Rviz" name="%s"><failure message="%s"/></testcase>' "$1" "$(printf '%s' "$2" | esc)"
  fi
}

# Ends a check: rviz's errors are the failure if nothing else failed; everything started is
# stopped; the folder of $result (the JUnit file) is made.
end_session() {
  local errors
  errors=$(rviz_errors "$work/rviz.log")
  if [ -z "$failure" ] && [ -n "$errors" ]; then failure="rviz reported errors: $errors"; fi
  cleanup
  trap - EXIT
  mkdir -p "$(dirname "$result")"
}
