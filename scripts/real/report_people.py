#!/usr/bin/env python3
"""The people demo's report (launch/real_people.launch; scripts/real/people runs it).

Plays the bag of opencv-doc's vtest.avi once through graphs/real_people.yaml (as fast as the graph
takes the frames), reads back the regions the graph recorded for each frame (its BagWriter), then
runs the same OpenCV calls with the same settings (read from the running graph) in a plain Python
loop on the same frames of the same bag. Prints detections per frame (mean, min, max) and frames
per second of both, and in how many frames the detections are equal; "people: OK" when the
count is equal in every frame.

    report_people.py BAG RECORD [FRAMES [--track]]     FRAMES: the first N frames only (0: all)
      --track: also each of the longest tracks, and fail if ids jump (more than 1 box in 100)

The tracks (the graph's MultiObjectTracker) are summed up in any case: how many ids, how long
they last, and how often an id jumps to another person: its box's centre moves further than the
box's size (its width or height, the larger) from one appearance to the next, which a walker does
not do in a frame or a few, while a box that grows as two blobs merge does not count. Those are the
id switches a tracker makes that can be told without ground truth.
"""
import os
import sys
import threading
import time

import cv2
import numpy as np
import rosbag
import rospy

import apex
from apex.msg import Regions
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # real_report.py is beside this script (also in devel)
import real_report  # (beside this script)
from real_report import node_errors

IMAGE_TOPIC = '/camera/image_raw'
RECORD_TOPIC = '/people/regions'  # graphs/real_people.yaml's record node: its input people_regions
TRACK_TOPIC = '/people/tracks'  # and people_tracks: the MultiObjectTracker's regions, ids in label

START_TIMEOUT = 60.0  # s: the runtime's services, the inspect topic's connection


def fail(why):
    real_report.fail('people', why)


def bag_timing(path):
    """(frames, first stamp in s, period in s, width, height) of the bag's images, from its index."""
    with rosbag.Bag(path) as bag:
        topics = bag.get_type_and_topic_info().topics
        if IMAGE_TOPIC not in topics:
            fail("the bag '%s' has no topic %s" % (path, IMAGE_TOPIC))
        count = topics[IMAGE_TOPIC].message_count
        start, end = bag.get_start_time(), bag.get_end_time()
        for _, msg, _ in bag.read_messages(topics=[IMAGE_TOPIC]):
            size = (msg.width, msg.height)
            break
    return count, start, (end - start) / max(count - 1, 1), size


def frame_index(stamp, start, period):
    return int(round((stamp.to_sec() - start) / period))


def settings_of(rt):
    """The graph's settings, as the plain loop needs them; fails if the graph is not the chain the loop repeats."""
    try:
        s = {name: rt.parameters(name) for name in ('background', 'foreground', 'morphology', 'contours', 'people', 'overlay')}
    except apex.ApexError as e:
        fail('the graph is not graphs/real_people.yaml: %s' % e.message)
    full = {'perimeter': [0.0, 1e5], 'aspect_ratio': [0.0, 100.0], 'solidity': [0.0, 1.0], 'circularity': [0.0, 1.0],
            'vertices': [0.0, 1000.0]}
    for name, interval in full.items():
        if list(s['people'][name]) != interval:
            fail('the loop repeats ContourFilter by area only; people/%s is %s' % (name, s['people'][name]))
    return s


def describe(s):
    b, f, m, c, p = s['background'], s['foreground'], s['morphology'], s['contours'], s['people']
    high = p['area'][1]
    return ('BackgroundSubtraction (%s, history %d, var_threshold %g, shadows %s) -> Threshold (%s %g) -> Morphology '
            '(%s, %s %d, %d x) -> FindContours (%s, %s) -> ContourFilter (area %g..%s px) -> ContoursToRegions'
            % (b['method'], b['history'], b['var_threshold'], 'on' if b['detect_shadows'] else 'off', f['type'],
               f['threshold'], m['operation'], m['shape'], m['kernel_size'], m['iterations'], c['mode'], c['method'],
               p['area'][0], 'any' if high >= 1e7 else '%g' % high))


class Loop:
    """The graph's OpenCV calls, one frame at a time, with the graph's settings."""

    def __init__(self, s):
        b, f, m, c, p, o = s['background'], s['foreground'], s['morphology'], s['contours'], s['people'], s['overlay']
        if b['method'] == 'mog2':
            self.model = cv2.createBackgroundSubtractorMOG2(b['history'], b['var_threshold'], b['detect_shadows'])
        else:
            self.model = cv2.createBackgroundSubtractorKNN(b['history'], b['dist2_threshold'], b['detect_shadows'])
        self.rate = b['learning_rate']
        types = {'binary': cv2.THRESH_BINARY, 'binary_inv': cv2.THRESH_BINARY_INV, 'trunc': cv2.THRESH_TRUNC,
                 'tozero': cv2.THRESH_TOZERO, 'tozero_inv': cv2.THRESH_TOZERO_INV}
        self.threshold = (f['threshold'], f['max_value'], types[f['type']] | (cv2.THRESH_OTSU if f['otsu'] else 0))
        shapes = {'rect': cv2.MORPH_RECT, 'cross': cv2.MORPH_CROSS, 'ellipse': cv2.MORPH_ELLIPSE}
        ops = {'erode': cv2.MORPH_ERODE, 'dilate': cv2.MORPH_DILATE, 'open': cv2.MORPH_OPEN, 'close': cv2.MORPH_CLOSE}
        self.kernel = cv2.getStructuringElement(shapes[m['shape']], (m['kernel_size'], m['kernel_size']))
        self.op, self.iterations = ops[m['operation']], m['iterations']
        self.mode = {'external': cv2.RETR_EXTERNAL, 'list': cv2.RETR_LIST, 'ccomp': cv2.RETR_CCOMP,
                     'tree': cv2.RETR_TREE}[c['mode']]
        self.method = {'none': cv2.CHAIN_APPROX_NONE, 'simple': cv2.CHAIN_APPROX_SIMPLE,
                       'tc89_l1': cv2.CHAIN_APPROX_TC89_L1, 'tc89_kcos': cv2.CHAIN_APPROX_TC89_KCOS}[c['method']]
        self.low, self.high = p['area']
        self.unbounded = self.high >= 1e7  # ContourFilter: at the top of its range, no upper limit
        self.colour, self.thickness = tuple(int(v) for v in reversed(o['color'])), o['thickness']  # rgb -> bgr

    def boxes(self, frame):
        mask = self.model.apply(frame, learningRate=self.rate)
        _, fg = cv2.threshold(mask, *self.threshold)
        fg = cv2.morphologyEx(fg, self.op, self.kernel, iterations=self.iterations)
        contours, _ = cv2.findContours(fg, self.mode, self.method)
        found = []
        for c in contours:
            area = cv2.contourArea(c)
            if area >= self.low and (area <= self.high or self.unbounded):
                found.append(cv2.boundingRect(c))
        overlay = frame.copy() if frame.ndim == 3 else cv2.cvtColor(frame, cv2.COLOR_GRAY2BGR)
        for box in found:
            cv2.rectangle(overlay, box, self.colour, self.thickness)
        return found


def image_of(msg):
    """A sensor_msgs/Image's pixels as the graph sees them (no conversion: MOG2 models the channels as they are)."""
    channels = {'bgr8': 3, 'rgb8': 3, 'mono8': 1}.get(msg.encoding)
    if channels is None:
        fail('the loop reads bgr8, rgb8 or mono8 frames, not %s' % msg.encoding)
    rows = np.frombuffer(msg.data, np.uint8).reshape(msg.height, msg.step)[:, :msg.width * channels]
    image = rows.reshape(msg.height, msg.width, channels) if channels == 3 else rows
    return np.ascontiguousarray(image)


def run_loop(path, frames, settings):
    """The plain loop over the bag's first `frames` frames: boxes per frame, seconds in the calls, seconds in all."""
    loop = Loop(settings)
    boxes, calls = [], 0.0
    began = time.perf_counter()
    with rosbag.Bag(path) as bag:
        for _, msg, _ in bag.read_messages(topics=[IMAGE_TOPIC]):
            if len(boxes) == frames:
                break
            image = image_of(msg)
            t = time.perf_counter()
            boxes.append(loop.boxes(image))
            calls += time.perf_counter() - t
    return boxes, calls, time.perf_counter() - began


def stats(counts):
    a = np.array(counts, float)
    return 'mean %.2f, min %d, max %d' % (a.mean(), a.min(), a.max()) if len(a) else 'none'


def jumped(a, b):
    """Box b, an id's next appearance after box a (x, y, w, h), is too far to be the same person."""
    dx = (b[0] + b[2] / 2) - (a[0] + a[2] / 2)
    dy = (b[1] + b[3] / 2) - (a[1] + a[3] / 2)
    return (dx * dx + dy * dy) ** 0.5 > max(a[2], a[3])


def track_summary(tracks):
    """tracks: {id: [(frame, box), ...]} in frame order. (ids, lengths longest first, jumps, boxes)."""
    lengths = sorted((len(seen) for seen in tracks.values()), reverse=True)
    jumps = sum(1 for seen in tracks.values() for (_, a), (_, b) in zip(seen, seen[1:]) if jumped(a, b))
    return len(tracks), lengths, jumps, sum(lengths)


def main():
    rospy.init_node('report_people', disable_signals=False)
    args = rospy.myargv(sys.argv)[1:]
    track = '--track' in args
    args = [a for a in args if a != '--track']
    if len(args) not in (2, 3):
        print(__doc__)
        sys.exit(2)
    bag_path, record = args[0], args[1]
    asked = int(args[2]) if len(args) == 3 else 0
    count, start, period, size = bag_timing(bag_path)
    frames = count if asked <= 0 else min(asked, count)

    try:
        rt = apex.Runtime('/apex', timeout=START_TIMEOUT)
    except apex.ApexError as e:
        fail(e.message)
    settings = settings_of(rt)

    # Each frame's regions arrive on the inspect topic (the timing: when the last one came); the
    # recording (lossless) gives the counts.
    topic, _ = rt.inspect('regions', 'regions')
    last = {'wall': None, 'first': None}
    done = threading.Event()
    last_index = frames - 1

    def arrived(msg):
        now = time.monotonic()
        if last['first'] is None:
            last['first'] = now
        if frame_index(msg.header.stamp, start, period) >= last_index:
            last['wall'] = now
            done.set()

    sub = rospy.Subscriber(topic, Regions, arrived, queue_size=1000)
    deadline = time.monotonic() + START_TIMEOUT
    while sub.get_num_connections() == 0:
        if time.monotonic() > deadline or rospy.is_shutdown():
            fail('no connection to %s within %g s%s' % (topic, START_TIMEOUT, node_errors(rt)))
        time.sleep(0.02)
    for old in (record, record + '.active'):
        if os.path.exists(old):
            os.remove(old)

    rt.set_parameter('bag', 'end', 0.0 if frames == count else (frames - 0.5) * period)
    began = time.monotonic()
    rt.set_parameter('bag', 'playing', True)
    pass_timeout = 120.0 + 0.5 * frames  # s: 2 frames a second at least
    while not done.wait(1.0):
        waited = time.monotonic() - began
        errors = node_errors(rt)
        if rospy.is_shutdown():
            fail('interrupted')
        if 'bag:' in errors or waited > pass_timeout:
            fail('the pass did not end (%.0f s, %s)%s' % (waited, 'timeout' if waited > pass_timeout else 'the bag does not play',
                                                       errors))
    apex_seconds = last['wall'] - began
    deadline = time.monotonic() + 30.0
    while not os.path.exists(record):  # BagWriter closes and names the file at the end of the pass
        if time.monotonic() > deadline or rospy.is_shutdown():
            fail("the graph's recording %s did not appear within 30 s of the last frame%s" % (record, node_errors(rt)))
        time.sleep(0.05)
    status = rt.status(timeout=10.0)
    errors = node_errors(rt)

    apex_boxes, tracks = {}, {}
    with rosbag.Bag(record) as bag:
        for topic, msg, _ in bag.read_messages(topics=[RECORD_TOPIC, TRACK_TOPIC]):
            frame = frame_index(msg.header.stamp, start, period)
            if topic == RECORD_TOPIC:
                apex_boxes[frame] = [(r.x, r.y, r.width, r.height) for r in msg.regions]
            else:
                for r in msg.regions:
                    tracks.setdefault(r.label, []).append((frame, (r.x, r.y, r.width, r.height)))
    for seen in tracks.values():
        seen.sort()
    ids, lengths, jumps, tracked = track_summary(tracks)

    cv_boxes, cv_calls, cv_all = run_loop(bag_path, frames, settings)

    apex_counts = [len(apex_boxes[i]) for i in range(frames) if i in apex_boxes]
    cv_counts = [len(b) for b in cv_boxes]
    same_count = sum(1 for i in range(frames) if i in apex_boxes and len(apex_boxes[i]) == len(cv_boxes[i]))
    same_boxes = sum(1 for i in range(frames) if i in apex_boxes and apex_boxes[i] == [tuple(b) for b in cv_boxes[i]])
    print('=== APEX people: %s, %d of its %d frames (%dx%d), as fast as each side goes'
          % (os.path.basename(bag_path), frames, count, size[0], size[1]))
    print('graph:  ' + describe(settings))
    print('                      APEX graph                       OpenCV in a Python loop (cv2 %s)' % cv2.__version__)
    print('detections per frame  %-32s %s' % (stats(apex_counts), stats(cv_counts)))
    print('frames per second     %-32s %.1f (the calls alone), %.1f (with reading the bag)'
          % ('%.1f (the whole graph)' % (frames / apex_seconds), frames / cv_calls, frames / cv_all))
    print('frames recorded       %d of %d' % (len(apex_boxes), frames))
    print('equal detections      counts in %d of %d frames, boxes in %d of %d' % (same_count, frames, same_boxes, frames))
    print('tracks (ids)          %d ids, the longest in %d frames (median %d); %d id jumps in %d tracked boxes'
          % (ids, lengths[0] if lengths else 0, lengths[len(lengths) // 2] if lengths else 0, jumps, tracked))
    if track:
        for i, (tid, seen) in enumerate(sorted(tracks.items(), key=lambda t: -len(t[1]))[:8]):
            print('  #%-4d in %4d frames, %d to %d' % (tid, len(seen), seen[0][0], seen[-1][0]))
    nodes = [n for n in status.nodes if n.firings > 0 and n.name != 'bag']
    print('per node (mean ms):   ' + ', '.join('%s %.2f' % (n.name, n.mean_ms) for n in nodes))
    first_diff = next((i for i in range(frames) if i not in apex_boxes or len(apex_boxes[i]) != len(cv_boxes[i])), None)
    if first_diff is not None:
        print('first difference:     frame %d: APEX %s, OpenCV %s'
              % (first_diff, apex_boxes.get(first_diff, 'not recorded'), [tuple(b) for b in cv_boxes[first_diff]]))
    jumpy = track and (not tracked or jumps * 100 > tracked)
    ok = not errors and len(apex_boxes) == frames and same_count == frames and not jumpy
    if ok:
        print('people: OK')
    elif errors:
        print('people: FAILED' + errors)
    elif jumpy:
        print('people: FAILED: %d id jumps in %d tracked boxes (at most 1 in 100)' % (jumps, tracked))
    else:
        print('people: FAILED: the detection counts differ in %d of %d frames' % (frames - same_count, frames))
    sys.stdout.flush()
    rospy.signal_shutdown('done')
    sys.exit(0 if ok else 1)


if __name__ == '__main__':
    main()
