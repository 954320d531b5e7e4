#!/usr/bin/env python3
"""Fails when a SetUpTestSuite body holds a fatal assertion (ASSERT_*, FAIL(), GTEST_SKIP).

gtest shows every test of a suite whose SetUpTestSuite failed fatally as SKIPPED, and ctest's
gtest skip regex then counts a broken suite as skipped, not failed. Record the failure there and
assert it in SetUp instead. Usage: check_suite_setup.py FILE... (exit 1 naming file:line)."""
import re
import sys

FATAL = re.compile(r"\b(ASSERT_[A-Z_]+|FAIL|GTEST_SKIP)\s*\(")


def bodies(text):
    for m in re.finditer(r"\bvoid\s+SetUpTestSuite\s*\(\s*\)\s*(override\s*)?\{", text):
        depth, i = 1, m.end()
        while i < len(text) and depth:
            depth += {"{": 1, "}": -1}.get(text[i], 0)
            i += 1
        yield m.end(), text[m.end():i]


bad = 0
for path in sys.argv[1:]:
    text = open(path, encoding="utf-8", errors="replace").read()
    for start, body in bodies(text):
        for f in FATAL.finditer(body):
            line = text.count("\n", 0, start + f.start()) + 1
            print(f"{path}:{line}: {f.group(1)} in SetUpTestSuite (record the failure, assert it in SetUp)")
            bad += 1
sys.exit(1 if bad else 0)
