#!/usr/bin/env bash
# What splitting the demo over two runtimes costs per frame: runs test/ros/split.test RUNS times
# (each run plays the bag through one runtime, then through the split pair, on this computer:
# TCPROS over loopback), and prints a markdown section: per variant the median (min-max) of the
# runs' median latencies from the player's firing to the overlay's arrival, and their ratio.
#   bench/split_latency.sh BAG [RUNS]     (with this package's devel space sourced)
set -u
bag=$1 runs=${2:-5}
results=$(mktemp)
for _ in $(seq "$runs"); do
  rostest apex split.test bag:="$bag" results:="$results" >/dev/null 2>&1 || echo "split_latency: a run failed" >&2
done
python3 - "$results" "$runs" <<'PY'
import statistics, sys
rows = [tuple(map(float, l.split())) for l in open(sys.argv[1]) if l.strip()]
one, two = [r[0] for r in rows], [r[1] for r in rows]
ratios = [b / a for a, b in rows]
fmt = lambda v: '%.1f (%.1f-%.1f)' % (statistics.median(v), min(v), max(v))
print('## The demo split over two runtimes: per-frame latency')
print()
print('`bench/split_latency.sh` (test/ros/split.test, %d runs): the demo bag (40 frames, 640x480,' % len(rows))
print('played at its pace) through graphs/demo.yaml in one runtime, then through split_front.yaml and')
print('split_back.yaml in two runtimes on this computer (TCPROS over loopback: the camera image and the')
print('thinned cloud cross between them). Latency per frame: from the player firing the frame (its')
print('`stamp` seen through ~inspect, the same hop for both) to the overlay arriving at a subscriber.')
print('Median (min-max) over the runs of each run\'s median, ms; the ratio of the medians, and its range')
print('over the runs. Both variants play in every run, one after the other.')
print()
print('| one runtime | split over two | split / one |')
print('|---|---|---|')
print('| %s | %s | %.2fx (%.2f-%.2f) |' % (fmt(one), fmt(two), statistics.median(two) / statistics.median(one), min(ratios), max(ratios)))
PY
rm -f "$results"
