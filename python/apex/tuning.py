"""Tuning a graph from Python: the search outside the runtime (Optuna), each evaluation inside it.

A graph made for the built-in Optimizer (graphs/tune_sign_detector.yaml: its outputs feed the tuned
parameters, its ``evaluate`` replays the bag and resets the mean, the mean's score comes back at its
``fitness``) is tuned by an Optuna study as it stands::

    import optuna, apex
    from apex.tuning import Tuning
    tuning = Tuning(apex.Runtime('/apex'))        # what the graph's Optimizer tunes, and how it scores
    study = optuna.create_study(direction=tuning.direction, sampler=optuna.samplers.TPESampler(seed=1),
                                pruner=optuna.pruners.MedianPruner(n_warmup_steps=10),
                                storage='sqlite:///signs.db', study_name='signs', load_if_exists=True)
    study.optimize(tuning, n_trials=200)           # a trial: set the values, replay, score
    tuning.apply(study.best_params)

The space is the Optimizer's own (its ``describe_space``: each dimension against the parameter it
tunes, on that parameter's grid), so every value a trial samples is one the built-in search could
send. Pruners get each frame's mean so far (the mean's ``running``) and a pruned pass is cut (the
Optimizer's ``cut`` targets: the player's ``end_pass``). Several processes, each with a runtime of
its own (on this machine or another) and one storage (sqlite, or any database URL), share one
study: Optuna hands each trial to one of them.

The runtime must not re-send a held frame after an edit (``runtime.launch rerun_on_edit:=false``;
launch/tune.launch sets it): the frame would count into the next pass.
"""
import threading
import time

import optuna
import rospy
import yaml
from std_msgs.msg import Float64, Int32

from .runtime import ApexError, ApexTimeout, decode, ros_node


class Tuning:
    """The evaluation loop of a graph's Optimizer, run from Python: an Optuna objective.

    ``Tuning(runtime, optimizer='optimizer', timeout=600)`` reads the Optimizer's space and wiring
    from the graph; ``timeout`` bounds one pass (ApexTimeout). Calling it with a trial samples the
    space (:meth:`suggest`), evaluates (:meth:`evaluate`) and returns the score. With the
    Optimizer's ``objectives: fitness_and_cost`` it returns two values, the score and the cost
    (the ms per frame the tuned nodes and those they feed, up to the mean, fired for), for a study
    of ``directions=tuning.directions`` (NSGA-II); such a trial reports no frame to a pruner
    (Optuna prunes single-objective studies only).
    """

    def __init__(self, runtime, optimizer='optimizer', timeout=600.0):
        self.runtime, self.optimizer, self.timeout = runtime, optimizer, timeout
        self._check_no_rerun()
        self.space = self._describe_space()
        links = runtime.connections()
        self.targets = {d['name']: self._links_from(links, d['name']) for d in self.space}
        for name, targets in self.targets.items():
            if not targets:
                raise ApexError(self._where(), "dimension '%s' feeds no parameter" % name)
        self._evaluate = self._slots(links, 'evaluate')
        self._cut = self._slots(links, 'cut')
        fitness = [(f, p) for f, p, t, tp, _ in links if (t, tp) == (optimizer, 'fitness')]
        if not fitness:
            raise ApexError(self._where(), "nothing feeds the Optimizer's fitness: connect the score's mean to it")
        self._mean_node, mean_port = fitness[0]
        self.direction = 'minimize' if runtime.parameter(optimizer, 'minimize') else 'maximize'
        # the Optimizer's objectives: fitness_and_cost adds the cost (ms per frame), to be minimised
        self.cost = runtime.parameter(optimizer, 'objectives') == 'fitness_and_cost'
        self.directions = [self.direction, 'minimize'] if self.cost else [self.direction]
        self._tuned = {node for targets in self.targets.values() for node, _ in targets}
        self._costly = self._between([l for l in links if optimizer not in (l[0], l[2])], self._tuned, self._mean_node)
        self._lock, self._changed = threading.Lock(), threading.Condition()
        self._means, self._counts, self._runnings = [], [], []
        outputs = {p.name for p in runtime.node(self._mean_node).ports if p.kind == 'output'}
        self._frames = {'count', 'running'} <= outputs  # a SequenceMean: frames counted, pruners fed
        self._subscribers = [self._subscribe(mean_port, Float64, self._means)]
        if self._frames:
            self._subscribers += [self._subscribe('count', Int32, self._counts),
                                  self._subscribe('running', Float64, self._runnings)]

    # ------------------------------------------------------------------ an Optuna objective

    def __call__(self, trial):
        return self.evaluate(self.suggest(trial), trial)

    def suggest(self, trial):
        """Samples each dimension with ``trial`` (an interval as its two ends, ``name.low`` and
        ``name.high``); returns the values by dimension, as :meth:`values` does."""
        for d in self.space:
            kind, name = d['kind'], d['name']
            if kind == 'choice':
                trial.suggest_categorical(name, d['options'])
            elif kind == 'flag':
                trial.suggest_categorical(name, [False, True])
            elif kind == 'integer':
                trial.suggest_int(name, int(d['low']), int(d['high']), step=int(d.get('step', 1)))
            else:
                for coordinate in ([name + '.low', name + '.high'] if kind == 'interval' else [name]):
                    trial.suggest_float(coordinate, d['low'], d['high'], step=d.get('step'))
        return self.values(trial.params)

    def values(self, params):
        """Optuna's parameters (a trial's ``params``, a study's ``best_params``) as the tuned
        parameters' values, by dimension: ``{'area': [800.0, 24000.0], 'operation': 'open'}``."""
        def grid(v, d):  # a step of 0.01 from 0.5 gives 0.6799999999999999: as 0.68, the parameter's value
            return min(max(float('%.12g' % v), d['low']), d['high']) if isinstance(v, float) else v
        out = {}
        for d in self.space:
            name = d['name']
            if d['kind'] == 'interval':
                ends = grid(params[name + '.low'], d), grid(params[name + '.high'], d)
                out[name] = [min(ends), max(ends)]
            else:
                out[name] = grid(params[name], d)
        return out

    # ------------------------------------------------------------------ evaluating in the runtime

    def evaluate(self, values, trial=None):
        """Sets the tuned parameters to ``values`` (by dimension; none: as they are), replays the
        data and returns the pass's score. With ``trial``: each frame's mean so far is reported (step: the frame) and,
        once the trial should be pruned, the pass is cut and ``optuna.TrialPruned`` raised. One
        pass at a time per runtime."""
        with self._lock:
            self.apply(values)
            if trial is not None:
                trial.set_user_attr('runtime', self.runtime.namespace)
            seen = self._mark()
            work = self._work() if self.cost else None
            for node, slot in self._evaluate:
                self.runtime.fire_slot(node, slot)
            score, frames, pruned = self._pass(seen, trial if not self.cost else None)
            if trial is not None and frames is not None:
                trial.set_user_attr('frames', frames)
            if pruned:
                raise optuna.TrialPruned('cut after %d frames, mean so far %g' % (frames, score))
            return (score, self._ms_per_frame(work)) if self.cost else score

    def apply(self, values):
        """Sets the tuned parameters: ``values`` by dimension (:meth:`values`), or Optuna's
        parameters (``study.best_params``)."""
        if not all(k in self.targets for k in values):  # Optuna's names (area.low, area.high)
            values = self.values(values)
        for name, value in values.items():
            for node, parameter in self.targets[name]:
                self.runtime.set_parameter(node, parameter, value)

    def play(self, node, parameter, value):
        """Sets a parameter that starts a pass (the player's ``file``) and returns that pass's
        score; if it held that value already (as the runtime applies it: a path made absolute),
        the data is replayed as :meth:`evaluate` does. Call it before the first trial: it waits for
        the pass, whose frames would otherwise count into that trial's."""
        with self._lock:
            before = self.runtime.parameter(node, parameter)
            seen = self._mark()
            if self.runtime.set_parameter(node, parameter, value) == before:
                for n, slot in self._evaluate:
                    self.runtime.fire_slot(n, slot)
            return self._pass(seen, None)[0]

    def pass_of(self, edit):
        """The score of the pass that ``edit()`` starts, e.g. ``lambda: rt.set_parameter('bag',
        'file', path)`` on a player that plays once its file is set: wait for it before the first
        trial, or its frames count into that trial's pass."""
        with self._lock:
            seen = self._mark()
            edit()
            return self._pass(seen, None)[0]

    def close(self):
        """Stops listening to the mean (the inspect topics stay published)."""
        for sub in self._subscribers:
            sub.unregister()
        self._subscribers = []

    # ------------------------------------------------------------------ the pass

    def _mark(self):
        with self._changed:
            return len(self._means), len(self._counts), len(self._runnings)

    def _pass(self, seen, trial):
        """Waits for the pass after ``seen`` to end: its score, its frames (None if not counted)
        and whether it was cut for the trial's pruner. Every frame's mean so far is reported to the
        trial, however late it comes (pruners compare trials frame by frame), up to a cut."""
        means, counts, first = seen  # this pass's first frame: the earlier passes' all came before the mark
        reported, pruned, counted = 0, False, None
        until = time.time() + self.timeout
        while True:
            with self._changed:
                frames = self._counts[counts] if self._frames and len(self._counts) > counts else None
                if frames is not None and len(self._means) > means and counted is None:
                    counted = time.time()
                # the frames' means come on their own topic, a moment behind; a pass's frames not all
                # seen (the graph was not at rest when this began) are waited for 10 s, no longer
                drained = frames is not None and (len(self._runnings) >= first + frames or
                                                  (counted is not None and time.time() > counted + 10))
                ended = len(self._means) > means and (not self._frames or drained)
                last = first + frames if frames is not None else len(self._runnings)
                new = self._runnings[first + reported:last] if trial is not None and self._frames and not pruned else []
                if ended and not new:
                    return self._means[means], frames, pruned
                if not new:
                    left = until - time.time()
                    if left <= 0 or rospy.is_shutdown():
                        raise ApexTimeout(self._where(), 'no pass ended within %g s (%d of its frames scored so far)'
                                          % (self.timeout, len(self._runnings) - first))
                    self._changed.wait(min(left, 0.5))
                    continue
            for value in new:  # outside the lock: a storage's write takes a while
                trial.report(value, reported)
                reported += 1
                if not ended and trial.should_prune():
                    pruned = True
                    for node, slot in self._cut:
                        self.runtime.fire_slot(node, slot)
                    break

    # ------------------------------------------------------------------ reading the graph

    def _where(self):
        return '%s: node %s' % (self.runtime.namespace, self.optimizer)

    def _check_no_rerun(self):
        if rospy.get_param(self.runtime.namespace.rstrip('/') + '/rerun_on_edit', True):
            raise ApexError(self._where(), 'the runtime re-sends a held frame after each edit, which would count '
                                           'into the next pass: start it with rerun_on_edit:=false (runtime.launch; '
                                           'tune.launch does)')

    def _describe_space(self):
        rt, node = self.runtime, self.optimizer
        rt.set_parameter(node, 'space', '')
        error_before = rt.node(node).error  # an error from before is not the slot's answer
        rt.fire_slot(node, 'describe_space')
        until = time.time() + 30
        while True:
            info = rt.node(node)
            space = next((p.value for p in info.parameters if p.name == 'space'), None)
            if space is None:
                raise ApexError(self._where(), 'is not an apex_nodes/Optimizer (no parameter space)')
            space = decode(space) if space else None  # the parameter's value: YAML text of the YAML text
            space = yaml.safe_load(space) if space else None
            if space:
                return space
            if info.error and info.error != error_before:
                raise ApexError(self._where(), info.error)
            if time.time() > until:
                raise ApexTimeout(self._where(), 'describe_space did not answer within 30 s' +
                                  (': ' + info.error if info.error else ''))
            time.sleep(0.05)

    def _work(self):
        """Each costly node's profile now (its firings, timed firings and their time)."""
        return {node: self.runtime.node_profile(node) for node in self._costly}

    def _ms_per_frame(self, before):
        """The ms per frame the costly nodes fired for since ``before`` (:meth:`_work`): each node's
        mean over its timed firings since then, times its firings, per frame (a tuned node's firings)."""
        after = self._work()
        frames = max((after[n]['firings'] - before[n]['firings'] for n in self._tuned if n in after), default=0)
        if frames <= 0:
            return 0.0
        ms = 0.0
        for node, now in after.items():
            timed = now['timed_firings'] - before[node]['timed_firings']
            if timed > 0:
                ms += (now['timed_ms'] - before[node]['timed_ms']) / timed * (now['firings'] - before[node]['firings'])
        return ms / frames

    @staticmethod
    def _between(links, tuned, mean):
        """The tuned nodes and the nodes they feed, up to the mean: the part a candidate's cost is of
        (``links`` without the Optimizer's)."""
        data = [(f, t) for f, _, t, _, kind in links if kind in ('data', 'parameter')]

        def reach(start, step):
            seen, todo = set(start), list(start)
            while todo:
                n = todo.pop()
                for nxt in step(n):
                    if nxt not in seen:
                        seen.add(nxt)
                        todo.append(nxt)
            return seen
        down = reach(tuned, lambda n: [t for f, t in data if f == n])
        up = reach({mean}, lambda n: [f for f, t in data if t == n])
        return down & up

    def _links_from(self, links, port):
        return [(t, tp) for f, p, t, tp, _ in links if (f, p) == (self.optimizer, port)]

    def _slots(self, links, trigger):
        """The slots a trigger of the Optimizer fires, those of nodes that receive data first (as the
        runtime orders a trigger's events: a player restarts after the mean was reset)."""
        receiving = {t for _, _, t, _, kind in links if kind == 'data'}
        return sorted(self._links_from(links, trigger), key=lambda s: s[0] not in receiving)

    def _subscribe(self, port, kind, into):
        ros_node()
        topic, _ = self.runtime.inspect(self._mean_node, port)

        def received(msg):
            with self._changed:
                into.append(msg.data)
                self._changed.notify_all()
        sub = rospy.Subscriber(topic, kind, received, queue_size=10000)
        until = time.time() + 30
        while sub.get_num_connections() == 0:
            if time.time() > until or rospy.is_shutdown():
                raise ApexTimeout(topic, 'no publisher within 30 s')
            time.sleep(0.01)
        return sub
