#!/usr/bin/env python3
"""The examples of the README and the docs/ pages, run as written (scripts/test): a user copies them,
so they must work.

The pages are read in the order given (a page given twice counts once, at its first place), and
their blocks run in that order, in one working folder: a `file` block serves the sessions after
it, on its own page or a later one.

A block right after `<!-- check: session -->` is a shell session. Each `$ command` runs in
order, in bash, in a working folder of the user's; one that ends in `&` starts in the background
(a launch: the next command waits until every runtime it started answers `get_graph`, as a person
waits for a launch to come up). The lines shown after a command are what it prints:
`success:`, `message:`, `value:` and `path:` lines exactly (/home/you is the user's home), other
`key: value` lines by their key, `...` for anything, any other line as a part of the output. A command exits 0 unless what it shows
says "error". At the block's end, what it started is stopped (SIGINT, as Ctrl-C).

A block right after `<!-- check: file NAME -->` is a file the user writes: it is saved as NAME in
the working folder, for the sessions after it (e.g. a Python script they then run).

A block right after `<!-- check: each -->` holds launch lines (roslaunch, rosrun) that are each
started alone; each must bring up a runtime that answers `get_graph`, and is then stopped.
`source` lines are left out (this check runs in the sourced devel space). A nodelet manager named
camera_manager runs for these lines, and an X server (Xvfb) for those that start rviz.

Every relative link of the pages (an image too) must name a file that exists, and a `#anchor`
a heading of the page it links to (as GitHub makes anchors): the case `links`.

The user's files: HOME is a fresh folder whose ~/data holds demo.bag (the generated demo bag),
train.bag and test.bag with their truth files (train_truth.yaml, test_truth.yaml); the working
folder ($PWD) holds my_graph.yaml (a small graph) and run3.bag (the demo bag).

    readme_check.py README.md [PAGE.md ...] RESULT_XML WORK_DIR    (with the devel space sourced)

A case is named after its page and the heading it is under (`ros.Recording_BagWriter`), or its file
(`ros.counting.py`).
"""
import os
import re
import shutil
import signal
import subprocess
import sys
import time
import xmlrpc.client

import yaml
from xml.sax.saxutils import escape, quoteattr

EXACT_KEYS = ("success", "message", "value", "path")
MY_GRAPH = """apex_graph: 2
nodes:
  - {name: clock, type: apex_nodes/Clock, parameters: {rate: 5}}
  - {name: count, type: apex_nodes/Counter}
connections:
  - {from: clock/count, to: count/in}
"""


def blocks(text, page):
    """(kind, name, file, first line number, [lines]) of every block of a page marked
    `<!-- check: kind -->`; the name is the page's, then the section's heading, numbered from its
    second block on, or the file's NAME; file is a `file` block's NAME (else None)."""
    lines = text.split("\n")
    out = []
    heading, seen, fenced = "", {}, False
    for i, line in enumerate(lines):
        fenced = fenced != line.strip().startswith("```")
        if line.startswith("#") and not fenced:
            heading = re.sub(r"[^A-Za-z0-9]+", "_", line.lstrip("#").strip()).strip("_")
        m = re.match(r"\s*<!-- check: (\w+)(?: (?!--)([\w.-]+))?", line)
        if not m:
            continue
        seen[heading] = seen.get(heading, 0) + 1
        name = (heading or "top") + ("" if seen[heading] == 1 else "_%d" % seen[heading])
        j = i + 1
        while j < len(lines) and not lines[j].strip():
            j += 1
        body = []
        if j == len(lines):
            raise SystemExit("%s line %d: a check marker with no block after it" % (page, i + 1))
        if lines[j].strip().startswith("```"):
            j += 1
            while j < len(lines) and not lines[j].strip().startswith("```"):
                body.append(lines[j])
                j += 1
        else:
            indent = len(lines[j]) - len(lines[j].lstrip())
            while j < len(lines) and (not lines[j].strip() or len(lines[j]) - len(lines[j].lstrip()) >= indent):
                body.append(lines[j][indent:])
                j += 1
        stem = os.path.splitext(os.path.basename(page))[0]
        out.append((m.group(1), "%s.%s" % (stem, m.group(2) or name), m.group(2), j + 1 - len(body),
                    [b.rstrip() for b in body]))
    return out


def anchor(heading):
    """The anchor GitHub gives a heading's text (without its numbering of repeats)."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading.strip()).lower()
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def anchors(path):
    """Every anchor of a markdown file's headings."""
    found, seen, fenced = set(), {}, False
    with open(path) as f:
        for line in f:
            if line.strip().startswith("```"):
                fenced = not fenced
            m = None if fenced else re.match(r"#{1,6} (.*)", line)
            if m:
                a = anchor(m.group(1))
                found.add(a if a not in seen else "%s-%d" % (a, seen[a]))
                seen[a] = seen.get(a, 0) + 1
    return found


def bad_links(pages):
    """Every relative link of the pages that names no file, or no heading of its page ([] if none)."""
    out = []
    for page in pages:
        fenced = False
        with open(page) as f:
            lines = f.read().split("\n")
        for n, line in enumerate(lines, 1):
            if line.strip().startswith("```"):
                fenced = not fenced
            if fenced:
                continue
            for target in re.findall(r"\]\(([^)\s]+)\)", re.sub(r"`[^`]*`", "", line)):
                if re.match(r"[a-z]+:", target):
                    continue
                path, _, part = target.partition("#")
                where = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
                if not os.path.exists(where):
                    out.append("%s line %d: %s: no file %s" % (page, n, target, where))
                elif part and where.endswith(".md") and part not in anchors(where):
                    out.append("%s line %d: %s: no heading of %s has the anchor #%s" % (page, n, target, where, part))
    return out


def commands(body):
    """[(command, [expected output lines])] of a session block."""
    out = []
    for line in body:
        if line.startswith("$ "):
            out.append((line[2:].strip(), []))
        elif line.strip() and not line.lstrip().startswith("#") and out:
            out[-1][1].append(line.strip())
    return out


def without_comment(command):
    """The command without a trailing `# comment` (outside quotes)."""
    quote = None
    for i, c in enumerate(command):
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c == "#" and (i == 0 or command[i - 1].isspace()):
            return command[:i].rstrip()
    return command


def answer(output):
    """The first YAML mapping a command printed (rosservice's answer, folded lines joined), or None."""
    try:
        for doc in yaml.safe_load_all(output):
            if isinstance(doc, dict):
                return doc
    except yaml.YAMLError:
        pass
    return None


def like(expected, actual):
    """Whether `actual` is `expected`, where `...` in a text stands for anything."""
    if isinstance(expected, str) and "..." in expected:
        pattern = ".*".join(re.escape(part) for part in expected.split("..."))
        return re.fullmatch(pattern, str(actual), re.S) is not None
    return expected == actual


def matches(expected, output):
    """Why `output` does not show `expected` ('' if it does)."""
    m = re.match(r"([a-z_]+): (.*)", expected)
    fields = answer(output) if m else None
    if m and fields is not None:
        key = m.group(1)
        value = m.group(2) if "..." in m.group(2) else yaml.safe_load(m.group(2))  # (YAML reads ... as its end)
        if isinstance(value, str) and len(value) > 1 and value[0] == value[-1] and value[0] in "'\"":
            value = value[1:-1]
        if key not in fields:
            return "no %r" % key
        if key in EXACT_KEYS and not like(value, fields[key]):
            return "%s is %r, not %r" % (key, fields[key], value)
        return ""
    lines = [l.strip() for l in output.split("\n")]
    if any(like(expected, l) for l in lines) or ("..." not in expected and expected in output):
        return ""
    return "%r not shown" % expected


class Session:
    """Processes a block started, stopped together at its end."""

    def __init__(self, env, cwd):
        self.env, self.cwd, self.started = env, cwd, []

    def services(self):
        """The get_graph services the master knows (asked over XML-RPC: `rosservice list` is a
        Python start-up, ~0.5 s of a core, each poll)."""
        try:
            master = xmlrpc.client.ServerProxy(self.env["ROS_MASTER_URI"])
            code, _, state = master.getSystemState("/readme_check")
        except (OSError, xmlrpc.client.Error):
            return set()
        return set(name for name, _ in state[2] if name.endswith("apex/get_graph")) if code == 1 else set()

    def start(self, command, log):
        before = self.services()
        p = subprocess.Popen(["bash", "-c", "exec " + command], cwd=self.cwd, env=self.env, stdout=log,
                             stderr=subprocess.STDOUT, start_new_session=True)
        self.started.append(p)
        return before, p

    def wait_runtime(self, before, p, limit=60.0):
        """Whether a new runtime answers get_graph within `limit` s (its services are up once loaded)."""
        end = time.time() + limit
        while time.time() < end and p.poll() is None:
            new = self.services() - before
            if new and all(self.answers(s) for s in new):
                return ""
            time.sleep(0.3)
        return "exited with %s" % p.returncode if p.poll() is not None else "no runtime answered in %.0f s" % limit

    def answers(self, service):
        try:
            r = subprocess.run(["rosservice", "call", service], env=self.env, capture_output=True, text=True, timeout=30)
        except subprocess.TimeoutExpired:
            return False
        return r.returncode == 0 and "success: True" in r.stdout

    def stop(self):
        for p in reversed(self.started):
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGINT)
        for p in self.started:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()
        self.started = []


def run_session(body, env, cwd, log):
    """The first failure of a session block ('' if none)."""
    s = Session(env, cwd)
    try:
        for command, expected in commands(body):
            log.write("\n$ %s\n" % command)
            log.flush()
            command = without_comment(command)
            if command.endswith("&"):
                before, p = s.start(command[:-1].strip(), log)
                if "roslaunch" in command or "apex_runtime_node" in command:
                    why = s.wait_runtime(before, p)
                    if why:
                        return "%s: %s" % (command, why)
                continue
            try:
                r = subprocess.run(["bash", "-c", command], cwd=cwd, env=env, capture_output=True, text=True, timeout=300)
            except subprocess.TimeoutExpired:
                return "%s: no answer in 300 s" % command
            log.write(r.stdout + r.stderr)
            log.flush()
            shows_error = any("error" in e.lower() for e in expected)
            if r.returncode != 0 and not shows_error:
                return "%s: exit %d: %s" % (command, r.returncode, (r.stderr or r.stdout).strip()[-300:])
            for e in expected:
                why = matches(e.replace("/home/you", env["HOME"]), r.stdout + r.stderr)
                if why:
                    return "%s: %s in %r" % (command, why, (r.stdout + r.stderr).strip()[-400:])
        return ""
    finally:
        s.stop()


def save_file(name, body, cwd):
    """A `file` block: saved in the working folder; None (no failure)."""
    with open(os.path.join(cwd, name), "w") as f:
        f.write("\n".join(body) + "\n")
    return None


def run_each(body, env, cwd, log):
    """The first launch line of an `each` block that brings up no runtime ('' if none)."""
    lines = [without_comment(l.strip()) for l in body if l.strip() and not l.strip().startswith(("#", "source "))]
    helpers = Session(env, cwd)
    try:
        if any("manager:=camera_manager" in l for l in lines):
            helpers.start("rosrun nodelet nodelet manager __name:=camera_manager", log)
        for line in lines:
            log.write("\n$ %s &\n" % line)
            log.flush()
            s = Session(env, cwd)
            before, p = s.start(line, log)
            why = s.wait_runtime(before, p)
            s.stop()
            if why:
                return "%s: %s" % (line, why)
        return ""
    finally:
        helpers.stop()


def user_files(work, env):
    """HOME with ~/data, and the working folder, as the module's docstring says."""
    home, cwd = os.path.join(work, "home"), os.path.join(work, "cwd")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(os.path.join(home, "data"))
    os.makedirs(cwd)
    data = os.path.join(home, "data")
    for name, seed, frames in (("demo", 3, 40), ("train", 1, 60), ("test", 2, 20)):
        subprocess.run(["rosrun", "apex", "apex_make_demo_bag", os.path.join(data, name + ".bag"),
                        os.path.join(data, name + "_truth.yaml"), "--seed", str(seed), "--frames", str(frames)],
                       env=env, check=True, capture_output=True)
    shutil.copy(os.path.join(data, "demo.bag"), os.path.join(cwd, "run3.bag"))
    with open(os.path.join(cwd, "my_graph.yaml"), "w") as f:
        f.write(MY_GRAPH)
    return home, cwd


def main():
    if len(sys.argv) < 4:
        raise SystemExit(__doc__)
    pages, result, work = [], sys.argv[-2], sys.argv[-1]
    for page in sys.argv[1:-2]:
        if os.path.realpath(page) not in map(os.path.realpath, pages):
            pages.append(page)
    work = os.path.abspath(work)
    env = dict(os.environ)
    port = 21000 + os.getpid() % 10000
    env["ROS_MASTER_URI"] = "http://localhost:%d" % port
    env["PATH"] = "/usr/bin:/bin:" + env.get("PATH", "")
    env.pop("ROS_HOME", None)  # the user's: ~/.ros
    home, cwd = user_files(work, env)
    env["HOME"] = home
    env["ROSCONSOLE_STDOUT_LINE_BUFFERED"] = "1"
    found = []
    for page in pages:
        with open(page) as f:
            found += [b + (page,) for b in blocks(f.read(), page)]
    core = subprocess.Popen(["roscore", "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL, start_new_session=True)
    xvfb = None
    cases = []
    try:
        for _ in range(100):
            if subprocess.run(["rosparam", "list"], env=env, capture_output=True).returncode == 0:
                break
            time.sleep(0.1)
        if any(k == "each" and any("rviz" in l for l in b) for k, _, _, _, b, _ in found) and shutil.which("Xvfb"):
            env["DISPLAY"], env["LIBGL_ALWAYS_SOFTWARE"] = ":%d" % (150 + os.getpid() % 50), "1"
            xvfb = subprocess.Popen(["Xvfb", env["DISPLAY"], "-nolisten", "tcp"], stdout=subprocess.DEVNULL,
                                    stderr=subprocess.DEVNULL)
        for kind, name, file_name, line, body, page in found:
            t0 = time.time()
            with open(os.path.join(work, name + ".log"), "w") as log:
                if kind == "file":
                    failure = save_file(file_name, body, cwd)
                else:
                    failure = (run_session if kind == "session" else run_each)(body, env, cwd, log)
            cases.append((name, failure, time.time() - t0))
            print("%s line %d, %s (%s): %s (%.0f s)" % (page, line, name, kind, failure or "OK", time.time() - t0),
                  flush=True)
    finally:
        if xvfb:
            xvfb.terminate()
        os.killpg(core.pid, signal.SIGINT)
        core.wait()
    if not found:
        cases.append(("blocks", "no block of the pages is marked for checking", 0))
    t0 = time.time()
    links = bad_links(pages)
    cases.append(("links", "; ".join(links), time.time() - t0))
    print("links of %d pages: %s" % (len(pages), "; ".join(links) or "OK"), flush=True)
    failures = sum(1 for _, f, _ in cases if f)
    with open(result, "w") as f:
        f.write('<?xml version="1.0" encoding="UTF-8"?>\n<testsuite name="readme" tests="%d" failures="%d">\n'
                % (len(cases), failures))
        for name, failure, seconds in cases:
            f.write('  <testcase classname="ReadmeExamples" name="%s" time="%.1f">' % (name, seconds))
            if failure:
                f.write("<failure message=%s>%s</failure>" % (quoteattr(failure), escape(failure)))
            f.write("</testcase>\n")
        f.write("</testsuite>\n")
    print("README and docs examples: %d cases, %d failed" % (len(cases), failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
