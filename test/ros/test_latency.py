#!/usr/bin/env python3
"""Latency on ~status against an outside measurement (latency.test): camera images stamped as they
are sent go through ImageSubscriber -> GaussianBlur -> ImagePublisher; a subscriber here takes
each result's age (the time it came minus its header stamp, as `rostopic delay` does). The
runtime's median latency at the publisher equals the outside median within 1 ms; frames sent
faster than the graph takes them are counted as dropped at the subscriber."""
import statistics
import threading
import time
import unittest

import numpy as np
import rospy
import rostest
from sensor_msgs.msg import Image
from waiting import wait_until

import apex


class Latency(unittest.TestCase):
    def test_the_publishers_latency_equals_a_subscriber_comparing_header_stamps(self):
        rt = apex.Runtime('/apex', timeout=60)
        rt.clear()
        rt.add_node('apex_nodes/ImageSubscriber', 'camera', params={'topic': '/latency/image'})
        rt.add_node('apex_nodes/GaussianBlur', 'blur')
        rt.add_node('apex_nodes/ImagePublisher', 'out', params={'topic': '/latency/out'})
        rt.connect('camera', 'image', 'blur', 'image')
        rt.connect('blur', 'image', 'out', 'image')

        ages, lock = [], threading.Lock()

        def received(msg):
            age = (rospy.Time.now() - msg.header.stamp).to_sec() * 1000
            with lock:
                ages.append((time.time(), age))
        rospy.Subscriber('/latency/out', Image, received, queue_size=10)
        pub = rospy.Publisher('/latency/image', Image, queue_size=1)
        pixels = (np.random.RandomState(1).rand(480, 640) * 255).astype(np.uint8).tobytes()
        end = time.time() + 12
        while time.time() < end:  # 20 frames a second, each stamped as it is sent
            img = Image(height=480, width=640, encoding='mono8', step=640, data=pixels)
            img.header.stamp = rospy.Time.now()
            img.header.frame_id = 'camera'
            pub.publish(img)
            time.sleep(0.05)
        inside = rt.status('out')
        with lock:  # the outside figure over the runtime's window: the last 5 to 10 s
            recent = [age for t, age in ages if t > end - 7.5]
        self.assertGreater(len(recent), 50, 'too few results came: %d' % len(recent))
        self.assertGreater(inside.latency_frames, 50)
        outside = statistics.median(recent)
        rospy.loginfo('latency at the publisher: runtime p50 %.2f ms (mean %.2f, p95 %.2f), outside p50 %.2f ms',
                      inside.latency_p50_ms, inside.latency_ms, inside.latency_p95_ms, outside)
        self.assertLess(abs(inside.latency_p50_ms - outside), 1.0)
        # along the chain a frame only gets older
        camera, blur = rt.status('camera'), rt.status('blur')
        self.assertGreaterEqual(camera.latency_frames, 50)
        self.assertLessEqual(camera.latency_ms, blur.latency_ms)
        self.assertLessEqual(blur.latency_ms, inside.latency_ms + 0.01)
        # each output has its own latency: the blur's one sends on every frame, so it is the node's
        image = blur.outputs.index('image')
        self.assertGreaterEqual(blur.output_latency_p50_ms[image], camera.latency_p50_ms)
        self.assertEqual(blur.output_latency_p95_ms[image], blur.latency_p95_ms)
        self.assertGreater(blur.p95_ms, 0)
        self.assertLessEqual(blur.p50_ms, blur.p95_ms)
        self.assertEqual(camera.dropped, 0)  # 20 a second: each taken before the next came

        # faster than the graph: the subscriber keeps the newest and counts what it dropped
        rt.add_node('apex_nodes/ImageSubscriber', 'burst', params={'topic': '/latency/burst'})
        rt.add_node('apex_nodes/BilateralFilter', 'slow', params={'d': 25})  # ~0.1 s a frame
        rt.connect('burst', 'image', 'slow', 'image')
        burst = rospy.Publisher('/latency/burst', Image, queue_size=100)
        wait_until(lambda: burst.get_num_connections() > 0, 10)
        for _ in range(60):  # 200 a second
            img.header.stamp = rospy.Time.now()
            burst.publish(img)
            time.sleep(0.005)
        rt.wait_for_status('burst', lambda s: s.dropped > 0, timeout=20)


if __name__ == '__main__':
    rospy.init_node('test_latency', anonymous=True)
    rostest.rosrun('apex', 'latency', Latency)
