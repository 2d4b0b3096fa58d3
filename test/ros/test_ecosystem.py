#!/usr/bin/env python3
"""APEX through the tools ROS users already have: dynamic_reconfigure's own Client and
/diagnostics, on the demo graph (grouped) with the generated bag looping inside it."""
import os
import shutil
import threading
import time
import unittest

import rosgraph
import rospy
import rostest
from waiting import wait_until
from apex.srv import AddNode, GetGraph, RemoveNode, RenameNode, SetEnabled, SetParameter, Connect
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from roscpp.srv import GetLoggers, SetLoggerLevel
from rosgraph_msgs.msg import Log
from dynamic_reconfigure.client import Client
from dynamic_reconfigure.encoding import encode_config
from dynamic_reconfigure.srv import Reconfigure

THRESHOLD = 'camera_detector/threshold'


def service(name, kind):
    rospy.wait_for_service('/apex/' + name, 60)
    return rospy.ServiceProxy('/apex/' + name, kind)


def parameter(node, name):
    """The value ~get_graph gives (YAML text)."""
    for n in service('get_graph', GetGraph)().graph.nodes:
        if n.name == node:
            for p in n.parameters:
                if p.name == name:
                    return p.value
    return None


def served(name):
    """Whether the master lists the service."""
    try:
        rosgraph.Master('/test_ecosystem').lookupService(name)
        return True
    except rosgraph.MasterError:
        return False


class Diagnostics:
    """The newest status of each name on /diagnostics."""

    def __init__(self):
        self.lock = threading.Lock()
        self.status = {}
        self.sub = rospy.Subscriber('/diagnostics', DiagnosticArray, self.received, queue_size=100)

    def received(self, msg):
        with self.lock:
            for s in msg.status:
                self.status[s.name] = s

    def of(self, node):
        with self.lock:
            return self.status.get('apex: node ' + node)

    def wait_level(self, node, level, timeout=30.0):
        ok = wait_until(lambda: self.of(node) is not None and self.of(node).level == level, timeout)
        return ok, self.of(node)


class Ecosystem(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.diagnostics = Diagnostics()

    def test_client_lists_sets_and_hears_changes(self):
        updates = []
        client = Client('/apex/' + THRESHOLD, timeout=60, config_callback=updates.append)
        params = {p['name']: p for p in client.get_parameter_descriptions(timeout=30)}
        self.assertEqual(params['block_size']['type'], 'int')
        self.assertEqual((params['block_size']['min'], params['block_size']['max']), (3, 101))
        self.assertEqual(params['c']['type'], 'double')
        self.assertLess(params['c']['min'], params['c']['max'])
        self.assertIn('gaussian', params['method']['edit_method'])  # a set: an enum of its options
        self.assertEqual(client.get_configuration(timeout=30)['block_size'], 101)

        applied = client.update_configuration({'c': 12.5, 'method': 'mean'})
        self.assertEqual((applied['c'], applied['method']), (12.5, 'mean'))
        self.assertEqual(parameter(THRESHOLD, 'c'), '12.5')
        self.assertEqual(parameter(THRESHOLD, 'method'), 'mean')

        # A change through the service reaches the client's callback.
        res = service('set_parameter', SetParameter)(node=THRESHOLD, parameter='c', value='30')
        self.assertTrue(res.success, res.message)
        self.assertTrue(wait_until(lambda: updates and updates[-1]['c'] == 30.0), updates[-1:])

        # A refused value is refused with the service's message, and nothing of the call is applied
        # (block_size, an int, is set before c, a double: it is put back).
        refused = service('set_parameter', SetParameter)(node=THRESHOLD, parameter='c', value='500.0')
        self.assertFalse(refused.success)
        raw = rospy.ServiceProxy('/apex/' + THRESHOLD + '/set_parameters', Reconfigure)
        with self.assertRaises(rospy.ServiceException) as error:
            raw(encode_config({'block_size': 51, 'c': 500.0}))
        self.assertIn(refused.message, str(error.exception))
        self.assertEqual(parameter(THRESHOLD, 'block_size'), '101')
        self.assertEqual(parameter(THRESHOLD, 'c'), '30.0')
        with self.assertRaises(Exception):  # the Client says so too
            client.update_configuration({'c': 500.0})
        client.close()

    def test_servers_come_and_go_with_their_nodes(self):
        add = service('add_node', AddNode)(type='apex_nodes/Clock', name='dr_clock', parameters='{rate: 5.0}')
        self.assertTrue(add.success, add.message)
        self.assertTrue(wait_until(lambda: served('/apex/dr_clock/set_parameters')), 'no server for an added node')
        client = Client('/apex/dr_clock', timeout=30)
        self.assertEqual(client.update_configuration({'rate': 2.0})['rate'], 2.0)
        client.close()
        renamed = service('rename_node', RenameNode)(name='dr_clock', new_name='dr_ticker')
        self.assertTrue(renamed.success, renamed.message)
        self.assertTrue(wait_until(lambda: served('/apex/dr_ticker/set_parameters')), 'no server after a rename')
        self.assertTrue(wait_until(lambda: not served('/apex/dr_clock/set_parameters')), 'the old name is served')
        removed = service('remove_node', RemoveNode)(name='dr_ticker')
        self.assertTrue(removed.success, removed.message)
        self.assertTrue(wait_until(lambda: not served('/apex/dr_ticker/set_parameters')), 'a removed node is served')

    # ---------------------------------------------------------------- /diagnostics

    def test_healthy_nodes_are_ok(self):
        ok, status = self.diagnostics.wait_level(THRESHOLD, DiagnosticStatus.OK)
        self.assertTrue(ok, status)
        values = {kv.key: kv.value for kv in status.values}
        self.assertGreater(int(values['firings']), 0)
        self.assertIn('rate (Hz)', values)
        self.assertTrue(wait_until(lambda: 'apex: thread group vision' in self.diagnostics.status),
                        'no status for the thread group vision')

    def test_the_shipped_analyzers_file_apex_statuses_under_apex(self):
        names = set()

        def received(msg):
            names.update(s.name for s in msg.status)
        sub = rospy.Subscriber('/diagnostics_agg', DiagnosticArray, received)
        ok = wait_until(lambda: any(n.startswith('/APEX/Nodes/') for n in set(names)) and
                        any(n.startswith('/APEX/Thread groups/') for n in set(names)))
        sub.unregister()
        self.assertTrue(ok, sorted(names))

    def test_a_node_slower_than_expected_is_warn(self):
        ok, status = self.diagnostics.wait_level('cloud_out', DiagnosticStatus.WARN)  # ~expected_rates: 1000 Hz
        self.assertTrue(ok, status)
        self.assertIn('slow', status.message)

    def test_a_stalled_node_is_warn_with_what_it_waits_for(self):
        add = service('add_node', AddNode)
        connect = service('connect', Connect)
        self.assertTrue(add(type='apex_nodes/Clock', name='stall_a', parameters='{rate: 20.0}').success)
        self.assertTrue(add(type='apex_nodes/Clock', name='stall_b', parameters='{rate: 20.0}').success)
        self.assertTrue(add(type='apex_nodes/Add', name='stall_sum').success)
        self.assertTrue(service('set_enabled', SetEnabled)(node='stall_b', enabled=False).success)
        self.assertTrue(connect(from_node='stall_a', from_port='time', to_node='stall_sum', to_port='a').success)
        self.assertTrue(connect(from_node='stall_b', from_port='time', to_node='stall_sum', to_port='b').success)
        ok, status = self.diagnostics.wait_level('stall_sum', DiagnosticStatus.WARN)
        self.assertTrue(ok, status)
        self.assertIn("waiting for input 'b' from 'stall_b'", status.message)

    def test_a_node_whose_bag_is_gone_is_error_with_its_text(self):
        bag = rospy.get_param('~bag')
        gone = os.path.join(os.path.dirname(bag), 'ecosystem_gone.bag')
        shutil.copyfile(bag, gone)
        res = service('add_node', AddNode)(type='apex_nodes/BagReader', name='gone',
                                           parameters="{file: '%s', topics: [/camera/image_raw]}" % gone)
        self.assertTrue(res.success, res.message)
        os.remove(gone)
        res = service('set_parameter', SetParameter)(node='gone', parameter='topics', value='[/camera/points]')
        ok, status = self.diagnostics.wait_level('gone', DiagnosticStatus.ERROR)
        self.assertTrue(ok, status)
        self.assertIn('cannot open bag', status.message)
        self.assertIn('ecosystem_gone.bag', status.message)

    # ---------------------------------------------------------------- rosconsole, a logger per node

    def test_a_nodes_logger_level_changes_that_node_alone(self):
        lines = []  # (stamp, text) of what the runtime logs
        sub = rospy.Subscriber('/rosout', Log, lambda m: lines.append((m.header.stamp, m.msg)), queue_size=1000)
        for name, kind, params in (('log_clock', 'apex_nodes/Clock', '{rate: 50.0}'),
                                   ('log_a', 'apex_nodes/Print', ''), ('log_b', 'apex_nodes/Print', '')):
            res = service('add_node', AddNode)(type=kind, name=name, parameters=params)
            self.assertTrue(res.success, res.message)
        for printer in ('log_a', 'log_b'):
            res = service('connect', Connect)(from_node='log_clock', from_port='count', to_node=printer, to_port='in')
            self.assertTrue(res.success, res.message)

        def logged(node, since):
            return [t for stamp, t in list(lines) if t.startswith('[%s]' % node) and stamp > since]
        start = rospy.Time.now()
        self.assertTrue(wait_until(lambda: logged('log_a', start) and logged('log_b', start)), 'no lines from the printers')
        loggers = rospy.ServiceProxy('/apex/get_loggers', GetLoggers)().loggers
        self.assertIn('ros.apex.log_a', [lg.name for lg in loggers])

        set_level = rospy.ServiceProxy('/apex/set_logger_level', SetLoggerLevel)
        set_level(logger='ros.apex.log_a', level='warn')
        quiet = rospy.Time.now() + rospy.Duration(0.3)  # what was on its way before
        self.assertTrue(wait_until(lambda: len(logged('log_b', quiet)) >= 20), 'log_b stopped too')
        self.assertEqual(logged('log_a', quiet), [], 'log_a still logs at info')

        for i in range(40):  # levels changing while the node logs at 50 Hz: the runtime stays up
            set_level(logger='ros.apex.log_a', level='debug' if i % 2 else 'info')
        again = rospy.Time.now()
        self.assertTrue(wait_until(lambda: logged('log_a', again)), 'log_a at info again logs nothing')
        for name in ('log_a', 'log_b', 'log_clock'):
            service('remove_node', RemoveNode)(name=name)
        sub.unregister()


if __name__ == '__main__':
    rospy.init_node('test_ecosystem')
    rostest.rosrun('apex', 'ecosystem', Ecosystem)
