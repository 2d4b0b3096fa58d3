"""Waiting on conditions in the Python rostests (imported from the tests' own folder)."""
import time

import rospy


def wait_until(done, timeout=30.0):
    """Whether `done()` holds within `timeout` seconds (wall time), checked every 20 ms."""
    end = time.time() + timeout
    while not done():
        if time.time() > end or rospy.is_shutdown():
            return False
        time.sleep(0.02)
    return True
