#!/usr/bin/env bash
# The sign detector on photographs, as `scripts/demo --backgrounds real`, `scripts/demo --numbers
# --backgrounds real` and `scripts/demo --tune --backgrounds real` run it (the numbers shortened:
# 80 training and 30 held-out frames): the demo's frames with the right count at least 38 of 40;
# detection F1 at least 0.90 and digit accuracy at least 0.97 on the held-out bag; tuned from the
# poor values, held-out F1 at least 0.85 and 0.3 above the start. Writes a JUnit result.
#   photographs_check.sh RESULT_XML WORK_DIR [TRAIN_FRAMES] [FRAMES]   (with this package's devel space sourced)
set -u
source "$(dirname "$0")/junit.sh"
source "$(dirname "$0")/master.sh"
export PATH=/usr/bin:/bin:$PATH
out=$1
mkdir -p "$2" && work=$(cd "$2" && pwd)
train_frames=${3:-80} frames=${4:-30}
failures=()
fail() { failures+=("$1"); }
make_bag() {  # name args...
  local name=$1
  shift
  rosrun apex apex_make_demo_bag "$work/$name.bag" "$work/${name}_truth.yaml" --backgrounds real "$@" >>"$work/make.log" 2>&1 ||
    fail "apex_make_demo_bag $name failed: $(tail -2 "$work/make.log")"
}
rm -f "$work/make.log"
make_bag demo --frames 40  # the demo's own bag: its default seed
make_bag train --seed 1 --frames "$train_frames"
make_bag test --seed 2 --frames "$frames"
make_bag tune_train --seed 1 --frames 40
make_bag tune_test --seed 2 --frames 40
rm -rf "$work/samples" "$work/digits.yaml"
port=$(free_port)
export ROS_MASTER_URI=http://localhost:$port ROS_HOME=${ROS_HOME:-$(mktemp -d)}
if [ ${#failures[@]} -eq 0 ]; then
  timeout 300 roslaunch -p "$port" apex demo.launch bag:="$work/demo.bag" truth:="$work/demo_truth.yaml" >"$work/demo.log" 2>&1
  right=$(sed -n 's/.*frames with the right count: \([0-9]*\) of 40.*/\1/p' "$work/demo.log")
  [ "${right:-0}" -ge 38 ] && grep -q '^demo: OK' "$work/demo.log" ||
    fail "the demo on photographs: $(grep -E '^(regions found|demo:)' "$work/demo.log" | tr '\n' ' ') (needs 38 of 40 frames right)"
  launch() {  # log mode args...
    local log=$1
    shift
    timeout 300 roslaunch -p "$port" apex numbers.launch data:="$work" "$@" >"$work/$log" 2>&1
  }
  launch export.log mode:=export bag:="$work/train.bag" truth:="$work/train_truth.yaml"
  grep -q '^exported: [1-9]' "$work/export.log" || fail "no samples exported: $(grep -E '^export' "$work/export.log" | tr '\n' ' ')"
  rosrun apex apex_train_mlp "$work/samples" "$work/digits.yaml" >"$work/train.log" 2>&1 ||
    fail "apex_train_mlp failed: $(tail -2 "$work/train.log")"
  launch classify.log mode:=classify bag:="$work/test.bag" truth:="$work/test_truth.yaml"
  f1=$(sed -n 's/^detection: *F1 \([0-9.]*\).*/\1/p' "$work/classify.log")
  accuracy=$(sed -n 's/^digits: *accuracy \([0-9.]*\).*/\1/p' "$work/classify.log")
  awk -v f="${f1:-0}" -v a="${accuracy:-0}" 'BEGIN { exit !(f >= 0.90 && a >= 0.97) }' ||
    fail "the numbers on photographs: detection F1 ${f1:-?} (needs 0.90), digit accuracy ${accuracy:-?} (needs 0.97)"
  timeout 600 roslaunch -p "$port" apex tune.launch data:="$work" graph:=tune_sign_detector.yaml train:=tune_train \
    test:=tune_test >"$work/tune.log" 2>&1
  read -r start tuned < <(sed -n 's/^held-out bag: *shipped parameters F1 \([0-9.]*\) *-> *tuned F1 \([0-9.]*\).*/\1 \2/p' "$work/tune.log")
  awk -v s="${start:-1}" -v t="${tuned:-0}" 'BEGIN { exit !(t >= 0.85 && t - s >= 0.3) }' ||
    fail "tuning on photographs: held-out F1 ${start:-?} -> ${tuned:-?} (needs 0.85, and 0.3 above the start)"
fi

failure="${failures[*]:-}"
junit_result "$out" photographs Photographs "DetectorNumbersAndTuningOnPhotographs" "$failure"
grep -E '^(regions found|demo:)' "$work/demo.log" 2>/dev/null
grep -E '^(exported|detection|digits|numbers)' "$work/export.log" "$work/classify.log" 2>/dev/null
grep -E '^(training|best|held-out|tune)' "$work/tune.log" 2>/dev/null
[ -z "$failure" ] && echo "photographs: OK" || { echo "photographs: $failure"; exit 1; }
