#!/usr/bin/env bash
# The real rviz, under Xvfb, opens an rviz config (launch/apex_panel.rviz) against a
# runtime playing a graph (graphs/demo.yaml) on a bag: the panel plugin loads
# without errors, shows the graph and the runtime's timing; and the config's layout
# leaves rviz's 3D view at least half of the window (test/panel/rviz_layout.py
# measures it: the render window, found by the view's background colour). Writes a
# JUnit result (NAME, NAME_3DViewKeepsHalfTheWindow) and a screenshot.
#   rviz_check.sh RESULT_XML SCREENSHOT_PNG BAG [GRAPH CONFIG [NAME]]
#   APEX_RVIZ_UNDOCK_SHOT=PNG   also undock the panel (a double-click on its title bar),
#                               screenshot it floating into PNG, and dock it back
#   APEX_RVIZ_WHOLE_WINDOW=1    also press Ctrl+M on the canvas: the editor over the whole window
#                               (screenshot *_whole_window.png), and again: rviz's layout back
# Needs the devel space sourced; starts (and stops) its own X server and master.
set -uo pipefail
result=$1 shot=$2 bag=$3
root=$(cd "$(dirname "$0")/../.." && pwd)
graph=${4:-$root/graphs/demo.yaml} config=${5:-$root/launch/apex_panel.rviz} name=${6:-PanelLoadsAndShowsTheDemoGraph}
failure=""
layout_failure=""
layout="the layout was not measured"
source "$root/test/panel/rviz_session.sh"

# The share of rviz's window that its 3D view has in the screenshot (rviz_layout.py measure),
# with the config's background colour (rviz's default: 48; 48; 48).
background=$(sed -n 's/^ *Background Color: *\([0-9]*\); *\([0-9]*\); *\([0-9]*\).*/\1,\2,\3/p' "$config" | head -1)
background=${background:-48,48,48}
measure_layout() {
  if ! layout=$(python3 "$root/test/panel/rviz_layout.py" measure "$shot" --windows "$work/windows.txt" \
                  --background "$background" --name "${config#"$root"/}" 2>&1); then
    layout_failure=$(printf '%s' "$layout" | tail -1)
  fi
  echo "rviz check: $layout" | head -1
}

# Undocks the panel by a double-click on its title bar (just below the 3D view), screenshots
# it floating, docks it back the same way; the panel must be a window of its own in between,
# and back in rviz's window afterwards, where it was (the 3D view measured again, screenshot
# beside: *_docked_again.png), with rviz still running.
undock_and_back() {
  local geometry x y w h floating
  geometry=$(printf '%s' "$layout" | head -1 | sed -n 's/.* is \([0-9]*\)x\([0-9]*\) at +\([0-9]*\)+\([0-9]*\),.*/\1 \2 \3 \4/p')
  read -r w h x y <<<"$geometry"
  if [ -z "$geometry" ]; then layout_failure="undock: the 3D view was not found"; return; fi
  python3 "$root/test/panel/rviz_layout.py" click 300 $((y + h + 16)) --double
  floats() { xwininfo -root -tree >"$work/undocked.txt" 2>&1 &&
             python3 "$root/test/panel/rviz_layout.py" window "APEX graph" --windows "$work/undocked.txt"; }
  wait_for 10 floats  # the panel a window of its own
  if ! floating=$(floats); then
    layout_failure="undock: a double-click on the panel's title bar (300, $((y + h + 16))) did not float it"
    import -display "$DISPLAY" -window root "$APEX_RVIZ_UNDOCK_SHOT" 2>/dev/null
    return
  fi
  import -display "$DISPLAY" -window root "$APEX_RVIZ_UNDOCK_SHOT" 2>"$work/import.log"
  echo "rviz check: the panel floats at $floating (screenshot $APEX_RVIZ_UNDOCK_SHOT)"
  python3 "$root/test/panel/rviz_layout.py" measure "$APEX_RVIZ_UNDOCK_SHOT" --windows "$work/undocked.txt" --min 0 \
    --background "$background" --name "rviz check: while it floats, ${config#"$root"/}"
  read -r x y <<<"$(printf '%s' "$floating" | sed 's/^[0-9]*x[0-9]*+\([0-9-]*\)+\([0-9-]*\)$/\1 \2/')"
  python3 "$root/test/panel/rviz_layout.py" click $((x + 100)) $((y + 10)) --double
  docked() { xwininfo -root -tree >"$work/windows.txt" 2>&1 &&
             ! python3 "$root/test/panel/rviz_layout.py" window "APEX graph" --windows "$work/windows.txt"; }
  wait_for 10 docked  # back in rviz's window
  if ! docked; then
    layout_failure="undock: a double-click on the floating panel's title bar did not dock it back"
  elif ! kill -0 "${pids[-1]}" 2>/dev/null; then
    layout_failure="undock: rviz ended"
  else  # back where it was: the 3D view as before
    local shot=${APEX_RVIZ_UNDOCK_SHOT%.png}_docked_again.png  # measure_layout reads it
    import -display "$DISPLAY" -window root "$shot" 2>"$work/import.log" && measure_layout
    [ -z "$layout_failure" ] || layout_failure="docked again: $layout_failure"
  fi
}

# The Whole window key (Ctrl+M, with the focus on the canvas, clicked just below the panel's tool
# bar): the editor over rviz's whole window (the 3D view gone from the screenshot), then, pressed
# again, rviz's layout as before (the 3D view measured again).
whole_window_and_back() {
  local geometry x y w h
  geometry=$(printf '%s' "$layout" | head -1 | sed -n 's/.* is \([0-9]*\)x\([0-9]*\) at +\([0-9]*\)+\([0-9]*\),.*/\1 \2 \3 \4/p')
  read -r w h x y <<<"$geometry"
  if [ -z "$geometry" ]; then layout_failure="whole window: the 3D view was not found"; return; fi
  local first=${shot%.png}_first.png  # the screenshot before the click: kept as the check's
  cp "$shot" "$first"
  python3 "$root/test/panel/rviz_layout.py" click $((x + w - 40)) $((y + h + 110))  # the canvas's right end
  python3 "$root/test/panel/rviz_layout.py" key ctrl+m
  whole() { shoot && python3 "$root/test/panel/rviz_layout.py" measure "$shot" --windows "$work/windows.txt" --min 0 \
              --max 0.05 --background "$background" --name "whole window" >/dev/null 2>&1; }
  wait_for 10 whole
  local big=${shot%.png}_whole_window.png
  cp "$shot" "$big"
  if ! whole; then
    layout_failure="whole window: Ctrl+M on the canvas left the 3D view shown (screenshot $big)"
    return
  fi
  echo "rviz check: Ctrl+M gives the editor the whole window (screenshot $big)"
  python3 "$root/test/panel/rviz_layout.py" key ctrl+m
  wait_for 10 measures
  shoot && measure_layout
  [ -z "$layout_failure" ] || layout_failure="after the whole window and back: $layout_failure"
  mv "$first" "$shot"
}

if start_x_and_master; then  # else `failure` says why
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
  # The picture once the 3D view is drawn: taken again (for up to 30 s) until it measures, since a
  # loaded machine draws rviz's first frames late; the last try's result counts.
  shoot() { xwininfo -root -tree >"$work/windows.txt" 2>&1 && import -display "$DISPLAY" -window root "$shot" 2>"$work/import.log"; }
  measures() { shoot && python3 "$root/test/panel/rviz_layout.py" measure "$shot" --windows "$work/windows.txt" \
                 --background "$background" --name "${config#"$root"/}" >/dev/null 2>&1; }
  wait_for 30 measures
  if shoot; then
    measure_layout
    [ -n "${APEX_RVIZ_UNDOCK_SHOT:-}" ] && [ -z "$failure$layout_failure" ] && undock_and_back
    [ -n "${APEX_RVIZ_WHOLE_WINDOW:-}" ] && [ -z "$failure$layout_failure" ] && whole_window_and_back
  else
    failure="${failure:-no screenshot: $(cat "$work/import.log")}"
    layout_failure="no screenshot"
  fi
fi
end_session
failures=$(( (${#failure} > 0) + (${#layout_failure} > 0) ))
if [ -z "$failure" ]; then
  echo "rviz check: ok (screenshot $shot)"
else
  echo "rviz check: FAILED: $failure"
  tail -20 "$work/rviz.log"
fi
[ -n "$layout_failure" ] && echo "rviz check: FAILED: $layout_failure"
{
  printf '<testsuite name="rviz" tests="2" failures="%d">' "$failures"
  testcase "$name" "$failure"
  testcase "${name}_3DViewKeepsHalfTheWindow" "$layout_failure"
  printf '</testsuite>\n'
} >"$result"
rm -rf "$work"
[ -z "$failure$layout_failure" ]
