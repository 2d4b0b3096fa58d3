#!/usr/bin/env bash
# What one edit costs through the ROS services in a big graph: for each size, a runtime loads a
# chain of N Relay nodes (a Clock at 0.5-2.5 Hz at its head, so frames flow), then a client with persistent service
# connections times K rounds of add_node, connect, set_parameter, disconnect and remove_node at
# the chain's tail, and a refused call (fire_slot on no node: the transport and the answer alone)
# as the baseline. One subscriber to ~graph, as a panel. Sizes are interleaved, RUNS times; prints
# a markdown section: median and p95 per call (ms) over all rounds of all runs, and the ratio of
# the median to the refused call's in the same runs.
#   bench/service_edits.sh [RUNS] [ROUNDS] [SIZES...]    (with this package's devel space sourced)
set -u
runs=${1:-3} rounds=${2:-100}
shift 2 2>/dev/null
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(500 5000)
home=$(mktemp -d)
export ROS_HOME=$home ROS_MASTER_URI=http://localhost:$((20000 + RANDOM % 12000))
mkdir -p "$home/apex"
roscore -p "${ROS_MASTER_URI##*:}" >"$home/roscore.log" 2>&1 &
master=$!
trap 'kill $master 2>/dev/null; wait $master 2>/dev/null; rm -rf "$home"' EXIT
until rostopic list >/dev/null 2>&1; do sleep 0.2; done  # the master is up
for n in "${sizes[@]}"; do
  python3 - "$n" >"$home/apex/chain_$n.yaml" <<'PY'
import sys
n = int(sys.argv[1])
print('apex_graph: 2\nnodes:\n  - {name: r0, type: apex_nodes/Clock, parameters: {rate: 1.0}}')
for i in range(1, n):
    print('  - {name: r%d, type: apex_nodes/Relay}' % i)
print('connections:')
for i in range(n - 1):
    print('  - {from: r%d/%s, to: r%d/in}' % (i, 'count' if i == 0 else 'out', i + 1))
PY
done
results=$home/results
for _ in $(seq "$runs"); do
  for n in "${sizes[@]}"; do
    rosrun apex apex_runtime_node __name:=apex_edits >"$home/runtime.log" 2>&1 &
    pid=$!
    rosservice call --wait /apex_edits/load_graph "{path: chain_$n.yaml}" 2>/dev/null | grep -q 'success: True' ||
      echo "service_edits: $n nodes did not load (see $home/runtime.log)" >&2
    python3 - "$n" "$rounds" >>"$results" <<'PY'
import sys, time
import rospy
from apex.msg import GraphState
from apex.srv import AddNode, Connect, RemoveNode, SetParameter, FireSlot
n, rounds = int(sys.argv[1]), int(sys.argv[2])
rospy.init_node('service_edits', anonymous=True)
graphs = []
rospy.Subscriber('/apex_edits/graph', GraphState, lambda g: graphs.append(g.revision), queue_size=1)
def proxy(name, kind):
    rospy.wait_for_service('/apex_edits/' + name)
    return rospy.ServiceProxy('/apex_edits/' + name, kind, persistent=True)
add, connect, disconnect = proxy('add_node', AddNode), proxy('connect', Connect), proxy('disconnect', Connect)
remove, setp, fire = proxy('remove_node', RemoveNode), proxy('set_parameter', SetParameter), proxy('fire_slot', FireSlot)
tail = 'r%d' % (n - 1)
calls = [
    ('add_node', lambda i: add(type='apex_nodes/Relay', name='x%d' % i, thread_group='', parameters='')),
    ('connect', lambda i: connect(from_node=tail, from_port='out', to_node='x%d' % i, to_port='in')),
    ('set_parameter', lambda i: setp(node='r0', parameter='rate', value=str(0.5 + 0.5 * (i % 5)))),
    ('disconnect', lambda i: disconnect(from_node=tail, from_port='out', to_node='x%d' % i, to_port='in')),
    ('remove_node', lambda i: remove(name='x%d' % i)),
    ('refused call', lambda i: fire(node='no_such_node', slot='reset')),
]
for i in range(rounds):
    for name, call in calls:
        t0 = time.perf_counter()
        res = call(i)
        t1 = time.perf_counter()
        if name != 'refused call' and not res.success:
            sys.exit('service_edits: %s failed: %s' % (name, res.message))
        print(n, name.replace(' ', '_'), (t1 - t0) * 1000)
PY
    kill -TERM $pid
    wait $pid
  done
done
cp "$results" "${APEX_BENCH_KEEP:-/dev/null}" 2>/dev/null
python3 - "$results" "$runs" "$rounds" <<'PY'
import statistics, sys
rows = {}
for line in open(sys.argv[1]):
    n, name, ms = line.split()
    rows.setdefault(int(n), {}).setdefault(name.replace('_', ' ', 1) if name == 'refused_call' else name, []).append(float(ms))
p95 = lambda v: sorted(v)[int(0.95 * (len(v) - 1))]
print('## Edits through the services in a big graph')
print()
print('`bench/service_edits.sh %s %s` (runs, rounds; sizes interleaved): a runtime loads a chain of N nodes,' % (sys.argv[2], sys.argv[3]))
print('then one client with persistent connections edits at its tail, one subscriber to ~graph. Per call,')
print('ms: median and p95 over all rounds; the median\'s ratio to a refused call\'s (the transport and')
print('the answer alone) at the same size. Target: an edit at 5,000 nodes in at most 2 ms.')
print()
names = ['add_node', 'connect', 'set_parameter', 'disconnect', 'remove_node', 'refused call']
print('| nodes | ' + ' | '.join(names) + ' |')
print('|---|' + '---|' * len(names))
for n in sorted(rows):
    base = statistics.median(rows[n]['refused call'])
    cells = []
    for name in names:
        v = rows[n][name]
        cells.append('%.2f / %.2f (%.1fx)' % (statistics.median(v), p95(v), statistics.median(v) / base))
    print('| %d | %s |' % (n, ' | '.join(cells)))
PY
