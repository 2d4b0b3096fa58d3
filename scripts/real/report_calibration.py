#!/usr/bin/python3
"""The calibration demo's report (launch/real_calibration.launch, graphs/real_calibration.yaml).

Taps the graph's chessboard corners, CameraCalibration's model and RMS (~inspect), and the
rectified frames (/real_calibration/rectified), then starts the bag. CameraCalibration calibrates
once it has a view of every frame and restarts the bag; the second pass rectifies every frame with
the model it wrote. Meanwhile this report does the same with OpenCV's Python bindings on the same
images (read from the same bag) and the same settings (read from the graph's nodes):
cv2.findChessboardCorners + cv2.cornerSubPix, cv2.calibrateCamera, and cv2.initUndistortRectifyMap
+ cv2.remap on APEX's model. It prints RMS and intrinsics of APEX, of cv2 and of OpenCV's own
calibration of the sequence (left_intrinsics.yml), and "calibration: OK" (exit 0) when APEX's figures
equal cv2's as printed, the model file holds the model sent, and every rectified frame equals cv2's.
    report_calibration.py BAG MODEL_FILE [--reference left_intrinsics.yml] [--timeout S] [--stay]
--stay (rviz): leaves the graph running (the bag loops) instead of ending the launch."""
import argparse
import os
import sys
import threading
import time

import cv2
import numpy as np
import rosbag
import rospy
import yaml
from sensor_msgs.msg import CameraInfo, Image
from std_msgs.msg import Float64

import apex
from apex.msg import ChessboardCorners
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # real_report.py is beside this script (also in devel)
import real_report  # (beside this script)
from real_report import node_errors

NAME = "calibration"
RECTIFIED = "/real_calibration/rectified"


def fail(text):
    real_report.fail(NAME, text)


def image_array(msg):
    """A bgr8 / mono8 sensor_msgs/Image as a numpy array (its rows, without padding)."""
    channels = {"bgr8": 3, "rgb8": 3, "mono8": 1}.get(msg.encoding)
    if channels is None:
        fail("an image of encoding '%s': this report reads bgr8, rgb8 and mono8" % msg.encoding)
    rows = np.frombuffer(msg.data, np.uint8).reshape(msg.height, msg.step)[:, :msg.width * channels]
    return rows.reshape(msg.height, msg.width, channels) if channels > 1 else rows.copy()


def bag_images(path):
    """The bag's frames on /camera/image_raw, in order: [(stamp in ns, image)]."""
    try:
        with rosbag.Bag(path) as bag:
            frames = [(m.header.stamp.to_nsec(), image_array(m)) for _, m, _ in bag.read_messages(topics=["/camera/image_raw"])]
    except (OSError, rosbag.ROSBagException) as e:
        fail("cannot read the bag %s: %s" % (path, e))
    if not frames:
        fail("the bag %s has no frames on /camera/image_raw" % path)
    return frames


class Taps:
    """What the graph sends, by stamp; a condition to wait on."""

    def __init__(self):
        self.changed = threading.Condition()
        self.corners, self.rectified = {}, {}
        self.rms, self.info = None, None

    def _keep(self, store, key, value, first=False):
        with self.changed:
            if not (first and key in store):
                store[key] = value
            self.changed.notify_all()

    def on_corners(self, m):
        self._keep(self.corners, m.header.stamp.to_nsec(), m, first=True)  # the first pass's: the views calibrated

    def on_rectified(self, m):
        self._keep(self.rectified, m.header.stamp.to_nsec(), m)

    def on_rms(self, m):
        with self.changed:
            self.rms = m.data
            self.changed.notify_all()

    def on_info(self, m):
        with self.changed:
            self.info = m
            self.changed.notify_all()


def wait_for_connections(subs, deadline):
    """Until each subscriber is connected to its publisher (a graph publisher sends only to listeners)."""
    for s in subs:
        while s.get_num_connections() == 0:
            if time.time() > deadline or rospy.is_shutdown():
                fail("nobody publishes %s (is the graph graphs/real_calibration.yaml loaded?)" % s.resolved_name)
            time.sleep(0.05)


def opencv_corners(frames, board):
    """cv2.findChessboardCorners (+ cv2.cornerSubPix) with ChessboardCorners' settings, per frame."""
    pattern = (board["pattern_columns"], board["pattern_rows"])
    flags = ((cv2.CALIB_CB_ADAPTIVE_THRESH if board["adaptive_thresh"] else 0) |
             (cv2.CALIB_CB_NORMALIZE_IMAGE if board["normalize_image"] else 0) |
             (cv2.CALIB_CB_FAST_CHECK if board["fast_check"] else 0))
    window = (board["refine_window"], board["refine_window"])
    out = []
    for stamp, image in frames:
        gray = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
        found, corners = cv2.findChessboardCorners(gray, pattern, flags=flags)
        if found and board["refine"]:
            corners = cv2.cornerSubPix(gray, corners, window, (-1, -1),
                                       (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_COUNT, 30, 0.001))
        out.append((stamp, corners.reshape(-1, 2) if found else None))
    return out


def opencv_calibration(views, pattern, size, calib):
    """cv2.calibrateCamera as CameraCalibration calls it: K starts as I (fx / fy = 1 for
    CALIB_FIX_ASPECT_RATIO), the board's corners row by row at square_size."""
    square = calib["square_size"]
    board = np.array([[j * square, i * square, 0] for i in range(pattern[1]) for j in range(pattern[0])], np.float32)
    flags = ((cv2.CALIB_FIX_ASPECT_RATIO if calib["fix_aspect_ratio"] else 0) |
             (cv2.CALIB_FIX_PRINCIPAL_POINT if calib["fix_principal_point"] else 0) |
             (cv2.CALIB_ZERO_TANGENT_DIST if calib["zero_tangent_dist"] else 0) |
             (cv2.CALIB_FIX_K3 if calib["fix_k3"] else 0))
    rms, K, D, _, _ = cv2.calibrateCamera([board] * len(views), [v.reshape(-1, 1, 2) for v in views], size,
                                          np.eye(3), None, flags=flags)
    return rms, K, D.ravel()


def figures(rms, K, D):
    """The printed figures: RMS, fx, fy, cx, cy, k1, k2, p1, p2, k3, as text."""
    D = list(D) + [0.0] * (5 - len(D))
    return (["%.6f" % rms] + ["%.4f" % v for v in (K[0][0], K[1][1], K[0][2], K[1][2])] +
            ["%.6f" % v for v in D[:5]])


def model_file(path):
    """K, D, R, P of a camera_calibration_parsers YAML file."""
    try:
        with open(path) as f:
            y = yaml.safe_load(f)
        return {k: list(map(float, y[key]["data"])) for k, key in
                (("K", "camera_matrix"), ("D", "distortion_coefficients"), ("R", "rectification_matrix"),
                 ("P", "projection_matrix"))}
    except (OSError, yaml.YAMLError, KeyError, TypeError) as e:
        return "cannot read it: %s" % e


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("bag")
    parser.add_argument("model")
    parser.add_argument("--reference", default="/usr/share/doc/opencv-doc/examples/data/left_intrinsics.yml")
    parser.add_argument("--timeout", type=float, default=300)
    parser.add_argument("--stay", action="store_true")
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node("real_calibration_report")
    deadline = time.time() + args.timeout

    frames = bag_images(args.bag)
    try:
        rt = apex.Runtime("/apex", timeout=60)
        board, calib = rt.parameters("board"), rt.parameters("calib")
        taps = Taps()
        subs = [rospy.Subscriber(RECTIFIED, Image, taps.on_rectified, queue_size=100)]
        for node, port, kind, callback in (("board", "corners", ChessboardCorners, taps.on_corners),
                                           ("calib", "rms", Float64, taps.on_rms),
                                           ("calib", "camera_info", CameraInfo, taps.on_info)):
            topic, _ = rt.inspect(node, port)
            subs.append(rospy.Subscriber(topic, kind, callback, queue_size=100))
        wait_for_connections(subs, min(deadline, time.time() + 30))
        rt.set_parameter("bag", "playing", True)
    except apex.ApexError as e:
        fail(str(e))

    # Meanwhile, OpenCV on the same images
    pattern = (board["pattern_columns"], board["pattern_rows"])
    ours = opencv_corners(frames, board)
    views = [c for _, c in ours if c is not None]
    if len(views) < 3:
        fail("cv2.findChessboardCorners found the board in %d of %d frames: too few to calibrate" % (len(views), len(frames)))
    size = (frames[0][1].shape[1], frames[0][1].shape[0])
    cv_rms, cv_K, cv_D = opencv_calibration(views, pattern, size, calib)

    # The graph: corners of every frame, the model, and every frame rectified
    stamps = [s for s, _ in frames]
    wanted = "the model (calib/camera_info, calib/rms) and %d rectified frames on %s" % (len(stamps), RECTIFIED)

    def had():
        return "had %d corners, %s model, %d rectified frames" % (
            len(taps.corners), "a" if taps.info else "no", len(taps.rectified))

    while True:
        with taps.changed:
            if (taps.rms is not None and taps.info is not None and all(s in taps.rectified for s in stamps)
                    and all(s in taps.corners for s in stamps)):
                rms, info = taps.rms, taps.info
                apex_corners, rectified = dict(taps.corners), dict(taps.rectified)
                break
            found = sum(m.found for m in taps.corners.values())
            if all(s in taps.corners for s in stamps) and found < calib["views"]:  # it would wait for more views
                fail("ChessboardCorners found the board in %d of the bag's %d frames, CameraCalibration waits for %d "
                     "views (its parameter 'views')" % (found, len(stamps), calib["views"]))
            taps.changed.wait(0.5)
        # a node in error will not deliver (e.g. calib cannot write its file): say so now, not at the timeout
        errors = node_errors(rt)
        if errors:
            fail("waiting for %s: %s; nodes in error%s" % (wanted, had(), errors))
        if time.time() > deadline or rospy.is_shutdown():
            fail("timed out after %g s waiting for %s: %s" % (args.timeout, wanted, had()))

    # Corners: APEX's against cv2's, frame by frame
    corner_diff, found_apex = 0.0, 0
    for stamp, mine in ours:
        m = apex_corners[stamp]
        found_apex += m.found
        if m.found != (mine is not None):
            fail("the frame stamped %d ns: ChessboardCorners %s the board, cv2.findChessboardCorners %s"
                 % (stamp, "found" if m.found else "did not find", "did" if mine is not None else "did not"))
        if mine is not None:
            theirs = np.array([[p.x, p.y] for p in m.corners], np.float32)
            corner_diff = max(corner_diff, float(np.abs(theirs - mine).max()))

    K = np.array(info.K).reshape(3, 3)
    D = np.array(info.D)
    apex_fig, cv_fig = figures(rms, K, D), figures(cv_rms, cv_K, cv_D)
    ref = cv2.FileStorage(args.reference, cv2.FILE_STORAGE_READ)
    ref_K, ref_D = ref.getNode("camera_matrix").mat(), ref.getNode("distortion_coefficients").mat()
    if ref_K is None or ref_D is None:
        ref_fig, ref_label = ["-"] * 10, "(not read: %s)" % args.reference
    else:
        ref_fig = figures(ref.getNode("avg_reprojection_error").real(), ref_K, ref_D.ravel())
        ref_label = "%s (%d views)" % (os.path.basename(args.reference), int(ref.getNode("nframes").real()))

    # The model file, and the rectified frames against cv2.remap on APEX's model
    saved = model_file(args.model)
    sent = {"K": list(info.K), "D": list(info.D), "R": list(info.R), "P": list(info.P)}
    file_ok = saved == sent
    R, P = np.array(info.R).reshape(3, 3), np.array(info.P).reshape(3, 4)
    map1, map2 = cv2.initUndistortRectifyMap(K, D, R, P[:, :3].copy(), size, cv2.CV_16SC2)
    rect_diff = 0
    for stamp, image in frames:
        want = cv2.remap(image, map1, map2, cv2.INTER_LINEAR)
        got = image_array(rectified[stamp])
        rect_diff = max(rect_diff, int(np.abs(got.astype(np.int16) - want.reshape(got.shape).astype(np.int16)).max()))

    flags = [f for f in ("fix_aspect_ratio", "fix_principal_point", "zero_tangent_dist", "fix_k3") if calib[f]]
    print("=== APEX real data: calibration of a camera from opencv-doc's chessboard sequence", flush=True)
    print("views:        %d frames of %dx%d, a %dx%d board found in %d (cv2: %d); CameraCalibration's flags: %s"
          % (len(frames), size[0], size[1], pattern[0], pattern[1], found_apex, len(views), ", ".join(flags) or "none"))
    print("corners:      APEX's and cv2.findChessboardCorners + cv2.cornerSubPix's on the same images differ by at most %g px"
          % corner_diff)
    print("%-13s %-20s %-20s %s" % ("", "APEX", "cv2.calibrateCamera", ref_label))
    for name, a, c, r in zip(("RMS error px", "fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2", "k3"), apex_fig, cv_fig, ref_fig):
        print("%-13s %-20s %-20s %s" % (name, a, c, r))
    print("model file:   %s (camera_calibration_parsers' YAML): %s"
          % (args.model, "K, D, R, P as sent" if file_ok else "differs from the model sent: %s" % (saved,)))
    print("rectified:    %d of %d frames on %s; against cv2.initUndistortRectifyMap + cv2.remap on APEX's model: "
          "largest difference %d" % (sum(s in rectified for s in stamps), len(stamps), RECTIFIED, rect_diff))
    problems = []
    if apex_fig != cv_fig:
        problems.append("APEX's calibration differs from cv2.calibrateCamera's (%s)" %
                        ", ".join(n for n, a, c in zip(("RMS", "fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2", "k3"),
                                                       apex_fig, cv_fig) if a != c))
    if not file_ok:
        problems.append("the model file does not hold the model sent")
    if rect_diff != 0:
        problems.append("the rectified frames differ from cv2.remap's")
    print("%s: %s" % (NAME, "OK" if not problems else "FAILED: " + "; ".join(problems)), flush=True)
    if args.stay:
        print("(the graph keeps running: the bag loops, rviz shows the raw and rectified frames; Ctrl-C ends)", flush=True)
        return 0 if not problems else 1
    rospy.signal_shutdown("done")
    return 0 if not problems else 1


if __name__ == "__main__":
    sys.exit(main())
