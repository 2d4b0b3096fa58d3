#!/usr/bin/env bash
# The node example of docs/writing-nodes.md is the real path: builds test/example_package
# (one node type, that page's code verbatim, and its library's one APEX_NODE_LIBRARY line) as a separate
# catkin package against this devel space, starts the runtime with it on the package
# path, adds the node through add_node and checks that it computes. Writes a JUnit result.
#   example_package.sh RESULT_XML WORK_DIR   (with this package's devel space sourced)
set -u
source "$(dirname "$0")/junit.sh"
source "$(dirname "$0")/master.sh"
export PATH=/usr/bin:/bin:$PATH   # catkin needs Debian's python3
out=$1
mkdir -p "$2" && work=$(cd "$2" && pwd)
src=$(cd "$(dirname "$0")/../example_package" && pwd)
readme=$(dirname "$src")/../docs/writing-nodes.md
failure=""
fail() { [ -n "$failure" ] || failure=$1; }

# docs/writing-nodes.md shows gain.cpp exactly.
awk '/^## A node type/{on=1} on&&/^```cpp/{grab=1;next} grab&&/^```/{exit} grab{print}' "$readme" >"$work/readme_gain.cpp"
diff -u "$work/readme_gain.cpp" "$src/gain.cpp" >"$work/readme.diff" || fail "the node example of docs/writing-nodes.md differs from test/example_package/gain.cpp: $(head -c 300 "$work/readme.diff")"

if [ -z "$failure" ]; then
  cmake -S "$src" -B "$work/build" -DCATKIN_DEVEL_PREFIX="$work/devel" >"$work/cmake.log" 2>&1 &&
    make -C "$work/build" -j2 >"$work/make.log" 2>&1 || fail "the example package does not build: $(grep -m3 -E 'error|Error' "$work/cmake.log" "$work/make.log")"
fi

if [ -z "$failure" ]; then
  set +u; source "$work/devel/setup.bash"; set -u
  export ROS_HOME=${ROS_HOME:-$(mktemp -d)}
  start_master "$work/roscore.log" || fail "$master_failure"
  rosrun apex apex_runtime_node >"$work/runtime.log" 2>&1 &
  node=$!
  timeout 30 bash -c 'until rosservice list 2>/dev/null | grep -q /apex/add_node; do sleep 0.2; done' || fail "the runtime never offered its services"
  call() { timeout 20 rosservice call "/apex/$1" "$2" 2>&1; }
  types=$(call list_node_types "{}")
  grep -q "id: \"demo/Gain\"" <<<"$types" || fail "list_node_types has no demo/Gain: $(grep -A3 load_errors <<<"$types" | head -5)"
  grep -q "description: \"Multiplies its input by a gain\"" <<<"$types" || fail "demo/Gain lacks its manifest's description"
  for c in "add_node {type: apex_nodes/Clock, name: clock, parameters: '{rate: 50}'}" \
           "add_node {type: demo/Gain, name: gain, parameters: '{gain: 3}'}" \
           "connect {from_node: clock, from_port: count, to_node: gain, to_port: in}" \
           "inspect {node: gain, port: out, enable: true}"; do
    r=$(call ${c%% *} "${c#* }")
    grep -q "success: True" <<<"$r" || fail "${c%% *} failed: $r"
  done
  # Clock counts 0, 1, 2, ...; gain 3 makes multiples of 3. Two messages: one past 0.
  values=$(timeout 20 rostopic echo -n 3 /apex/inspect/gain/out 2>&1 | grep -o 'data: [0-9-]*' | cut -d' ' -f2)
  [ -n "$values" ] || fail "no output from demo/Gain within 20 s"
  for v in $values; do [ $((v % 3)) -eq 0 ] || fail "demo/Gain sent $v, not a multiple of 3"; done
  [ "$(tail -1 <<<"$values")" -gt 0 ] 2>/dev/null || fail "demo/Gain's output never grew: $values"
  kill -INT "$node" 2>/dev/null; wait "$node" 2>/dev/null
  kill -TERM "$core" 2>/dev/null; wait "$core" 2>/dev/null
fi

junit_result "$out" example_package NodeApi "TheReadmesNodeTypeBuildsInItsOwnPackageAndRunsViaAddNode" "$failure"
[ -z "$failure" ] && echo "example package: built, loaded, ran" || { echo "example package: $failure"; exit 1; }
