#!/usr/bin/env bash
# "Show in rviz" in the real rviz, under Xvfb: the panel (launch/apex_panel.rviz) on the demo graph
# (graphs/demo.yaml, playing BAG), with a markers port added (test/panel/rviz_displays.py
# add-markers), shows the demo's overlay image, its filtered cloud and the markers port in rviz as
# the port menu's "Show in rviz" does (APEX_PANEL_SHOW_IN_RVIZ: a script cannot open the menu).
# Asserts, from rviz's own saved config and its node's bus stats, that rviz then has the three
# displays, of the right class, enabled, on the ports' inspection topics, and receives messages on
# each; and that removing the three nodes from the runtime removes their displays from rviz.
# Writes a JUnit result (ShowInRvizAddsDisplaysThatReceive, ShowInRvizDisplaysGoWithTheirNodes).
#   rviz_show_check.sh RESULT_XML BAG
# Needs the devel space sourced; starts (and stops) its own X server and master.
set -uo pipefail
result=$1 bag=$2
root=$(cd "$(dirname "$0")/../.." && pwd)
failure=""
gone_failure="not checked: the displays were not shown"
source "$root/test/panel/rviz_session.sh"
displays=$root/test/panel/rviz_displays.py

# port -> its display's class, as rviz_displays.cpp's table maps the port's message type
declare -A class=([camera_detector/overlay]=rviz/Image [cloud_filter/cloud]=rviz/PointCloud2
                  [features/features]=rviz/MarkerArray)
ports=(camera_detector/overlay cloud_filter/cloud features/features)
wanted=() names=() nodes=()
for p in "${ports[@]}"; do
  wanted+=("apex: $p=${class[$p]}") names+=("apex: $p") nodes+=("${p%/*}")
done

if start_x_and_master; then  # else `failure` says why
  rosparam set /apex/overrides "{bag: {file: '$bag', loop: true}}"
  rosrun apex apex_runtime_node __name:=apex _graph:="$root/graphs/demo.yaml" >"$work/runtime.log" 2>&1 &
  pids+=($!)
  if ! added=$(/usr/bin/python3 "$displays" add-markers /apex 2>&1); then
    failure="the markers port was not added: $(printf '%s' "$added" | tail -1)"
  else
    APEX_PANEL_SHOW_IN_RVIZ="${ports[*]}" rosrun rviz rviz -d "$root/launch/apex_panel.rviz" >"$work/rviz.log" 2>&1 &
    pids+=($!)
    if ! wait_for 120 grep -q "GraphPanel: showing the graph of /apex" "$work/rviz.log"; then
      failure="the panel did not show the graph of /apex"
    elif ! shown=$(/usr/bin/python3 "$displays" wait "$work/saved.rviz" "${wanted[@]}" --timeout 30 2>&1); then
      failure=$(printf '%s\n' "$shown" | sed -n 's/^rviz displays: //p' | paste -sd ';' -)
      failure=${failure:-"rviz_displays.py wait failed: $(printf '%s' "$shown" | tail -1)"}
    fi
    printf '%s\n' "${shown:-}" | grep "^rviz: " | sed 's/^/rviz show check: /'
  fi
  if [ -z "$failure" ]; then
    removed() { for n in "${names[@]}"; do grep -qF "GraphPanel: removed display '$n'" "$work/rviz.log" || return 1; done; }
    if ! out=$(/usr/bin/python3 "$displays" remove /apex "${nodes[@]}" 2>&1); then
      gone_failure=$(printf '%s' "$out" | tail -1)
    elif ! wait_for 20 removed; then
      gone_failure="the panel did not remove every display after remove_node ${nodes[*]}: $(grep "removed display" "$work/rviz.log" | paste -sd ';' -)"
    elif ! out=$(/usr/bin/python3 "$displays" gone "$work/saved.rviz" "${names[@]}" 2>&1); then
      gone_failure=$(printf '%s' "$out" | tail -1)
    else
      gone_failure=""
    fi
  fi
fi
end_session
for f in "$failure" "$gone_failure"; do [ -z "$f" ] || echo "rviz show check: FAILED: $f"; done
[ -z "$failure$gone_failure" ] && echo "rviz show check: ok"
[ -z "$failure" ] || tail -20 "$work/rviz.log"
{
  printf '<testsuite name="rviz_show" tests="2" failures="%d">' $(( (${#failure} > 0) + (${#gone_failure} > 0) ))
  testcase ShowInRvizAddsDisplaysThatReceive "$failure"
  testcase ShowInRvizDisplaysGoWithTheirNodes "$gone_failure"
  printf '</testsuite>\n'
} >"$result"
rm -rf "$work"
[ -z "$failure$gone_failure" ]
