#!/usr/bin/python3
"""The stereo demo's report (launch/real_stereo.launch, graphs/real_stereo.yaml).

Listens to the graph's disparity (/real_stereo/disparity, 32FC1, pixels, NaN where no match) and
cloud (/real_stereo/points), then starts the bag: the Middlebury pair aloeL.jpg / aloeR.jpg, halved
by PyrDown (as OpenCV's stereo_match.py halves it) and matched by StereoMatcher. Meanwhile it runs
OpenCV's own matcher (cv2.StereoSGBM, or cv2.StereoBM) with StereoMatcher's settings, read from the
graph, on the same images read from the same bag, halved by cv2.pyrDown. Both are scored against
the ground truth aloeGT.png: the share of the pixels whose true disparity is known that are off by
more than 1 px or have no match (Middlebury's bad-pixel measure). Prints both, and "stereo: OK"
(exit 0) when they are equal as printed and the cloud has a point per valid disparity.
    report_stereo.py BAG [--truth aloeGT.png] [--timeout S] [--stay]
--stay (rviz): leaves the graph running, paused on its frame, instead of ending the launch."""
import argparse
import os
import sys
import threading
import time

import cv2
import numpy as np
import rosbag
import rosgraph
import rospy
from sensor_msgs.msg import Image, PointCloud2

import apex
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # real_report.py is beside this script (also in devel)
import real_report  # (beside this script)

NAME = "stereo"
DISPARITY, POINTS = "/real_stereo/disparity", "/real_stereo/points"
LEFT, RIGHT = "/stereo/left/image_raw", "/stereo/right/image_raw"


def fail(text):
    real_report.fail(NAME, text)


def image_array(msg):
    """A sensor_msgs/Image (bgr8, rgb8, mono8 or 32FC1) as a numpy array."""
    kinds = {"bgr8": (np.uint8, 3), "rgb8": (np.uint8, 3), "mono8": (np.uint8, 1), "32FC1": (np.float32, 1)}
    if msg.encoding not in kinds:
        fail("an image of encoding '%s': this report reads %s" % (msg.encoding, ", ".join(kinds)))
    dtype, channels = kinds[msg.encoding]
    rows = np.frombuffer(msg.data, np.uint8).reshape(msg.height, msg.step)[:, :msg.width * channels * np.dtype(dtype).itemsize]
    if msg.is_bigendian != (sys.byteorder == "big"):
        fail("an image of the other byte order")
    pixels = np.ascontiguousarray(rows).view(dtype)
    return pixels.reshape(msg.height, msg.width, channels) if channels > 1 else pixels


def bag_pair(path):
    """The first stereo pair of the bag: (left, right) as bgr8 arrays."""
    pair = {}
    try:
        with rosbag.Bag(path) as bag:
            for topic, m, _ in bag.read_messages(topics=[LEFT, RIGHT]):
                pair.setdefault(topic, image_array(m))
    except (OSError, rosbag.ROSBagException) as e:
        fail("cannot read the bag %s: %s" % (path, e))
    if len(pair) != 2:
        fail("the bag %s lacks %s" % (path, " and ".join(t for t in (LEFT, RIGHT) if t not in pair)))
    return pair[LEFT], pair[RIGHT]


def opencv_disparity(left, right, p):
    """OpenCV's own matcher made as StereoMatcher makes it from its parameters `p`, on the pair as
    gray: the disparity in pixels, NaN where there is no match (below min_disparity)."""
    block, cap = p["block_size"], p["pre_filter_cap"]
    if p["algorithm"] == "bm":
        m = cv2.StereoBM_create(p["num_disparities"], block)
        m.setMinDisparity(p["min_disparity"])
        m.setPreFilterCap(cap if cap > 0 else 31)
        m.setTextureThreshold(p["texture_threshold"])
        m.setUniquenessRatio(p["uniqueness_ratio"])
        m.setSpeckleWindowSize(p["speckle_window_size"])
        m.setSpeckleRange(p["speckle_range"])
        m.setDisp12MaxDiff(p["disp12_max_diff"])
        what = "cv2.StereoBM"
    else:
        mode = {"sgbm": cv2.STEREO_SGBM_MODE_SGBM, "hh": cv2.STEREO_SGBM_MODE_HH,
                "sgbm_3way": cv2.STEREO_SGBM_MODE_SGBM_3WAY, "hh4": cv2.STEREO_SGBM_MODE_HH4}[p["mode"]]
        area = block * block  # one channel: matched as gray
        m = cv2.StereoSGBM_create(p["min_disparity"], p["num_disparities"], block,
                                  p["p1"] if p["p1"] > 0 else 8 * area, p["p2"] if p["p2"] > 0 else 32 * area,
                                  p["disp12_max_diff"], cap if cap > 0 else 63, p["uniqueness_ratio"],
                                  p["speckle_window_size"], p["speckle_range"], mode)
        what = "cv2.StereoSGBM"
    gray = [cv2.cvtColor(i, cv2.COLOR_BGR2GRAY) for i in (left, right)]
    fixed = m.compute(gray[0], gray[1])
    d = fixed.astype(np.float32) / 16
    d[fixed < p["min_disparity"] * 16] = np.nan
    return d, what, m


def settings_text(m, what):
    if what == "cv2.StereoBM":
        return "min_disparity %d, num_disparities %d, block_size %d, pre_filter_cap %d, texture_threshold %d, " \
               "uniqueness_ratio %d, speckle %d px / %d, disp12_max_diff %d" % (
                   m.getMinDisparity(), m.getNumDisparities(), m.getBlockSize(), m.getPreFilterCap(),
                   m.getTextureThreshold(), m.getUniquenessRatio(), m.getSpeckleWindowSize(), m.getSpeckleRange(),
                   m.getDisp12MaxDiff())
    modes = {cv2.STEREO_SGBM_MODE_SGBM: "sgbm", cv2.STEREO_SGBM_MODE_HH: "hh", cv2.STEREO_SGBM_MODE_SGBM_3WAY: "sgbm_3way",
             cv2.STEREO_SGBM_MODE_HH4: "hh4"}
    return "min_disparity %d, num_disparities %d, block_size %d, P1 %d, P2 %d, uniqueness_ratio %d, speckle %d px / %d, " \
           "disp12_max_diff %d, pre_filter_cap %d, mode %s" % (
               m.getMinDisparity(), m.getNumDisparities(), m.getBlockSize(), m.getP1(), m.getP2(), m.getUniquenessRatio(),
               m.getSpeckleWindowSize(), m.getSpeckleRange(), m.getDisp12MaxDiff(), m.getPreFilterCap(),
               modes.get(m.getMode(), str(m.getMode())))


def bad_pixels(d, truth, scale, left_of):
    """Middlebury's bad-pixel share of disparity `d` (pixels at its own size, NaN: no match) against
    `truth` (full size, 0: unknown): over the pixels whose truth is known, the share off by more than
    1 px of d's size, or without a match; also that share where x >= left_of, and the share unmatched.
    The truth of pixel (x, y) is truth(scale x, scale y) / scale."""
    t = truth[::scale, ::scale][:d.shape[0], :d.shape[1]].astype(np.float64)
    known = t > 0
    t = t / scale
    unmatched = known & np.isnan(d)
    with np.errstate(invalid="ignore"):
        bad = known & (np.isnan(d) | (np.abs(d - t) > 1))
    cols = np.arange(d.shape[1])[None, :] >= left_of
    return (bad.sum() / known.sum(), (bad & cols).sum() / (known & cols).sum(), unmatched.sum() / known.sum(),
            int(known.sum()))


def wait_for_viewer(topic, deadline):
    """rviz mode: until someone besides this report subscribes to `topic` (a graph publisher sends only
    to listeners, and the bag has one frame), or the deadline."""
    master = rosgraph.Master(rospy.get_name())
    while time.time() < deadline and not rospy.is_shutdown():
        try:
            _, subscribers, _ = master.getSystemState()
        except (rosgraph.MasterException, OSError):
            subscribers = []
        if any(t == topic and [n for n in nodes if n != rospy.get_name()] for t, nodes in subscribers):
            return True
        time.sleep(0.2)
    return False


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("bag")
    parser.add_argument("--truth", default="/usr/share/doc/opencv-doc/examples/data/aloeGT.png")
    parser.add_argument("--timeout", type=float, default=300)
    parser.add_argument("--stay", action="store_true")
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node("real_stereo_report")
    deadline = time.time() + args.timeout

    left, right = bag_pair(args.bag)
    truth = cv2.imread(args.truth, cv2.IMREAD_UNCHANGED)
    if truth is None:
        fail("cannot read the ground truth %s (is opencv-doc installed?)" % args.truth)
    if truth.ndim != 2 or truth.dtype != np.uint8:
        fail("the ground truth %s is not an 8-bit gray image" % args.truth)
    got = {}
    changed = threading.Condition()

    def keep(key):
        def received(m):
            with changed:
                got.setdefault(key, m)
                changed.notify_all()
        return received

    try:
        rt = apex.Runtime("/apex", timeout=60)
        p = rt.parameters("matcher")
        subs = [rospy.Subscriber(DISPARITY, Image, keep("disparity"), queue_size=2),
                rospy.Subscriber(POINTS, PointCloud2, keep("cloud"), queue_size=2)]
        connected_by = min(deadline, time.time() + 30)
        for s in subs:
            while s.get_num_connections() == 0:
                if time.time() > connected_by or rospy.is_shutdown():
                    fail("nobody publishes %s (is the graph graphs/real_stereo.yaml loaded?)" % s.resolved_name)
                time.sleep(0.05)
        if args.stay and not wait_for_viewer(POINTS, time.time() + 60):
            print("(rviz has not subscribed to %s within 60 s: playing anyway)" % POINTS, flush=True)
        rt.set_parameter("bag", "playing", True)
    except apex.ApexError as e:
        fail(str(e))

    # Meanwhile, OpenCV's matcher on the same pair, halved as stereo_match.py halves it
    half_left, half_right = cv2.pyrDown(left), cv2.pyrDown(right)
    theirs, what, matcher = opencv_disparity(half_left, half_right, p)

    while True:
        with changed:
            if "disparity" in got and "cloud" in got:
                break
            changed.wait(0.5)
        missing = " and ".join(t for k, t in (("disparity", DISPARITY), ("cloud", POINTS)) if k not in got)
        errors = real_report.node_errors(rt)  # a node in error will not deliver: say so now, not at the timeout
        if errors:
            fail("waiting for %s: nodes in error%s" % (missing, errors))
        if time.time() > deadline or rospy.is_shutdown():
            fail("timed out after %g s waiting for %s" % (args.timeout, missing))
    ours = image_array(got["disparity"])
    cloud = got["cloud"]
    if ours.shape != theirs.shape:
        fail("the graph's disparity is %dx%d, cv2's %dx%d" % (ours.shape[1], ours.shape[0], theirs.shape[1], theirs.shape[0]))

    scale = int(round(left.shape[1] / ours.shape[1]))  # 2: PyrDown halved the pair
    if truth.shape != left.shape[:2]:
        fail("the ground truth is %dx%d, the images %dx%d" % (truth.shape[1], truth.shape[0], left.shape[1], left.shape[0]))
    left_of = p["min_disparity"] + p["num_disparities"]  # columns left of this cannot be searched in full
    a_share, a_fits, a_unmatched, known = bad_pixels(ours, truth, scale, left_of)
    c_share, c_fits, c_unmatched, _ = bad_pixels(theirs, truth, scale, left_of)
    same = int(((ours == theirs) | (np.isnan(ours) & np.isnan(theirs))).sum())
    valid = int((np.isfinite(ours) & (ours > rt.parameter("cloud", "min_disparity"))).sum())
    points = cloud.width * cloud.height
    # the ground truth's scale: twice a half-size disparity against the truth where both are known
    t = truth[::scale, ::scale][:ours.shape[0], :ours.shape[1]].astype(np.float64)
    both = (t > 0) & np.isfinite(ours)
    ratio = float(np.median(ours[both] * scale / t[both])) if both.any() else float("nan")

    pct = lambda v: "%.2f%%" % (100 * v)
    print("=== APEX real data: stereo on opencv-doc's Middlebury pair aloeL.jpg / aloeR.jpg", flush=True)
    print("images:       %dx%d, matched at 1/%d size, %dx%d (PyrDown, as OpenCV's stereo_match.py), as gray"
          % (left.shape[1], left.shape[0], scale, ours.shape[1], ours.shape[0]))
    print("settings:     %s" % settings_text(matcher, what))
    print("truth:        %s, %dx%d, disparities in full-size pixels (median of %d x disparity / truth: %.3f); 0: unknown "
          "(occluded or unmeasured), left out; known at %d of %d pixels at 1/%d size (%.1f%%)"
          % (args.truth.split("/")[-1], truth.shape[1], truth.shape[0], scale, ratio, known, ours.size, scale,
             100.0 * known / ours.size))
    print("bad pixels:   off by more than 1 px (at 1/%d size) or no match, of the pixels with a known truth" % scale)
    print("%-20s %-12s %-22s %s" % ("", "all known", "x >= %d (full range)" % left_of, "no match"))
    print("%-20s %-12s %-22s %s" % ("APEX StereoMatcher", pct(a_share), pct(a_fits), pct(a_unmatched)))
    print("%-20s %-12s %-22s %s" % (what, pct(c_share), pct(c_fits), pct(c_unmatched)))
    print("disparities:  equal at %d of %d pixels (NaN on both where no match)" % (same, ours.size))
    print("cloud:        %d points on %s (frame '%s'), one per valid disparity: %d" % (points, POINTS, cloud.header.frame_id, valid))
    problems = []
    if (pct(a_share), pct(a_fits), pct(a_unmatched)) != (pct(c_share), pct(c_fits), pct(c_unmatched)):
        problems.append("APEX's bad-pixel shares differ from %s's" % what)
    if points != valid:
        problems.append("the cloud has %d points for %d valid disparities" % (points, valid))
    if not 0.9 < ratio < 1.1:
        problems.append("the ground truth's scale is not the images' (median ratio %.3f): the measure is off" % ratio)
    print("%s: %s" % (NAME, "OK" if not problems else "FAILED: " + "; ".join(problems)), flush=True)
    if args.stay:
        try:  # paused, the bag sends its frame again after each edit in the panel: tune and watch
            rt.set_parameter("bag", "playing", False)
        except apex.ApexError as e:
            print("(could not pause the bag: %s)" % e.message)
        print("(the graph keeps running, paused on the pair: edit the matcher in the panel and rviz shows the result; "
              "Ctrl-C ends)", flush=True)
        return 0 if not problems else 1
    rospy.signal_shutdown("done")
    return 0 if not problems else 1


if __name__ == "__main__":
    sys.exit(main())
