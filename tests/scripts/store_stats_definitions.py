#!/usr/bin/env python3
"""issue 47: the definitions behind the tables results-tables computes itself (scripts/lib/
trn_store_stats.py). The quantile is experiments::quantile's (R type 7); the generator is
trn/detail/splitmix.hpp's; the check that Table 3.6's median is that quantile finds the upper-middle
median the sampling merge printed before issue 47 (1.0 m where the median is 0.93 m); the bootstrap
is a pure function of the store and its seed (the docs regenerate byte for byte).
usage: store_stats_definitions.py REPO_ROOT WORK_DIR"""
import json
import math
import shutil
import sys
from pathlib import Path

repo, work = Path(sys.argv[1]), Path(sys.argv[2])
sys.dont_write_bytecode = True
sys.path.insert(0, str(repo / "scripts" / "lib"))
import trn_store_stats as st  # noqa: E402

failures = []


def expect(ok, what):
    if not ok:
        failures.append(what)


# The quantile: linear between order statistics, NaN and None left out.
q = st.quantile
expect(q([4, 1, 3, 2], 0.5) == 2.5, f"median of 1..4: {q([4, 1, 3, 2], 0.5)}, expected 2.5 (not the upper middle 3)")
expect(abs(q(list(range(1, 11)), 0.9) - 9.1) < 1e-12, f"0.9-quantile of 1..10: {q(list(range(1, 11)), 0.9)}, expected 9.1")
expect(q([5.0], 0.5) == 5.0 and math.isnan(q([], 0.5)) and q([1, None, math.nan, 3], 0.5) == 2, "single, empty, non-finite")
expect(q([3, 1, 2], 0) == 1 and q([3, 1, 2], 1) == 3, "the ends")
try:
    q([1], 1.5)
    expect(False, "q outside 0..1 accepted")
except ValueError:
    pass

# SplitMix64 from state 0: the published reference outputs (and trn::splitmix::next64's).
g = st.SplitMix64(0)
expect([g.next() for _ in range(3)] == [0xE220A8397B1DCDAF, 0x6E789E6AA1B965F4, 0x06C45D188009454F], "SplitMix64 sequence")
g = st.SplitMix64(47)
draws = [g.below(40) for _ in range(4000)]
expect(min(draws) == 0 and max(draws) == 39, "below(40) covers 0..39 only")

# Table 3.6's median against the store: a merge folder with the upper-middle value fails the check.
shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)
jobs = []
for m in ("rejection", "importance", "kld"):
    for i, e in enumerate((1.0, 2.0, 3.0, 10.0)):
        jobs.append({"job": f"{m}-{i}", "config": "h", "params": {"method": m, "start": i}, "result": {"best_error_m": e}})
jobs.append({"job": "kld-0", "config": "h", "params": {"method": "kld", "start": 0}, "result": {"best_error_m": 99.0}})  # repeat: ignored
jobs.append({"job": "kld-9", "config": "other", "params": {"method": "kld", "start": 9}, "result": {"best_error_m": 99.0}})
(work / "store.jsonl").write_text("".join(json.dumps(j) + "\n" for j in jobs) + '{"job": "cut off')
(work / "provenance.json").write_text(json.dumps({"results_store": "store.jsonl", "config_hash": "h", "jobs": 12}))


def table_3_6(median):
    rows = ["Algorithm,End particle count (ours),Median best-particle error m (ours)"]
    rows += [f"{m},500.0,{median}" for m in ("rejection", "importance", "kld")]
    (work / "table_3_6.csv").write_text("\n".join(rows) + "\n")


table_3_6("2.5")
try:
    st.check_sampling_median(work, work)
except st.Disagrees as e:
    expect(False, f"the true median was refused: {e}")
table_3_6("3.0")  # errors[n / 2], as the merge took it before
try:
    st.check_sampling_median(work, work)
    expect(False, "the upper-middle median passed the check")
except st.Disagrees:
    pass

# The bootstrap: the same store and seed give the same resamples; the full-data ratios are the
# cell means' (a 2-scenario store: linear twice logistic:0.2's error, softmax 1.5x).
prov = {"config": {"presets": ["A", "B"], "conversions": ["linear", "softmax", "logistic:0.2"]}}
flights = []
for p, scale in (("A", 1.0), ("B", 3.0)):
    for age in (0, 2):
        for run in range(5):
            base = scale * (1 + run + age)
            for f, k in (("linear", 2.0), ("softmax", 1.5), ("logistic:0.2", 1.0)):
                flights.append({"params": {"preset": p, "conversion": f, "map_age": age, "run": run},
                                "result": {"filter_mean_error_m": base * k}})
fl = st.Flights(prov, flights)
st.RESAMPLES = 50
full, a = st.bootstrap(fl)
_, b = st.bootstrap(fl)
expect(a == b, "two bootstraps of the same store differ")
expect(abs(full[("ratio", "Logistic 0.2 / Linear")] - 100.0) < 1e-9, f"ratio {full[('ratio', 'Logistic 0.2 / Linear')]}, expected 100 %")
expect(abs(full[("ratio", "Softmax / Linear")] - 100 / 3) < 1e-9, "softmax over linear, expected 33.3 %")
expect(all(abs(s[("ratio", "Logistic 0.2 / Linear")] - 100.0) < 1e-9 for s in a), "a constant ratio must stay constant in every resample")
expect(len({s[("lost", "linear")] for s in a}) >= 1 and all(s[("flights", "linear")] == 20 for s in a), "20 flights per resample")

if failures:
    for f in failures:
        print("FAILED:", f, file=sys.stderr)
    sys.exit(1)
print("ok: quantile (type 7), SplitMix64, Table 3.6's median check, a reproducible bootstrap")
