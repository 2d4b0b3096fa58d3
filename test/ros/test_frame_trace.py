#!/usr/bin/env python3
"""The frame trace on the demo graph (frame_trace.test): started, saved and stopped through ~trace
as the panel and apex.Runtime do; the file is Chrome trace event JSON (checked field by field
against the format Perfetto and chrome://tracing read), with a track per thread group and each
frame's firings linked by a flow across groups."""
import collections
import json
import os
import unittest

import rospy
import rostest

import apex

PHASES_WITH_TS = set('BEXiIbnesftPCNOD')
FLOW = set('stf')


def check_trace_events(trace):
    """The trace event format (Chrome's "Trace Event Format" document): every problem, in words."""
    problems = []
    if not isinstance(trace, dict) or not isinstance(trace.get('traceEvents'), list):
        return ['not an object with a traceEvents list']
    if trace.get('displayTimeUnit', 'ms') not in ('ms', 'ns'):
        problems.append('displayTimeUnit %r' % trace['displayTimeUnit'])
    for k, e in enumerate(trace['traceEvents']):
        def bad(what):
            problems.append('event %d (%s): %s' % (k, json.dumps(e)[:120], what))
        if not isinstance(e, dict):
            bad('not an object')
            continue
        ph = e.get('ph')
        if not isinstance(ph, str) or len(ph) != 1:
            bad('no one-letter ph')
            continue
        if not isinstance(e.get('name'), str):
            bad('no name')
        for key in ('pid', 'tid'):
            if not isinstance(e.get(key), int):
                bad('%s is not an integer' % key)
        if 'args' in e and not isinstance(e['args'], dict):
            bad('args is not an object')
        if 'cat' in e and not isinstance(e['cat'], str):
            bad('cat is not a string')
        if ph in PHASES_WITH_TS and not isinstance(e.get('ts'), (int, float)):
            bad('ts is not a number')
        if ph == 'X' and not (isinstance(e.get('dur'), (int, float)) and e['dur'] >= 0):
            bad('a complete event without a duration >= 0')
        if ph in FLOW:
            if not isinstance(e.get('id'), (int, str)) or not isinstance(e.get('cat'), str):
                bad('a flow event without id and cat')
            if 'bp' in e and e['bp'] != 'e':
                bad('bp %r' % e['bp'])
        if ph == 'M':
            if e['name'] not in ('process_name', 'thread_name', 'process_sort_index', 'thread_sort_index', 'process_labels'):
                bad('unknown metadata %r' % e['name'])
            elif e['name'].endswith('_name') and not isinstance(e.get('args', {}).get('name'), str):
                bad('a name record without args.name')
        if ph not in PHASES_WITH_TS | set('M'):
            bad('unknown phase %r' % ph)
    flows = collections.defaultdict(list)
    for e in trace['traceEvents']:
        if isinstance(e, dict) and e.get('ph') in FLOW:
            flows[(e.get('cat'), e.get('id'))].append(e['ph'])
    for key, phases in flows.items():
        if phases[0] != 's' or phases[-1] != 'f' or phases.count('s') != 1 or phases.count('f') != 1:
            problems.append('flow %s: phases %s, not s t* f' % (key, ''.join(phases)))
    return problems


def enclosing(slices, flow_event):
    """The one complete event on the flow event's track that holds its time (where Perfetto binds it)."""
    found = [s for s in slices[flow_event['tid']] if s['ts'] < flow_event['ts'] < s['ts'] + s['dur']]
    return found[0] if len(found) == 1 else None


class FrameTrace(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.rt = apex.Runtime('/apex', timeout=60)
        # a bare file name goes to the runtime's first writable file root, $ROS_HOME/apex
        cls.folder = os.path.join(os.environ.get('ROS_HOME', os.path.expanduser('~/.ros')), 'apex')

    def test_a_before_any_start_saving_is_refused_and_the_trace_is_off(self):
        self.assertFalse(self.rt.trace('status'))
        with self.assertRaises(apex.ApexError) as error:
            self.rt.save_trace('nothing.json')
        self.assertIn('nothing traced: start the trace first', error.exception.message)
        self.assertFalse(os.path.exists(os.path.join(self.folder, 'nothing.json')))
        with self.assertRaises(apex.ApexError) as error:
            self.rt.trace('begin')
        self.assertIn("unknown command 'begin': start, stop, save or status", error.exception.message)

    def test_b_a_trace_of_the_demo_opens_as_chrome_trace_json_with_frames_linked_across_groups(self):
        self.assertTrue(self.rt.trace('start'))
        self.assertTrue(self.rt.wait_for_status('overlay_out', lambda s: s.firings > 0, timeout=60))
        started = self.rt.status('overlay_out').firings
        self.rt.wait_for_status('overlay_out', lambda s: s.firings >= started + 10, timeout=60)
        with self.assertRaises(apex.ApexError) as error:  # outside the runtime's file roots
            self.rt.save_trace('/proc/trace.json')
        self.assertIn('/proc/trace.json', error.exception.message)
        path = self.rt.save_trace('demo_trace.json')
        self.assertEqual(path, os.path.join(self.folder, 'demo_trace.json'))
        with open(path) as f:
            trace = json.load(f)
        self.assertEqual(check_trace_events(trace), [])

        events = trace['traceEvents']
        tracks = {e['tid']: e['args']['name'] for e in events if e['ph'] == 'M' and e['name'] == 'thread_name'}
        self.assertEqual(sorted(tracks.values()),
                         ['thread group cloud', 'thread group default', 'thread group vision'])
        slices = collections.defaultdict(list)
        for e in events:
            if e['ph'] == 'X':
                slices[e['tid']].append(e)
        names = {tracks[tid]: {s['name'] for s in s_list} for tid, s_list in slices.items()}
        self.assertIn('bag', names['thread group default'])
        self.assertIn('overlay_out', names['thread group vision'])
        self.assertIn('cloud_out', names['thread group cloud'])

        # Each flow binds to firings of one frame; the frames reach both groups from the bag.
        flows = collections.defaultdict(list)
        for e in events:
            if e['ph'] in FLOW:
                flows[e['id']].append(e)
        self.assertGreater(len(flows), 5)
        linked, starts = set(), []
        for steps in sorted(flows.values(), key=lambda steps: steps[0]['ts']):
            bound = [enclosing(slices, e) for e in steps]
            self.assertNotIn(None, bound, 'a flow step outside every firing: %s' % steps)
            self.assertEqual({s['args']['frame'] for s in bound}, {steps[0]['args']['frame']})
            starts.append(bound[0]['name'])
            if {s['name'] for s in bound} >= {'bag', 'overlay_out', 'cloud_out'}:  # both chains, one frame
                linked |= {tracks[e['tid']] for e in steps}
        # a frame starts at the source (but those in flight when the trace began: one on a quiet machine)
        self.assertEqual(set(starts[3:]), {'bag'}, starts)
        self.assertEqual(linked, {'thread group cloud', 'thread group default', 'thread group vision'})

        # Stopped, what was kept can still be saved, and the graph runs on
        self.assertFalse(self.rt.trace('stop'))
        again = self.rt.save_trace('demo_trace_stopped.json')
        with open(again) as f:
            self.assertEqual(check_trace_events(json.load(f)), [])
        self.rt.wait_for_status('overlay_out', lambda s: s.firings >= started + 20, timeout=60)


if __name__ == '__main__':
    rospy.init_node('test_frame_trace', anonymous=True)
    rostest.rosrun('apex', 'frame_trace', FrameTrace)
