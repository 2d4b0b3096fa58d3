# __doc__ assigned, not a bare docstring: the devel space runs this file with exec() (catkin_python_setup)
__doc__ = """Scripting an APEX runtime from Python: its services (``/apex/add_node``, ``/apex/connect``, ...)
as the methods of :class:`Runtime`, their refusals as :class:`ApexError`.

After sourcing the devel (or install) space::

    import apex
    rt = apex.Runtime('/apex', timeout=30)        # waits for the runtime's services
    rt.add_node('apex_nodes/Clock', 'clock', params={'rate': 5.0})
    rt.add_node('Counter', 'count')               # a type without its package, when unambiguous
    rt.connect('clock', 'count', 'count', 'in')
    rt.set_parameter('clock', 'rate', 20)         # -> 20.0, the value applied
    rt.parameter('clock', 'rate')                 # -> 20.0, read back from the graph
    rt.wait_for_status('count', lambda s: s.firings > 10, timeout=10)
    try:
        rt.set_parameter('clock', 'rate', 5000)
    except apex.ApexError as e:
        print(e.message)    # node 'clock': parameter 'rate': 5000 is out of range [0.01, 1000]
    rt.save_graph('counting.yaml')                # -> '/home/you/.ros/apex/counting.yaml'

Tuning a graph with an Optuna study (what its Optimizer tunes, scored as it scores):
:class:`apex.tuning.Tuning` (``from apex.tuning import Tuning``; needs python3-optuna).

Values are Python values: they travel as the YAML text the services take (:func:`encode`), and
parameter values come back decoded (:func:`decode`). The generated messages and services stay
where they are: ``apex.msg`` (GraphState, NodeInfo, NodeStatus, ...) and ``apex.srv``.
"""
from .runtime import ApexError, ApexTimeout, Runtime, decode, encode

__all__ = ['ApexError', 'ApexTimeout', 'Runtime', 'decode', 'encode']
