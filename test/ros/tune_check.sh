#!/usr/bin/env bash
# The tuning demo's path, shortened: hard training and held-out bags (seeds 1 and 2), then
# launch/tune.launch as `scripts/demo --tune` runs it. Passes if it ends with "tune: OK" (the
# tuned parameters beat the shipped ones on the held-out bag) and the tuned graph it wrote holds
# the applied best values. Writes a JUnit result.
#   tune_check.sh RESULT_XML WORK_DIR [FRAMES] [BUDGET]   (with this package's devel space sourced)
set -u
source "$(dirname "$0")/junit.sh"
export PATH=/usr/bin:/bin:$PATH
out=$1
mkdir -p "$2" && work=$(cd "$2" && pwd)
frames=${3:-20} budget=${4:-30}
failure=""
fail() { [ -n "$failure" ] || failure=$1; }

for set in "train 1" "test 2"; do
  read -r name seed <<<"$set"
  rosrun apex apex_make_demo_bag "$work/$name.bag" "$work/${name}_truth.yaml" --seed "$seed" --frames "$frames" --difficulty hard \
    >"$work/make_$name.log" 2>&1 || fail "apex_make_demo_bag failed: $(tail -2 "$work/make_$name.log")"
done
rm -f "$work/tuned_paper_pipeline.yaml"
if [ -z "$failure" ]; then
  port=$((20000 + RANDOM % 20000))
  export ROS_MASTER_URI=http://localhost:$port ROS_HOME=${ROS_HOME:-$(mktemp -d)}
  timeout 600 roslaunch -p "$port" apex tune.launch data:="$work" budget:="$budget" >"$work/tune.log" 2>&1
  grep -q '^tune: OK' "$work/tune.log" || fail "the tuning demo did not end with 'tune: OK': $(grep -E '^(tune|held-out|best)' "$work/tune.log" | tr '\n' ' ')"
  grep -qE "state: [\"']?applied the best values" "$work/tuned_paper_pipeline.yaml" 2>/dev/null ||
    fail "the tuned graph $work/tuned_paper_pipeline.yaml is missing or does not hold the applied best values"
fi

junit_result "$out" tune Tuning "TheOptimizerTunesThePipelineOnHardDataAndTheHeldOutScoreImproves" "$failure"
grep -E '^(training|best|held-out|tune)' "$work/tune.log" 2>/dev/null
[ -z "$failure" ] && echo "tuning: OK" || { echo "tuning: $failure"; exit 1; }
