#!/usr/bin/env python3
"""What a resting runtime asks of the ROS master does not grow with its graph (#54 item 5).

A runtime watches the master (MasterWatch: a new master, or lost registration). Its check once
asked the master about every service it offered, each second: a paused 5,000-node graph used 61%
of a core doing so. Here a proxy between the runtime and a real master counts the runtime's calls
per method. The runtime loads a chain of 10 nodes, then one of 2,000 (each with parameters, so
each with dynamic_reconfigure's services), pauses, and the calls of the same number of checks
are counted for both: the big graph's must be no more than the small one's, and neither may list
the whole system (getSystemState) while nothing is edited.
   master_calls.py RESULT_XML     (with the devel space sourced)
"""
import os
import subprocess
import sys
import tempfile
import threading
import time
import xmlrpc.client
from collections import Counter
from socketserver import ThreadingMixIn
from xmlrpc.server import SimpleXMLRPCServer
from xml.sax.saxutils import quoteattr

NAME = '/apex_calls'
CHECKS = 5  # MasterWatch checks once a second, each with one getPid
SLACK = 2  # a window's ends may cut a check (getPid, then /run_id): what differs by that is the same


class Proxy(ThreadingMixIn, SimpleXMLRPCServer):
    daemon_threads = True


class Counting:
    """Forwards every call to the real master; counts the runtime's by method."""

    def __init__(self, master):
        self.master = master
        self.calls = Counter()
        self.lock = threading.Lock()

    def _dispatch(self, method, params):
        if params and str(params[0]).startswith(NAME):
            with self.lock:
                self.calls[method] += 1
        return getattr(xmlrpc.client.ServerProxy(self.master), method)(*params)

    def snapshot(self):
        with self.lock:
            return Counter(self.calls)


def chain(path, n):
    with open(path, 'w') as f:
        f.write('apex_graph: 2\nnodes:\n')
        for i in range(n):
            f.write('  - {name: b%d, type: apex_nodes/MedianBlur}\n' % i)
        f.write('connections:\n')
        for i in range(n - 1):
            f.write('  - {from: b%d/image, to: b%d/image}\n' % (i, i + 1))


def call(env, service, request, timeout=600):
    out = subprocess.run(['rosservice', 'call', '--wait', NAME + '/' + service, request], env=env,
                         capture_output=True, text=True, timeout=timeout)
    if 'success: True' not in out.stdout:
        raise RuntimeError('%s %s: %s%s' % (service, request, out.stdout, out.stderr))


def window(counting, limit=60):
    """The runtime's calls over CHECKS checks (each begins with one getPid), however long they take."""
    before = counting.snapshot()
    deadline = time.time() + limit
    while (counting.snapshot() - before)['getPid'] < CHECKS and time.time() < deadline:
        time.sleep(0.05)  # (polling the count: the condition is the checks made)
    return counting.snapshot() - before


def resting_calls(counting, at_most=None, limit=120):
    """The calls of CHECKS checks once what an edit set off is done (the parameters mirrored, the
    services listed once): the first window without a listing, and with no more calls than
    `at_most` if given; else, after `limit` s, the last window."""
    deadline = time.time() + limit
    while True:
        calls = window(counting)
        rested = not calls['getSystemState'] and (at_most is None or sum(calls.values()) <= sum(at_most.values()) + SLACK)
        if rested or time.time() > deadline:
            return calls


def main():
    out_xml = sys.argv[1]
    home = tempfile.mkdtemp()
    os.makedirs(os.path.join(home, 'apex'))
    chain(os.path.join(home, 'apex', 'small.yaml'), 10)
    chain(os.path.join(home, 'apex', 'big.yaml'), 2000)
    real_port, proxy_port = 20000 + os.getpid() % 10000, 30000 + os.getpid() % 2000
    env = dict(os.environ, ROS_HOME=home, ROS_MASTER_URI='http://localhost:%d' % real_port)
    procs = [subprocess.Popen(['roscore', '-p', str(real_port)], env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)]
    failure = ''
    try:
        deadline = time.time() + 60
        while subprocess.run(['rosparam', 'get', '/run_id'], env=env, capture_output=True).returncode != 0:
            if time.time() > deadline:
                raise RuntimeError('the master did not come up')
            time.sleep(0.2)
        counting = Counting(env['ROS_MASTER_URI'])
        proxy = Proxy(('localhost', proxy_port), logRequests=False, allow_none=True)
        proxy.register_instance(counting)
        threading.Thread(target=proxy.serve_forever, daemon=True).start()
        env['ROS_MASTER_URI'] = 'http://localhost:%d' % proxy_port
        log = open(os.path.join(home, 'runtime.log'), 'w')
        procs.append(subprocess.Popen(['rosrun', 'apex', 'apex_runtime_node', '__name:=' + NAME[1:]], env=env,
                                      stdout=log, stderr=subprocess.STDOUT))
        call(env, 'load_graph', '{path: small.yaml}')
        call(env, 'control', '{command: pause}')
        small = resting_calls(counting)
        call(env, 'load_graph', '{path: big.yaml}')
        call(env, 'control', '{command: pause}')
        big = resting_calls(counting, at_most=small)
        print('calls of %d checks, 10 nodes: %s; 2000 nodes: %s' % (CHECKS, dict(small), dict(big)))
        if sum(big.values()) > sum(small.values()) + SLACK:
            failure = ('a resting runtime of 2000 nodes asked the master more than one of 10 in %d checks: %s against %s'
                       % (CHECKS, dict(big), dict(small)))
        elif big['getSystemState'] or small['getSystemState']:
            failure = 'a resting runtime listed the whole system (getSystemState): %s' % dict(big + small)
    except Exception as e:  # noqa: BLE001 - any failure is the check's
        failure = str(e)
    finally:
        for p in reversed(procs):
            p.terminate()
            try:
                p.wait(timeout=30)
            except subprocess.TimeoutExpired:
                p.kill()
    with open(out_xml, 'w') as f:
        f.write('<?xml version="1.0" encoding="UTF-8"?>\n<testsuite name="master_calls" tests="1" failures="%d">\n'
                '  <testcase classname="MasterWatch" name="ARestingRuntimeAsksTheMasterTheSameWhateverItsSize">\n'
                % (1 if failure else 0))
        if failure:
            f.write('    <failure message=%s/>\n' % quoteattr(failure))
        f.write('  </testcase>\n</testsuite>\n')
    print('master_calls: ' + (failure or 'ok'))
    return 1 if failure else 0


if __name__ == '__main__':
    sys.exit(main())
