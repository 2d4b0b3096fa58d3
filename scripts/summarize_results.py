#!/usr/bin/env python3
"""Counts test cases in gtest/JUnit XML result files and prints failures.

Usage: summarize_results.py [--extra-failure TEXT ...] [--log FILE ...] DIR [DIR ...]
Prints every failed case, then 'N passed, N failed'; exits 1 on any failure
or when no test ran at all. With failures, the lines of each --log FILE that
tell of a crash or an error (a node that died, an exception) come before the
count, so that a CI log's tail says why."""
import glob
import os
import re
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
         "Aborted", "what():", "never appeared", "time limit", "][FAILURE]", "[  FAILED  ]")
ANSI = re.compile(r"\x1b\[[0-9;]*m")


def log_sections(path):
    """The log split at each test command that catkin's run_tests prints."""
    try:
        with open(path, errors="replace") as f:
            lines = [ANSI.sub("", l.rstrip()) for l in f]
    except OSError:
        return []
    sections = [[]]
    for line in lines:
        if line.startswith("-- run_tests.py: execute commands"):
            sections.append([])
        sections[-1].append(line)
    return sections


def telling_lines(lines, limit):
    """Crash and error lines, each kind once (numbers ignored) with how often it came."""
    seen = {}  # first line of each kind and its count, in order of first appearance
    for line in lines:
        if any(s in line for s in SIGNS):
            seen.setdefault(re.sub(r"\d+", "#", line), [line, 0])[1] += 1
    return [line[:300] + ("  (%d times)" % n if n > 1 else "") for line, n in list(seen.values())[-limit:]]


def print_diagnostics(path, failed_files, limit=12):
    """For each failed result file, the error lines of the test run that wrote it."""
    sections = log_sections(path)
    shown = False
    for result in sorted(set(failed_files)):
        stem = os.path.splitext(os.path.basename(result))[0]
        for section in sections:
            if not any(stem in l for l in section):
                continue
            command = next((l.strip() for l in section[1:3] if l.strip()), "?")
            print("--- %s, from %s:" % (stem, path))
            print("  ran: " + command[-200:])
            for line in telling_lines(section, limit):
                print("  " + line)
            shown = True
    if not shown and sections:
        lines = telling_lines([l for s in sections for l in s], limit)
        if lines:
            print("--- from %s (errors and crashes):" % path)
            for line in lines:
                print("  " + line)


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
    passed, failed, failed_files = 0, [], []
    for d in dirs:
        for path in sorted(glob.glob(os.path.join(d, "**", "*.xml"), recursive=True)):
            for name, why in cases(path):
                if why is None:
                    passed += 1
                else:
                    failed.append(("%s (%s)" % (name, os.path.basename(path)), why))
                    failed_files.append(path)
    failed += [(e, "") for e in extra]
    for name, why in failed:
        print("FAILED %s\n  %s" % (name, why.replace("\n", "\n  ")[:2000]))
    if failed:
        for log in logs:
            print_diagnostics(log, failed_files)
    print("%d passed, %d failed" % (passed, len(failed)))
    return 1 if failed or passed == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
