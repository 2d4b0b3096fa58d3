#!/usr/bin/env python3
"""The displays a running rviz has, as rviz itself saves them, and whether rviz receives their topics;
for test/panel/rviz_show_check.sh.

  rviz_displays.py add-markers NS                 adds to the demo graph at NS (graphs/demo.yaml) a
        port that rviz shows as markers: EuclideanClustering 'clusters' and ClusterFeatures 'features'
        after cloud_filter (features/features inspects as visualization_msgs/MarkerArray)
  rviz_displays.py wait SAVE NAME=CLASS ... [--timeout S]
        waits until rviz's config (saved through its ~save_config service into SAVE) has each display
        NAME, of CLASS, enabled, with a topic property (Topic, Image Topic, Marker Topic) set, and
        rviz's node has received messages on each of these topics (its bus stats: the count of
        messages its subscriptions took in). Prints each display's class, topic and count.
  rviz_displays.py gone SAVE NAME ...             fails if rviz's config has a display named NAME
  rviz_displays.py remove NS NODE ...             removes each node from the runtime at NS

rviz's SendFilePath service has no Python module on Debian: its request and response are built here
from the .srv's text, and its MD5 is the wildcard roscpp accepts.
"""
import argparse
import os
import sys
import threading
import time
import xmlrpc.client

import rosgraph
import rospy
import yaml
from genpy.dynamic import generate_dynamic

CALLER = "/rviz_displays_check"


def send_file_path_class():
    req_text = "std_msgs/String path\n" + "=" * 80 + "\nMSG: std_msgs/String\nstring data\n"
    req = generate_dynamic("rviz/SendFilePathRequest", req_text)["rviz/SendFilePathRequest"]
    resp = generate_dynamic("rviz/SendFilePathResponse", "bool success\n")["rviz/SendFilePathResponse"]
    return type("SendFilePath", (), {"_type": "rviz/SendFilePath", "_md5sum": "*",
                                     "_request_class": req, "_response_class": resp})


class Rviz:
    """The running rviz: found by its ~save_config service (rviz names its node anonymously)."""

    def __init__(self):
        self.master = rosgraph.Master(CALLER)
        self.service = self.node = None
        self.srv_class = send_file_path_class()

    def find(self):
        if self.service:
            return True
        _, _, services = self.master.getSystemState()
        for name, providers in services:
            if name.endswith("/save_config") and providers and providers[0].startswith("/rviz"):
                self.service, self.node = name, providers[0]
                return True
        return False

    def displays(self, save_path):
        """Every display in rviz's config now, groups flattened: name -> its saved settings."""
        proxy = rospy.ServiceProxy(self.service, self.srv_class)
        req = self.srv_class._request_class()
        req.path.data = save_path
        if not proxy(req).success:
            raise RuntimeError("rviz's %s did not save %s" % (self.service, save_path))
        with open(save_path) as f:
            config = yaml.safe_load(f)
        out = {}

        def walk(displays):
            for d in displays or []:
                out[d.get("Name", "")] = d
                walk(d.get("Displays"))
        walk(config.get("Visualization Manager", {}).get("Displays"))
        return out

    def received(self):
        """topic -> messages rviz's node has received on it, over every connection."""
        uri = self.master.lookupNode(self.node)
        answer = xmlrpc.client.ServerProxy(uri).getBusStats(CALLER)
        # the API's [code, message, stats]; roscpp answers with the stats alone
        if len(answer) == 3 and isinstance(answer[0], int):
            if answer[0] != 1:
                raise RuntimeError("%s's getBusStats failed: %s" % (self.node, answer[1]))
            answer = answer[2]
        # stats: [published, subscribed, ...]; subscribed: [topic, [[connection id, bytes, messages,
        # drops, connected], ...]] each
        return {s[0]: sum(c[2] for c in s[1]) for s in answer[1]}


def topic_of(display):
    """The display's topic: its property named ..."Topic" (rviz/Image: "Image Topic")."""
    topics = [v for k, v in display.items() if k.endswith("Topic") and isinstance(v, str) and v]
    return topics[0] if topics else ""


def problems(rviz, save_path, wanted):
    """What is not yet as wanted (name -> class), and a line per display found."""
    displays, received = rviz.displays(save_path), rviz.received()
    missing, lines = [], []
    for name, cls in wanted.items():
        d = displays.get(name)
        if d is None:
            missing.append("no display '%s' in rviz (it has: %s)" % (name, ", ".join(sorted(displays)) or "none"))
            continue
        topic = topic_of(d)
        count = received.get(topic, 0)
        lines.append("'%s' %s on %s, enabled %s, %d messages received" % (name, d.get("Class"), topic or "no topic",
                                                                          d.get("Enabled"), count))
        if d.get("Class") != cls:
            missing.append("'%s' is a %s, not a %s" % (name, d.get("Class"), cls))
        elif not topic:
            missing.append("'%s' has no topic" % name)
        elif d.get("Enabled") is not True:
            missing.append("'%s' is disabled" % name)
        elif count == 0:
            missing.append("rviz received nothing on %s ('%s')" % (topic, name))
    return missing, lines


class Changes:
    """Something that can change what rviz has: a line rviz logs (the panel making a display) or a
    message on a display's topic (rviz receiving it). wait_for() returns at the next one."""

    def __init__(self, topics):
        rospy.init_node("rviz_displays_check", anonymous=True, disable_signals=True)
        self.cond, self.count = threading.Condition(), 0
        self.subs = [rospy.Subscriber(t, rospy.AnyMsg, self.seen, queue_size=1) for t in ["/rosout"] + topics]

    def seen(self, _):
        with self.cond:
            self.count += 1
            self.cond.notify_all()

    def wait_for(self, since, timeout):
        with self.cond:
            self.cond.wait_for(lambda: self.count != since, timeout=max(timeout, 0))
            return self.count


def wait(save_path, wanted, timeout):
    rviz, end = Rviz(), time.monotonic() + timeout
    # a display named "apex: node/port" shows the runtime's /apex/inspect/node/port
    changes = Changes(["/apex/inspect/" + name.split(": ", 1)[-1] for name in wanted])
    missing, lines, seen = ["rviz has no save_config service"], [], 0
    while time.monotonic() < end:
        if rviz.find():
            missing, lines = problems(rviz, save_path, wanted)
            if not missing:
                break
        seen = changes.wait_for(seen, end - time.monotonic())
    for line in lines:
        print("rviz: " + line)
    for m in missing:
        print("rviz displays: " + m)
    return not missing


def add_markers(ns):
    from apex.srv import AddNode, Connect  # the devel space's
    rospy.wait_for_service(ns + "/add_node", timeout=30)
    add, connect = rospy.ServiceProxy(ns + "/add_node", AddNode), rospy.ServiceProxy(ns + "/connect", Connect)
    for name, kind in (("clusters", "apex_nodes/EuclideanClustering"), ("features", "apex_nodes/ClusterFeatures")):
        r = add(type=kind, name=name, parameters="", thread_group="cloud")
        if not r.success:
            raise SystemExit("add_node %s (%s): %s" % (name, kind, r.message))
    for a, b in (("cloud_filter/cloud", "clusters/cloud"), ("clusters/clusters", "features/clusters")):
        (fn, fp), (tn, tp) = a.split("/"), b.split("/")
        r = connect(from_node=fn, from_port=fp, to_node=tn, to_port=tp)
        if not r.success:
            raise SystemExit("connect %s -> %s: %s" % (a, b, r.message))


def remove(ns, nodes):
    from apex.srv import RemoveNode
    proxy = rospy.ServiceProxy(ns + "/remove_node", RemoveNode)
    for n in nodes:
        r = proxy(name=n)
        if not r.success:
            raise SystemExit("remove_node %s: %s" % (n, r.message))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="cmd", required=True)
    sub.add_parser("add-markers").add_argument("ns")
    w = sub.add_parser("wait")
    w.add_argument("save")
    w.add_argument("displays", nargs="+", help="NAME=CLASS")
    w.add_argument("--timeout", type=float, default=30)
    g = sub.add_parser("gone")
    g.add_argument("save")
    g.add_argument("names", nargs="+")
    r = sub.add_parser("remove")
    r.add_argument("ns")
    r.add_argument("nodes", nargs="+")
    a = p.parse_args()

    if a.cmd == "add-markers":
        add_markers(a.ns)
    elif a.cmd == "wait":
        wanted = dict(d.rsplit("=", 1) for d in a.displays)
        sys.exit(0 if wait(os.path.abspath(a.save), wanted, a.timeout) else 1)
    elif a.cmd == "gone":
        rviz = Rviz()
        if not rviz.find():
            raise SystemExit("rviz has no save_config service")
        left = sorted(set(a.names) & set(rviz.displays(os.path.abspath(a.save))))
        if left:
            raise SystemExit("rviz still has " + ", ".join("'%s'" % n for n in left))
    elif a.cmd == "remove":
        remove(a.ns, a.nodes)


if __name__ == "__main__":
    main()
