#!/usr/bin/env python3
"""The table demo's report: starts the bag once it listens, reads the boxes MarkerPublisher sends
for each frame, and compares their count with the ground truth's. Prints 'table: OK' (and exits
0) when every frame showed every box.
    table_report.py TRUTH.yaml"""
import sys

import rospy
import yaml
from apex.srv import SetParameter
from visualization_msgs.msg import Marker, MarkerArray


def main():
    rospy.init_node("table_report")
    truth = yaml.safe_load(open(sys.argv[1]))
    frames, expected = len(truth["frames"]), truth["boxes_per_frame"]
    counts = []
    sub = rospy.Subscriber("/table/boxes", MarkerArray,
                           lambda m: counts.append(sum(1 for k in m.markers if k.type == Marker.CUBE and k.action == Marker.ADD)))
    rospy.wait_for_service("/apex/set_parameter", timeout=60)
    deadline = rospy.Time.now() + rospy.Duration(30)
    while sub.get_num_connections() == 0 and rospy.Time.now() < deadline:  # the publisher builds boxes only for a listener
        rospy.sleep(0.05)
    play = rospy.ServiceProxy("/apex/set_parameter", SetParameter)("bag", "playing", "true")
    if not play.success:
        print("table: FAILED: cannot start the bag: " + play.message)
        sys.exit(1)
    deadline = rospy.Time.now() + rospy.Duration(120)
    while len(counts) < frames and rospy.Time.now() < deadline and not rospy.is_shutdown():
        rospy.sleep(0.05)
    print("=== APEX table demo: %d frames, boxes seen per frame: %s" % (len(counts), counts))
    ok = len(counts) == frames and all(c == expected for c in counts)
    print("table: " + ("OK" if ok else "FAILED (expected %d frames of %d boxes)" % (frames, expected)))
    rospy.signal_shutdown("done")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
