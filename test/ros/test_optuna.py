#!/usr/bin/env python3
"""Tuning from Python with Optuna (python/apex/tuning.py, scripts/apex_optuna) against two runtimes
with the paper's tuning graph on the demo bag (optuna.test): the Optimizer's space, two processes
sharing one study through sqlite with each trial evaluated once, a pruned pass cut short
without a frame of it counting into the next, and two objectives (the score and ms per frame)
with their Pareto front. The built-in search across the two runtimes: one Optimizer's remote
worker is the other runtime's Optimizer, each candidate evaluated once, by one of them."""
import os
import shutil
import subprocess
import tempfile
import threading
import unittest

import optuna
import rospy
import rostest
from roslib.packages import find_node
from std_msgs.msg import Float64
from waiting import wait_until

import apex
from apex.tuning import Tuning

RUNTIMES = ('/a/apex', '/b/apex')
FRAMES = 40  # the demo bag's (test/CMakeLists.txt)


class PassCount:
    """The passes a runtime ends, counted from its mean's topic (apart from the Tuning's own)."""

    def __init__(self, rt):
        topic, _ = rt.inspect('mean', 'mean')
        self.n, self.lock = 0, threading.Lock()
        self.sub = rospy.Subscriber(topic, Float64, self.received, queue_size=1000)
        assert wait_until(lambda: self.sub.get_num_connections() > 0, 30), topic

    def received(self, _):
        with self.lock:
            self.n += 1

    def __call__(self):
        with self.lock:
            return self.n


class PruneEven(optuna.pruners.BasePruner):
    """Prunes each even-numbered trial at its fifth frame."""

    def prune(self, study, trial):
        return trial.number % 2 == 0 and trial.last_step is not None and trial.last_step >= 4


class Optuna(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_optuna')
        optuna.logging.set_verbosity(optuna.logging.WARNING)
        data = rospy.get_param('~data')
        cls.bag, cls.truth = os.path.join(data, 'test_demo.bag'), os.path.join(data, 'test_truth.yaml')
        cls.work = tempfile.mkdtemp(prefix='apex_optuna_')
        cls.rts = {ns: apex.Runtime(ns, timeout=60) for ns in RUNTIMES}
        cls.passes = {ns: PassCount(rt) for ns, rt in cls.rts.items()}

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.work, ignore_errors=True)

    def test_1_the_space_is_the_optimizers_on_the_parameters_grids(self):
        tuning = Tuning(self.rts['/a/apex'])
        space = {d['name']: d for d in tuning.space}
        self.assertEqual(list(space), ['c', 'block_size', 'kernel_size', 'min_area', 'max_area'])
        self.assertEqual((space['c']['kind'], space['c']['low'], space['c']['high']), ('number', 0, 40))
        self.assertNotIn('step', space['c'])
        # the threshold's block size is odd (3, 5, ...): 'block_size 15 101 int' samples 15, 17, ... 101
        self.assertEqual((space['block_size']['kind'], space['block_size']['low'], space['block_size']['high'],
                          space['block_size']['step']), ('integer', 15, 101, 2))
        self.assertEqual(tuning.targets['block_size'], [('threshold', 'block_size')])
        self.assertEqual(tuning.direction, 'maximize')
        trial = optuna.trial.FixedTrial({'c': 12.5, 'block_size': 31, 'kernel_size': 3, 'min_area': 100, 'max_area': 9000})
        self.assertEqual(tuning.suggest(trial), {'c': 12.5, 'block_size': 31, 'kernel_size': 3, 'min_area': 100,
                                                 'max_area': 9000})

    def test_2_two_runtimes_share_one_study_each_trial_evaluated_once(self):
        storage = 'sqlite:///' + os.path.join(self.work, 'shared.db')
        before = {ns: self.passes[ns]() for ns in RUNTIMES}
        workers = [subprocess.Popen(
            [find_node('apex', 'apex_optuna')[0], '--runtime', ns, '--storage', storage, '--study', 'shared',
             '--trials', '12', '--sampler', 'random', '--seed', str(seed), '--set', 'score/truth=' + self.truth,
             '--play', 'bag/file=' + self.bag], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            for seed, ns in enumerate(RUNTIMES)]
        try:
            outputs = [w.communicate(timeout=240)[0] for w in workers]
        except subprocess.TimeoutExpired:
            for w in workers:
                w.kill()
            self.fail('a worker did not end within 240 s: ' + ' | '.join(w.communicate()[0] for w in workers))
        for w, out in zip(workers, outputs):
            self.assertEqual(w.returncode, 0, out)
            self.assertIn('the graph as it is: ', out)

        trials = optuna.load_study(study_name='shared', storage=storage).trials
        self.assertGreaterEqual(len(trials), 12)
        self.assertTrue(all(t.state == optuna.trial.TrialState.COMPLETE for t in trials), trials)
        by = {ns: [t for t in trials if t.user_attrs['runtime'] == ns] for ns in RUNTIMES}
        self.assertEqual(sum(len(v) for v in by.values()), len(trials))
        for ns in RUNTIMES:
            self.assertGreater(len(by[ns]), 0, 'no trial ran on %s' % ns)
            self.assertTrue(all(t.user_attrs['frames'] == FRAMES for t in by[ns]))
            # every frame's mean so far reported to the pruner (none lost on the way)
            self.assertTrue(all(sorted(t.intermediate_values) == list(range(FRAMES)) for t in by[ns]))
            # each of its trials one pass, and the pass of --play: nothing evaluated twice, nothing more
            self.assertTrue(wait_until(lambda: self.passes[ns]() - before[ns] == len(by[ns]) + 1, 30),
                            '%s: %d passes for %d trials' % (ns, self.passes[ns]() - before[ns], len(by[ns])))
        self.assertTrue(all(0 <= t.value <= 1 for t in trials))

    def test_3_a_pruned_pass_is_cut_and_counts_nothing_into_the_next(self):
        rt = self.rts['/b/apex']
        rt.set_parameter('score', 'truth', self.truth)
        tuning = Tuning(rt)
        tuning.play('bag', 'file', self.bag)  # a pass, whether the file was set already or not
        study = optuna.create_study(direction=tuning.direction, sampler=optuna.samplers.RandomSampler(seed=7),
                                    pruner=PruneEven())
        rate = rt.parameter('bag', 'rate')
        rt.set_parameter('bag', 'rate', 0.5)  # 5 frames a second: the cut at the fifth comes long before the end
        try:
            study.optimize(tuning, n_trials=4)
        finally:
            rt.set_parameter('bag', 'rate', rate)
        for t in study.trials:
            if t.number % 2 == 0:
                self.assertEqual(t.state, optuna.trial.TrialState.PRUNED)
                self.assertLess(t.user_attrs['frames'], FRAMES)  # the player's end_pass cut the pass
                self.assertEqual(sorted(t.intermediate_values), [0, 1, 2, 3, 4])
            else:
                self.assertEqual(t.state, optuna.trial.TrialState.COMPLETE)
                self.assertEqual(t.user_attrs['frames'], FRAMES)
                # the whole pass after a cut one scores as the same values evaluated again
                self.assertEqual(tuning.evaluate(tuning.values(t.params)), t.value)

    def test_4_a_runtime_that_reruns_edits_is_refused(self):
        rospy.set_param('/a/apex/rerun_on_edit', True)
        try:
            with self.assertRaises(apex.ApexError) as error:
                Tuning(self.rts['/a/apex'])
            self.assertIn('rerun_on_edit:=false', str(error.exception))
        finally:
            rospy.set_param('/a/apex/rerun_on_edit', False)

    def test_5_two_objectives_give_a_pareto_front_of_score_and_ms_per_frame(self):
        rt = self.rts['/a/apex']
        storage = 'sqlite:///' + os.path.join(self.work, 'costed.db')
        rt.set_parameter('optimizer', 'objectives', 'fitness_and_cost')
        try:
            self.assertEqual(Tuning(rt).directions, ['maximize', 'minimize'])
            out = subprocess.run(
                [find_node('apex', 'apex_optuna')[0], '--runtime', '/a/apex', '--storage', storage, '--study', 'costed',
                 '--trials', '8', '--sampler', 'nsga2', '--seed', '3', '--set', 'score/truth=' + self.truth,
                 '--play', 'bag/file=' + self.bag], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                timeout=240)
        finally:
            rt.set_parameter('optimizer', 'objectives', 'fitness')
        self.assertEqual(out.returncode, 0, out.stdout)
        study = optuna.load_study(study_name='costed', storage=storage)
        self.assertEqual(study.directions, [optuna.study.StudyDirection.MAXIMIZE, optuna.study.StudyDirection.MINIMIZE])
        trials = study.get_trials(states=(optuna.trial.TrialState.COMPLETE,))
        self.assertEqual(len(trials), 8, out.stdout)
        for t in trials:
            score, ms = t.values
            self.assertTrue(0 <= score <= 1, t.values)
            self.assertGreater(ms, 0, 'the tuned nodes fired for no time: %s' % t.values)
            self.assertEqual(t.user_attrs['frames'], FRAMES)
        front = study.best_trials
        self.assertIn('front: %d trials' % len(front), out.stdout)
        self.assertEqual(out.stdout.count('\n  front: '), len(front), out.stdout)
        for a in front:  # none of the front is beaten on both by another trial
            self.assertFalse(any(b.values[0] >= a.values[0] and b.values[1] <= a.values[1] and b.values != a.values
                                 for b in trials), a.values)

    def test_6_the_built_in_search_evaluates_one_study_in_both_runtimes_each_candidate_once(self):
        here, there = self.rts['/a/apex'], self.rts['/b/apex']
        for rt in (here, there):  # both reach the same files
            rt.set_parameter('score', 'truth', self.truth)
            Tuning(rt).play('bag', 'file', self.bag)
        study = os.path.join(rospy.get_param('~data'), 'built_in_%d.csv' % os.getpid())  # in the file roots
        self.addCleanup(lambda: os.path.exists(study) and os.remove(study))
        settings = {'algorithm': 'differential_evolution', 'budget': 12, 'population': 6, 'workers': 1,
                    'remote_workers': ['/b/apex'], 'study': study}
        before = {name: here.parameter('optimizer', name) for name in settings}
        passes = {ns: self.passes[ns]() for ns in RUNTIMES}
        try:
            for name, value in settings.items():
                here.set_parameter('optimizer', name, value)
            here.fire_slot('optimizer', 'start')
            self.assertTrue(wait_until(lambda: here.parameter('optimizer', 'state').startswith(('finished', 'stopped')), 240),
                            here.parameter('optimizer', 'state'))
        finally:
            for name, value in before.items():
                here.set_parameter('optimizer', name, value)
        state, served = here.parameter('optimizer', 'state'), there.parameter('optimizer', 'state')
        self.assertTrue(state.startswith('finished after 12 evaluations'), state)
        remote = int(state.split(' evaluated by /b/apex')[0].split('; ')[-1])
        self.assertTrue(0 < remote < 12, state)  # both evaluated some
        self.assertEqual(served, 'served %d candidates for other runtimes' % remote)
        with open(study) as f:
            rows = [line.split(',') for line in f.read().splitlines()[2:]]
        self.assertEqual([int(r[0]) for r in rows], list(range(1, 13)))  # each candidate once, in the order asked
        self.assertTrue(all(0 <= float(r[1]) <= 1 for r in rows), rows)
        for ns in RUNTIMES:  # the graphs rested: copies evaluated, here and there
            self.assertEqual(self.passes[ns](), passes[ns], ns)


if __name__ == '__main__':
    rostest.rosrun('apex', 'optuna', Optuna)
