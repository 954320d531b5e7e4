#!/usr/bin/env python3
"""Fuzz entry for bench.json's reader (scripts/lib/trn_bench_json.py, issue 45): the one Python
reader among the fuzzed ones, so it has its own replay driver in the shape of fuzz/replay_main.cpp
(ctest fuzz_replay_bench_json): every seed, then N deterministic mutations of them (seeded, so a run
is repeatable; half byte-level with the dictionary's tokens, half structural: one value anywhere in
the parsed seed replaced by a hostile one). Each input must be read or refused with
BenchJsonError, never another exception, and what is read must keep the reader's promises (the
shapes bench-report uses; every text writable as UTF-8). A failing input is written to
fuzz-bench-json-failure-N.json in the working folder (the test's build folder) and the run fails.

usage: fuzz_bench_json.py -dict=FILE -runs=N [-lib=DIR] SEED_FILE_OR_FOLDER...
"""
import json
import math
import os
import random
import sys
import traceback

args = [a for a in sys.argv[1:] if not a.startswith("-")]
opts = dict(a[1:].split("=", 1) for a in sys.argv[1:] if a.startswith("-") and "=" in a)
sys.path.insert(0, opts.get("lib", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts", "lib")))
import trn_bench_json  # noqa: E402

runs = int(opts.get("runs", "1000"))
tokens = []
if "dict" in opts:
    with open(opts["dict"], "rb") as f:
        for line in f:
            line = line.strip()
            if line.startswith(b'"') and line.endswith(b'"') and len(line) >= 2:
                tokens.append(line[1:-1].decode("unicode_escape").encode("latin-1"))
tokens += [b'"benchmarks"', b'"context"', b'"run_name"', b'"name"', b'"run_type"', b'"aggregate"', b'"median"',
           b'"error_occurred"', b'"load_avg"', b'"date"', b"/", b"manual_time", b"ncc/640x480/dense/N", b"NaN", b"Infinity"]

seeds = []
for a in args:
    paths = [os.path.join(a, n) for n in sorted(os.listdir(a))] if os.path.isdir(a) else [a]
    for p in paths:
        if os.path.isfile(p):
            with open(p, "rb") as f:
                seeds.append(f.read())
if not seeds:
    sys.exit("fuzz_bench_json: no seeds")

HOSTILE = [None, True, False, 0, -1, 1.5, float("nan"), 10 ** 400, -(10 ** 400), "", "/", "\ud800", "a\udfffb", "x" * 1000,
           "ncc/640x480/dense/Nabc/dev:cpu", "ncc/640x480/dense/N99999999999/dev:cpu", "manual_time", "iterations:3",
           "sobel//hot/dev:cpu", [], {}, [1, "2", None], {"name": 1}, {"\ud800": "k"}]


def paths_of(v, path=()):
    yield path
    if isinstance(v, dict):
        for k, x in v.items():
            yield from paths_of(x, path + (k,))
    elif isinstance(v, list):
        for i, x in enumerate(v):
            yield from paths_of(x, path + (i,))


def structural(rng, data):
    try:
        doc = json.loads(data)
    except (ValueError, RecursionError):
        return data
    every = list(paths_of(doc))
    path = rng.choice(every)
    value = rng.choice(HOSTILE)
    deep = rng.random() < 0.05  # a value nested 5000 deep, spliced into the text
    if deep:
        value = "\u2603deep"
    if not path:
        doc = value
    else:
        parent = doc
        for p in path[:-1]:
            parent = parent[p]
        if isinstance(parent, dict) and rng.random() < 0.2:
            parent[rng.choice(["name", "run_name", "error_occurred", "context", "benchmarks", "load_avg", "GB/s", "date"])] = value
        else:
            parent[path[-1]] = value
    try:
        text = json.dumps(doc).encode("utf-8", "surrogatepass")
    except (ValueError, RecursionError):
        return data
    return text.replace(b'"\\u2603deep"', b"[" * 5000 + b"]" * 5000) if deep else text


def bytewise(rng, data):
    b = bytearray(data)
    for _ in range(rng.randint(1, 4)):
        op = rng.randrange(4)
        at = rng.randint(0, len(b))
        if op == 0 and b:
            b[min(at, len(b) - 1)] ^= 1 << rng.randrange(8)
        elif op == 1:
            b[at:at] = rng.choice(tokens)
        elif op == 2:
            del b[at:at + rng.randint(1, 16)]
        else:
            b[at:at] = b[max(0, at - 32):at]
    if rng.random() < 0.01:
        b = bytearray(b"[" * 100000) + b
    return bytes(b)


def promises(ctx, runs):
    assert isinstance(ctx, dict)
    for key in trn_bench_json.CONTEXT_TEXT:
        assert key not in ctx or isinstance(ctx[key], str), key
    assert all(isinstance(x, float) and not math.isinf(x) for x in ctx.get("load_avg", []))
    assert isinstance(runs, dict)
    for name, r in runs.items():
        assert isinstance(name, str) and isinstance(r, dict)
        parts = r["parts"]
        assert isinstance(parts, list) and parts and all(isinstance(p, str) and p for p in parts), parts
        if parts[0] == "ncc" and len(parts) == 5:
            int(parts[3][1:])  # as the report reads the particle count
        if "error" in r:
            assert isinstance(r["error"], str)
            continue
        assert r["cv"] is None or isinstance(r["cv"], float)
        assert isinstance(r["unstable_any"], bool)
        for key in trn_bench_json.RUN_NUMBERS:
            assert key not in r or (isinstance(r[key], float) and not math.isinf(r[key])), key
    # Every text can be written as UTF-8 (report.md, chart titles).
    json.dumps([ctx, runs], ensure_ascii=False).encode("utf-8")


failures = 0
read = refused = 0


def check(data, what):
    global failures, read, refused
    try:
        ctx, rs = trn_bench_json.read_bench_json(data, "bench.json")
    except trn_bench_json.BenchJsonError:
        refused += 1
        return
    except Exception:  # noqa: BLE001  (anything else is the finding)
        problem = traceback.format_exc(limit=3)
    else:
        try:
            promises(ctx, rs)
            read += 1
            return
        except Exception:  # noqa: BLE001
            problem = "read, but a promise is broken:\n" + traceback.format_exc(limit=3)
    failures += 1
    if failures <= 5:
        print(f"FAILED ({what}), input (first 400 bytes) {data[:400]!r}:\n{problem}", file=sys.stderr)


for i, s in enumerate(seeds):
    check(s, f"seed {i}")
for k in range(runs):
    rng = random.Random(k)
    seed = rng.choice(seeds)
    data = structural(rng, seed) if rng.random() < 0.5 else bytewise(rng, seed)
    check(data, f"mutation {k}")
print(f"fuzz_bench_json: {len(seeds)} seeds + {runs} mutations: {read} read, {refused} refused, {failures} failed")
sys.exit(1 if failures else 0)
