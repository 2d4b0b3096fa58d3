#!/usr/bin/env python3
"""Any ROS message type through a runtime (issue #34), scripted with the module `apex`:
TopicSubscriber, FieldExtract driving a parameter, BagWriter recording the raw messages, TopicPublisher,
and NodeletHost running Debian's pcl_ros VoxelGrid against APEX's own VoxelGrid, its dynamic_reconfigure parameters
mirrored as the node's own."""
import os
import tempfile
import unittest

import rosbag
import rospy
import rostest
from waiting import wait_until
import apex
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Imu, PointCloud2
from sensor_msgs import point_cloud2


def wait_for(done, timeout, what):
    """Waits until `done()` holds; fails the test naming `what` if it does not within `timeout` s."""
    if not wait_until(done, timeout):
        raise AssertionError('waited %g s for %s' % (timeout, what))


def odometry(i):
    m = Odometry()
    m.header.stamp = rospy.Time(1000 + i, 250)
    m.header.frame_id = 'odom'
    m.child_frame_id = 'base_link'
    m.pose.pose.position.x = 1.5 + i
    m.pose.pose.orientation.w = 1.0
    m.twist.twist.linear.x = 0.25 * i
    m.pose.covariance = [0.01 * k for k in range(36)]
    return m


def imu(i):
    m = Imu()
    m.header.stamp = rospy.Time(1000 + i, 500)
    m.header.frame_id = 'imu'
    m.orientation.w = 1.0
    m.linear_acceleration.z = 9.81 + 0.1 * i
    m.angular_velocity.y = -0.5 * i
    return m


class Received:
    """The messages of a topic, as a subscriber in the test gets them."""

    def __init__(self, topic, kind):
        self.messages = []
        self.sub = rospy.Subscriber(topic, kind, self.messages.append, queue_size=100)


POINTS = [((k * 37 % 101) / 50.0 - 1, (k * 53 % 103) / 51.5 - 1, (k * 71 % 107) / 53.5 - 1) for k in range(3000)]


def add_nodelet_voxels(rt):
    """A cloud from /points into NodeletHost 'pcl_voxels' running pcl_ros's VoxelGrid at 0.1."""
    rt.add_node('PointCloudSubscriber', 'cloud', params={'topic': '/points'})
    rt.add_node('NodeletHost', 'pcl_voxels', params={
        'nodelet': 'pcl/VoxelGrid', 'inputs': ['input:sensor_msgs/PointCloud2'],
        'outputs': ['output:sensor_msgs/PointCloud2'], 'config': "{leaf_size: 0.1, filter_field_name: ''}"})


def add_apex_voxels_and_publish(rt, leaf_size, nodelet_topic, apex_topic):
    """APEX's VoxelGrid at `leaf_size` beside 'pcl_voxels', both fed by 'cloud'; their outputs
    published on the two topics. Returns what the test receives there, once connected, and the
    publisher of /points, once the runtime subscribes."""
    rt.add_node('VoxelGrid', 'voxels', params={'leaf_size': leaf_size})
    rt.add_node('PointCloudPublisher', 'pub_nodelet', params={'topic': nodelet_topic})
    rt.add_node('PointCloudPublisher', 'pub_apex', params={'topic': apex_topic})
    rt.connect('cloud', 'cloud', 'pcl_voxels', 'input')
    rt.connect('cloud', 'cloud', 'voxels', 'cloud')
    rt.connect('pcl_voxels', 'output', 'pub_nodelet', 'cloud')
    rt.connect('voxels', 'cloud', 'pub_apex', 'cloud')
    by_nodelet, by_apex = Received(nodelet_topic, PointCloud2), Received(apex_topic, PointCloud2)
    wait_for(lambda: by_nodelet.sub.get_num_connections() > 0 and by_apex.sub.get_num_connections() > 0, 30,
             'the publishers connect')
    pub = rospy.Publisher('/points', PointCloud2, queue_size=10)
    wait_for(lambda: pub.get_num_connections() > 0, 30, 'the runtime subscribes to /points')
    return by_nodelet, by_apex, pub


class AnyTopic(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_any_topic')
        cls.rt = apex.Runtime('/apex', timeout=60)

    def setUp(self):
        self.rt.clear()

    def test_odometry_and_imu_drive_a_parameter_and_are_recorded_as_they_were(self):
        rt = self.rt
        bag = os.path.join(tempfile.mkdtemp(dir='/tmp'), 'motion.bag')
        rt.add_node('TopicSubscriber', 'odom', params={'topic': '/odom'})
        rt.add_node('TopicSubscriber', 'imu', params={'topic': '/imu'})
        rt.add_node('FieldExtract', 'x', params={'field': 'pose.pose.position.x'})
        rt.add_node('FieldExtract', 'az', params={'field': 'linear_acceleration.z'})
        rt.add_node('Scale', 'gain')
        rt.set_interactive('gain', 'factor', True)
        rt.add_node('BagWriter', 'rec', params={'file': bag, 'topics': ['/odom', '/imu']})
        rt.connect('odom', 'message', 'x', 'message')
        rt.connect('imu', 'message', 'az', 'message')
        rt.connect('az', 'value', 'gain', 'in')
        rt.connect('x', 'value', 'gain', 'factor')  # the odometry's x drives a parameter
        rt.connect('odom', 'message', 'rec', 'odom')
        rt.connect('imu', 'message', 'rec', 'imu')
        odom_pub = rospy.Publisher('/odom', Odometry, queue_size=10)
        imu_pub = rospy.Publisher('/imu', Imu, queue_size=10)
        sent_odom = [odometry(i) for i in range(6)]
        sent_imu = [imu(i) for i in range(6)]
        wait_for(lambda: imu_pub.get_num_connections() > 0 and odom_pub.get_num_connections() > 0, 30,
                   'the runtime subscribes to /imu and /odom')
        for k in range(6):  # each pair once the graph has taken the last (a subscriber keeps only the newest)
            imu_pub.publish(sent_imu[k])
            odom_pub.publish(sent_odom[k])
            rt.wait_for_status('gain', lambda s, k=k: s.firings > k, timeout=20)
            # the odometry's value travels apart from the IMU's firing: waited for, not assumed there
            x = sent_odom[k].pose.pose.position.x
            wait_for(lambda x=x: abs(rt.parameter('gain', 'factor') - x) < 1e-9, 20,
                     'gain/factor = odometry %d\'s x (%s)' % (k, x))
        rt.wait_for_status('rec', lambda s: s.firings >= 6, timeout=20)
        rt.fire_slot('rec', 'stop')
        wait_for(lambda: os.path.exists(bag), 20, bag + ' closed')
        recorded = {'/odom': [], '/imu': []}
        with rosbag.Bag(bag) as b:
            types = {t: info.msg_type for t, info in b.get_type_and_topic_info().topics.items()}
            self.assertEqual(types, {'/odom': 'nav_msgs/Odometry', '/imu': 'sensor_msgs/Imu'})
            for topic, msg, t in b.read_messages():
                recorded[topic].append(msg)
                self.assertEqual(t, msg.header.stamp)  # each at its own stamp
        # every message sent was recorded once, equal field for field (rosbag gives its own classes)
        self.assertEqual([m.header.stamp for m in recorded['/odom']], [m.header.stamp for m in sent_odom])
        for got, sent in zip(recorded['/odom'], sent_odom):
            self.assertEqual(got.pose.pose.position.x, sent.pose.pose.position.x)
            self.assertEqual(list(got.pose.covariance), list(sent.pose.covariance))
            self.assertEqual((got.child_frame_id, got.twist.twist.linear.x), (sent.child_frame_id, sent.twist.twist.linear.x))
        self.assertEqual(sorted(m.header.stamp for m in recorded['/imu']), [m.header.stamp for m in sent_imu])
        for got in recorded['/imu']:
            sent = next(s for s in sent_imu if s.header.stamp == got.header.stamp)
            self.assertEqual((got.linear_acceleration.z, got.angular_velocity.y), (sent.linear_acceleration.z, sent.angular_velocity.y))

    def test_topic_publisher_relays_any_type_and_a_wrong_type_is_an_error_naming_both(self):
        rt = self.rt
        rt.add_node('TopicSubscriber', 'odom', params={'topic': '/odom_in'})
        rt.add_node('TopicPublisher', 'out', params={'topic': '/odom_out'})
        rt.connect('odom', 'message', 'out', 'message')
        received = Received('/odom_out', Odometry)
        pub = rospy.Publisher('/odom_in', Odometry, queue_size=10)
        wait_for(lambda: pub.get_num_connections() > 0, 30, 'the runtime subscribes to /odom_in')
        sent = odometry(7)
        wait_for(lambda: (pub.publish(sent), received.messages)[1], 30, 'the relayed odometry')  # until /odom_out is connected
        got = received.messages[0]
        got.header.seq = sent.header.seq  # (rospy numbers each publish of `sent` anew)
        self.assertEqual(got, sent)
        # ~inspect shows the message itself, as its own type
        topic, _ = rt.inspect('odom', 'message')
        inspected = Received(topic, Odometry)
        wait_for(lambda: (pub.publish(sent), inspected.messages)[1], 30, 'the inspected odometry on ' + topic)
        got = inspected.messages[0]
        got.header.seq = sent.header.seq
        self.assertEqual(got, sent)
        # a subscriber told the type refuses another one, naming both
        rt.add_node('TopicSubscriber', 'wrong', params={'topic': '/odom_in', 'type': 'sensor_msgs/Imu'})
        wait_for(lambda: (pub.publish(sent), rt.node('wrong').error)[1], 30, 'the type error')
        self.assertIn('nav_msgs/Odometry', rt.node('wrong').error)
        self.assertIn('sensor_msgs/Imu', rt.node('wrong').error)

    def test_nodelet_host_runs_pcl_ros_voxel_grid_equal_to_apexs_own(self):
        rt = self.rt
        add_nodelet_voxels(rt)
        by_nodelet, by_apex, pub = add_apex_voxels_and_publish(rt, 0.1, '/voxels_nodelet', '/voxels_apex')
        header = rospy.Header(stamp=rospy.Time(2000, 7), frame_id='lidar')
        try:
            wait_for(lambda: (pub.publish(point_cloud2.create_cloud_xyz32(header, POINTS)),
                              by_nodelet.messages and by_apex.messages)[1], 30, 'both voxel clouds')
        except AssertionError as e:
            raise AssertionError('%s; %s' % (e, ' | '.join(' '.join(str(rt.status(n)).split())
                                                              for n in ('cloud', 'pcl_voxels', 'voxels')))) from None
        a, b = by_nodelet.messages[0], by_apex.messages[0]
        self.assertEqual(a.header.stamp, header.stamp)  # the output belongs to the input's frame
        self.assertEqual(b.header.stamp, header.stamp)
        pa = sorted(point_cloud2.read_points(a, ('x', 'y', 'z')))
        pb = sorted(point_cloud2.read_points(b, ('x', 'y', 'z')))
        self.assertGreater(len(pa), 100)
        self.assertEqual(pa, pb)
        self.assertEqual(rt.node('pcl_voxels').error, '')
        # a nodelet nobody declares: an error naming it and the closest ones, the graph runs on
        rt.set_parameter('pcl_voxels', 'nodelet', 'pcl/VoxelGrd')
        wait_for(lambda: (pub.publish(point_cloud2.create_cloud_xyz32(header, POINTS)), rt.node('pcl_voxels').error)[1],
                   30, 'the missing plugin reported')
        self.assertIn("'pcl/VoxelGrd'", rt.node('pcl_voxels').error)
        self.assertIn('pcl/VoxelGrid', rt.node('pcl_voxels').error)
        count = len(by_apex.messages)
        wait_for(lambda: (pub.publish(point_cloud2.create_cloud_xyz32(header, POINTS)), len(by_apex.messages) > count)[1],
                   30, "APEX's VoxelGrid still sends")

    def test_a_hosted_nodelets_dynamic_reconfigure_parameters_are_its_nodes_own(self):
        rt = self.rt
        add_nodelet_voxels(rt)
        # what the nodelet offers becomes the node's parameters, with the values it loaded with
        wait_for(lambda: 'leaf_size' in rt.parameters('pcl_voxels'), 30, "the nodelet's leaf_size as a parameter")
        params = rt.parameters('pcl_voxels')
        self.assertAlmostEqual(params['leaf_size'], 0.1)
        self.assertEqual(params['filter_field_name'], '')
        self.assertIn('filter_limit_max', params)
        self.assertEqual(rt.node('pcl_voxels').error, '')
        # set like any parameter: the nodelet gets it live (its dynamic_reconfigure server), not reloaded
        # topics of their own: rospy may keep a connection of another test's publisher of the same name
        by_nodelet, by_apex, pub = add_apex_voxels_and_publish(rt, 0.25, '/offered_nodelet', '/offered_apex')
        rt.set_parameter('pcl_voxels', 'leaf_size', 0.25)
        wait_for(lambda: rospy.get_param('/apex/nodelets/pcl_voxels/leaf_size', 0) == 0.25, 30,
                 "the nodelet's own leaf_size to follow")
        header = rospy.Header(stamp=rospy.Time(3000, 1), frame_id='lidar')
        wait_for(lambda: (pub.publish(point_cloud2.create_cloud_xyz32(header, POINTS)),
                          by_nodelet.messages and by_apex.messages)[1], 30, 'both voxel clouds')
        pa = sorted(point_cloud2.read_points(by_nodelet.messages[-1], ('x', 'y', 'z')))
        pb = sorted(point_cloud2.read_points(by_apex.messages[-1], ('x', 'y', 'z')))
        self.assertGreater(len(pa), 20)
        self.assertEqual(pa, pb)  # VoxelGrid at 0.25 both, so the nodelet had the new value
        # bounds are the nodelet's own: refused here, with the parameter named
        with self.assertRaises(apex.ApexError) as refused:
            rt.set_parameter('pcl_voxels', 'leaf_size', 5.0)
        self.assertIn('leaf_size', str(refused.exception))
        # saved with the graph and loaded with it: the nodelet starts with the value
        path = os.path.join(tempfile.mkdtemp(dir='/tmp'), 'voxels.yaml')
        rt.save_graph(path)
        with open(path) as f:
            self.assertIn('leaf_size: 0.25', f.read())
        rt.clear()
        wait_for(lambda: not rospy.has_param('/apex/nodelets/pcl_voxels'), 30, "the nodelet's parameters to go")
        rt.load_graph(path)
        wait_for(lambda: rospy.get_param('/apex/nodelets/pcl_voxels/leaf_size', 0) == 0.25, 30,
                 'the loaded nodelet to start with the saved value')
        self.assertAlmostEqual(rt.parameter('pcl_voxels', 'leaf_size'), 0.25)
        self.assertEqual(rt.node('pcl_voxels').error, '')


if __name__ == '__main__':
    rostest.rosrun('apex', 'any_topic', AnyTopic)
