#!/usr/bin/env bash
# The number-sign demo's path, shortened: a training bag (seed 1) and a held-out bag (seed 2),
# samples exported by graphs/export_samples.yaml, apex_train_mlp, and graphs/number_signs.yaml
# on the held-out bag, all as `scripts/demo --numbers` runs them. Passes if it ends with
# "numbers: OK" (digit accuracy >= 95%); and if, with a damaged model file, the same launch
# still plays the whole bag (detection scored) and names the model in the classifier's error.
# Writes a JUnit result.
#   numbers_check.sh RESULT_XML WORK_DIR [TRAIN_FRAMES] [FRAMES]   (with this package's devel space sourced)
set -u
source "$(dirname "$0")/junit.sh"
source "$(dirname "$0")/master.sh"
export PATH=/usr/bin:/bin:$PATH
out=$1
mkdir -p "$2" && work=$(cd "$2" && pwd)
train_frames=${3:-80} frames=${4:-20}
failures=()
fail() { failures+=("$1"); }

rosrun apex apex_make_demo_bag "$work/train.bag" "$work/train_truth.yaml" --seed 1 --frames "$train_frames" >"$work/make.log" 2>&1 &&
  rosrun apex apex_make_demo_bag "$work/test.bag" "$work/test_truth.yaml" --seed 2 --frames "$frames" >>"$work/make.log" 2>&1 ||
  fail "apex_make_demo_bag failed: $(tail -2 "$work/make.log")"
rm -rf "$work/samples" "$work/digits.yaml"
port=$(free_port)
export ROS_MASTER_URI=http://localhost:$port ROS_HOME=${ROS_HOME:-$(mktemp -d)}
launch() {  # log mode args...
  local log=$1
  shift
  timeout 300 roslaunch -p "$port" apex numbers.launch data:="$work" "$@" >"$work/$log" 2>&1
}
if [ ${#failures[@]} -eq 0 ]; then
  launch export.log mode:=export bag:="$work/train.bag" truth:="$work/train_truth.yaml"
  grep -q '^exported: [1-9]' "$work/export.log" || fail "no samples exported: $(grep -E '^export' "$work/export.log" | tr '\n' ' ')"
  rosrun apex apex_train_mlp "$work/samples" "$work/digits.yaml" >"$work/train.log" 2>&1 ||
    fail "apex_train_mlp failed: $(tail -2 "$work/train.log")"
  grep -q '^epoch ' "$work/train.log" || fail "apex_train_mlp showed no progress"
  launch classify.log mode:=classify bag:="$work/test.bag" truth:="$work/test_truth.yaml"
  grep -q '^numbers: OK' "$work/classify.log" ||
    fail "the held-out bag did not end with 'numbers: OK': $(grep -E '^(detection|digits|numbers)' "$work/classify.log" | tr '\n' ' ')"
  head -c 300 "$work/digits.yaml" >"$work/damaged.yaml"  # a model file cut short
  launch damaged.log mode:=classify bag:="$work/test.bag" truth:="$work/test_truth.yaml" model:="$work/damaged.yaml"
  grep -q '^detection: *F1 1.000' "$work/damaged.log" ||
    fail "with a damaged model the bag was not played to its end: $(grep -E '^(detection|numbers)' "$work/damaged.log" | tr '\n' ' ')"
  grep -q "^numbers: FAILED: classify: .*the model '$work/damaged.yaml' is damaged" "$work/damaged.log" ||
    fail "a damaged model was not named in the classifier's error: $(grep '^numbers' "$work/damaged.log")"
fi

failure="${failures[*]:-}"
junit_result "$out" numbers NumberSigns "ExportTrainAndClassifyAHeldOutBagAbove95PercentAndSurviveADamagedModel" "$failure"
grep -E '^(exported|detection|digits|numbers)' "$work/export.log" "$work/classify.log" 2>/dev/null
[ -z "$failure" ] && echo "number signs: OK" || { echo "number signs: $failure"; exit 1; }
