#!/usr/bin/env bash
# What workers and racing buy the tuning demo: runs `scripts/demo --tune` (or with the demo
# options given after --, e.g. -- --backgrounds real) ROUNDS times, each round the five variants
# in turn (1 worker, 1 worker racing, 2 workers, 2 workers racing (paired), 2 workers racing with
# the bound rule), and prints a markdown section:
# per variant the median (min-max) of the Optimizer's run time, its ratio to the one-worker run of
# the same round, the best training F1, the held-out F1, how many candidates were cut short and
# the share of the frames scored.
#   bench/tune_workers.sh [ROUNDS] [-- demo options]   (with this package's devel space sourced)
set -u
rounds=${1:-3}
shift || true
[ "${1:-}" = -- ] && shift
here=$(cd "$(dirname "$0")/.." && pwd)
results=$(mktemp)
variants=("--workers 1" "--workers 1 --racing" "--workers 2" "--workers 2 --racing" "--workers 2 --racing bound")
for round in $(seq "$rounds"); do
  for v in "${variants[@]}"; do
    # shellcheck disable=SC2086  # the variant is words
    out=$("$here/scripts/demo" --tune $v "$@" 2>&1)
    took=$(sed -n 's/^the run took \([0-9.]*\) s.*/\1/p' <<<"$out")
    best=$(sed -n 's/^best on the training bag: F1 \([0-9.]*\).*/\1/p' <<<"$out")
    held=$(sed -n 's/.*->  tuned F1 \([0-9.]*\).*/\1/p' <<<"$out")
    cut=$(sed -n 's/^optimiser: .* \([0-9]*\) cut short.*/\1/p' <<<"$out")
    share=$(sed -n 's/^optimiser: .* cut short, \([0-9]*\)% of the frames scored.*/\1/p' <<<"$out")
    [ -n "$took" ] || { echo "tune_workers: '$v' failed:" >&2; tail -5 <<<"$out" >&2; continue; }
    echo "$round|$v|$took|$best|$held|${cut:-0}|${share:-100}" >>"$results"
  done
done
python3 - "$results" "$*" <<'PY'
import statistics, sys
rows = [l.strip().split('|') for l in open(sys.argv[1]) if l.strip()]
base = {r[0]: float(r[2]) for r in rows if r[1] == '--workers 1'}
fmt = lambda v, d=1: ('%.*f (%.*f-%.*f)' % (d, statistics.median(v), d, min(v), d, max(v))) if v else '-'
print('| variant | run time, s | / 1 worker | best F1 (training) | tuned F1 (held out) | cut short | frames scored, % |')
print('|---|---|---|---|---|---|---|')
for v in ['--workers 1', '--workers 1 --racing', '--workers 2', '--workers 2 --racing', '--workers 2 --racing bound']:
    mine = [r for r in rows if r[1] == v]
    ratios = [float(r[2]) / base[r[0]] for r in mine if r[0] in base]
    print('| `%s` | %s | %s | %s | %s | %s | %s |' % (v, fmt([float(r[2]) for r in mine]), fmt(ratios, 2),
          ', '.join(sorted({r[3] for r in mine})), ', '.join(sorted({r[4] for r in mine})),
          fmt([float(r[5]) for r in mine], 0), fmt([float(r[6]) for r in mine], 0)))
print()
print('%d rounds, the variants in turn in each; demo options: %s' % (len(base), sys.argv[2] or '(none)'))
PY
