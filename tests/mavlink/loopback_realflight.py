#!/usr/bin/env python3
"""A replayed real flight streamed as MAVLink over 127.0.0.1 (issue 43 item 3): node-mavlink listens
on a free port, `trnkit localize --mavlink udp:127.0.0.1:PORT` localizes the first STEPS rows of an
AIR folder, and every message it sent must decode to that run's CSV estimates: one GPS_INPUT,
GLOBAL_POSITION_SENSOR and ODOMETRY per step, in order, "no fix" exactly on the steps the filter
lost, HEARTBEATs at 1 Hz of the flight's clock. Exit 77 (NOT AVAILABLE) without node, node-mavlink
or the shared data."""
import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

INT32_MAX = 2**31 - 1


def unavailable(why):
    print("NOT AVAILABLE: " + why)
    sys.exit(77)


def copy_first_rows(air, steps, into):
    """The AIR folder cut to its first `steps` rows (files copied, never linked)."""
    os.makedirs(into)
    for name in ("flight.json", "map.png"):
        shutil.copyfile(os.path.join(air, name), os.path.join(into, name))
    with open(os.path.join(air, "metadata.csv"), newline="") as f:
        rows = list(csv.reader(f))
    with open(os.path.join(into, "metadata.csv"), "w", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows(rows[: steps + 1])
    for row in rows[1 : steps + 1]:
        shutil.copyfile(os.path.join(air, row[0]), os.path.join(into, row[0]))


def no_fix(row):
    """The CLI's rule (apps/trnkit/mavlink_option.cpp) from the CSV's columns."""
    return (row["lock_state"] == "lost" or row["reinitialised"] == "1" or int(row["particles"]) == 0
            or int(row["off_map"]) >= int(row["particles"]) or row["est_lat"] == "")


def check(decoded, rows, mpp):
    problems = []
    end = decoded[-1]
    if end.get("crc_errors") or end.get("unknown"):
        problems.append("decoder: %s" % end)
    packets = decoded[:-1]
    if any(p["seq"] != i % 256 for i, p in enumerate(packets)):
        problems.append("sequence numbers are not 0, 1, 2 ...")
    steps, beats = [], 0
    for p in packets:
        if p["msgid"] == 0:
            beats += 1
        elif p["msgid"] == 232:
            steps.append([p])
        elif steps:
            steps[-1].append(p)
    if len(steps) != len(rows):
        return problems + ["%d message sets for %d CSV rows" % (len(steps), len(rows))]
    x0, y0 = float(rows[0]["estimate_x"]), float(rows[0]["estimate_y"])
    last_beat, want_beats, resets = None, 0, 0
    for i, (row, msgs) in enumerate(zip(rows, steps)):
        where = "step %d: " % i
        t = round(float(row["time_s"]) * 1e6)
        if last_beat is None or t - last_beat >= 1e6:
            want_beats, last_beat = want_beats + 1, t
        resets += row["reinitialised"] == "1"
        if [m["name"] for m in msgs] != ["GPS_INPUT", "GLOBAL_POSITION_SENSOR", "ODOMETRY"]:
            problems.append(where + "messages %s" % [m["name"] for m in msgs])
            continue
        gps, pos, odo = (m["fields"] for m in msgs)
        for name, f in (("GPS_INPUT", gps), ("GLOBAL_POSITION_SENSOR", pos), ("ODOMETRY", odo)):
            if abs(int(f["time_usec"]) - t) > 1:
                problems.append(where + "%s time_usec %s, CSV time_s %s" % (name, f["time_usec"], row["time_s"]))
        if odo["reset_counter"] != resets % 256:
            problems.append(where + "reset_counter %s, %d re-initialisations so far" % (odo["reset_counter"], resets))
        if no_fix(row):
            if gps["fix_type"] != 1 or pos["lat"] != INT32_MAX or pos["flags"] != 1 or odo["quality"] != -1 or odo["x"] != "NaN":
                problems.append(where + "the filter lost (CSV) but a fix was sent: %s %s" % (gps, pos))
            continue
        lat, lon = round(float(row["est_lat"]) * 1e7), round(float(row["est_lon"]) * 1e7)
        for name, f in (("GPS_INPUT", gps), ("GLOBAL_POSITION_SENSOR", pos)):
            if abs(f["lat"] - lat) > 1 or abs(f["lon"] - lon) > 1:  # the CSV keeps 9 decimals
                problems.append(where + "%s lat/lon %s %s, CSV %s %s" % (name, f["lat"], f["lon"], row["est_lat"], row["est_lon"]))
        if gps["fix_type"] != 3 or not gps["horiz_accuracy"] > 0 or gps["horiz_accuracy"] != pos["eph"]:
            problems.append(where + "fix_type %s horiz_accuracy %s eph %s" % (gps["fix_type"], gps["horiz_accuracy"], pos["eph"]))
        # horiz_accuracy is the CSV covariance's worst axis (1 sigma: its largest eigenvalue's root)
        nn, ne, ee = float(row["cov_nn_m2"]), float(row["cov_ne_m2"]), float(row["cov_ee_m2"])
        sigma = math.sqrt((nn + ee) / 2 + math.hypot((nn - ee) / 2, ne))
        if abs(gps["horiz_accuracy"] - sigma) > 1e-4 * max(1.0, sigma):
            problems.append(where + "horiz_accuracy %s, the CSV covariance's worst axis %.4f m" % (gps["horiz_accuracy"], sigma))
        north = -(float(row["estimate_y"]) - y0) * mpp
        east = (float(row["estimate_x"]) - x0) * mpp
        if abs(odo["x"] - north) > 0.01 or abs(odo["y"] - east) > 0.01:
            problems.append(where + "ODOMETRY x, y %s %s; CSV gives %.3f %.3f" % (odo["x"], odo["y"], north, east))
    if beats != want_beats:
        problems.append("%d HEARTBEATs, 1 Hz of the flight's clock gives %d" % (beats, want_beats))
    return problems


def refused(trnkit, air, tmp):
    """Bad --mavlink input stops localize before any step, with a message naming the option."""
    problems = []
    no_origin = os.path.join(tmp, "no_origin")
    shutil.copytree(air, no_origin)
    with open(os.path.join(air, "flight.json")) as f:
        flight = json.load(f)
    del flight["origin"]
    with open(os.path.join(no_origin, "flight.json"), "w") as f:
        json.dump(flight, f)
    cases = [(air, ["--mavlink", "udpin:0.0.0.0:14550"], "--mavlink udpin:0.0.0.0:14550: trnkit only sends"),
             (air, ["--mavlink", "udp:127.0.0.1:99999"], "1..65535"),
             (air, ["--mavlink", "udp:127.0.0.1:14550", "--mavlink-messages", "gps"], "--mavlink-messages: 'gps' is not one of"),
             (air, ["--mavlink", "udp:127.0.0.1:14550", "--mavlink-sysid", "0"], "--mavlink-sysid"),
             (air, ["--mavlink-sensor-id", "3"], "--mavlink-sensor-id requires --mavlink"),
             (no_origin, ["--mavlink", "udp:127.0.0.1:14550"], "--mavlink: needs latitude/longitude")]
    for dataset, extra, want in cases:
        run = subprocess.run([trnkit, "localize", "--dataset", dataset, "--out", os.path.join(tmp, "refused"), "--no-plots",
                              "--backend", "cpu"] + extra, capture_output=True, text=True, timeout=60)
        if run.returncode == 0 or want not in run.stderr or "steps" in run.stdout:
            problems.append("%s: exit %d, stderr %r (wanted %r, before any step)" % (" ".join(extra), run.returncode, run.stderr[-300:], want))
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--trnkit", required=True)
    ap.add_argument("--node", default="")
    ap.add_argument("--decoder", required=True)
    ap.add_argument("--air", required=True)
    ap.add_argument("--steps", type=int, default=24)
    a = ap.parse_args()
    if not a.node or not os.path.exists(a.node):
        unavailable("node (nodejs) not found when configuring (scripts/install-deps.sh)")
    modules = os.path.join(os.path.dirname(a.decoder), "node_modules", "node-mavlink")
    if not os.path.isdir(modules):
        unavailable("node-mavlink not installed in %s (scripts/install-deps.sh)" % os.path.dirname(modules))
    if not os.path.isfile(os.path.join(a.air, "metadata.csv")):
        unavailable("no real flight at %s (the shared data)" % a.air)
    with open(os.path.join(a.air, "flight.json")) as f:
        mpp = json.load(f)["metres_per_pixel"]

    with tempfile.TemporaryDirectory(prefix="trn_mavlink_") as tmp:
        air = os.path.join(tmp, "air")
        copy_first_rows(a.air, a.steps, air)
        errors = refused(a.trnkit, air, tmp)
        listener = subprocess.Popen([a.node, a.decoder, "--udp", "2000"], stdout=subprocess.PIPE, text=True)
        try:
            port = json.loads(listener.stdout.readline())["port"]
            target = "udp:127.0.0.1:%d" % port
            cmd = [a.trnkit, "localize", "--dataset", air, "--out", os.path.join(tmp, "out"), "--no-plots", "--backend", "cpu",
                   "--mavlink", target]
            print("running:", " ".join(cmd[:1] + ["localize", "--dataset", "AIR(first %d rows)" % a.steps] + cmd[4:]))
            run = subprocess.run(cmd, capture_output=True, text=True, timeout=100)
            print(run.stdout[-600:])
            if run.returncode != 0:
                print(run.stderr[-2000:])
                return 1
            out, _ = listener.communicate(timeout=60)
        finally:
            if listener.poll() is None:
                listener.kill()
        decoded = [json.loads(line) for line in out.splitlines() if line.strip()]
        with open(os.path.join(tmp, "out", "localization.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
    problems = errors + check(decoded, rows, mpp)
    lost = sum(no_fix(r) for r in rows)
    print("%d steps (%d without a fix), %d packets decoded by node-mavlink, %d CRC errors" %
          (len(rows), lost, decoded[-1]["packets"], decoded[-1]["crc_errors"]))
    for p in problems[:20]:
        print("FAIL:", p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
