#!/usr/bin/env python3
"""The built-in Optimizer against Optuna's samplers on one tuning graph, at equal budgets, over
several seeds (bench/tune_compare.sh starts the runtime). Per method and seed: the search's wall
time, its best on the training bag and the held-out F1 of its best values; printed as a markdown
table of medians (min-max) and each method's time as a ratio to the built-in one-worker run of the
same seed (the methods run in turn for each seed: interleaved).

    tune_compare.py DATA TRAIN TEST BUDGET SEEDS   (TRAIN, TEST: bag stems in DATA, e.g. train_s1_f40_easy_real;
                                                   SEEDS: a count, 1 to N, or a list, e.g. 4,5)
"""
import statistics
import sys
import time

import optuna

import apex
from apex.tuning import Tuning

BUILT_IN = {'DE, 1 worker': (1, False), 'DE, 1 worker, racing': (1, True), 'DE, 2 workers': (2, False),
            'DE, 2 workers, racing': (2, True)}
OPTUNA = {'Optuna TPE': lambda s: (optuna.samplers.TPESampler(seed=s), None),
          'Optuna TPE, median pruner': lambda s: (optuna.samplers.TPESampler(seed=s),
                                                  optuna.pruners.MedianPruner(n_startup_trials=5, n_warmup_steps=5)),
          'Optuna CMA-ES': lambda s: (optuna.samplers.CmaEsSampler(seed=s, warn_independent_sampling=False), None),
          'Optuna random': lambda s: (optuna.samplers.RandomSampler(seed=s), None)}


def state(rt):
    return rt.parameter('optimizer', 'state')


def wait(rt, prefix, timeout=1800):
    until = time.time() + timeout
    while not str(state(rt)).startswith(prefix):
        if time.time() > until:
            raise RuntimeError('optimizer: no %r within %d s: %s' % (prefix, timeout, state(rt)))
        time.sleep(0.05)


def train(rt, tuning, data, stem):
    rt.set_parameter('score', 'truth', '%s/%s_truth.yaml' % (data, stem))
    if rt.parameter('bag', 'file') == '%s/%s.bag' % (data, stem):
        return tuning.evaluate({})
    return tuning.pass_of(lambda: rt.set_parameter('bag', 'file', '%s/%s.bag' % (data, stem)))


def held_out(rt, tuning, data, stem, values):
    tuning.apply(values)
    return train(rt, tuning, data, stem)


def built_in(rt, tuning, workers, racing, seed, budget):
    for p, v in (('budget', budget), ('seed', seed), ('workers', workers), ('racing', racing), ('study', '')):
        rt.set_parameter('optimizer', p, v)
    t0 = time.time()
    rt.fire_slot('optimizer', 'start')
    wait(rt, 'finished')
    took = time.time() - t0
    s = str(state(rt))
    best = float(s.split('; best ')[1].split(' at ')[0])
    return took, best, apex.decode(rt.parameter('optimizer', 'best_values'))


def with_optuna(tuning, make, seed, budget):
    sampler, pruner = make(seed)
    study = optuna.create_study(direction=tuning.direction, sampler=sampler, pruner=pruner)
    t0 = time.time()
    study.optimize(tuning, n_trials=budget)
    return time.time() - t0, study.best_value, tuning.values(study.best_params)


def main(data, train_stem, test_stem, budget, seeds):
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    rt = apex.Runtime('/apex', timeout=60)
    rows = []
    for seed in seeds:
        for name in list(BUILT_IN) + list(OPTUNA):
            tuning = Tuning(rt)
            train(rt, tuning, data, train_stem)
            if name in BUILT_IN:
                took, best, values = built_in(rt, tuning, *BUILT_IN[name], seed, budget)
            else:
                took, best, values = with_optuna(tuning, OPTUNA[name], seed, budget)
            held = held_out(rt, tuning, data, test_stem, values)
            rows.append((seed, name, took, best, held))
            print('seed %d  %-26s %6.1f s  best %.3f  held out %.3f' % (seed, name, took, best, held), flush=True)
            tuning.close()
    base = {r[0]: r[2] for r in rows if r[1] == 'DE, 1 worker'}

    def fmt(v, d=3):
        return '%.*f (%.*f-%.*f)' % (d, statistics.median(v), d, min(v), d, max(v))
    print()
    print('| method | held-out F1 | best F1 (training) | wall time, s | / DE 1 worker |')
    print('|---|---|---|---|---|')
    for name in list(BUILT_IN) + list(OPTUNA):
        mine = [r for r in rows if r[1] == name]
        print('| %s | %s | %s | %s | %s |' % (name, fmt([r[4] for r in mine]), fmt([r[3] for r in mine]),
                                             fmt([r[2] for r in mine], 1), fmt([r[2] / base[r[0]] for r in mine], 2)))
    print()
    print('seeds %s, budget %d, training %s, held out %s' % (', '.join(map(str, seeds)), budget, train_stem, test_stem))


if __name__ == '__main__':
    seeds = [int(x) for x in sys.argv[5].split(',')] if ',' in sys.argv[5] else list(range(1, int(sys.argv[5]) + 1))
    main(sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), seeds)
