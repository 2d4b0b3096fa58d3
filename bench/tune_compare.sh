#!/usr/bin/env bash
# The built-in Optimizer (DE with 1 and 2 workers, with and without racing) against Optuna (TPE,
# TPE with the median pruner, CMA-ES, random) on the sign detector and the photographs of
# `scripts/demo --tune --backgrounds real` (training seed 1, held-out seed 2, 40 frames each):
# bench/tune_compare.py in one runtime. Run the demo once first (it makes the bags).
#   bench/tune_compare.sh [SEEDS] [BUDGET] [GRAPH] [TRAIN] [TEST]   (SEEDS: N for 1..N, or a list: 4,5;
#   with this package's devel space sourced)
set -u
seeds=${1:-5} budget=${2:-200} graph=${3:-tune_sign_detector.yaml}
train=${4:-train_s1_f40_easy_real} test=${5:-test_s2_f40_easy_real}
here=$(cd "$(dirname "$0")/.." && pwd)
data=$here/build-ros/tune_data
[ -f "$data/$train.bag" ] && [ -f "$data/$test.bag" ] || { echo "tune_compare: no $data/$train.bag or $test.bag: run scripts/demo --tune --backgrounds real first" >&2; exit 1; }
port=$((20000 + RANDOM % 20000))
export ROS_MASTER_URI=http://localhost:$port
roslaunch -p "$port" apex runtime.launch graph:="$here/graphs/$graph" file_roots:="$data" rerun_on_edit:=false output:=log \
  >"$data/tune_compare_runtime.log" 2>&1 &
launch=$!
trap 'kill -INT $launch 2>/dev/null; wait $launch 2>/dev/null' EXIT
python3 "$here/bench/tune_compare.py" "$data" "$train" "$test" "$budget" "$seeds"
