"""The Runtime class: an APEX runtime's services as Python calls (see the package's docstring)."""
import re
import threading
import time

import rosgraph
import rospy
import yaml

from apex.msg import RuntimeStatus
from apex.srv import (AddNode, Connect, Control, FireSlot, FrameTrace, GetGraph, GetNodeProfile, Group, Inspect,
                      ListNodeTypes, LoadGraph, RemoveNode, RenameNode, SaveGraph, SetEnabled, SetInteractive,
                      SetParameter, SetThreadGroup, SetUi, Ungroup)

_SERVICES = {
    'list_node_types': ListNodeTypes, 'add_node': AddNode, 'remove_node': RemoveNode, 'connect': Connect,
    'disconnect': Connect, 'set_parameter': SetParameter, 'set_interactive': SetInteractive,
    'set_enabled': SetEnabled, 'set_thread_group': SetThreadGroup, 'set_ui': SetUi, 'fire_slot': FireSlot,
    'group': Group, 'ungroup': Ungroup, 'rename_node': RenameNode, 'get_graph': GetGraph,
    'load_graph': LoadGraph, 'save_graph': SaveGraph, 'control': Control, 'inspect': Inspect, 'trace': FrameTrace,
    'node_profile': GetNodeProfile,
}


class ApexError(Exception):
    """A service refused the call (its ``success`` was false) or could not be called.

    ``message`` is the service's own message (e.g. ``unknown node type 'Countr': did you mean
    apex_nodes/Counter? ...``), ``service`` the service's full name, ``response`` its answer (None
    when the call itself failed). ``str(error)`` is ``"<service>: <message>"``.
    """

    def __init__(self, service, message, response=None):
        super().__init__('%s: %s' % (service, message))
        self.service, self.message, self.response = service, message, response


class ApexTimeout(ApexError, TimeoutError):
    """Something awaited did not come in time: the runtime's services (no runtime under that
    namespace) or a node's status in :meth:`Runtime.wait_for_status`. Also a ``TimeoutError``."""


class _Loader(yaml.SafeLoader):
    """YAML as the runtime (yaml-cpp) writes it: ``1e-05`` is a number, not text."""


_Loader.add_implicit_resolver('tag:yaml.org,2002:float', re.compile(r'^[-+]?[0-9]+(\.[0-9]*)?[eE][-+]?[0-9]+$'),
                              list('-+0123456789'))


def encode(value):
    """A Python value as the YAML text the services take: ``5`` -> ``'5'``, ``2.0`` -> ``'2.0'``,
    ``True`` -> ``'true'``, ``'mean'`` -> ``'mean'`` (quoted where YAML would read it otherwise:
    ``'5'`` -> ``"'5'"``), ``[1, 2]`` and tuples -> ``'[1, 2]'``, dicts -> ``'{a: 1}'``."""
    def plain(v):  # tuples as lists (safe_dump has none), numpy values as Python's
        if hasattr(v, 'tolist'):
            v = v.tolist()
        if isinstance(v, (list, tuple)):
            return [plain(x) for x in v]
        return {k: plain(x) for k, x in v.items()} if isinstance(v, dict) else v
    text = yaml.safe_dump(plain(value), default_flow_style=True, width=float('inf'), allow_unicode=True,
                          sort_keys=False)
    return text[:-len('\n...\n')] if text.endswith('\n...\n') else text.rstrip('\n')


def decode(text):
    """The YAML text a service or message gives (a parameter's value) as a Python value; text that
    is not valid YAML is returned as it is."""
    try:
        return yaml.load(text, Loader=_Loader)
    except yaml.YAMLError:
        return text


def ros_node():
    """Starts an anonymous ROS node (``apex_script_...``) for subscriptions, unless the script
    has started its own with ``rospy.init_node``."""
    if not rospy.core.is_initialized():
        rospy.init_node('apex_script', anonymous=True,
                        disable_signals=threading.current_thread() is not threading.main_thread())


class Runtime:
    """One APEX runtime, reached through its services under ``namespace``.

    Each edit calls one service and returns what was applied; a refusal raises :class:`ApexError`
    with the service's message. Edits are immediate: the runtime has applied them when the method
    returns (``graph()`` shows them). Reading: :meth:`graph`, :meth:`nodes`, :meth:`parameter`, ...
    from ``~get_graph``; :meth:`status` and :meth:`wait_for_status` from the ``~status`` topic.
    """

    def __init__(self, namespace='/apex', timeout=30.0):
        """Waits up to ``timeout`` seconds (None: forever) for the runtime's services under
        ``namespace`` (the runtime node's name, ``/apex`` by default; ``/robot1/apex`` for
        ``runtime.launch ns:=robot1``). Raises :class:`ApexTimeout` naming the namespace if they do
        not appear. Service calls need no ROS node; :meth:`status` and :meth:`wait_for_status`
        start an anonymous one (``apex_script_...``) if the script has not called
        ``rospy.init_node``."""
        self.namespace = rospy.resolve_name(namespace).rstrip('/')
        self._wait_for_services(timeout)
        self._proxies = {name: rospy.ServiceProxy(self._name(name), kind) for name, kind in _SERVICES.items()}
        self._status, self._status_sub = None, None
        self._status_changed = threading.Condition()

    def __repr__(self):
        return 'apex.Runtime(%r)' % self.namespace

    def _wait_for_services(self, timeout):
        """All of them (advertised one after another), asking the master every 0.1 s."""
        master, pending = rosgraph.Master(rospy.get_caller_id()), [self._name(n) for n in _SERVICES]
        end = None if timeout is None else time.time() + timeout
        while pending:
            try:
                master.lookupService(pending[0])
                pending.pop(0)
                continue
            except rosgraph.MasterException:
                problem = 'service %s is not advertised (is apex_runtime_node running under this name, on the ' \
                          'master %s?)' % (pending[0], rosgraph.get_master_uri())
            except OSError as e:
                problem = 'no ROS master at %s (%s)' % (rosgraph.get_master_uri(), e)
            if rospy.is_shutdown() or (end is not None and time.time() >= end):
                raise ApexTimeout(self.namespace, 'no APEX runtime within %g s: %s' % (timeout or 0, problem))
            time.sleep(0.1)

    def _name(self, service):
        return self.namespace + '/' + service

    def _call(self, service, **request):
        """Calls ``service``; its answer, or ApexError with its message when it refused."""
        try:
            res = self._proxies[service](**request)
        except (rospy.ServiceException, rospy.ROSException) as e:
            raise ApexError(self._name(service), 'call failed (is the runtime still running?): %s' % e) from None
        if hasattr(res, 'success') and not res.success:
            raise ApexError(self._name(service), res.message or 'refused (no message)', res)
        return res

    # ------------------------------------------------------------------ graph edits

    def add_node(self, type, name='', params=None, thread_group=''):
        """Adds a node of ``type`` (``apex_nodes/GaussianBlur``, or ``GaussianBlur`` when only one
        package has it; a graph file such as ``package://apex/graphs/cloud_filter.yaml`` adds a
        subgraph) named ``name`` (empty: from the type; ``a/b`` adds ``b`` inside subgraph ``a``),
        with ``params`` (a dict of parameter: Python value) in ``thread_group`` (empty: default;
        a new name creates it). Returns the node's name."""
        return self._call('add_node', type=type, name=name, parameters=encode(params) if params else '',
                          thread_group=thread_group).name

    def remove_node(self, name):
        """Removes the node (or the subgraph, with all inside it) and its connections."""
        self._call('remove_node', name=name)

    def rename_node(self, name, new_name):
        """Renames a node in its place (``new_name`` is a name, not a path); its connections and
        settings follow. Returns its new path, e.g. ``camera_detector/binary``."""
        return self._call('rename_node', name=name, new_name=new_name).path

    def connect(self, from_node, from_port, to_node, to_port):
        """Connects an output (or parameter output, or trigger) to an input (or parameter, or slot)."""
        self._call('connect', from_node=from_node, from_port=from_port, to_node=to_node, to_port=to_port)

    def disconnect(self, from_node, from_port, to_node, to_port):
        """Removes the connection, as it was made by :meth:`connect`."""
        self._call('disconnect', from_node=from_node, from_port=from_port, to_node=to_node, to_port=to_port)

    def set_parameter(self, node, parameter, value):
        """Sets a parameter to a Python value (sent as YAML text, see :func:`encode`; a path is
        confined to the runtime's file roots). Returns the value applied, as Python (e.g. ``2``
        given to a double gives ``2.0``). An out-of-range or ill-typed value raises ApexError and
        leaves the old one."""
        return decode(self._call('set_parameter', node=node, parameter=parameter, value=encode(value)).value)

    def set_interactive(self, node, parameter, interactive=True):
        """Gives a parameter an input and an output port (or takes them away)."""
        self._call('set_interactive', node=node, parameter=parameter, interactive=interactive)

    def enable(self, node):
        """Enables a node (a subgraph: all of its nodes)."""
        self._call('set_enabled', node=node, enabled=True)

    def disable(self, node):
        """Disables a node (a subgraph: all of its nodes): it stops firing, its outputs pass Nothing."""
        self._call('set_enabled', node=node, enabled=False)

    def set_thread_group(self, node, group):
        """Moves a node to a thread group (created if new)."""
        self._call('set_thread_group', node=node, group=group)

    def set_ui(self, node, ui):
        """Sets a node's front-end metadata (a dict such as ``{'x': 10, 'y': 20}``)."""
        self._call('set_ui', node=node, ui=encode(ui))

    def fire_slot(self, node, slot):
        """Fires one of a node's slots (e.g. a Counter's ``reset``, a BagWriter's ``stop``)."""
        self._call('fire_slot', node=node, slot=slot)

    def group(self, nodes, name, restore=False):
        """Makes ``nodes`` (beside each other) one subgraph ``name`` in their place; connections
        crossing it become its exports. ``restore``: undo of an :meth:`ungroup` of ``name``."""
        self._call('group', nodes=list(nodes), name=name, restore=restore)

    def ungroup(self, name):
        """Dissolves a subgraph: its nodes move up beside where it was, connections stay."""
        self._call('ungroup', name=name)

    def load_graph(self, path):
        """Replaces the graph by a graph file (in the runtime's file roots; relative: in the first
        writable one). Returns the LoadGraph response: ``path`` (absolute), ``warnings`` (e.g.
        placeholders for unknown types) and ``revision``."""
        return self._call('load_graph', path=path)

    def save_graph(self, path):
        """Saves the graph to a file in the runtime's file roots (a bare name: ``$ROS_HOME/apex``).
        Returns the absolute path written."""
        return self._call('save_graph', path=path).path

    def control(self, command):
        """Sends ``pause``, ``resume``, ``step`` or ``clear``; returns whether the runtime is paused."""
        return self._call('control', command=command).paused

    def pause(self):
        """Pauses the graph (sources stop; edits still apply). Same as ``control('pause')``."""
        return self.control('pause')

    def resume(self):
        """Resumes a paused graph. Same as ``control('resume')``."""
        return self.control('resume')

    def step(self):
        """While paused: every ready source sends one frame and the graph finishes it."""
        return self.control('step')

    def clear(self):
        """Removes every node: an empty graph, as a load of an empty file."""
        return self.control('clear')

    def inspect(self, node, port, enable=True, preview=False):
        """Publishes an output (or interactive parameter) while enabled; ``preview``: at most 5
        messages a second, images scaled down. Returns ``(topic, message_type)``, e.g.
        ``('/apex/inspect/count/count', 'std_msgs/Int32')``."""
        res = self._call('inspect', node=node, port=port, enable=enable, preview=preview)
        return res.topic, res.message_type

    def trace(self, command):
        """The frame trace: ``'start'`` (each thread group keeps its last firings), ``'stop'`` or
        ``'status'``; returns whether it is on. See :meth:`save_trace`."""
        return self._call('trace', command=command).tracing

    def save_trace(self, path='', seconds=0):
        """Saves the firings traced in the last ``seconds`` (0: every one kept) as Chrome trace
        event JSON (Perfetto, chrome://tracing) to a file in the runtime's file roots (empty:
        ``trace_<date>_<time>.json`` in the first). Returns the absolute path written."""
        return self._call('trace', command='save', path=path, seconds=seconds).path

    def node_profile(self, node):
        """``node``'s histograms over the last 5-10 s (``~node_profile``): a dict with ``window_s``
        and ``time`` and ``latency``, each a list of ``(lower_ms, upper_ms, count)`` bars (the
        buckets that hold any; ``latency`` empty without live stamps); and since it was added,
        ``firings``, ``timed_firings`` and their summed ``timed_ms``."""
        res = self._call('node_profile', node=node)
        return {'window_s': res.window_s,
                'time': list(zip(res.time_lower_ms, res.time_upper_ms, res.time_counts)),
                'latency': list(zip(res.latency_lower_ms, res.latency_upper_ms, res.latency_counts)),
                'firings': res.firings, 'timed_firings': res.timed_firings, 'timed_ms': res.timed_ms}

    # ------------------------------------------------------------------ reading the graph

    def graph(self):
        """The graph as the runtime has it now: an ``apex/GraphState`` (``revision``, ``paused``,
        ``thread_groups``, ``nodes`` as ``apex/NodeInfo``, ``connections``)."""
        return self._call('get_graph').graph

    def graph_text(self):
        """The graph in the graph file format (YAML text), as :meth:`save_graph` would write it."""
        return self._call('get_graph').yaml

    def nodes(self):
        """The graph's nodes by name (paths inside subgraphs: ``detector/threshold``): a dict of
        name -> ``apex/NodeInfo`` (``type``, ``thread_group``, ``enabled``, ``state``, ``error``,
        ``ports``, ``parameters``, ...)."""
        return {n.name: n for n in self.graph().nodes}

    def node(self, name):
        """One node's ``apex/NodeInfo``; ApexError if there is no such node."""
        found = self.nodes().get(name)
        if found is None:
            raise ApexError(self._name('get_graph'), "no node '%s' in the graph" % name)
        return found

    def parameters(self, node):
        """A node's parameter values as a dict of name -> Python value."""
        return {p.name: decode(p.value) for p in self.node(node).parameters}

    def parameter(self, node, name):
        """One parameter's current value as Python; ApexError if the node has no such parameter."""
        values = self.parameters(node)
        if name not in values:
            raise ApexError(self._name('get_graph'), "node '%s' has no parameter '%s' (it has: %s)"
                            % (node, name, ', '.join(sorted(values))))
        return values[name]

    def connections(self):
        """The connections as tuples ``(from_node, from_port, to_node, to_port, kind)``, kind one
        of data, parameter, event, export."""
        return [(c.from_node, c.from_port, c.to_node, c.to_port, c.kind) for c in self.graph().connections]

    def node_types(self):
        """The node types the runtime knows: a dict of id (``apex_nodes/Clock``) ->
        ``apex/NodeTypeInfo`` (``description``, ``category``, ``ports``, ``parameters``)."""
        return {t.id: t for t in self._call('list_node_types').types}

    def load_errors(self):
        """The plugin libraries that could not be loaded, each with its file and the reason."""
        return list(self._call('list_node_types').load_errors)

    # ------------------------------------------------------------------ status (~status topic)

    def _subscribe(self):
        if self._status_sub is None:
            ros_node()
            self._status_sub = rospy.Subscriber(self._name('status'), RuntimeStatus, self._received, queue_size=1)

    def latest_status(self):
        """The newest ``apex/RuntimeStatus`` received, at once; None before the first (it starts
        listening to ``~status`` at the first call)."""
        self._subscribe()
        with self._status_changed:
            return self._status

    def _received(self, msg):
        with self._status_changed:
            self._status = msg
            self._status_changed.notify_all()

    def status(self, node=None, timeout=10.0):
        """The next ``apex/RuntimeStatus`` from ``~status`` (about 2 Hz), or with ``node`` that
        node's ``apex/NodeStatus`` (``state``, ``error``, ``firings``, ``nothing_firings``,
        ``last_ms``, ``mean_ms``, ``max_ms``, ``waiting_for``, ``idle_s``). Waits up to
        ``timeout`` seconds for it (ApexTimeout)."""
        return self.wait_for_status(node, lambda s: True, timeout) if node else self._wait(lambda m: m, timeout)

    def wait_for_status(self, node, condition, timeout=10.0):
        """Waits until ``condition(status)`` holds for ``node``'s ``apex/NodeStatus`` (e.g.
        ``lambda s: s.firings > 10``, ``lambda s: s.state == 'error'``) and returns that status.
        Only statuses received after the call count (they come ~0.5 s apart), so what an edit made just
        before changed is seen. Raises ApexTimeout after ``timeout`` seconds, with the last status seen."""
        def holds(msg):
            s = next((n for n in msg.nodes if n.name == node), None)
            return s if s is not None and condition(s) else None
        try:
            return self._wait(holds, timeout)
        except ApexTimeout:
            last = self._status and next((n for n in self._status.nodes if n.name == node), None)
            raise ApexTimeout(self._name('status'), 'node %s: condition not met within %g s; last status: %s'
                              % (node, timeout, 'none (no such node)' if last is None
                                 else ' '.join(str(last).split()))) from None

    def _wait(self, found, timeout):
        self._subscribe()
        end = time.time() + timeout
        with self._status_changed:
            seen = self._status  # judged on statuses published after the call, not an older one
            while True:
                if self._status is not None and self._status is not seen:
                    seen = self._status
                    result = found(seen)
                    if result is not None:
                        return result
                left = end - time.time()
                if left <= 0 or rospy.is_shutdown():
                    raise ApexTimeout(self._name('status'), 'no status within %g s' % timeout)
                self._status_changed.wait(min(left, 0.5))
