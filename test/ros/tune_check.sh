#!/usr/bin/env bash
# The tuning demo's path, shortened: hard training and held-out bags (seeds 1 and 2), then
# launch/tune.launch as `scripts/demo --tune` runs it. Passes if it ends with "tune: OK" (the
# tuned parameters beat the shipped ones on the held-out bag) and the tuned graph it wrote holds
# the applied best values; and if the same run with a study file, its runtime killed (SIGKILL)
# half-way and launched again, ends with the same best as the unbroken one; and if two workers with
# racing by the bound end as two workers without, and by the paired test at the same held-out F1
# (within 0.02), with candidates cut short; and if two workers judging by two
# objectives (fitness and cost) end with that best too, and print a Pareto front. Writes a JUnit result.
#   tune_check.sh RESULT_XML WORK_DIR [FRAMES] [BUDGET]   (with this package's devel space sourced)
set -u
source "$(dirname "$0")/junit.sh"
source "$(dirname "$0")/master.sh"
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
  port=$(free_port)
  export ROS_MASTER_URI=http://localhost:$port ROS_HOME=${ROS_HOME:-$(mktemp -d)}
  timeout 600 roslaunch -p "$port" apex tune.launch data:="$work" budget:="$budget" >"$work/tune.log" 2>&1
  grep -q '^tune: OK' "$work/tune.log" || fail "the tuning demo did not end with 'tune: OK': $(grep -E '^(tune|held-out|best)' "$work/tune.log" | tr '\n' ' ')"
  grep -qE "state: [\"']?applied the best values" "$work/tuned_paper_pipeline.yaml" 2>/dev/null ||
    fail "the tuned graph $work/tuned_paper_pipeline.yaml is missing or does not hold the applied best values"

  # The same run with a study file, its runtime killed half-way, then launched again
  rm -f "$work/study.csv"
  timeout 600 roslaunch -p "$port" apex tune.launch data:="$work" budget:="$budget" study:="$work/study.csv" \
    >"$work/killed.log" 2>&1 &
  launch=$!
  half=$((2 + budget / 2))  # the header, the column names, half the evaluations
  lines() { cat "$work/study.csv" 2>/dev/null | wc -l; }
  pid=
  for _ in $(seq 15000); do  # the runtime's pid first (rosnode takes a while), then half the run
    [ -n "$pid" ] || pid=$(rosnode info /apex 2>/dev/null | sed -n 's/^Pid: //p')
    [ -n "$pid" ] && [ "$(lines)" -ge "$half" ] && break
    kill -0 "$launch" 2>/dev/null || break
    sleep 0.02
  done
  if [ -n "$pid" ] && [ "$(lines)" -lt $((2 + budget)) ]; then
    kill -9 "$pid"
    wait "$launch"
    killed_at=$(($(wc -l <"$work/study.csv") - 2))
    timeout 600 roslaunch -p "$port" apex tune.launch data:="$work" budget:="$budget" study:="$work/study.csv" \
      >"$work/resumed.log" 2>&1
    unbroken=$(grep '^best on the training bag' "$work/tune.log") resumed=$(grep '^best on the training bag' "$work/resumed.log")
    [ -n "$unbroken" ] && [ "$unbroken" = "$resumed" ] ||
      fail "killed after $killed_at evaluations and launched again, the run ended with '$resumed', not '$unbroken'"
    [ "$(lines)" -eq $((2 + budget)) ] || fail "the resumed run's study holds $(($(lines) - 2)) evaluations, not $budget"
    grep -rqs "resumed from the study '$work/study.csv': $killed_at evaluations" "$ROS_HOME/log" ||
      fail "the run launched again did not resume from its study's $killed_at evaluations (the runtime's log says nothing of it)"
  else
    wait "$launch"
    fail "the run with a study file did not reach half its budget alive: $(grep -E '^(tune|best)' "$work/killed.log" | tr '\n' ' ')"
  fi

  # Two workers (copies of the evaluated part), without and with racing: the same best, some cut short
  # and with a second objective, the cost: the search follows the fitness, so the same best, and a front
  # (racing by the bound: exactly the same best; by the paired test: the same held-out F1, within 0.02)
  for v in "false bound fitness workers2" "true bound fitness raced" "true paired fitness paired" \
    "false bound fitness_and_cost costed"; do
    read -r racing rule objectives name <<<"$v"
    timeout 600 roslaunch -p "$port" apex tune.launch data:="$work" budget:="$budget" workers:=2 racing:="$racing" \
      racing_rule:="$rule" objectives:="$objectives" tuned:="tuned_$name.yaml" >"$work/$name.log" 2>&1
    grep -q '^tune: OK' "$work/$name.log" || fail "with 2 workers ($name) the demo did not end with 'tune: OK'"
  done
  two=$(grep '^best on the training bag' "$work/workers2.log") raced=$(grep '^best on the training bag' "$work/raced.log")
  [ -n "$two" ] && [ "$two" = "$raced" ] || fail "2 workers with racing ended with '$raced', not as without: '$two'"
  for name in raced paired; do
    grep -qE '^optimiser: finished after [0-9]+ evaluations \(racing (paired|bound): [1-9][0-9]* cut short, ' "$work/$name.log" ||
      fail "racing ($name) cut no candidate short: $(grep '^optimiser' "$work/$name.log")"
  done
  held() { sed -n 's/.*->  tuned F1 \([0-9.]*\).*/\1/p' "$work/$1.log"; }
  python3 -c "import sys; sys.exit(abs(float('$(held paired)') - float('$(held workers2)')) > 0.02)" 2>/dev/null ||
    fail "racing by the paired test ended at held-out F1 '$(held paired)', not within 0.02 of '$(held workers2)'"
  costed=$(grep '^best on the training bag' "$work/costed.log")
  [ -n "$costed" ] && [ "$costed" = "$two" ] || fail "2 workers on two objectives ended with '$costed', not as on one: '$two'"
  grep -qE '^optimiser: .*; a front of [1-9][0-9]* points?$' "$work/costed.log" && grep -q '^  front: F1 ' "$work/costed.log" ||
    fail "two objectives printed no Pareto front: $(grep -E '^(optimiser|  front)' "$work/costed.log")"
fi

junit_result "$out" tune Tuning "TheOptimizerTunesThePipelineOnHardDataAndTheHeldOutScoreImprovesAndAKilledRunResumes" "$failure"
grep -E '^(training|best|held-out|tune)' "$work/tune.log" 2>/dev/null
[ -z "${killed_at:-}" ] || echo "killed after $killed_at of $budget evaluations, launched again: $(grep '^best on' "$work/resumed.log")"
for name in workers2 raced paired costed; do
  [ -f "$work/$name.log" ] && echo "$name: $(grep -E '^(the run took|optimiser)' "$work/$name.log" | tr '\n' ' ')"
done
[ -z "$failure" ] && echo "tuning: OK" || { echo "tuning: $failure"; exit 1; }
