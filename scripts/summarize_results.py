#!/usr/bin/env python3
"""Counts test cases in gtest/JUnit XML result files and prints failures.

Usage: summarize_results.py [--extra-failure TEXT ...] [--log FILE ...] DIR [DIR ...]
Prints every failed case, then 'N passed, N failed'; exits 1 on any failure
or when no test ran at all. With failures, the lines of each --log FILE that
tell of a crash or an error (a node that died, an exception) come before the
count, so that a CI log's tail says why."""
import glob
import os
import sys
import xml.etree.ElementTree as ET


def cases(path):
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as e:
        yield (os.path.basename(path), "unreadable result file: %s" % e)
        return
    for case in root.iter("testcase"):
        if case.get("status") == "notrun" or case.find("skipped") is not None:
            continue
        bad = case.find("failure")
        if bad is None:
            bad = case.find("error")
        name = "%s.%s" % (case.get("classname", "?"), case.get("name", "?"))
        if bad is None:
            yield (name, None)
        else:
            yield (name, (bad.get("message") or bad.text or "failed").strip())


SIGNS = ("process has died", "[FATAL]", "[ERROR]", "terminate called", "Segmentation fault",
         "Aborted", "what():", "never appeared", "time limit")


def print_diagnostics(path, limit=25):
    try:
        with open(path, errors="replace") as f:
            lines = [l.rstrip() for l in f if any(s in l for s in SIGNS)]
    except OSError:
        return
    if lines:
        print("--- from %s (errors and crashes, last %d):" % (path, limit))
        for l in lines[-limit:]:
            print("  " + l[:300])


def main(argv):
    extra, dirs, logs = [], [], []
    it = iter(argv)
    for a in it:
        if a == "--extra-failure":
            extra.append(next(it))
        elif a == "--log":
            logs.append(next(it))
        else:
            dirs.append(a)
    passed, failed = 0, []
    for d in dirs:
        for path in sorted(glob.glob(os.path.join(d, "**", "*.xml"), recursive=True)):
            for name, why in cases(path):
                if why is None:
                    passed += 1
                else:
                    failed.append((name, why))
    failed += [(e, "") for e in extra]
    for name, why in failed:
        print("FAILED %s\n  %s" % (name, why.replace("\n", "\n  ")[:2000]))
    if failed:
        for log in logs:
            print_diagnostics(log)
    print("%d passed, %d failed" % (passed, len(failed)))
    return 1 if failed or passed == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
