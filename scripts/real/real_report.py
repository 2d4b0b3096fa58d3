"""What the real-data demos' reports (scripts/real/report_*.py) share: how they fail, and which nodes
of the graph are in error (said at once, as a node in error will not deliver what a report waits for)."""
import sys

import rospy

import apex


def fail(name, why):
    """Ends the report with '<name>: FAILED: <why>' (the demo's script looks for '<name>: OK')."""
    print('%s: FAILED: %s' % (name, why), flush=True)
    rospy.signal_shutdown('failed')
    sys.exit(1)


def node_errors(rt):
    """The graph's nodes in error as '; name: error' each ('' if none), from the runtime's graph."""
    try:
        return ''.join('; %s: %s' % (name, n.error) for name, n in sorted(rt.nodes().items()) if n.state == 'error')
    except apex.ApexError as e:
        return '; (the graph could not be read: %s)' % e.message
