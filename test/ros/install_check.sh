#!/usr/bin/env bash
# The install space is the real path onto a robot: `make install` of this build into its
# CMAKE_INSTALL_PREFIX (scripts/test configures it as BUILD_DIR/install: catkin writes setup.bash
# to the prefix given at configure time, so `cmake --install --prefix` is not enough; removed
# again at the end), then, in an environment that has only that
# prefix's setup.bash (no source tree, no devel space), checks that rospack, pluginlib and
# roslaunch find everything: `roslaunch apex runtime.launch graph:=.../demo.yaml bag:=...` loads
# the shipped graph with its subgraph files and node types and publishes the overlay; the
# node libraries, the nodelet and the rviz panel are declared from share/apex. Writes a JUnit result.
#   install_check.sh RESULT_XML BUILD_DIR WORK_DIR BAG
set -u
source "$(dirname "$0")/junit.sh"
source "$(dirname "$0")/master.sh"
export PATH=/usr/bin:/bin:$PATH
out=$1 bag=$(realpath "$4")
build=$(cd "$2" && pwd)
mkdir -p "$3" && work=$(cd "$3" && pwd)
failure=""
fail() { [ -n "$failure" ] || failure=$1; }

prefix=$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' "$build/CMakeCache.txt")
case "$prefix" in
  "$build"/?*)
    rm -rf "$prefix"
    make -C "$build" install >"$work/install.log" 2>&1 || fail "make install failed: $(tail -3 "$work/install.log")" ;;
  *) fail "the build's CMAKE_INSTALL_PREFIX is '$prefix': configure it inside the build folder (-DCMAKE_INSTALL_PREFIX=$build/install) so that this check never writes elsewhere" ;;
esac

# Everything below runs with only the install space's environment.
in_install() {
  env -i HOME="$HOME" PATH=/usr/bin:/bin ROS_HOME="$work/ros_home" ROS_MASTER_URI="http://localhost:$port" \
    bash -c "source '$prefix/setup.bash' && $1"
}
port=$(free_port)
if [ -z "$failure" ]; then
  found=$(in_install "rospack find apex" 2>&1)
  [ "$found" = "$prefix/share/apex" ] || fail "rospack finds apex at '$found', not in the install space $prefix/share/apex"
  for kind in apex nodelet rviz; do
    declared=$(in_install "rospack plugins --attrib=plugin $kind" 2>&1 | grep '^apex ' | cut -d' ' -f2)
    [ -n "$declared" ] && [ -f "$declared" ] || fail "the $kind plugins of apex are not declared from an installed file: '$declared'"
    case "$declared" in "$prefix"/*) ;; *) fail "the $kind plugins come from '$declared', outside the install space" ;; esac
  done
  leaks=$(in_install "ldd '$prefix/lib/apex/apex_runtime_node' '$prefix/lib/libapex_nodes_opencv.so'" 2>&1 | grep -v "$prefix" | grep -E "$build|not found")
  [ -z "$leaks" ] || fail "installed binaries load from the build tree or miss libraries: $leaks"
fi

if [ -z "$failure" ]; then
  cat >"$work/launch.sh" <<EOF
source '$prefix/setup.bash'
exec roslaunch -p $port apex runtime.launch graph:=\$(rospack find apex)/graphs/demo.yaml bag:=$bag loop:=true
EOF
  # in a session of its own: SIGINT to the whole group reaches roslaunch and what it started
  setsid env -i HOME="$HOME" PATH=/usr/bin:/bin PYTHONUNBUFFERED=1 ROS_HOME="$work/ros_home" ROS_MASTER_URI="http://localhost:$port" \
    bash "$work/launch.sh" >"$work/roslaunch.log" 2>&1 &
  launch=$!
  status=$(in_install "timeout 60 bash -c 'until rosservice list 2>/dev/null | grep -q /apex/get_graph; do sleep 0.2; done' && \
                       timeout 20 rosservice call /apex/get_graph '{}'" 2>&1)
  grep -q 'name: "camera_detector/threshold"' <<<"$status" || fail "the installed demo graph did not load with its subgraphs (roslaunch: $(tail -3 "$work/roslaunch.log"))"
  types=$(in_install "timeout 20 rosservice call /apex/list_node_types '{}'" 2>&1)
  grep -q 'id: "apex_nodes/BagWriter"' <<<"$types" || fail "list_node_types from the install space lacks the node libraries"
  grep -A2 'load_errors' <<<"$types" | grep -q '"' && fail "node libraries failed to load: $(grep -A3 load_errors <<<"$types")"
  overlay=$(in_install "timeout 60 rostopic echo -n 1 /apex_demo/overlay/encoding" 2>&1)
  grep -q 'bgr8' <<<"$overlay" || fail "no overlay from the installed demo within 60 s: $overlay"
  kill -INT -- "-$launch" 2>/dev/null
  timeout 30 tail --pid="$launch" -f /dev/null || kill -KILL -- "-$launch" 2>/dev/null
fi

# Gone again: the prefix lies inside this package's folder, where rosrun would find a second
# apex_runtime_node beside the devel space's and ask which one.
case "$prefix" in "$build"/?*) rm -rf "$prefix" ;; esac
junit_result "$out" install Install "RoslaunchRunsTheDemoFromTheInstallSpaceAlone" "$failure"
[ -z "$failure" ] && echo "install space: rospack, pluginlib and roslaunch run the demo from $prefix" || { echo "install space: $failure"; exit 1; }
