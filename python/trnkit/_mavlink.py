"""MAVLink v2 out: an estimate as the frames an autopilot takes (docs/AUTOPILOT.md), over the C++
module `trnkit localize --mavlink` uses (trn/io/mavlink_stream.hpp), so the bytes are the same.

    import socket, trnkit
    encoder = trnkit.MavlinkEncoder(messages=("gps_input",))          # ArduPilot: GPS1_TYPE 14 (MAV)
    udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    udp.sendto(encoder.encode(time_us=t, valid=True, lat_deg=lat, lon_deg=lon, spread_m=e.spread_m),
               ("127.0.0.1", 14550))
"""
from __future__ import annotations

import math
import numbers
from collections.abc import Iterable

import numpy

from . import _trnkit

__all__ = ["MavlinkEncoder"]

_MESSAGES = {"gps_input": 1, "global_position": 2, "odometry": 4}
_FLOATS = ("lat_deg", "lon_deg", "alt_msl_m", "north_m", "east_m", "cov_nn", "cov_ne", "cov_ee", "spread_m", "vel_north", "vel_east",
           "vel_var", "yaw_rad", "yaw_var")


def _whole(value, keyword: str, lo: int, hi: int) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or not lo <= value <= hi:
        raise _trnkit.Error(f"{keyword}={value!r}: expected a whole number in [{lo}, {hi}]")
    return int(value)


class MavlinkEncoder:
    """Encodes one estimate per call as MAVLink v2 frames: a HEARTBEAT whenever a second of time_us
    has passed since the last (and first), then GPS_INPUT (232), GLOBAL_POSITION_SENSOR (296) and
    ODOMETRY (331), those named in messages ("gps_input", "global_position", "odometry"). One
    sequence number runs over every frame. system_id / component_id: the sender's ids (1, the
    vehicle's; 197, MAV_COMP_ID_VISUAL_INERTIAL_ODOMETRY). sensor_id: GPS_INPUT's gps_id and
    GLOBAL_POSITION_SENSOR's id. satellites: GPS_INPUT's satellites_visible with a fix (there are
    none; ArduPilot refuses fewer than 6)."""

    def __init__(self, *, system_id: int = 1, component_id: int = 197,
                 messages: Iterable[str] = ("gps_input", "global_position", "odometry"), sensor_id: int = 0, satellites: int = 10):
        if isinstance(messages, str):
            messages = (messages,)
        bits = 0
        for name in messages:
            if name not in _MESSAGES:
                raise _trnkit.Error(f"messages: {name!r} is not one of 'gps_input', 'global_position' (GLOBAL_POSITION_SENSOR), 'odometry'")
            bits |= _MESSAGES[name]
        if not bits:
            raise _trnkit.Error("messages: empty; name at least one of 'gps_input', 'global_position', 'odometry'")
        self._stream = _trnkit._MavlinkStream(_whole(system_id, "system_id", 1, 255), _whole(component_id, "component_id", 1, 255), bits,
                                              _whole(sensor_id, "sensor_id", 0, 255), _whole(satellites, "satellites", 0, 255))

    def encode(self, *, time_us: int, valid: bool, reset: bool = False, lat_deg: float = math.nan, lon_deg: float = math.nan,
               alt_msl_m: float = math.nan, north_m: float = math.nan, east_m: float = math.nan, cov_nn: float = math.nan,
               cov_ne: float = math.nan, cov_ee: float = math.nan, spread_m: float = math.nan, vel_north: float = math.nan,
               vel_east: float = math.nan, vel_var: float = math.nan, yaw_rad: float = math.nan, yaw_var: float = math.nan,
               processing_us: int = 0) -> bytes:
        """The frames for one estimate (send them as one UDP datagram, or write them to a serial port).

        time_us: the frame's time, microseconds (UNIX epoch or since boot). valid: False while the
        filter is lost (then "no fix" is sent). reset: the estimate jumped (ODOMETRY's reset_counter
        steps). lat_deg, lon_deg (WGS84), alt_msl_m; north_m, east_m: the position in a fixed local
        frame (ODOMETRY); cov_nn, cov_ne, cov_ee: horizontal position covariance in m^2, or spread_m
        (the rms distance of the estimate's samples) without one; vel_north, vel_east in m/s and
        vel_var per axis; yaw_rad clockwise from true north and yaw_var; processing_us: frame to
        message. NaN (the default): not known. Out-of-range values raise trnkit.Error naming the field."""
        values = dict(lat_deg=lat_deg, lon_deg=lon_deg, alt_msl_m=alt_msl_m, north_m=north_m, east_m=east_m, cov_nn=cov_nn, cov_ne=cov_ne,
                      cov_ee=cov_ee, spread_m=spread_m, vel_north=vel_north, vel_east=vel_east, vel_var=vel_var, yaw_rad=yaw_rad,
                      yaw_var=yaw_var)
        for keyword in _FLOATS:
            v = values[keyword]
            if isinstance(v, bool) or not isinstance(v, numbers.Real):
                raise _trnkit.Error(f"{keyword}={v!r}: expected a number (NaN: not known)")
            values[keyword] = float(v)
        for keyword, flag in (("valid", valid), ("reset", reset)):
            if not isinstance(flag, (bool, numpy.bool_)):  # 1 or "yes" would be a guess
                raise _trnkit.Error(f"{keyword}={flag!r}: expected True or False")
        return self._stream.encode(_whole(time_us, "time_us", 0, 2**64 - 1), bool(valid), bool(reset), processing_us=_whole(
            processing_us, "processing_us", 0, 2**32 - 1), **values)
