#!/usr/bin/env python3
"""The demo graph split over two runtimes joined by ROS topics gives, frame by frame, what the
same graph gives in one runtime; and what the split costs per frame, from the player's firing
to the overlay's arrival (one process vs two, played one after the other)."""
import statistics
import threading
import time
import unittest
import xmlrpc.client

import rosbag
import rosgraph
import rospy
import rostest
from waiting import wait_until
from apex.srv import Inspect, SetParameter
from sensor_msgs.msg import Image, PointCloud2
from std_msgs.msg import Float64


def service(runtime, name, kind):
    rospy.wait_for_service(runtime + '/' + name, 60)
    return rospy.ServiceProxy(runtime + '/' + name, kind)


class Outputs:
    """A graph's published outputs by stamp, with when they arrived here; and, from ~inspect,
    when its player fired each frame (the player's `stamp` output)."""

    def __init__(self, ns, player_runtime):
        self.lock = threading.Lock()
        self.overlays, self.clouds, self.fired = {}, {}, {}
        self.subs = [
            rospy.Subscriber(ns + '/apex_demo/overlay', Image, self.add(self.overlays), queue_size=100),
            rospy.Subscriber(ns + '/apex_demo/points', PointCloud2, self.add(self.clouds), queue_size=100)]
        answer = service(player_runtime, 'inspect', Inspect)(node='bag', port='stamp', enable=True)
        assert answer.success, answer.message
        self.subs.append(rospy.Subscriber(answer.topic, Float64, self.player_fired, queue_size=100))

    def add(self, into):
        def received(msg):
            with self.lock:
                into[msg.header.stamp.to_nsec()] = (time.monotonic(), msg)
        return received

    def player_fired(self, msg):
        with self.lock:
            self.fired[round(msg.data, 3)] = time.monotonic()

    def connected(self):
        return all(s.get_num_connections() > 0 for s in self.subs)

    def count(self):
        with self.lock:
            return min(len(self.overlays), len(self.clouds))

    def latencies_ms(self):
        """Per frame: the overlay's arrival after the player's firing of its frame."""
        with self.lock:
            return [1e3 * (arrived - self.fired[round(stamp * 1e-9, 3)])
                    for stamp, (arrived, _) in self.overlays.items() if round(stamp * 1e-9, 3) in self.fired]


def subscribed(topic, node):
    """Whether the master lists `node` as a subscriber of `topic`."""
    _, subscribers, _ = rosgraph.Master('/test_split').getSystemState()
    return any(t == topic and node in nodes for t, nodes in subscribers)


def connected(publisher, topic, subscriber):
    """Whether `publisher` has a live connection sending `topic` to `subscriber` (its own bus info)."""
    uri = rosgraph.Master('/test_split').lookupNode(publisher)
    _, _, connections = xmlrpc.client.ServerProxy(uri).getBusInfo('/test_split')
    return any(c[1] == subscriber and c[2] == 'o' and c[4] == topic and c[5] for c in connections)


def describe(values):
    return 'median %.1f ms (range %.1f-%.1f, %d frames)' % (statistics.median(values), min(values), max(values), len(values))


class Split(unittest.TestCase):
    def test_the_split_graph_outputs_what_one_process_outputs_frame_by_frame(self):
        with rosbag.Bag(rospy.get_param('~bag')) as bag:
            frames = bag.get_message_count('/camera/image_raw')
        self.assertGreater(frames, 10)
        single = Outputs('/single', '/single/apex')
        split = Outputs('/back', '/front/apex')
        self.assertTrue(wait_until(lambda: single.connected() and split.connected(), 60), 'outputs never connected')
        self.assertTrue(wait_until(lambda: subscribed('/front/sensors/image', '/back/apex') and
                                   subscribed('/front/sensors/points', '/back/apex'), 60),
                        'the second runtime never subscribed to the first one\'s topics')
        self.assertTrue(wait_until(lambda: connected('/front/apex', '/front/sensors/image', '/back/apex') and
                                   connected('/front/apex', '/front/sensors/points', '/back/apex'), 60),
                        'the first runtime never connected to the second')

        # the demo graph stamps each frame as it sends it (restamp); the split one keeps the bag's
        # stamps: both at the bag's, so that their frames pair up by stamp
        answer = service('/single/apex', 'set_parameter', SetParameter)(node='bag', parameter='restamp', value='false')
        self.assertTrue(answer.success, answer.message)
        for outputs, runtime in ((single, '/single/apex'), (split, '/front/apex')):  # one after the other
            answer = service(runtime, 'set_parameter', SetParameter)(node='bag', parameter='playing', value='true')
            self.assertTrue(answer.success, answer.message)
            self.assertTrue(wait_until(lambda: outputs.count() >= frames, 120),
                            '%s: %d of %d frames' % (runtime, outputs.count(), frames))
        self.assertEqual(len(split.overlays), frames)
        self.assertEqual(sorted(split.overlays), sorted(single.overlays))
        self.assertEqual(sorted(split.clouds), sorted(single.clouds))
        for stamp in sorted(single.overlays):
            a, b = single.overlays[stamp][1], split.overlays[stamp][1]
            self.assertEqual((a.width, a.height, a.encoding), (b.width, b.height, b.encoding))
            self.assertTrue(a.data == b.data, 'the overlay stamped %d ns differs' % stamp)
        for stamp in sorted(single.clouds):
            c, d = single.clouds[stamp][1], split.clouds[stamp][1]
            self.assertEqual((c.width, c.point_step), (d.width, d.point_step))
            self.assertTrue(c.data == d.data, 'the cloud stamped %d ns differs' % stamp)

        one, two = single.latencies_ms(), split.latencies_ms()
        self.assertGreater(len(one), frames // 2)
        self.assertGreater(len(two), frames // 2)
        report = ('per-frame latency, player to overlay: one process %s; split over two runtimes %s; '
                  'ratio of medians %.2f' % (describe(one), describe(two), statistics.median(two) / statistics.median(one)))
        print(report)
        results = rospy.get_param('~results', '')
        if results:  # one line per run: the medians (ms) of one process and of the split
            with open(results, 'a') as f:
                f.write('%.3f %.3f\n' % (statistics.median(one), statistics.median(two)))


if __name__ == '__main__':
    rospy.init_node('test_split')
    rostest.rosrun('apex', 'split', Split)
