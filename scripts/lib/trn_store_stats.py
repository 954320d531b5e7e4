"""Tables that scripts/results-tables computes itself from the results store (issue 47): bootstrap
confidence intervals over flights, and the claims of chapter 3's text that no study merge prints.

Each table reads the same jobs as `trnkit experiment STUDY --merge` (the store and configuration hash
of the merge's provenance.json, the first line of each job) and checks its own point estimates
against the merge's CSV tables before printing anything: a table here that disagreed with the
study's own merge would be a second definition, and results-tables fails on it.

Definitions, each in one place:
  - quantile(values, q): linear between order statistics (R's type 7, NumPy's default), as
    experiments::quantile (host/experiments/flight_outputs.hpp); quantile(v, 0.5) is the median.
  - SplitMix64: the generator of trn/detail/splitmix.hpp (the project's one random generator), so a
    fixed bootstrap seed gives the same intervals on every machine and Python version.
  - The bootstrap (conversion study): the 40 flights of a scenario (4 map years x 10 runs) are drawn
    with replacement, the same draw for every function (a function's flight of a scenario, map year
    and run flies the same simulated flight as every other function's), 12 scenarios independently;
    RESAMPLES draws; the interval is the 2.5 % and 97.5 % quantiles of the statistic over the draws.
"""
import csv
import json
import math
from pathlib import Path

RESAMPLES = 1000
BOOTSTRAP_SEED = 47
MASK64 = (1 << 64) - 1
BASELINES = ("linear", "softmax")
PARAMETRIC = ("rectifying:0.2", "rectifying:0.1", "rectifying:0", "rectifying:-0.1", "rectifying:-0.2",
              "logistic:0.7", "logistic:0.4", "logistic:0.2", "logistic:0.1", "logistic:0.05")
LOST_M = 100.0


class Disagrees(Exception):
    """A point estimate here differs from the study merge's own table."""


class SplitMix64:
    def __init__(self, seed):
        self.state = seed & MASK64

    def next(self):
        self.state = (self.state + 0x9E3779B97F4A7C15) & MASK64
        z = self.state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK64
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK64
        return z ^ (z >> 31)

    def below(self, n):
        """An index in 0..n-1 (53-bit uniform times n)."""
        return int((self.next() >> 11) * (1.0 / (1 << 53)) * n)


def quantile(values, q):
    """The q-quantile of the finite values; NaN when none. The definition of experiments::quantile."""
    if not 0 <= q <= 1:
        raise ValueError(f"quantile: q = {q} is outside 0..1")
    v = sorted(x for x in values if x is not None and math.isfinite(x))
    if not v:
        return math.nan
    at = q * (len(v) - 1)
    below = math.floor(at)
    above = min(below + 1, len(v) - 1)
    return v[below] + (at - below) * (v[above] - v[below])


def store_jobs(root, folder):
    """The jobs the merge in `folder` read: (config dict, [job line dicts]) from its provenance.json."""
    prov = json.loads((Path(folder) / "provenance.json").read_text())
    seen = {}
    with (Path(root) / prov["results_store"]).open() as f:
        for line in f:
            try:
                job = json.loads(line)
            except json.JSONDecodeError:
                continue  # a line cut off by a killed writer: the merge ignores it too
            if job.get("config") == prov["config_hash"]:
                seen.setdefault(job["job"], job)
    return prov, list(seen.values())


def store_commits(root, folder):
    """The short commits of the jobs the merge in `folder` read, in the order they first appear."""
    seen = []
    for job in store_jobs(root, folder)[1]:
        c = job.get("commit", "?")[:7]
        if c not in seen:
            seen.append(c)
    return seen


def read_csv(folder, table):
    with (Path(folder) / f"{table}.csv").open() as f:
        return list(csv.reader(f))


def fmt(x, digits=2):
    return "-" if x is None or not math.isfinite(x) else f"{x:.{digits}f}"


def interval(values, digits=2, suffix=""):
    return f"[{fmt(quantile(values, 0.025), digits)}{suffix}, {fmt(quantile(values, 0.975), digits)}{suffix}]"


def store_line(prov, profile):
    return (f"Store: {profile}; {len(prov['_jobs'])} jobs of {prov['jobs']} ({prov['results_store']}, configuration "
            f"{prov['config_hash']}); {RESAMPLES} bootstrap resamples, seed {BOOTSTRAP_SEED}.")


# ---- the conversion study -------------------------------------------------------------------------

class Flights:
    """The conversion store as error[scenario][function][(map_age, run)]."""

    def __init__(self, prov, jobs, key="filter_mean_error_m"):
        self.presets = list(prov["config"]["presets"])
        self.functions = list(prov["config"]["conversions"])
        self.flight_keys = {}
        self.value = {}
        for job in jobs:
            p = job["params"]
            v = job["result"].get(key)
            self.value[(p["preset"], p["conversion"], p["map_age"], p["run"])] = v if v is not None else math.nan
            self.flight_keys.setdefault(p["preset"], set()).add((p["map_age"], p["run"]))
        self.flight_keys = {s: sorted(k) for s, k in self.flight_keys.items()}

    def cell_mean(self, preset, function, draw):
        vals = [self.value.get((preset, function) + k, math.nan) for k in draw]
        vals = [v for v in vals if math.isfinite(v)]
        return sum(vals) / len(vals) if vals else math.nan


def rank_sums(errors):
    """Sum over scenarios of each function's rank (1 = lowest error; ties in list order, NaN last):
    diss::rank_sums (host/experiments/dissertation_tables.cpp)."""
    sums = [0] * len(errors[0])
    for row in errors:
        order = sorted(range(len(row)), key=lambda f: math.inf if math.isnan(row[f]) else row[f])
        for r, f in enumerate(order):
            sums[f] += r + 1
    return sums


def ranks_of(scores):
    order = sorted(range(len(scores)), key=lambda f: scores[f])  # stable: the merge's std::stable_sort
    rank = [0] * len(scores)
    for r, f in enumerate(order):
        rank[f] = r + 1
    return rank


RATIOS = (("Softmax / Linear", "linear", "softmax"), ("Logistic 0.2 / Linear", "linear", "logistic:0.2"),
          ("Logistic 0.2 / Softmax", "softmax", "logistic:0.2"))


def statistics(fl, draws):
    """Every bootstrapped statistic for one draw (dict scenario -> list of flight keys)."""
    means = {(s, f): fl.cell_mean(s, f, draws[s]) for s in fl.presets for f in fl.functions}
    out = {}
    for name, base, new in RATIOS:
        per = [(means[(s, base)] / means[(s, new)] - 1) * 100 for s in fl.presets]
        per = [x for x in per if math.isfinite(x)]
        out[("ratio", name)] = sum(per) / len(per) if per else math.nan
        out[("wins", name)] = sum(1 for x in per if x > 0)
    ranked = [f for f in PARAMETRIC if f in fl.functions]
    scores = rank_sums([[means[(s, f)] for f in ranked] for s in fl.presets])
    for f, r, sc in zip(ranked, ranks_of(scores), scores):
        out[("rank", f)], out[("score", f)] = r, sc
    for f in fl.functions:
        vals = [fl.value.get((s, f) + k, math.nan) for s in fl.presets for k in draws[s]]
        out[("lost", f)] = sum(1 for v in vals if math.isfinite(v) and v > LOST_M)
        out[("flights", f)] = sum(1 for v in vals if math.isfinite(v))
    return out


def bootstrap(fl):
    """(the full data's statistics, a list of RESAMPLES resampled ones)."""
    full = statistics(fl, fl.flight_keys)
    rng = SplitMix64(BOOTSTRAP_SEED)
    samples = []
    for _ in range(RESAMPLES):
        draws = {}
        for s in fl.presets:
            keys = fl.flight_keys[s]
            draws[s] = [keys[rng.below(len(keys))] for _ in keys]
        samples.append(statistics(fl, draws))
    return full, samples


def check_against_merge(folder, full, fl):
    """The point estimates must be the merge's: Table 3.10's averages, Table 3.9's ranks, the spread
    table's share of flights over 100 m."""
    t310 = {r[0]: r for r in read_csv(folder, "table_3_10")}
    avg = next(r for k, r in t310.items() if k.startswith("Average"))
    head = read_csv(folder, "table_3_10")[0]
    for name, _, _ in RATIOS:
        mine = f"{full[('ratio', name)]:.2f}%"
        theirs = avg[head.index(name)]
        if mine != theirs:
            raise Disagrees(f"Table 3.10 average {name}: {mine} here, {theirs} in the merge")
    for row in read_csv(folder, "table_3_9")[1:]:
        if full[("rank", row[0])] != int(row[2]) or full[("score", row[0])] != int(row[1]):
            raise Disagrees(f"Table 3.9 {row[0]}: rank {full[('rank', row[0])]} here, {row[2]} in the merge")
    spread = read_csv(folder, "table_error_spread")
    col = spread[0].index("Over 100 m")
    for row in spread[1:]:
        mine = f"{100 * full[('lost', row[0])] / full[('flights', row[0])]:.1f}%"
        if mine != row[col]:
            raise Disagrees(f"flights over 100 m, {row[0]}: {mine} here, {row[col]} in the merge")


_cache = {}


def conversion_bootstrap(root, folder):
    if folder not in _cache:
        prov, jobs = store_jobs(root, folder)
        prov["_jobs"] = jobs
        fl = Flights(prov, jobs)
        full, samples = bootstrap(fl)
        check_against_merge(folder, full, fl)
        _cache[folder] = (prov, fl, full, samples)
    return _cache[folder]


def seed_table_3_10(folder):
    t = read_csv(folder, "table_3_10")
    avg = next(r for r in t[1:] if r[0].startswith("Average"))
    wins = {}
    for name, _, _ in RATIOS:
        j = t[0].index(name) + 1  # its "(diss.)" column
        wins[name] = (avg[j], sum(1 for r in t[1:] if not r[0].startswith("Average") and float(r[j].rstrip("%")) > 0))
    return wins


def ci_table_3_10(root, ours, diss):
    (f_o, _), (f_d, _) = ours, diss
    runs = [conversion_bootstrap(root, f) for f in (f_o, f_d)]
    seed = seed_table_3_10(f_o)
    lines = ["**Table 3.10's average ratios with 95 % bootstrap intervals over flights, and in how many of the 12 scenarios "
             "the new function is the more accurate (point value [2.5 %, 97.5 % of the resamples])**", "",
             "| Ratio | Average: ours | Average: dissertation | Average: seed | Scenarios better: ours | Scenarios better: dissertation | seed |",
             "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for name, _, _ in RATIOS:
        cells = [name]
        for _, _, full, samples in runs:
            cells.append(f"{full[('ratio', name)]:.2f}% {interval([s[('ratio', name)] for s in samples], 1, '%')}")
        cells.append(seed[name][0])
        for _, fl, full, samples in runs:
            cells.append(f"{full[('wins', name)]} of {len(fl.presets)} {interval([s[('wins', name)] for s in samples], 0)}")
        cells.append(f"{seed[name][1]} of 12")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n\n" + store_line(runs[0][0], "ours") + "\n" + store_line(runs[1][0], "dissertation") + "\n"


def ci_table_3_9(root, ours, diss):
    (f_o, _), (f_d, _) = ours, diss
    runs = [conversion_bootstrap(root, f) for f in (f_o, f_d)]
    seed = {r[0]: r[4] for r in read_csv(f_o, "table_3_9")[1:]}
    lines = ["**Table 3.9's ranking under resampling: each function's rank on all flights, how often the resamples give it "
             "that rank, and the range of its rank (2.5 % to 97.5 % of the resamples)**", "",
             "| Function | Rank: ours | Same rank in resamples: ours | Rank range: ours | Rank: dissertation | "
             "Same rank in resamples: dissertation | Rank range: dissertation | Rank: seed |",
             "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for f in PARAMETRIC:
        cells = [f]
        for _, _, full, samples in runs:
            r = full[("rank", f)]
            same = sum(1 for s in samples if s[("rank", f)] == r) / len(samples)
            got = [s[("rank", f)] for s in samples]
            low, high = f"{quantile(got, 0.025):.0f}", f"{quantile(got, 0.975):.0f}"
            cells += [str(r), f"{100 * same:.0f}%", low if low == high else f"{low}-{high}"]
        cells.append(seed[f])
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n\n" + store_line(runs[0][0], "ours") + "\n" + store_line(runs[1][0], "dissertation") + "\n"


def ci_lost_flights(root, ours, diss):
    (f_o, _), (f_d, _) = ours, diss
    runs = [conversion_bootstrap(root, f) for f in (f_o, f_d)]
    lines = [f"**Lost flights (mean error over {LOST_M:.0f} m) per function, of its flights, with 95 % bootstrap intervals "
             "over flights (not in the dissertation)**", "",
             "| Function | Lost: ours | Lost: dissertation |", "| --- | ---: | ---: |"]
    for f in runs[0][1].functions:
        cells = [f]
        for _, _, full, samples in runs:
            cells.append(f"{full[('lost', f)]} of {full[('flights', f)]} {interval([s[('lost', f)] for s in samples], 0)}")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n\n" + store_line(runs[0][0], "ours") + "\n" + store_line(runs[1][0], "dissertation") + "\n"


# ---- checks of other merges' medians against the one quantile ---------------------------------------

def check_sampling_median(root, folder):
    """Table 3.6's median column must be quantile(best errors, 0.5) of the store's jobs."""
    prov, jobs = store_jobs(root, folder)
    t = read_csv(folder, "table_3_6")
    col = next(j for j, h in enumerate(t[0]) if h.startswith("Median"))
    for row in t[1:]:
        errors = [j["result"]["best_error_m"] for j in jobs if j["params"]["method"] == row[0]]
        mine = fmt(quantile(errors, 0.5), 1)
        if mine != row[col]:
            raise Disagrees(f"Table 3.6 {row[0]} median best-particle error: quantile gives {mine}, the merge {row[col]}")


# ---- chapter 3 claims from the sampling and odometry stores ------------------------------------------

def kld_cost(root, ours, diss):
    """2.3.8: KLD "decreases computational costs up to 1.7 times"; Table 3.6 and General Conclusion 2: 2.6x."""
    lines = ["**KLD's cost against rejection and importance sampling (Table 3.6's jobs): total time and particles "
             "evaluated, other method / KLD**", "",
             "| Profile | Time, rejection / KLD | Time, importance / KLD | Particles evaluated, rejection / KLD | "
             "Particles evaluated, importance / KLD | KLD capped at |",
             "| --- | ---: | ---: | ---: | ---: | --- |"]
    tails = []
    for profile, (folder, _) in (("ours", ours), ("dissertation", diss)):
        prov, jobs = store_jobs(root, folder)
        check_sampling_median(root, folder)
        tot = {}
        for m in ("rejection", "importance", "kld"):
            sel = [j["result"] for j in jobs if j["params"]["method"] == m]
            tot[m] = (sum(r["seconds"] for r in sel), sum(r["evaluated"] for r in sel))
        cap = (f"{prov['config']['particles']} (ours: the fixed count is KLD's maximum)" if profile == "ours"
               else "no maximum but the 100000 safety cap")
        lines.append(f"| {profile} | {tot['rejection'][0] / tot['kld'][0]:.2f}x | {tot['importance'][0] / tot['kld'][0]:.2f}x | "
                     f"{tot['rejection'][1] / tot['kld'][1]:.2f}x | {tot['importance'][1] / tot['kld'][1]:.2f}x | {cap} |")
        tails.append(f"Store: {profile}; {len(jobs)} jobs of {prov['jobs']} ({prov['results_store']}, configuration {prov['config_hash']}).")
    lines.append("| seed | 2.63x (215 / 81.8 s) | 2.68x (219 / 81.8 s) | - | - | not given |")
    return "\n".join(lines) + "\n\n" + "\n".join(tails) + "\n"


ODOMETRY_STUDIES = ("odometry", "odometry-wind", "odometry-visual", "odometry-long")


def within_50m(root, merged, profile="ours"):
    """3.6: "Particle filter localization was able to keep error values in an around 50-meter range"."""
    lines = ["**Section 3.6's \"error values in an around 50-meter range\": flights whose filter error stays near 50 m "
             f"(profile {profile}; the store keeps each flight's mean and final error, not its largest)**", "",
             "| Study | Flights | Filter mean error <= 50 m | Filter final error <= 50 m | Largest filter mean error m | "
             "Odometry mean error <= 50 m |", "| --- | ---: | ---: | ---: | ---: | ---: |"]
    tails = []
    for study in ODOMETRY_STUDIES:
        folder, head = merged(study, profile)
        if head is None:
            continue
        prov, jobs = store_jobs(root, folder)
        r = [j["result"] for j in jobs]
        n = len(r)
        mean_ok = sum(1 for x in r if x["filter_mean_error_m"] <= 50)
        final_ok = sum(1 for x in r if x["filter_final_error_m"] <= 50)
        odo_ok = sum(1 for x in r if x["odometry_mean_error_m"] <= 50)
        worst = max(x["filter_mean_error_m"] for x in r)
        lines.append(f"| {study} | {n} | {mean_ok} of {n} | {final_ok} of {n} | {worst:.2f} | {odo_ok} of {n} |")
        tails.append(f"Store: {profile}; {n} jobs of {prov['jobs']} ({prov['results_store']}, configuration {prov['config_hash']}).")
    return "\n".join(lines) + "\n\n" + "\n".join(tails) + "\n"


def job_cost(root, ours, diss):
    """What a conversion flight costs per function (the stored wall times) and how often it re-seeds."""
    runs = []
    for profile, (folder, _) in (("ours", ours), ("dissertation", diss)):
        prov, jobs = store_jobs(root, folder)
        runs.append((profile, prov, jobs))
    functions = list(runs[0][1]["config"]["conversions"])
    lines = ["**What a conversion flight costs: mean job wall time per function (one job a core on the shared 2-core VMs) "
             "and the most re-initialisations in one flight**", "",
             "| Function | Wall s: ours | Wall s: dissertation | Most re-initialisations: ours | Most re-initialisations: dissertation |",
             "| --- | ---: | ---: | ---: | ---: |"]
    for f in functions + ["all"]:
        cells = [f]
        for _, _, jobs in runs:
            sel = [j for j in jobs if f == "all" or j["params"]["conversion"] == f]
            cells.append(f"{sum(j['wall_s'] for j in sel) / len(sel):.2f}" if sel else "-")
        for _, _, jobs in runs:
            sel = [j["result"].get("reinitialisations") for j in jobs if f == "all" or j["params"]["conversion"] == f]
            sel = [x for x in sel if x is not None]
            cells.append(f"{max(sel)}" if sel else "-")
        lines.append("| " + " | ".join(cells) + " |")
    hours = " and ".join(f"{sum(j['wall_s'] for j in jobs) / 3600:.1f} core-hours ({profile})" for profile, _, jobs in runs)
    tails = [f"Store: {profile}; {len(jobs)} jobs of {prov['jobs']} ({prov['results_store']}, configuration {prov['config_hash']})."
             for profile, prov, jobs in runs]
    return "\n".join(lines) + f"\n\nThe whole sweep: {hours}.\n\n" + "\n".join(tails) + "\n"


SENSITIVITY_STORE = "results/conversion/dissertation-sensitivity.jsonl"


def sensitivity(root, ours, diss):
    """Issue 47 item 5, a sample: Table 3.10/3.11's functions on a few conversion cells under the
    dissertation profile with other particle maxima and the other KLD quantile. Each setting is a
    configuration of its own in SENSITIVITY_STORE; the setting `--max-particles 100000` is the
    profile's own, so its flights must equal the sweep's stored ones (checked: a rerun that differed
    would make every comparison here meaningless)."""
    (f_d, _) = diss
    _, sweep = store_jobs(root, f_d)
    sweep = {j["job"]: j["result"] for j in sweep}
    path = Path(root) / SENSITIVITY_STORE
    if not path.exists():
        return "_No sensitivity jobs in the results store yet._\n"
    settings, jobs = {}, {}
    with path.open() as f:
        for line in f:
            try:
                job = json.loads(line)
            except json.JSONDecodeError:
                continue
            jobs.setdefault(job["config"], {}).setdefault(job["job"], job)
    for h in jobs:
        c = json.loads((path.parent / "configs" / f"{h}.json").read_text())
        if c.get("profile") != "dissertation":
            raise Disagrees(f"{SENSITIVITY_STORE}: configuration {h} is not the dissertation profile's")
        settings[h] = (c.get("max_particles", 100000), c.get("kld_upper_quantile", 0.1))

    def label(s):
        cap, q = s
        return f"at most {cap}, z = {'+1.28' if q > 0.5 else '-1.28'}"

    order = sorted(settings, key=lambda h: (settings[h][1] > 0.5, -settings[h][0]))
    base = next((h for h in order if settings[h] == (100000, 0.1)), None)
    if base is not None:
        for jid, job in jobs[base].items():
            stored = sweep.get(jid)
            for key in ("filter_mean_error_m", "mean_particles"):
                if stored is not None and stored[key] != job["result"][key]:
                    raise Disagrees(f"{SENSITIVITY_STORE}: {jid} {key} {job['result'][key]}, the sweep stored {stored[key]}")
    cells = sorted({j for h in jobs for j in jobs[h]}, key=lambda j: (j.split("-")[0] + j.split("-")[1], j))
    lines = ["**Sensitivity to what the text leaves open (dissertation profile, a sample of cells: map age 0, run 0): "
             "mean error m / mean particles a step / most particles in one step**", "",
             "| Flight | " + " | ".join(label(settings[h]) for h in order) + " |",
             "| --- |" + " ---: |" * len(order)]
    for jid in cells:
        row = [jid]
        for h in order:
            r = jobs[h].get(jid, {}).get("result")
            row.append("-" if r is None else
                       f"{r['filter_mean_error_m']:.2f} / {r['mean_particles']:.0f} / {r.get('max_particles_step', '-')}")
        lines.append("| " + " | ".join(row) + " |")
    presets = sorted({j.split("-")[0] + "-" + j.split("-")[1] for j in cells})
    for p in presets:
        for name, base_f, new_f in RATIOS[1:2] + RATIOS[2:]:
            row = [f"{p}: particles, {name}"]
            for h in order:
                a = jobs[h].get(f"{p}-{base_f.replace(':', '_')}-age0-0", {}).get("result")
                b = jobs[h].get(f"{p}-{new_f.replace(':', '_')}-age0-0", {}).get("result")
                row.append("-" if a is None or b is None else f"{a['mean_particles'] / b['mean_particles']:.2f}x")
            lines.append("| " + " | ".join(row) + " |")
    commits = sorted({j.get("commit", "?")[:7] for h in jobs for j in jobs[h].values()})
    tail = (f"Store: dissertation; {sum(len(v) for v in jobs.values())} jobs in {SENSITIVITY_STORE} "
            f"({len(jobs)} configurations, run at {', '.join('`' + c + '`' for c in commits)}); "
            f"the flights at most 100000, z = -1.28 equal the sweep's stored ones.")
    return "\n".join(lines) + "\n\n" + tail + "\n"
