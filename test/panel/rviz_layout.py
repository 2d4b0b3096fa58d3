#!/usr/bin/env python3
"""Where the shipped rviz configs put the graph panel, and the check that rviz's 3D view keeps its room.

rviz keeps its window's layout in a config's `Window Geometry: QMainWindow State:` as the hex of
QMainWindow::saveState(). Each dock is named there by its objectName, which rviz sets to the panel's
`Name` (a display's image dock: the display's `Name`); the 3D view is the central widget. This script
writes that state from the layouts below (Qt 5's format, written out here: no Qt needed), reads one
back, and measures an rviz screenshot.

  rviz_layout.py state CONFIG.rviz [--write]     the state for CONFIG's layout (--write: into CONFIG)
  rviz_layout.py decode CONFIG.rviz|HEX           what a state holds: dock areas, docks, sizes, tool bars
  rviz_layout.py measure SHOT.png --windows TREE [--background R,G,B] [--min F] [--max F] [--name N]
        the 3D view's share of rviz's window in a screenshot of the X root window; TREE is the output
        of `xwininfo -root -tree` taken with it. The 3D view is the X window (rviz's render widget is
        a native one) of rviz's that shows the most of the view's background colour; without one,
        the box of the columns, then rows, at least a quarter that colour. Exits 1 below F (0.5) or above --max.
  rviz_layout.py key COMBINATION                 a key pressed with modifiers held (e.g. ctrl+m), on
        $DISPLAY, through the XTEST extension
  rviz_layout.py click X Y [--double]            a (double) click of the left button at X,Y on
        $DISPLAY, through the XTEST extension (to undock a panel by its title bar)
  rviz_layout.py window NAME --windows TREE      the geometry of the top-level X window named NAME
        (a child of the root window; exits 1 if there is none)

Python 3's standard library only; `measure` converts the PNG with ImageMagick's `convert`.
"""
import argparse
import ctypes
import re
import struct
import subprocess
import sys

# --- the layouts ---------------------------------------------------------------------------------
# At rviz's default size (1200x846) the window has ~755 px between the tool bar and the status bar.
# The graph panel is docked at the bottom across the window: its tool bar (Pause ... Load...) fits
# in one row, the palette sits beside a canvas ~1000 px wide, which suits graphs laid out left to
# right; PANEL_HEIGHT is about the least the panel takes (its canvas has a minimum of 180 px) and
# leaves the 3D view ~460 of the 755 px over the whole width: more than half the window. A display's
# image goes beside the panel, in the bottom row, at a 4:3 image's width. The Displays panel is kept,
# hidden, at the left (Panels > Displays shows it there, at DISPLAYS_WIDTH): shown, it would take the
# 3D view's room.
PANEL = "APEX graph"
DISPLAYS = "Displays"
PANEL_HEIGHT = 290  # the bottom dock area, title bar included
IMAGE_WIDTH = 360  # an image dock in the bottom row: 4:3 at the dock's height
DISPLAYS_WIDTH = 260
SEPARATOR = 6  # QMainWindow's separator between dock areas and between docks
USABLE_HEIGHT = 755  # 846 less the menu bar, rviz's tool bar and the status bar

# config file name -> the docks (objectNames) of each area, left to right or top to bottom; 'hidden':
# docks kept in their place but not shown; 'right_width': the right area's width
LAYOUTS = {
    "apex_panel.rviz": {"bottom": [PANEL], "left": [DISPLAYS], "hidden": {DISPLAYS}},
    "table_demo.rviz": {"bottom": [PANEL], "left": [DISPLAYS], "hidden": {DISPLAYS}},
    "demo.rviz": {"bottom": [PANEL, "Overlay (blob detection)"], "left": [DISPLAYS], "hidden": {DISPLAYS}},
    "real_people.rviz": {"bottom": [PANEL, "People (people/overlay)"], "left": [DISPLAYS],
                         "hidden": {DISPLAYS}},
    # The digits demo draws nothing in 3D: its result is the labelled sheet (2:1), which takes the
    # top of the window at the right; the 3D view keeps what is left.
    "real_digits.rviz": {"bottom": [PANEL], "left": [DISPLAYS], "hidden": {DISPLAYS},
                         "right": ["Held-out digits, the SVM's labels (digits/overlay)"], "right_width": 880},
}

# --- Qt 5's QMainWindow::saveState() ---------------------------------------------------------------
LEFT, RIGHT, TOP, BOTTOM = range(4)  # QInternal::DockPosition
HORIZONTAL, VERTICAL = 1, 2  # Qt::Orientation
VERSION_MARKER, DOCK_MARKER, SEQUENCE_MARKER, TAB_MARKER, WIDGET_MARKER, TOOLBAR_MARKER_EX = (
    0xFF, 0xFD, 0xFC, 0xFA, 0xFB, 0xFC)
VISIBLE, FLOATING = 1, 2
QWIDGETSIZE_MAX = (1 << 24) - 1


def qstring(text):
    data = text.encode("utf-16-be")
    return struct.pack(">I", len(data)) + data


def dock(name, pos, size, visible=True):
    """A docked widget in a QDockAreaLayoutInfo: pos and size along the area's orientation."""
    return (bytes([WIDGET_MARKER]) + qstring(name) + bytes([VISIBLE if visible else 0]) +
            struct.pack(">iiii", pos, size, 0, QWIDGETSIZE_MAX))


def sequence(orientation, items):
    return bytes([SEQUENCE_MARKER, orientation]) + struct.pack(">i", len(items)) + b"".join(items)


def row(names, length, orientation, hidden, fixed):
    """Docks side by side over `length` px: those in `fixed` get that size, the first shown one the rest.
    A hidden dock keeps a place (and the size it gets when shown) but takes no room."""
    visible = [n for n in names if n not in hidden]
    rest = length - sum(fixed.get(n, 0) for n in visible[1:]) - SEPARATOR * max(len(visible) - 1, 0)
    items, pos = [], 0
    for n in names:
        if n in hidden:
            items.append(dock(n, pos, fixed.get(n, length), False))
            continue
        size = rest if n == visible[0] else fixed[n]
        items.append(dock(n, pos, size))
        pos += size + SEPARATOR
    return sequence(orientation, items)


def window_state(layout, width=1200, height=846):
    """The bytes of QMainWindow::saveState() for `layout` (one of LAYOUTS' values)."""
    hidden = layout.get("hidden", set())
    bottom = layout.get("bottom", [])
    right = layout.get("right", [])
    left = layout.get("left", [])
    top_height = USABLE_HEIGHT - (PANEL_HEIGHT + SEPARATOR if bottom else 0)
    right_width = layout.get("right_width", DISPLAYS_WIDTH)
    areas = []
    if left:
        # a column of docks, each as tall as the area; hidden ones take no room
        areas.append(struct.pack(">iii", LEFT, DISPLAYS_WIDTH, top_height) +
                     row(left, top_height, VERTICAL, hidden, {}))
    if right:
        areas.append(struct.pack(">iii", RIGHT, right_width, top_height) +
                     row(right, top_height, VERTICAL, hidden, {}))
    if bottom:
        areas.append(struct.pack(">iii", BOTTOM, width, PANEL_HEIGHT) +
                     row(bottom, width, HORIZONTAL, hidden, {n: IMAGE_WIDTH for n in bottom[1:]}))
    central_width = width - (right_width + SEPARATOR if right and not set(right) <= hidden else 0)
    out = struct.pack(">ii", VERSION_MARKER, 0) + bytes([DOCK_MARKER]) + struct.pack(">i", len(areas))
    out += b"".join(areas)
    out += struct.pack(">ii", central_width, top_height)
    # the corners: top and bottom areas take them (a bottom dock spans the whole window)
    out += struct.pack(">iiii", 4, 4, 8, 8)  # Qt::TopDockWidgetArea, ..., Qt::BottomDockWidgetArea
    # rviz's tool bar ("Tools") in one line at the top, shown, in its place
    out += bytes([TOOLBAR_MARKER_EX]) + struct.pack(">i", 1) + struct.pack(">ii", TOP, 1)
    out += qstring("Tools") + bytes([1]) + struct.pack(">iiII", 0, -1, 0, 0)
    return out


# --- reading a state back --------------------------------------------------------------------------
class Reader:
    def __init__(self, data):
        self.data, self.at = data, 0

    def take(self, fmt):
        values = struct.unpack_from(">" + fmt, self.data, self.at)
        self.at += struct.calcsize(">" + fmt)
        return values if len(values) > 1 else values[0]

    def string(self):
        n = self.take("I")
        if n == 0xFFFFFFFF:
            return None
        text = self.data[self.at:self.at + n].decode("utf-16-be")
        self.at += n
        return text


def decode_info(r, depth, lines):
    marker = r.take("B")
    tab = None
    if marker == TAB_MARKER:
        tab = r.take("i")
    elif marker != SEQUENCE_MARKER:
        raise ValueError("bad marker %#x at %d" % (marker, r.at - 1))
    orientation, count = r.take("B"), r.take("i")
    lines.append("%s%s %s, %d item(s)%s" % ("  " * depth, "tabs" if tab is not None else "sequence",
                                            {1: "horizontal", 2: "vertical"}.get(orientation, orientation),
                                            count, "" if tab is None else ", current %d" % tab))
    for _ in range(count):
        kind = r.take("B")
        if kind == WIDGET_MARKER:
            name, flags = r.string(), r.take("B")
            a, b, c, d = r.take("iiii")
            if flags & FLOATING:
                lines.append("%s'%s' floating at %dx%d+%d+%d%s" % ("  " * (depth + 1), name, c, d, a, b,
                                                                 "" if flags & VISIBLE else ", hidden"))
            else:
                lines.append("%s'%s' pos %d size %d (min %d max %d)%s" % ("  " * (depth + 1), name, a, b, c, d,
                                                                        "" if flags & VISIBLE else ", hidden"))
        elif kind == SEQUENCE_MARKER:
            a, b, _, _ = r.take("iiii")
            lines.append("%snested at pos %d size %d:" % ("  " * (depth + 1), a, b))
            decode_info(r, depth + 2, lines)
        else:
            raise ValueError("bad item marker %#x at %d" % (kind, r.at - 1))


def decode(data):
    r, lines = Reader(data), []
    marker, version = r.take("ii")
    if marker != VERSION_MARKER:
        raise ValueError("not a QMainWindow state (marker %#x)" % marker)
    lines.append("version %d" % version)
    while r.at < len(data):
        kind = r.take("B")
        if kind == DOCK_MARKER:
            for _ in range(r.take("i")):
                area, w, h = r.take("iii")
                lines.append("dock area %s, %dx%d:" % (["left", "right", "top", "bottom"][area], w, h))
                decode_info(r, 1, lines)
            w, h = r.take("ii")
            lines.append("central widget %dx%d; corners %s" % (w, h, list(r.take("iiii"))))
        elif kind == TOOLBAR_MARKER_EX:
            for _ in range(r.take("i")):
                area, count = r.take("ii")
                for _ in range(count):
                    name, shown = r.string(), r.take("B")
                    pos, preferred, _, _ = r.take("iiII")
                    lines.append("tool bar '%s' in area %d, %s, pos %d, preferred size %d" %
                                 (name, area, "shown" if shown & 1 else "hidden", pos, preferred))
        else:
            raise ValueError("unknown section %#x at %d" % (kind, r.at - 1))
    return lines


STATE_LINE = re.compile(r"^(\s*)QMainWindow State: *([0-9a-fA-F]*)\s*$", re.M)


def state_of(config_text):
    m = STATE_LINE.search(config_text)
    return bytes.fromhex(m.group(2)) if m else None


def write_state(path, state):
    """Puts the state, and Hide Left/Right Dock: false, into the config's Window Geometry."""
    text = open(path).read()
    lines = text.rstrip("\n").split("\n")
    try:
        start = lines.index("Window Geometry:")
    except ValueError:
        lines += ["Window Geometry:", "  Height: 846", "  Width: 1200"]
        start = len(lines) - 3
    end = start + 1
    while end < len(lines) and (lines[end].startswith(" ") or not lines[end].strip()):
        end += 1
    keep = [l for l in lines[start + 1:end]
            if not re.match(r"\s*(QMainWindow State|Hide Left Dock|Hide Right Dock):", l)]
    # rviz reads "Hide Right Dock" into what "Hide Left Dock" left when it is missing: both are written
    keep += ["  Hide Left Dock: false", "  Hide Right Dock: false", "  QMainWindow State: " + state.hex()]
    lines[start + 1:end] = keep
    open(path, "w").write("\n".join(lines) + "\n")


# --- measuring a screenshot ------------------------------------------------------------------------
WINDOW_LINE = re.compile(r'^(\s*)(0x[0-9a-f]+) (\(has no name\)|"([^"]*)")?.*?(\d+)x(\d+)[+-]-?\d+[+-]-?\d+\s+\+(-?\d+)\+(-?\d+)\s*$')


def windows(tree_text):
    """(depth, id, name, x, y, w, h) of each window in `xwininfo -root -tree` output, in order."""
    out = []
    for line in tree_text.splitlines():
        m = WINDOW_LINE.match(line)
        if m:
            out.append((len(m.group(1)), m.group(2), m.group(4) or "", int(m.group(7)), int(m.group(8)),
                        int(m.group(5)), int(m.group(6))))
    return out


def rviz_window(tree):
    """rviz's main window and the windows inside it."""
    for i, (depth, _, name, x, y, w, h) in enumerate(tree):
        if name == "RViz" or name.endswith(" - RViz"):  # "CONFIG.rviz - RViz", "CONFIG.rviz* - RViz"
            inside = []
            for d, wid, n, cx, cy, cw, ch in tree[i + 1:]:
                if d <= depth:
                    break
                inside.append((wid, n, cx, cy, cw, ch))
            return (x, y, w, h), inside
    return None, []


def read_ppm(png, crop):
    x, y, w, h = crop
    ppm = subprocess.run(["convert", png, "-crop", "%dx%d+%d+%d" % (w, h, x, y), "+repage", "-depth", "8",
                          "ppm:-"], check=True, stdout=subprocess.PIPE).stdout
    m = re.match(rb"P6\s+(\d+)\s+(\d+)\s+(\d+)\s", ppm)
    pw, ph = int(m.group(1)), int(m.group(2))
    pixels = ppm[m.end():]
    return pw, ph, [pixels[r * pw * 3:(r + 1) * pw * 3] for r in range(ph)]


def count_colour(rows, colour, rect):
    """Pixels of `colour` in rect (x, y, w, h, relative to the rows)."""
    x, y, w, h = rect
    pattern = bytes(colour)
    return sum(r[3 * x:3 * (x + w)].count(pattern) for r in rows[max(y, 0):y + h])


def colour_box(rows, colour, share=0.25):
    """The bounding box of the columns, then the rows within them, that are at least `share` `colour`."""
    pattern, h, w = bytes(colour), len(rows), len(rows[0]) // 3
    column = [0] * w
    for r in rows[::2]:
        at = r.find(pattern)
        while at >= 0:
            if at % 3 == 0:
                column[at // 3] += 2
                at = r.find(pattern, at + 3)
            else:
                at = r.find(pattern, at + 1)
    xs = [x for x in range(w) if column[x] >= share * h]
    if not xs:
        return None
    x0, x1 = min(xs), max(xs) + 1
    ys = [y for y in range(h) if rows[y][3 * x0:3 * x1].count(pattern) >= share * (x1 - x0)]
    if not ys:
        return None
    return x0, min(ys), x1 - x0, max(ys) - min(ys) + 1


def measure(shot, tree_text, colour, fallback_size):
    """(fraction, view rect, window rect, how) for the screenshot."""
    tree = windows(tree_text)
    frame, inside = rviz_window(tree)
    if frame is None:
        frame = (0, 0) + fallback_size
    fx, fy, fw, fh = frame
    _, _, rows = read_ppm(shot, frame)
    best = None
    for wid, name, x, y, w, h in inside:
        if w < 64 or h < 64 or (w, h) == (fw, fh):
            continue
        rect = (x - fx, y - fy, w, h)
        n = count_colour(rows, colour, rect)
        # the most of the colour; of windows holding the same pixels (the render widget, Ogre's
        # window in it, the central widget around them) the smallest
        if n > 0.05 * w * h and (best is None or (n, -w * h) > best[:2]):
            best = (n, -w * h, rect)
    if best is not None:
        view, how = best[2], "rviz's render window (X)"
    else:
        view, how = colour_box(rows, colour), "where the background colour is dense: no render window"
        if view is None:
            return 0.0, None, frame, "no pixel of the background colour"
    return view[2] * view[3] / float(fw * fh), view, frame, how


# --- clicks through XTEST --------------------------------------------------------------------------
def click(x, y, double=False):
    x11 = ctypes.CDLL("libX11.so.6")
    xtst = ctypes.CDLL("libXtst.so.6")
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XFlush.argtypes = [ctypes.c_void_p]
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
    xtst.XTestFakeMotionEvent.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.c_int, ctypes.c_ulong]
    xtst.XTestFakeButtonEvent.argtypes = [ctypes.c_void_p, ctypes.c_uint, ctypes.c_int, ctypes.c_ulong]
    dpy = x11.XOpenDisplay(None)
    if not dpy:
        raise SystemExit("click: cannot open the display")
    # The X server paces the click itself (XTest's delay, in ms, before each event): the pointer
    # comes to rest, then each press and release as a person's double-click; XSync returns once
    # the server has taken them all.
    xtst.XTestFakeMotionEvent(dpy, -1, x, y, 0)
    for i in range(2 if double else 1):
        xtst.XTestFakeButtonEvent(dpy, 1, 1, 200 if i == 0 else 80)
        xtst.XTestFakeButtonEvent(dpy, 1, 0, 30)
    x11.XSync.argtypes = [ctypes.c_void_p, ctypes.c_int]
    x11.XSync(dpy, 0)
    x11.XCloseDisplay(dpy)


def key(combination):
    """A key pressed with its modifiers held, e.g. "ctrl+m", as a keyboard does it (XTEST)."""
    x11 = ctypes.CDLL("libX11.so.6")
    xtst = ctypes.CDLL("libXtst.so.6")
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XStringToKeysym.restype = ctypes.c_ulong
    x11.XStringToKeysym.argtypes = [ctypes.c_char_p]
    x11.XKeysymToKeycode.restype = ctypes.c_ubyte
    x11.XKeysymToKeycode.argtypes = [ctypes.c_void_p, ctypes.c_ulong]
    x11.XSync.argtypes = [ctypes.c_void_p, ctypes.c_int]
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
    xtst.XTestFakeKeyEvent.argtypes = [ctypes.c_void_p, ctypes.c_uint, ctypes.c_int, ctypes.c_ulong]
    dpy = x11.XOpenDisplay(None)
    if not dpy:
        raise SystemExit("key: cannot open the display")
    names = {"ctrl": "Control_L", "shift": "Shift_L", "alt": "Alt_L"}
    codes = []
    for part in combination.split("+"):
        code = x11.XKeysymToKeycode(dpy, x11.XStringToKeysym(names.get(part.lower(), part).encode()))
        if not code:
            raise SystemExit("key: no key for '%s'" % part)
        codes.append(code)
    for c in codes:
        xtst.XTestFakeKeyEvent(dpy, c, 1, 50)
    for c in reversed(codes):
        xtst.XTestFakeKeyEvent(dpy, c, 0, 30)
    x11.XSync(dpy, 0)
    x11.XCloseDisplay(dpy)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="cmd", required=True)
    s = sub.add_parser("state")
    s.add_argument("config")
    s.add_argument("--write", action="store_true")
    d = sub.add_parser("decode")
    d.add_argument("what")
    m = sub.add_parser("measure")
    m.add_argument("shot")
    m.add_argument("--windows", required=True, help="a file with `xwininfo -root -tree`'s output")
    m.add_argument("--background", default="48,48,48")
    m.add_argument("--size", default="1200x846", help="rviz's window if the tree does not show it")
    m.add_argument("--min", type=float, default=0.5)
    m.add_argument("--max", type=float, default=1.0, help="fail above this share (a view that should be hidden)")
    m.add_argument("--name", default="rviz")
    c = sub.add_parser("click")
    c.add_argument("x", type=int)
    c.add_argument("y", type=int)
    c.add_argument("--double", action="store_true")
    k = sub.add_parser("key")
    k.add_argument("combination", help='e.g. "ctrl+m"')
    w = sub.add_parser("window")
    w.add_argument("name")
    w.add_argument("--windows", required=True)
    a = p.parse_args()

    if a.cmd == "state":
        import os
        base = os.path.basename(a.config)
        if base not in LAYOUTS:
            raise SystemExit("no layout for %s (LAYOUTS has %s)" % (base, ", ".join(sorted(LAYOUTS))))
        state = window_state(LAYOUTS[base])
        decode(state)  # it reads back
        if a.write:
            write_state(a.config, state)
        print(state.hex())
    elif a.cmd == "decode":
        data = state_of(open(a.what).read()) if a.what.endswith(".rviz") else bytes.fromhex(a.what)
        print("no QMainWindow State" if data is None else "\n".join(decode(data)))
    elif a.cmd == "measure":
        colour = [int(v) for v in a.background.split(",")]
        size = tuple(int(v) for v in a.size.split("x"))
        fraction, view, frame, how = measure(a.shot, open(a.windows).read(), colour, size)
        where = "none" if view is None else "%dx%d at +%d+%d" % (view[2], view[3], view[0], view[1])
        print("%s: the 3D view (%s) is %s, %.1f%% of rviz's %dx%d window" %
              (a.name, how, where, 100 * fraction, frame[2], frame[3]))
        if fraction < a.min:
            print("%s: the 3D view covers %.1f%% of the window, less than %.0f%%" % (a.name, 100 * fraction, 100 * a.min))
            sys.exit(1)
        if fraction > a.max:
            print("%s: the 3D view covers %.1f%% of the window, more than %.0f%%" % (a.name, 100 * fraction, 100 * a.max))
            sys.exit(1)
    elif a.cmd == "click":
        click(a.x, a.y, a.double)
    elif a.cmd == "key":
        key(a.combination)
    elif a.cmd == "window":  # a top-level one (a child of the root window): a docked panel's keeps its name
        tree = windows(open(a.windows).read())
        top = min(t[0] for t in tree)
        for depth, _, name, x, y, ww, hh in tree:
            if depth == top and name == a.name:
                print("%dx%d+%d+%d" % (ww, hh, x, y))
                return
        sys.exit(1)


if __name__ == "__main__":
    main()
