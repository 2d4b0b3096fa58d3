#!/usr/bin/env python3
"""The digits demo's data and report (scripts/real/digits; launch/real_digits.launch).

opencv-doc's digits.png holds 5,000 handwritten digits of 20x20 pixels, 50 rows of 100; rows 0-4 are
zeros, 5-9 ones, and so on. The split is OpenCV's sample digits.py's: the 5,000 shuffled by
numpy.random.RandomState(321).permutation; here the first half of that order trains and the
second half is held out (digits.py itself trains on the first 90%).

    report_digits.py prepare DATA     writes DATA/train.bag and DATA/test.bag (one frame each: the
                                      whole sheet on /digits/image, and on /digits/cells an
                                      apex/Regions with a 20x20 box per digit of that half) and
                                      DATA/train_truth.yaml, DATA/test_truth.yaml (each box's digit)
    report_digits.py export           (in the launch) plays the training bag through
                                      graphs/real_digits_export.yaml once; SampleExport's count
    report_digits.py classify         (in the launch) plays the held-out bag through
                                      graphs/real_digits.yaml once (FeatureExtract -> Classifier with
                                      apex_train's SVM and MLP), then runs digits.py's own steps on
                                      the same split; prints both accuracies and confusion matrices;
                                      "digits: OK" when APEX's SVM is at most one point below
                                      OpenCV's
"""
import os
import sys
import threading
import time

import numpy as np
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # real_report.py is beside this script (also in devel)

DIGITS_PNG = '/usr/share/doc/opencv-doc/examples/data/digits.png'
SZ, CLASSES, SEED = 20, 10, 321  # digits.py's cell size, classes and shuffling seed
STAMP_NS = 1700000000 * 10**9  # the one frame's stamp (apex_make_bag's first stamp)
START_TIMEOUT, PASS_TIMEOUT = 60.0, 300.0  # s
OK_POINTS = 1.0  # percentage points APEX's SVM may be below OpenCV's digits.py


def load():
    import cv2
    sheet = cv2.imread(DIGITS_PNG, cv2.IMREAD_GRAYSCALE)
    if sheet is None:
        raise SystemExit("digits: FAILED: cannot read %s (Debian's opencv-doc)" % DIGITS_PNG)
    if sheet.shape != (50 * SZ, 100 * SZ):
        raise SystemExit('digits: FAILED: %s is %dx%d, not 2000x1000' % (DIGITS_PNG, sheet.shape[1], sheet.shape[0]))
    return sheet


def cell_box(i):
    """Digit i's box in the sheet (x, y, w, h): row-major, 100 a row."""
    return (i % 100) * SZ, (i // 100) * SZ, SZ, SZ


def digit_of(i):
    return i // 500  # digits.py: np.repeat(np.arange(10), 500)


def split():
    """digits.py's shuffle; (training half, held-out half) as indices into the sheet's 5,000."""
    order = np.random.RandomState(SEED).permutation(5000)
    return order[:2500], order[2500:]


# ---------------------------------------------------------------- prepare (no ROS master needed)

def prepare(data):
    import rosbag
    import rospy
    from apex.msg import Region, Regions
    from sensor_msgs.msg import Image
    sheet = load()
    stamp = rospy.Time(STAMP_NS // 10**9, STAMP_NS % 10**9)
    image = Image(height=sheet.shape[0], width=sheet.shape[1], encoding='mono8', is_bigendian=0, step=sheet.shape[1],
                  data=sheet.tobytes())
    image.header.stamp, image.header.frame_id = stamp, 'digits'
    os.makedirs(data, exist_ok=True)
    for name, cells in zip(('train', 'test'), split()):
        regions = Regions(width=sheet.shape[1], height=sheet.shape[0])
        regions.header = image.header
        for i in cells:
            x, y, w, h = (int(v) for v in cell_box(i))
            regions.regions.append(Region(x=x, y=y, width=w, height=h, area=float(w * h), centroid_x=x + w / 2.0,
                                          centroid_y=y + h / 2.0, label=-1, confidence=0.0))
        bag_path = os.path.join(data, name + '.bag')
        with rosbag.Bag(bag_path + '.active', 'w') as bag:
            bag.write('/digits/image', image, stamp)
            bag.write('/digits/cells', regions, stamp)
        truth = ['# %s half of digits.png (digits.py shuffle, RandomState(%d)): each box and its digit' % (name, SEED),
                 'frames:', '  - stamp: %d' % STAMP_NS,
                 '    boxes: [%s]' % ', '.join('[%d, %d, %d, %d]' % cell_box(i) for i in cells),
                 '    digits: [%s]' % ', '.join(str(digit_of(i)) for i in cells)]
        with open(os.path.join(data, name + '_truth.yaml.tmp'), 'w') as f:
            f.write('\n'.join(truth) + '\n')
        os.replace(os.path.join(data, name + '_truth.yaml.tmp'), os.path.join(data, name + '_truth.yaml'))
        os.replace(bag_path + '.active', bag_path)
    print('apex: wrote %s/train.bag and test.bag (the sheet, and 2,500 cells each) with their truth' % data)


# ---------------------------------------------------------------- OpenCV's digits.py, its steps as they are

def opencv_digits(sheet, train, test):
    """digits.py's preprocessing and SVM, on the given split: (labels predicted for `test`, seconds)."""
    import cv2
    from numpy.linalg import norm

    def deskew(img):
        m = cv2.moments(img)
        if abs(m['mu02']) < 1e-2:
            return img.copy()
        skew = m['mu11'] / m['mu02']
        M = np.float32([[1, skew, -0.5 * SZ * skew], [0, 1, 0]])
        return cv2.warpAffine(img, M, (SZ, SZ), flags=cv2.WARP_INVERSE_MAP | cv2.INTER_LINEAR)

    def preprocess_hog(digits):
        samples = []
        for img in digits:
            gx = cv2.Sobel(img, cv2.CV_32F, 1, 0)
            gy = cv2.Sobel(img, cv2.CV_32F, 0, 1)
            mag, ang = cv2.cartToPolar(gx, gy)
            bin_n = 16
            bins = np.int32(bin_n * ang / (2 * np.pi))
            bin_cells = bins[:10, :10], bins[10:, :10], bins[:10, 10:], bins[10:, 10:]
            mag_cells = mag[:10, :10], mag[10:, :10], mag[:10, 10:], mag[10:, 10:]
            hists = [np.bincount(b.ravel(), m.ravel(), bin_n) for b, m in zip(bin_cells, mag_cells)]
            hist = np.hstack(hists)
            eps = 1e-7  # transform to Hellinger kernel
            hist /= hist.sum() + eps
            hist = np.sqrt(hist)
            hist /= norm(hist) + eps
            samples.append(hist)
        return np.float32(samples)

    began = time.perf_counter()
    cells = [sheet[y:y + h, x:x + w] for x, y, w, h in (cell_box(i) for i in range(5000))]
    samples = preprocess_hog([deskew(c) for c in cells])
    labels = np.array([digit_of(i) for i in range(5000)], np.int32)
    model = cv2.ml.SVM_create()  # digits.py's SVM(C=2.67, gamma=5.383)
    model.setGamma(5.383)
    model.setC(2.67)
    model.setKernel(cv2.ml.SVM_RBF)
    model.setType(cv2.ml.SVM_C_SVC)
    model.train(samples[train], cv2.ml.ROW_SAMPLE, labels[train])
    predicted = model.predict(samples[test])[1].ravel().astype(int)
    return predicted, time.perf_counter() - began


def confusion(truth, predicted):
    m = np.zeros((CLASSES, CLASSES + 1), int)  # the last column: rejected or unknown labels
    for t, p in zip(truth, predicted):
        m[t, p if 0 <= p < CLASSES else CLASSES] += 1
    return m


def print_matrices(titled):
    """Confusion matrices side by side: a row per true digit, a column per label."""
    width = 4 * CLASSES + 5
    print('confusion matrices (a row per true digit, a column per label; ?: none):')
    print('      ' + ' | '.join(title.ljust(width) for title, _ in titled))
    print('true  ' + ' | '.join((''.join('%4d' % c for c in range(CLASSES)) + '    ?').ljust(width) for _ in titled))
    for t in range(CLASSES):
        print('%4d  ' % t + ' | '.join((''.join('%4d' % v for v in m[t, :CLASSES]) + '%5d' % m[t, CLASSES]).ljust(width)
                                       for _, m in titled))


# ---------------------------------------------------------------- the launch's report

def read_svm(path):
    """(C, gamma) of an SVM model file apex_train wrote (OpenCV's YAML)."""
    import cv2
    fs = cv2.FileStorage(path, cv2.FILE_STORAGE_READ)
    node = fs.getNode('opencv_ml_svm')
    values = node.getNode('C').real(), node.getNode('kernel').getNode('gamma').real()
    fs.release()
    return values


def hog_text(p):
    return '%dx%d cells x %d bins' % (p['cells'], p['cells'], p['bins'])


def fail(why):
    import real_report  # (beside this script; its ROS imports only where a graph runs)
    real_report.fail('digits', why)


def node_errors(rt):
    import real_report
    return real_report.node_errors(rt)


class Outputs:
    """The first message of each inspected output: each comes once, at the end of the pass."""

    def __init__(self, rt, wanted):
        import rospy
        self.values, self.changed = {}, threading.Condition()
        self.subs = []
        for node, port, kind in wanted:
            topic, _ = rt.inspect(node, port)
            self.subs.append(rospy.Subscriber(topic, kind, self.keep, callback_args='%s/%s' % (node, port), queue_size=10))
        deadline = time.monotonic() + START_TIMEOUT
        while any(s.get_num_connections() == 0 for s in self.subs):
            if time.monotonic() > deadline or rospy.is_shutdown():
                fail('the inspect topics did not connect within %g s%s' % (START_TIMEOUT, node_errors(rt)))
            time.sleep(0.02)

    def keep(self, msg, key):
        with self.changed:
            self.values.setdefault(key, msg)
            self.changed.notify_all()

    def wait(self, rt, began):
        import rospy
        with self.changed:
            while len(self.values) < len(self.subs):
                self.changed.wait(1.0)
                waited = time.monotonic() - began
                if rospy.is_shutdown():
                    fail('interrupted')
                errors = node_errors(rt) if len(self.values) < len(self.subs) else ''
                if 'bag:' in errors or waited > PASS_TIMEOUT:
                    fail('the pass did not end (%.0f s, %s)%s; outputs seen: %s'
                         % (waited, 'timeout' if waited > PASS_TIMEOUT else 'the bag does not play', errors,
                            ', '.join(sorted(self.values)) or 'none'))
        return self.values


def report(mode):
    import rospy
    from std_msgs.msg import Float64, Int32

    import apex
    from apex.msg import Regions
    rospy.init_node('report_digits')
    try:
        rt = apex.Runtime('/apex', timeout=START_TIMEOUT)
    except apex.ApexError as e:
        fail(e.message)
    if mode == 'export':
        outputs = Outputs(rt, [('export', 'samples', Int32)])
        began = time.monotonic()
        rt.set_parameter('bag', 'playing', True)  # only now: nothing is sent before we listen
        samples = outputs.wait(rt, began)['export/samples'].data
        errors = node_errors(rt)
        print('exported: %d labelled samples in %s (%.1f s)'
              % (samples, rt.parameter('export', 'directory'), time.monotonic() - began))
        ok = not errors and samples == 2500
        print('export: ' + ('OK' if ok else 'FAILED' + (errors or ': expected 2500 samples')))
        sys.stdout.flush()
        rospy.signal_shutdown('done')
        sys.exit(0 if ok else 1)

    wanted = [('svm', 'regions', Regions), ('mlp', 'regions', Regions), ('svm_2x2', 'regions', Regions),
              ('svm_score', 'accuracy', Float64), ('mlp_score', 'accuracy', Float64)]
    outputs = Outputs(rt, wanted)
    began = time.monotonic()
    rt.set_parameter('bag', 'playing', True)
    got = outputs.wait(rt, began)
    graph_seconds = time.monotonic() - began
    status = rt.status(timeout=10.0)
    errors = node_errors(rt)

    train, test = split()
    truth_of = {tuple(int(v) for v in cell_box(i)[:2]): digit_of(i) for i in test}
    apex_results = {}
    for model in ('svm', 'mlp', 'svm_2x2'):
        regions = got[model + '/regions'].regions
        if len(regions) != len(test):
            fail('%s labelled %d regions, not the %d held-out digits%s' % (model, len(regions), len(test), errors))
        truth = [truth_of[(r.x, r.y)] for r in regions]
        labels = [r.label for r in regions]
        apex_results[model] = (np.mean(np.array(truth) == np.array(labels)), confusion(truth, labels))
    for model in ('svm', 'mlp'):  # the graph's own scoring (DigitScore against the truth file) must agree
        scored = got[model + '_score/accuracy'].data
        if abs(scored - apex_results[model][0]) > 1e-9:
            fail("%s: DigitScore's accuracy %.4f differs from the labels' %.4f" % (model, scored, apex_results[model][0]))

    import cv2
    sheet = load()
    opencv_labels, opencv_seconds = opencv_digits(sheet, train, test)
    opencv_truth = [digit_of(i) for i in test]
    opencv_accuracy = np.mean(np.array(opencv_truth) == opencv_labels)
    order = np.random.RandomState(SEED).permutation(5000)  # digits.py exactly: 90% to train, 10% held out
    own_labels, _ = opencv_digits(sheet, order[:4500], order[4500:])
    own_accuracy = np.mean(np.array([digit_of(i) for i in order[4500:]]) == own_labels)

    nodes = {n.name: n for n in status.nodes}
    features, layout = rt.parameters('features'), rt.parameters('features_2x2')
    svm, svm_2x2 = read_svm(rt.parameter('svm', 'model')), read_svm(rt.parameter('svm_2x2', 'model'))
    print('=== APEX digits: digits.png (opencv-doc), 5,000 digits of 20x20, shuffled as digits.py shuffles '
          '(RandomState(%d)); the first 2,500 train, the other 2,500 are held out' % SEED)
    print('APEX:   SampleExport -> apex_train -> FeatureExtract (cv::HOGDescriptor, L2-Hys, of the deskewed digit) -> '
          'Classifier')
    print('OpenCV: digits.py\'s own steps in cv2 %s: deskew, its HOG (2x2 cells x 16 bins, hard-binned, Hellinger), '
          'SVM' % cv2.__version__)
    rows = [('APEX    SVM (RBF, C %g, gamma %g), HOG %s' % (svm[0], svm[1], hog_text(features)), apex_results['svm'][0],
             '(DigitScore in the graph: %.4f)' % got['svm_score/accuracy'].data),
            ("APEX    MLP (apex_train's), HOG %s" % hog_text(features), apex_results['mlp'][0],
             '(DigitScore in the graph: %.4f)' % got['mlp_score/accuracy'].data),
            ("APEX    SVM (RBF, C %g, gamma %g), HOG %s: digits.py's layout" % (svm_2x2[0], svm_2x2[1], hog_text(layout)),
             apex_results['svm_2x2'][0], ''),
            ("OpenCV  digits.py: SVM (RBF, C 2.67, gamma 5.383), its own HOG 2x2 cells x 16 bins", opencv_accuracy, ''),
            ("OpenCV  digits.py on its own split (4,500 to train, 500 held out)", own_accuracy, '(for reference)')]
    print('accuracy on the 2,500 held-out digits:')
    for text, accuracy, note in rows:
        print(('  %-82s %.4f  %s' % (text, accuracy, note)).rstrip())
    print_matrices([('APEX SVM', apex_results['svm'][1]), ('APEX MLP', apex_results['mlp'][1]),
                    ('OpenCV digits.py', confusion(opencv_truth, opencv_labels))])
    times = ', '.join('%s %.0f ms' % (name, nodes[name].mean_ms) for name in ('features', 'svm', 'mlp', 'features_2x2', 'svm_2x2')
                      if name in nodes)
    print('time:   the graph\'s pass %.1f s (%s); digits.py\'s steps %.1f s (features of all 5,000, training, labelling)'
          % (graph_seconds, times, opencv_seconds))
    gap = 100 * (apex_results['svm'][0] - opencv_accuracy)
    ok = not errors and gap >= -OK_POINTS
    if ok:
        print('digits: OK (APEX\'s SVM %+.2f points against OpenCV\'s digits.py)' % gap)
    elif errors:
        print('digits: FAILED' + errors)
    else:
        print('digits: FAILED: APEX\'s SVM is %.2f points below OpenCV\'s digits.py (at most %g allowed)' % (-gap, OK_POINTS))
    sys.stdout.flush()
    rospy.signal_shutdown('done')
    sys.exit(0 if ok else 1)


def main():
    import rospy
    args = rospy.myargv(sys.argv)[1:]
    if len(args) == 2 and args[0] == 'prepare':
        prepare(args[1])
    elif len(args) == 1 and args[0] in ('export', 'classify'):
        report(args[0])
    else:
        print(__doc__)
        sys.exit(2)


if __name__ == '__main__':
    main()
