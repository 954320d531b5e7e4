"""The one reader of a benchmark JSON (trn_bench's --benchmark_out, kept as bench.json; issue 45).

bench.json comes back from device machines, so scripts/bench-report reads it as outside input:
read_bench_json(raw, name) returns (context, runs) in the shapes the report uses, or raises
BenchJsonError naming the file, the benchmark and the field. What it guarantees of what it returns:
  - context: a dict; its text fields (date, host_name, trn_*: trn_bench's custom context is always
    text) are str, load_avg a list of numbers; other fields (num_cpus ...) are only printed;
  - runs: {run name: record}, one record per case (the median aggregate when repetitions ran, else
    the single run; an errored case as {"error": text, "parts": [...]}); every record has "parts",
    a non-empty list of str (the name split at "/" without manual_time, iterations:, repeats:; an
    ncc case's particle part is a letter and digits), "cv" (None or a float) and "unstable_any";
    every numeric field the report reads is a float, finite or NaN;
  - every str (values and keys) is valid Unicode text: lone surrogates (JSON "\\ud800") become
    U+FFFD, as the C++ writers' one rule for outside text (trn/io/outside_text.hpp).
Anything else (not JSON, nested past Python's recursion limit, a wrong type, an infinite or
unrepresentable number, an empty case name) is a BenchJsonError, never another exception: the fuzz
entry fuzz/fuzz_bench_json.py checks that over mutations of fuzz/corpus/bench_json.
The device kit carries this file in tools/lib beside tools/bench-report.
"""
import json
import math
import re


class BenchJsonError(Exception):
    """bench.json is not a benchmark JSON the report can read; the message says where and why."""


# Fields the report reads as text / as numbers (context; a benchmark's own counters).
CONTEXT_TEXT = ("date", "host_name", "trn_command", "trn_sweep", "trn_devices", "trn_device_types", "trn_map",
                "trn_opencv", "trn_openmp", "trn_cold_working_set_MiB", "trn_cold_working_set_basis", "trn_arch",
                "trn_cpu_backend")
RUN_TEXT = ("name", "run_name", "run_type", "aggregate_name", "error_message", "label")
RUN_NUMBERS = ("real_time", "GB/s", "exec_GB/s", "Mpix/s", "particles/s", "Msamples/s", "write_ms", "exec_ms", "read_ms",
               "allocs_per_iter", "passes", "pass_cv", "max_cv", "unstable", "create_ms", "first_calls_ms")
NCC_PARTICLES = re.compile(r"[A-Za-z][0-9]{1,9}")


def _text(s):
    """`s` with each lone surrogate replaced by U+FFFD (such a str cannot be written as UTF-8)."""
    if not any(0xD800 <= ord(c) <= 0xDFFF for c in s):
        return s
    return "".join("\ufffd" if 0xD800 <= ord(c) <= 0xDFFF else c for c in s)


def _clean(v):
    """Every str and key of a JSON value through _text."""
    if isinstance(v, str):
        return _text(v)
    if isinstance(v, list):
        return [_clean(x) for x in v]
    if isinstance(v, dict):
        return {_text(k): _clean(x) for k, x in v.items()}
    return v


def _number(v, where):
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise BenchJsonError(f"{where} is {type(v).__name__}, not a number")
    try:
        f = float(v)
    except OverflowError:
        raise BenchJsonError(f"{where} = {str(v)[:20]}... is too large for a number") from None
    if math.isinf(f):
        raise BenchJsonError(f"{where} is {f}, not a finite number")
    return f


def case_parts(run_name):
    # "sobel/1920x1080/hot/dev:cpu/manual_time" -> ["sobel", "1920x1080", "hot", "dev:cpu"]
    return [p for p in run_name.split("/")
            if p != "manual_time" and not p.startswith("iterations:") and not p.startswith("repeats:")]


def _context(ctx, name):
    if not isinstance(ctx, dict):
        raise BenchJsonError(f"{name}: context is {type(ctx).__name__}, not an object")
    out = dict(ctx)
    for key in CONTEXT_TEXT:
        if key in out and not isinstance(out[key], str):
            raise BenchJsonError(f"{name}: context.{key} is {type(out[key]).__name__}, not text")
    if "load_avg" in out:
        if not isinstance(out["load_avg"], list):
            raise BenchJsonError(f"{name}: context.load_avg is {type(out['load_avg']).__name__}, not a list")
        out["load_avg"] = [_number(x, f"{name}: context.load_avg[{i}]") for i, x in enumerate(out["load_avg"])]
    return out


def _benchmark(b, i, name):
    where = f"{name}: benchmarks[{i}]"
    if not isinstance(b, dict):
        raise BenchJsonError(f"{where} is {type(b).__name__}, not an object")
    for key in RUN_TEXT:
        if key in b and not isinstance(b[key], str):
            raise BenchJsonError(f"{where}.{key} is {type(b[key]).__name__}, not text")
    run = b.get("run_name", b.get("name"))
    if run is None:
        raise BenchJsonError(f"{where} has no name")
    parts = case_parts(run)
    if not parts or any(p == "" for p in parts):
        raise BenchJsonError(f"{where}: case name {run!r} has an empty part")
    if parts[0] == "ncc" and len(parts) == 5 and not NCC_PARTICLES.fullmatch(parts[3]):
        raise BenchJsonError(f"{where}: ncc case {run!r}: particle part {parts[3]!r} is not a letter and a count")
    if "error_occurred" in b and not isinstance(b["error_occurred"], bool):
        raise BenchJsonError(f"{where}.error_occurred is {type(b['error_occurred']).__name__}, not true or false")
    out = dict(b)
    for key in RUN_NUMBERS:
        if key in out:
            out[key] = _number(out[key], f"{where} ({run}): {key}")
    return run, parts, out


def read_bench_json(raw, name):
    """(context, runs) of the benchmark JSON `raw` (bytes) read from `name`; BenchJsonError otherwise."""
    try:
        doc = json.loads(raw)
    except (ValueError, RecursionError) as e:  # UnicodeDecodeError is a ValueError
        raise BenchJsonError(f"{name}: not JSON ({str(e)[:200]})") from None
    if not isinstance(doc, dict):
        raise BenchJsonError(f"{name}: not a benchmark JSON object")
    try:
        doc = _clean(doc)
    except RecursionError:  # json.loads nests deeper than this walk may
        raise BenchJsonError(f"{name}: nested too deeply") from None
    ctx = _context(doc.get("context", {}), name)
    benchmarks = doc.get("benchmarks", [])
    if not isinstance(benchmarks, list):
        raise BenchJsonError(f"{name}: benchmarks is {type(benchmarks).__name__}, not a list")
    runs, noise, means = {}, {}, {}
    for i, b in enumerate(benchmarks):
        run, parts, b = _benchmark(b, i, name)
        if b.get("error_occurred"):
            runs[run] = {"error": b.get("error_message", "error"), "parts": parts}
            continue
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                runs[run] = dict(b, parts=parts)
            elif b.get("aggregate_name") == "cv":
                noise[run] = b.get("real_time", float("nan"))
            elif b.get("aggregate_name") == "mean":
                means[run] = b
        elif run not in runs:
            runs[run] = dict(b, parts=parts)
    for run, r in runs.items():
        r["cv"] = noise.get(run)
        # STREAM: any repetition whose passes never agreed (mean of the 0/1 counter above 0).
        r["unstable_any"] = means.get(run, r).get("unstable", 0) > 0
    return ctx, runs
