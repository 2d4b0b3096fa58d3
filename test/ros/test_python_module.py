#!/usr/bin/env python3
"""The Python module `apex` (python/apex) against a runtime with an empty graph (python_module.test):
edits read back from the graph, statuses waited for, and refusals raised with the services' own messages."""
import os
import tempfile
import unittest

import rospy
import rostest
from waiting import wait_until
from std_msgs.msg import Int32

import apex
from apex.srv import AddNode, Connect, SetParameter


def raw(service, kind, **request):
    """The runtime's own answer, called without the module."""
    return rospy.ServiceProxy('/apex/' + service, kind)(**request)


class PythonModule(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.rt = apex.Runtime('/apex', timeout=60)

    def setUp(self):
        self.rt.resume()
        self.assertFalse(self.rt.clear())  # an empty graph, running

    def counting(self, rate=50.0):
        """clock -> count, the clock ticking at `rate`."""
        self.assertEqual(self.rt.add_node('apex_nodes/Clock', 'clock', params={'rate': rate}), 'clock')
        self.assertEqual(self.rt.add_node('Counter', 'count'), 'count')  # a type without its package
        self.rt.connect('clock', 'count', 'count', 'in')

    def test_an_absent_runtime_is_a_timeout_naming_its_namespace(self):
        with self.assertRaises(apex.ApexTimeout) as error:
            apex.Runtime('/nowhere', timeout=1.0)
        self.assertIn('/nowhere', str(error.exception))
        self.assertIsInstance(error.exception, TimeoutError)
        self.assertIsInstance(error.exception, apex.ApexError)

    def test_add_connect_set_wait_remove(self):
        self.counting()
        nodes = self.rt.nodes()
        self.assertEqual(nodes['clock'].type, 'apex_nodes/Clock')
        self.assertEqual(nodes['count'].type, 'apex_nodes/Counter')
        self.assertEqual(self.rt.parameter('clock', 'rate'), 50.0)
        self.assertIn(('clock', 'count', 'count', 'in', 'data'), self.rt.connections())

        self.assertEqual(self.rt.set_parameter('clock', 'rate', 20), 20.0)  # an int to a double: applied as 20.0
        self.assertEqual(self.rt.parameter('clock', 'rate'), 20.0)  # from ~get_graph
        rate = next(p for p in self.rt.node('clock').parameters if p.name == 'rate')
        self.assertEqual(rate.value, '20.0')

        status = self.rt.wait_for_status('count', lambda s: s.firings > 10, timeout=20)
        self.assertGreater(status.firings, 10)
        self.assertEqual((status.name, status.state), ('count', 'ok'))
        self.assertEqual(self.rt.status('clock').name, 'clock')
        self.assertIn('count', [n.name for n in self.rt.status().nodes])
        profile = self.rt.node_profile('count')  # its firing times as bars; a count carries no stamp
        self.assertGreater(sum(count for _, _, count in profile['time']), 0)
        self.assertTrue(all(lower < upper for lower, upper, _ in profile['time']))
        self.assertEqual(profile['latency'], [])

        self.rt.disconnect('clock', 'count', 'count', 'in')
        self.assertEqual(self.rt.connections(), [])
        self.rt.remove_node('count')
        self.rt.remove_node('clock')
        self.assertEqual(self.rt.nodes(), {})

    def test_refusals_carry_the_services_messages(self):
        with self.assertRaises(apex.ApexError) as error:
            self.rt.add_node('Countr', 'count')
        self.assertEqual(error.exception.message, raw('add_node', AddNode, type='Countr', name='count').message)
        self.assertIn("unknown node type 'Countr': did you mean apex_nodes/Counter?", str(error.exception))
        self.assertEqual(error.exception.service, '/apex/add_node')

        self.counting()
        with self.assertRaises(apex.ApexError) as error:
            self.rt.connect('clock', 'no_such_port', 'count', 'in')
        expected = raw('connect', Connect, from_node='clock', from_port='no_such_port', to_node='count', to_port='in')
        self.assertFalse(expected.success)
        self.assertEqual(error.exception.message, expected.message)
        self.assertIn('no_such_port', error.exception.message)

        with self.assertRaises(apex.ApexError) as error:
            self.rt.set_parameter('clock', 'rate', 5000)
        self.assertEqual(error.exception.message, "node 'clock': parameter 'rate': 5000 is out of range [0.01, 1000]")
        self.assertEqual(error.exception.message,
                         raw('set_parameter', SetParameter, node='clock', parameter='rate', value='5000').message)
        self.assertEqual(error.exception.response.value, '50.0')  # the value that stays
        self.assertEqual(self.rt.parameter('clock', 'rate'), 50.0)

        for call in (lambda: self.rt.remove_node('nobody'), lambda: self.rt.fire_slot('count', 'no_slot'),
                     lambda: self.rt.parameter('clock', 'no_param'), lambda: self.rt.node('nobody'),
                     lambda: self.rt.control('jump'), lambda: self.rt.load_graph('/tmp/apex_no_such_graph.yaml')):
            with self.assertRaises(apex.ApexError) as error:
                call()
            self.assertTrue(error.exception.message)

    def test_a_condition_not_met_is_a_timeout_with_the_last_status(self):
        self.counting()
        with self.assertRaises(apex.ApexTimeout) as error:
            self.rt.wait_for_status('count', lambda s: s.firings < 0, timeout=1.5)
        self.assertIn('firings', str(error.exception))
        with self.assertRaises(apex.ApexTimeout) as error:
            self.rt.wait_for_status('nobody', lambda s: True, timeout=1.5)
        self.assertIn('no such node', str(error.exception))

    def test_values_travel_as_yaml(self):
        self.assertEqual(self.rt.add_node('apex_nodes/Print', 'print', params={'prefix': 'a: b'}), 'print')
        self.assertEqual(self.rt.parameter('print', 'prefix'), 'a: b')  # not a mapping
        self.assertEqual(self.rt.set_parameter('print', 'prefix', '5'), '5')  # text, not a number
        self.assertEqual(self.rt.set_parameter('print', 'prefix', 'true'), 'true')
        self.rt.add_node('apex_nodes/WarpPerspective', 'warp')
        m = (1.0, 0.0, 5.0, 0.0, 1.0, 1e-5, 0.0, 0.0, 1.0)  # a tuple, and a number YAML 1.1 would read as text
        self.assertEqual(self.rt.set_parameter('warp', 'm', m), list(m))
        self.assertEqual(self.rt.parameters('warp')['m'], list(m))
        self.assertIs(self.rt.set_parameter('warp', 'inverse_map', True), True)
        self.assertEqual(self.rt.set_parameter('warp', 'interpolation', 'cubic'), 'cubic')
        self.assertEqual(apex.encode({'rate': 5.0, 'topics': ['/a', '/b']}), '{rate: 5.0, topics: [/a, /b]}')
        self.assertEqual(apex.decode('1e-05'), 1e-5)

    def test_rename_enable_groups_and_slots(self):
        self.counting()
        self.assertEqual(self.rt.rename_node('count', 'counter'), 'counter')
        self.assertIn(('clock', 'count', 'counter', 'in', 'data'), self.rt.connections())  # the connection followed
        self.rt.disable('counter')
        self.assertFalse(self.rt.node('counter').enabled)
        self.assertEqual(self.rt.wait_for_status('counter', lambda s: s.state == 'disabled').state, 'disabled')
        self.rt.enable('counter')
        self.assertTrue(self.rt.node('counter').enabled)
        self.rt.set_thread_group('counter', 'py_group')
        self.assertEqual(self.rt.node('counter').thread_group, 'py_group')
        self.assertIn('py_group', self.rt.graph().thread_groups)
        self.rt.set_ui('counter', {'x': 10, 'y': 20})
        self.assertEqual(apex.decode(self.rt.node('counter').ui), {'x': 10, 'y': 20})

        topic, kind = self.rt.inspect('counter', 'count')
        self.assertEqual(kind, 'std_msgs/Int32')
        counts = []
        sub = rospy.Subscriber(topic, Int32, lambda msg: counts.append(msg.data))
        self.assertTrue(wait_until(lambda: counts and counts[-1] >= 10), counts[-1:])
        before, seen = counts[-1], len(counts)
        self.rt.fire_slot('counter', 'reset')  # from zero again
        self.assertTrue(wait_until(lambda: any(c < before for c in counts[seen:])), (before, counts[seen:]))
        sub.unregister()

        self.rt.group(['clock', 'counter'], 'sub')
        self.assertEqual(sorted(self.rt.nodes()), ['sub', 'sub/clock', 'sub/counter'])
        self.rt.ungroup('sub')
        self.assertEqual(sorted(self.rt.nodes()), ['clock', 'counter'])

    def test_types_files_and_control(self):
        types = self.rt.node_types()
        self.assertIn('rate', [p.name for p in types['apex_nodes/Clock'].parameters])
        self.assertIsInstance(self.rt.load_errors(), list)

        self.counting()
        self.assertTrue(self.rt.pause())
        self.assertTrue(self.rt.graph().paused)
        self.rt.step()
        self.assertFalse(self.rt.resume())
        folder = tempfile.mkdtemp(prefix='apex_python_module_', dir='/tmp')
        path = self.rt.save_graph(os.path.join(folder, 'counting.yaml'))
        self.assertEqual(path, os.path.join(folder, 'counting.yaml'))
        self.assertTrue(os.path.isfile(path))
        self.assertIn('apex_nodes/Counter', self.rt.graph_text())
        self.assertFalse(self.rt.clear())
        self.assertEqual(self.rt.nodes(), {})
        loaded = self.rt.load_graph(path)
        self.assertEqual((loaded.path, list(loaded.warnings)), (path, []))
        self.assertEqual(sorted(self.rt.nodes()), ['clock', 'count'])
        self.assertGreaterEqual(self.rt.graph().revision, loaded.revision)
        os.remove(path)
        os.rmdir(folder)


if __name__ == '__main__':
    rospy.init_node('test_python_module')
    rostest.rosrun('apex', 'python_module', PythonModule)
