#!/usr/bin/env python3
"""apex_top in tmux (apex_top.test), as a person on ssh uses it: it shows the demo's nodes, its
keys pause and resume the graph and change the sort, q ends it with status 0; --once prints the
table for scripts."""
import os
import subprocess
import tempfile
import unittest

import rospy
import rostest
from roslib.packages import find_node
from waiting import wait_until

import apex


class ApexTop(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.rt = apex.Runtime('/apex', timeout=60)
        cls.command = find_node('apex', 'apex_top')[0]
        cls.tmux = ['tmux', '-L', 'apex_top_%d' % os.getpid(), '-f', '/dev/null']

    def screen(self):
        return subprocess.run(self.tmux + ['capture-pane', '-p', '-t', 'top'], capture_output=True, text=True).stdout

    def key(self, key):
        subprocess.run(self.tmux + ['send-keys', '-t', 'top', key], check=True)

    def test_the_demo_in_tmux_paused_and_resumed_by_its_key(self):
        self.rt.wait_for_status('overlay_out', lambda s: s.firings > 0, timeout=60)
        status = tempfile.NamedTemporaryFile(prefix='apex_top_status_', delete=False).name
        os.remove(status)  # written when apex_top has ended: its exit status
        shell = "'%s'; echo $? > '%s'" % (self.command, status)
        subprocess.run(self.tmux + ['new-session', '-d', '-s', 'top', '-x', '160', '-y', '40', shell], check=True)
        try:
            self.assertTrue(wait_until(lambda: 'camera_detector/threshold' in self.screen(), 30), self.screen())
            screen = self.screen()
            for node in ('bag', 'overlay_out', 'cloud_out', 'camera_detector/deviation'):
                self.assertIn(node, screen)
            self.assertIn('running', screen.splitlines()[0])
            self.assertIn('sort: share of time', screen)

            self.key('p')
            self.assertTrue(wait_until(lambda: self.rt.graph().paused, 10))
            self.assertTrue(wait_until(lambda: 'PAUSED' in self.screen().splitlines()[0], 10), self.screen())
            self.key('p')
            self.assertTrue(wait_until(lambda: not self.rt.graph().paused, 10))
            self.assertTrue(wait_until(lambda: 'running' in self.screen().splitlines()[0], 10), self.screen())

            self.key('s')
            self.assertTrue(wait_until(lambda: 'sort: firings per second' in self.screen(), 10), self.screen())
            self.key('q')
            self.assertTrue(wait_until(lambda: os.path.exists(status) and os.path.getsize(status) > 0, 10), self.screen())
            with open(status) as f:
                self.assertEqual(f.read().strip(), '0')
        finally:
            subprocess.run(self.tmux + ['kill-server'], capture_output=True)

    def test_once_prints_the_table(self):
        out = subprocess.run([self.command, '--once', '--sort', 'name'], capture_output=True, text=True, timeout=60)
        self.assertEqual(out.returncode, 0, out.stderr)
        lines = out.stdout.splitlines()
        self.assertTrue(lines[0].startswith('apex_top /apex'), out.stdout)
        names = [line.split()[0] for line in lines[4:]]
        self.assertEqual(names, sorted(names))
        self.assertIn('overlay_out', names)
        absent = subprocess.run([self.command, '--runtime', '/nowhere', '--timeout', '1', '--once'],
                                capture_output=True, text=True, timeout=60)
        self.assertEqual(absent.returncode, 1)
        self.assertIn('/nowhere', absent.stderr)


if __name__ == '__main__':
    rospy.init_node('test_apex_top', anonymous=True)
    rostest.rosrun('apex', 'apex_top', ApexTop)
