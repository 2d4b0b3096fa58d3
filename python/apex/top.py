"""apex_top: a runtime's nodes in a terminal, as `top` shows processes (scripts/apex_top).

For a robot reached over ssh: each node's share of time, rate, mean/p95/max ms, latency from its
frames' stamps (p50, p95), firings, frames dropped, state and what
a stalled node waits for, from ``~status``; keys sort, pause the graph and turn the frame trace on
and off through the runtime's services, as the panel does. The table is built by :func:`table`
(plain text, no terminal needed): ``apex_top --once`` prints it once.
"""
import time

SORTS = ('time', 'rate', 'p95', 'latency', 'name', 'state')
SORT_HELP = {'time': 'share of time (rate x mean)', 'rate': 'firings per second', 'p95': '95th percentile of the time',
             'latency': 'latency from the frame\'s stamp (p95)', 'name': 'name', 'state': 'errors and stalls first'}
KEYS = 'q quit  p pause/resume  s sort  t trace on/off  space freeze  r reverse'


class Rates:
    """Each node's firings per second, from two statuses (their stamps and firing counts)."""

    def __init__(self):
        self._last = None  # (stamp in s, {node: firings})
        self.rates = {}

    def update(self, status):
        now = status.stamp.to_sec()
        counts = {n.name: n.firings for n in status.nodes}
        if self._last is not None and now > self._last[0]:
            dt = now - self._last[0]
            self.rates = {name: max(0.0, (count - self._last[1].get(name, count)) / dt) for name, count in counts.items()}
        self._last = (now, counts)
        return self.rates


def _state(node):
    if node.state == 'error':
        return 'ERROR'
    if node.state == 'disabled':
        return 'off'
    return 'stalled' if node.waiting_for else 'ok'


def _key(sort, rates):
    rank = {'ERROR': 0, 'stalled': 1, 'ok': 2, 'off': 3}
    return {
        'time': lambda n: -rates.get(n.name, 0.0) * n.mean_ms,
        'rate': lambda n: -rates.get(n.name, 0.0),
        'p95': lambda n: -n.p95_ms,
        'latency': lambda n: -n.latency_p95_ms,
        'name': lambda n: n.name,
        'state': lambda n: (rank[_state(n)], n.name),
    }[sort]


def table(status, rates, sort='time', reverse=False, width=120, paused=False, namespace='/apex'):
    """The screen as lines of text: a header (runtime, paused, tracing, thread groups' load), then
    one line per node sorted by `sort` (one of SORTS)."""
    groups = '  '.join('%s %3.0f%%' % (g.name, 100 * g.load) for g in status.groups)
    busy = sum(rates.get(n.name, 0.0) * n.mean_ms for n in status.nodes) / 10.0  # % of one core
    lines = [
        ('apex_top %s  %s%s  %d nodes  %.0f%% of a core  groups: %s' %
         (namespace, 'PAUSED' if paused else 'running', '  TRACING' if status.tracing else '', len(status.nodes),
          busy, groups or '-'))[:width],
        ('sort: %s%s   keys: %s' % (SORT_HELP[sort], ' (reversed)' if reverse else '', KEYS))[:width],
        '',
        '%-36s %6s %8s %8s %8s %8s %9s %9s %9s %7s %8s  %s' % (
            'NODE', '%TIME', 'RATE Hz', 'MEAN ms', 'P95 ms', 'MAX ms', 'LAT50 ms', 'LAT95 ms', 'FIRINGS', 'DROPPED',
            'STATE', 'WAITS FOR / ERROR'),
    ]
    nodes = sorted(status.nodes, key=_key(sort, rates), reverse=reverse)
    for n in nodes:
        rate = rates.get(n.name, 0.0)
        why = n.error if n.state == 'error' else n.waiting_for
        latency = lambda ms: '%9.1f' % ms if ms >= 0 else '%9s' % '-'
        line = '%-36s %6.1f %8.1f %8.2f %8.2f %8.2f %s %s %9d %7d %8s  %s' % (
            n.name[:36], rate * n.mean_ms / 10.0, rate, n.mean_ms, n.p95_ms, n.max_ms, latency(n.latency_p50_ms),
            latency(n.latency_p95_ms), n.firings, n.dropped, _state(n), why)
        lines.append(line[:width])
    return lines


class View:
    """What the person chose: sort, order, frozen; and a line of news (what a key did)."""

    def __init__(self):
        self.sort, self.reverse, self.frozen, self.note = 'time', False, False, ''

    def key(self, key, runtime, namespace, status):
        """Acts on one key; False for quit."""
        if key in ('q', 'Q'):
            return False
        if key == 'p':
            paused = runtime.control('resume' if runtime.graph().paused else 'pause')
            self.note = 'PAUSED: the graph holds, edits still apply (p resumes)' if paused else 'resumed'
        elif key == 's':
            self.sort = SORTS[(SORTS.index(self.sort) + 1) % len(SORTS)]
        elif key == 'r':
            self.reverse = not self.reverse
        elif key == ' ':
            self.frozen = not self.frozen
        elif key == 't' and status is not None:
            on = runtime.trace('stop' if status.tracing else 'start')
            self.note = ('tracing: save it with  rosservice call %s/trace "{command: save}"' % namespace if on
                         else 'stopped tracing')
        return True


def run_curses(screen, runtime, namespace):
    """The interactive view: redrawn at each status (~2 Hz) and after each key."""
    import curses
    curses.curs_set(0)
    screen.timeout(100)
    rates, view, shown, paused, asked = Rates(), View(), None, runtime.graph().paused, time.time()
    while True:
        status = runtime.latest_status()
        fresh = status is not None and status is not shown
        if fresh and not view.frozen:
            rates.update(status)
            shown = status
        elif shown is None:
            shown = status
        if time.time() - asked > 2.0:
            paused, asked = runtime.graph().paused, time.time()
        if fresh or shown is not None:
            height, width = screen.getmaxyx()
            lines = table(shown, rates.rates, view.sort, view.reverse, width - 1, paused, namespace) if shown else \
                ['apex_top %s: waiting for %s/status' % (namespace, namespace)]
            if view.frozen:
                lines[0] = (lines[0] + '  FROZEN')[:width - 1]
            if view.note and len(lines) > 2:
                lines[2] = view.note[:width - 1]
            screen.erase()
            for y, line in enumerate(lines[:height - 1]):
                screen.addstr(y, 0, line, curses.A_REVERSE if y == 3 else curses.A_NORMAL)
            screen.refresh()
        code = screen.getch()
        if code < 0 or code > 255:
            continue
        if not view.key(chr(code), runtime, namespace, shown):
            return
        if chr(code) == 'p':
            paused, asked = runtime.graph().paused, time.time()
