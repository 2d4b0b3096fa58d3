#!/usr/bin/env python3
"""Counts test cases in gtest/JUnit XML result files and prints failures.

Usage: summarize_results.py [--extra-failure TEXT ...] DIR [DIR ...]
Prints every failed case, then 'N passed, N failed'; exits 1 on any failure
or when no test ran at all."""
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


def main(argv):
    extra, dirs = [], []
    it = iter(argv)
    for a in it:
        if a == "--extra-failure":
            extra.append(next(it))
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
    print("%d passed, %d failed" % (passed, len(failed)))
    return 1 if failed or passed == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
