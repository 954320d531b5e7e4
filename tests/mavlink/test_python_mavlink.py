"""trnkit.MavlinkEncoder (issue 43 item 3): the C++ Stream from Python. Its frames decoded by
node-mavlink (the independent decoder; skipped, visibly, without it), "no fix" while lost, the
heartbeat's rate, and errors naming the keyword."""
import json
import math
import os
import subprocess
import tempfile

import numpy
import pytest

import trnkit

NODE = os.environ.get("TRN_NODE", "")
DECODER = os.environ.get("TRN_MAVLINK_DECODER", "")


def frames(data):
    """(msgid, seq, payload length) of each v2 frame in data."""
    out, i = [], 0
    while i < len(data):
        assert data[i] == 0xFD
        n = data[i + 1]
        out.append((data[i + 7] | data[i + 8] << 8 | data[i + 9] << 16, data[i + 4], n))
        i += 10 + n + 2
    assert i == len(data)
    return out


def decode(data):
    if not NODE or not os.path.exists(NODE) or not os.path.isdir(os.path.join(os.path.dirname(DECODER), "node_modules", "node-mavlink")):
        pytest.skip("NOT AVAILABLE: node or node-mavlink (scripts/install-deps.sh)")
    with tempfile.NamedTemporaryFile(suffix=".bin") as f:
        f.write(data)
        f.flush()
        out = subprocess.run([NODE, DECODER, f.name], capture_output=True, text=True, check=True).stdout
    return [json.loads(line) for line in out.splitlines()]


def test_a_fix_decodes_to_what_was_given():
    enc = trnkit.MavlinkEncoder(system_id=7, component_id=191)
    data = enc.encode(time_us=1_700_000_000_250_000, valid=True, lat_deg=41.0349018, lon_deg=-83.3057413, alt_msl_m=250.5,
                      north_m=10.5, east_m=-2.0, cov_nn=9.0, cov_ne=1.0, cov_ee=4.0, vel_north=3.0, vel_east=-1.5, vel_var=0.25,
                      yaw_rad=math.pi, yaw_var=0.01, processing_us=150_000)
    lines = decode(data)
    assert lines[-1]["crc_errors"] == 0 and lines[-1]["packets"] == 4
    hb, gps, pos, odo = lines[:4]
    assert [l["name"] for l in (hb, gps, pos, odo)] == ["HEARTBEAT", "GPS_INPUT", "GLOBAL_POSITION_SENSOR", "ODOMETRY"]
    assert all(l["sysid"] == 7 and l["compid"] == 191 for l in lines[:4])
    g, p, o = gps["fields"], pos["fields"], odo["fields"]
    assert (g["lat"], g["lon"], g["fix_type"], g["yaw"]) == (410349018, -833057413, 3, 18000)
    assert g["time_usec"] == "1700000000250000" and g["alt"] == 250.5
    sigma = math.sqrt(6.5 + math.sqrt(2.5 ** 2 + 1.0))  # the covariance's largest eigenvalue
    assert g["horiz_accuracy"] == pytest.approx(sigma, rel=1e-6) and p["eph"] == g["horiz_accuracy"]
    assert (g["vn"], g["ve"], g["speed_accuracy"]) == (3.0, -1.5, 0.5)
    assert (p["lat"], p["lon"], p["alt"], p["source"], p["flags"], p["processing_time"]) == (410349018, -833057413, 250.5, 2, 0, 150000)
    assert (o["x"], o["y"], o["z"], o["vx"], o["vy"]) == (10.5, -2.0, "NaN", 3.0, -1.5)
    assert o["pose_covariance"][:2] == [9.0, 1.0] and o["pose_covariance"][6] == 4.0
    assert o["pose_covariance"][20] == pytest.approx(0.01)


def test_lost_is_no_fix_and_heartbeats_come_once_a_second():
    enc = trnkit.MavlinkEncoder(messages=("gps_input",))
    sent = [frames(enc.encode(time_us=t, valid=False)) for t in range(0, 3_000_000, 250_000)]
    ids = [f[0] for step in sent for f in step]
    assert ids.count(0) == 3 and ids.count(232) == 12
    assert [f[1] for step in sent for f in step] == list(range(15)), "one sequence over every frame"
    lines = decode(b"".join(enc.encode(time_us=t, valid=False) for t in (3_000_000,)))
    gps = [l for l in lines if l.get("name") == "GPS_INPUT"][0]["fields"]
    assert (gps["fix_type"], gps["lat"], gps["ignore_flags"], gps["satellites_visible"]) == (1, 0, 255, 0)


@pytest.mark.parametrize("kwargs, word", [
    (dict(lat_deg=95.0, lon_deg=0.0), "lat_deg"),
    (dict(lat_deg=1.0, lon_deg=1.0, cov_nn=-1.0), "cov_nn"),
    (dict(lat_deg="41", lon_deg=1.0), "lat_deg"),
    (dict(lat_deg=math.nan, lon_deg=1.0), "valid needs"),
    (dict(lat_deg=1.0, lon_deg=1.0, processing_us=-1), "processing_us"),
])
def test_bad_values_name_their_keyword(kwargs, word):
    with pytest.raises(trnkit.Error, match=word):
        trnkit.MavlinkEncoder().encode(time_us=1, valid=True, **kwargs)


def test_bad_settings_name_their_keyword():
    with pytest.raises(trnkit.Error, match="messages: 'gps'"):
        trnkit.MavlinkEncoder(messages=("gps",))
    with pytest.raises(trnkit.Error, match="system_id=0"):
        trnkit.MavlinkEncoder(system_id=0)
    with pytest.raises(trnkit.Error, match="time_us=-1"):
        trnkit.MavlinkEncoder().encode(time_us=-1, valid=False)
    with pytest.raises(trnkit.Error, match="valid=1"):
        trnkit.MavlinkEncoder().encode(time_us=1, valid=1)
    assert trnkit.MavlinkEncoder().encode(time_us=numpy.uint64(1), valid=numpy.bool_(False))  # NumPy scalars are fine
    with pytest.raises(TypeError):
        trnkit.MavlinkEncoder().encode(1, True)  # keywords only: a position is never mistaken for another field
