#!/usr/bin/env bash
# What a big graph costs while it does nothing, and how fast its runtime stops: for each size, a
# runtime loads a chain of N Relay nodes, is paused, and its CPU time is read over SECONDS s
# (/proc/<pid>/stat); then SIGTERM, timed to the exit. Sizes are interleaved, RUNS times; prints a
# markdown section with the median (min-max) and the ratio to the smallest size in the same runs.
#   bench/big_graph_idle.sh [RUNS] [SECONDS] [SIZES...]    (with this package's devel space sourced)
set -u
runs=${1:-3} seconds=${2:-10}
shift 2 2>/dev/null
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(100 1000 5000)
home=$(mktemp -d)
export ROS_HOME=$home ROS_MASTER_URI=http://localhost:$((20000 + RANDOM % 20000))
mkdir -p "$home/apex"
roscore -p "${ROS_MASTER_URI##*:}" >"$home/roscore.log" 2>&1 &
master=$!
trap 'kill $master 2>/dev/null; wait $master 2>/dev/null; rm -rf "$home"' EXIT
for n in "${sizes[@]}"; do
  python3 - "$n" >"$home/apex/chain_$n.yaml" <<'PY'
import sys
n = int(sys.argv[1])
print('apex_graph: 2\nnodes:')
for i in range(n):
    print('  - {name: r%d, type: apex_nodes/Relay}' % i)
print('connections:')
for i in range(n - 1):
    print('  - {from: r%d/out, to: r%d/in}' % (i, i + 1))
PY
done
ticks=$(getconf CLK_TCK)
cpu() { awk '{print $14 + $15}' "/proc/$1/stat"; }
results=$home/results
for _ in $(seq "$runs"); do
  for n in "${sizes[@]}"; do
    rosrun apex apex_runtime_node __name:=apex_idle >"$home/runtime.log" 2>&1 &
    pid=$!
    rosservice call --wait /apex_idle/load_graph "{path: chain_$n.yaml}" | grep -q 'success: True' ||
      echo "big_graph_idle: $n nodes did not load (see $home/runtime.log)" >&2
    rosservice call /apex_idle/control "{command: pause}" >/dev/null
    sleep 2  # what the load and the pause set off settles
    a=$(cpu $pid)
    sleep "$seconds"
    b=$(cpu $pid)
    t0=$(date +%s.%N)
    kill -TERM $pid
    wait $pid
    t1=$(date +%s.%N)
    echo "$n $(echo "($b - $a) * 100 / $ticks / $seconds" | bc -l) $(echo "$t1 - $t0" | bc -l)" >>"$results"
  done
done
cp "$results" "${APEX_BENCH_KEEP:-/dev/null}" 2>/dev/null
python3 - "$results" "$seconds" <<'PY'
import statistics, sys
rows = {}
for line in open(sys.argv[1]):
    n, cpu, stop = line.split()
    rows.setdefault(int(n), []).append((float(cpu), float(stop)))
fmt = lambda v, f: (f + ' (' + f + '-' + f + ')') % (statistics.median(v), min(v), max(v))
base = min(rows)
base_stop = statistics.median(r[1] for r in rows[base])
print('## A big graph at rest, and its stop')
print()
print('`bench/big_graph_idle.sh` (%d runs, sizes interleaved): a runtime loads a chain of' % len(rows[base]))
print('N Relay nodes, is paused, and its CPU time is read over %s s; then SIGTERM, timed to its exit.' % sys.argv[2])
print('No subscriber to /diagnostics. Median (min-max) over the runs; the stop\'s ratio to the')
print('%d-node graph\'s.' % base)
print()
print('| nodes | CPU while paused, %% of a core | stop on SIGTERM, s | stop / %d nodes |' % base)
print('|---|---|---|---|')
for n in sorted(rows):
    cpu, stop = [r[0] for r in rows[n]], [r[1] for r in rows[n]]
    print('| %d | %s | %s | %.2fx |' % (n, fmt(cpu, '%.2f'), fmt(stop, '%.2f'), statistics.median(stop) / base_stop))
PY
