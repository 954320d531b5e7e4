"""Localization from Python: the online DPC-PFL Localizer (trn::localize::Localizer), the rows of a
recorded AIR folder as a robot's sensors would feed it, and a whole flight at once.

Conventions: positions in map pixels (x east = column, y south = row, pixel centres at integers);
yaw and headings in RADIANS, clockwise from north; odometry in metres east/north since the previous
step; altitudes in metres above the ground. Same inputs and seed: the estimates of `trnkit localize`,
bit for bit."""
import inspect
import json
import math
import warnings

from . import _trnkit
from ._backend import Backend, YawUnitWarning

__all__ = ["Localizer", "load_gray", "load_map", "localize", "localizer_defaults", "read_air_folder"]

# The library's defaults (trn/localize/localizer_defaults.hpp: the one home of `trnkit localize`'s,
# the C API's and these): the keywords below take theirs from it.
_D = json.loads(_trnkit._localizer_settings())


class Localizer:
    """The online DPC-PFL localizer, built once and stepped once per camera frame.

    map: 2-D uint8 array (grey orthophoto); valid: its no-data (2-D uint8, same shape, non-zero
    valid; trnkit.load_validity) or None; metres_per_pixel: its resolution; backend: a
    trnkit.Backend (its keywords, e.g. threads=, cache_dir=, apply) or a spec string "cpu-ref", "cpu",
    "opencl[:N]", "vulkan[:N]" (a backend made and owned by the localizer; never a silent fallback).
    start: (x, y) map pixels, the last known position (required). start_heading_rad: centre of the
    initial headings in RADIANS (None: the first step's heading). camera_hfov_deg: the camera's
    horizontal field of view in degrees, needed when steps give altitude_agl_m or attitude.
    max_tilt_deg: frames tilted further from nadir are not scored. template_width: frames are
    downscaled to this width before scoring (0: full). sparse: share of template pixels scored.
    seed: same seed, same run. conversion ("logistic:0.2", "linear", "softmax", "rectifying:D"),
    sampling ("kld", "importance", "rejection"), min_particles / max_particles (KLD bounds; under
    "ours" the initial set is max_particles), particles (fixed count of importance / rejection
    sampling), init_radius_m (initial particles uniform within this radius of start),
    reinit_radius_m (after a collapse): the filter's settings (trn/filter/particle_filter.hpp); None
    takes the profile's value (ours: 100, 2000, 1000, 50 m, 300 m: localizer_defaults() has every
    default, the same as `trnkit localize`'s and the C API's). compassless_max_particles: with
    heading="none" and a uniform yaw prior, max_particles is raised to at least this (None: the
    profile's, ours 6000, dissertation 0; 0 when max_particles is given). profile: "ours" or
    "dissertation", the filter's reading of the text (docs/PROFILES.md: KLD quantile, initial set,
    motion model ...); lock_monitor: True / False, or None for the profile's (ours on, dissertation off). heading: "compass" (each
    step's heading_rad sets the particles' yaw) or "none" (no compass: yaw is estimated; the prior is
    uniform with start_heading_rad None, else Gaussian around it with start_heading_sd_deg degrees;
    each step then gives odometry=(right_m, forward_m) in the previous frame's axes and
    odometry_yaw_rad, the frame's rotation since then: read_air_folder's step_without_compass).
    map_origin: (latitude, longitude) in degrees of map pixel (0, 0) on a north-up map: estimates then
    also carry latitude_deg / longitude_deg (None: map pixels only). visual_odometry: True: a step
    given no odometry (None) takes it from its frame against the previous frame's, as `trnkit
    localize --odometry visual` does (scaled by the previous frame's scale or altitude, turned by the
    previous heading_rad, or with heading="none" by its own measured rotations); odometry given is
    used as given. Each estimate's "odometry_source" says which ("given", "none", "visual:...").

    Use it in a `with` block or call close() to release the map and the backend."""

    def __init__(self, map, metres_per_pixel, backend=_trnkit.DEFAULT_BACKEND, *, valid=None, start, start_heading_rad=None,
                 camera_hfov_deg=None, max_tilt_deg=_D["max_tilt_deg"], template_width=_D["template_width"], sparse=_D["sparse"],
                 seed=_D["seed"], conversion=_D["conversion"], sampling=_D["sampling"], min_particles=None, max_particles=None,
                 particles=None, init_radius_m=None, reinit_radius_m=None, heading=_D["heading"], start_heading_sd_deg=None,
                 profile="ours", lock_monitor=None, map_origin=None, compassless_max_particles=None,
                 visual_odometry=_D["visual_odometry"]):
        if start_heading_rad is not None and abs(start_heading_rad) > 2 * math.pi:
            warnings.warn(f"start_heading_rad={start_heading_rad} is beyond 2 pi: degrees? (math.radians converts)", YawUnitWarning,
                          stacklevel=2)
        self._own_backend = None  # a backend made here from a spec string, closed with the localizer
        if isinstance(backend, str):
            backend = self._own_backend = Backend(backend)
        self._impl = _user_terms(_trnkit._Localizer, "trnkit.Localizer")(
            map, metres_per_pixel, backend, valid=valid, start=tuple(start), start_heading_rad=start_heading_rad, camera_hfov_deg=camera_hfov_deg,
            max_tilt_deg=max_tilt_deg, template_width=template_width, sparse=sparse, seed=seed, conversion=conversion,
            sampling=sampling, min_particles=min_particles, max_particles=max_particles, particles=particles,
            init_radius_m=init_radius_m, reinit_radius_m=reinit_radius_m, heading=heading, start_heading_sd_deg=start_heading_sd_deg,
            profile=profile, lock_monitor=lock_monitor, map_origin=None if map_origin is None else tuple(map_origin),
            compassless_max_particles=compassless_max_particles, visual_odometry=visual_odometry)

    def step(self, frame=None, *, odometry=None, heading_rad=None, altitude_agl_m=None, scale=None, attitude=None,
             odometry_yaw_rad=None, time_s=None):
        """One camera frame and what the other sensors said since the previous step.

        frame: 2-D uint8 array, grey, as taken (None: no frame this step; the particles are moved,
        not scored). odometry: (east_m, north_m) displacement since the previous step, metres (None:
        lost). heading_rad: compass heading in RADIANS, clockwise from north (None: none). The frame's
        scale: altitude_agl_m (metres above the ground, with camera_hfov_deg) or scale (map pixels
        per frame pixel). attitude: (roll_rad, pitch_rad) in RADIANS: a tilted frame is warped to
        nadir; beyond max_tilt_deg it is not scored (too_oblique). odometry_yaw_rad (heading="none"):
        the frame's rotation since the previous step in RADIANS, clockwise (None: unknown); odometry
        is then (right_m, forward_m) in the previous frame's axes. time_s: when the frame was taken,
        seconds on one clock (None: unknown); the velocity needs two steps with it.

        Returns a dict: x, y, yaw (map pixels, radians), best_x, best_y, best_yaw, best_ncc (the
        best particle), spread_m, particles, off_map, frame_missing, too_oblique, tilt_deg (degrees),
        odometry_lost, reinitialised, odometry_source (the odometry used: "given", "none", or with
        visual_odometry "visual:start", "visual:features", "visual:phase", "visual:lost",
        "visual:no-frame"), lock_state ("none", "unknown", "ok", "weak", "inconsistent", "fix",
        "lost"), lock_contrast, lock_drift_m, score_ms, step_ms (milliseconds), yaw_sd (circular sd of the
        particles' yaws, radians: the heading's spread), the position's covariance in the map's frame
        (cov_xx_px2, cov_xy_px2, cov_yy_px2) and north/east in metres^2 (cov_nn_m2, cov_ne_m2,
        cov_ee_m2), eph_m (1 sigma, worst axis), latitude_deg / longitude_deg (with map_origin),
        time_s, vel_north_mps, vel_east_mps and vel_var_m2ps2 (None when unknown): typed in the
        package's stubs (Estimate)."""
        if heading_rad is not None and abs(heading_rad) > 2 * math.pi:
            warnings.warn(f"heading_rad={heading_rad} is beyond 2 pi: degrees? (math.radians converts)", YawUnitWarning, stacklevel=2)
        return _user_terms(self._impl.step, "trnkit.Localizer.step")(frame, odometry=odometry, heading_rad=heading_rad, altitude_agl_m=altitude_agl_m, scale=scale,
                               attitude=attitude, odometry_yaw_rad=odometry_yaw_rad, time_s=time_s)

    def reanchor(self, position, *, radius_m, heading_rad=None):
        """Re-anchors the filter on a new position, e.g. when a GNSS fix comes back: the particles
        scattered uniformly within radius_m METRES of position (x, y) map pixels, every setting kept;
        headings around heading_rad in RADIANS (None: without a compass the yaw learnt so far, with
        one the next step's heading). lock_state reads "unknown" again until the next fix; no velocity
        across the jump. Before the first step it starts the filter there. trnkit.Error off the map
        (naming its size) or with radius_m not > 0."""
        if heading_rad is not None and abs(heading_rad) > 2 * math.pi:
            warnings.warn(f"heading_rad={heading_rad} is beyond 2 pi: degrees? (math.radians converts)", YawUnitWarning, stacklevel=2)
        x, y = position
        _user_terms(self._impl.reanchor, "trnkit.Localizer.reanchor")((float(x), float(y)), radius_m=radius_m, heading_rad=heading_rad)

    def __copy__(self):
        raise TypeError("trnkit.Localizer cannot be copied: a copy would share the filter's state and device map with the "
                        "original (make a second Localizer from the same map and settings instead)")

    def __deepcopy__(self, memo):
        self.__copy__()

    def __reduce__(self):
        raise TypeError("trnkit.Localizer cannot be pickled: it holds a filter on a device (make one in each process)")

    def close(self):
        """Releases the map on the device now (and the backend when it was made from a spec string); a
        later step raises trnkit.Error. Closing the backend also releases every localizer built on it."""
        self._impl.close()
        if self._own_backend is not None:
            self._own_backend.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def _user_terms(function, name):
    """function, with pybind11's TypeError for arguments of the wrong type reworded in the terms of
    `name` (the public call), without the extension's internal names (trnkit._trnkit._Localizer)."""
    def call(*args, **kwargs):
        try:
            return function(*args, **kwargs)
        except TypeError as e:
            text = str(e)
            if "incompatible" not in text and "_trnkit" not in text:
                raise
            raise TypeError(f"{name}: an argument has the wrong type (numbers for positions, sizes and "
                            "angles, (x, y) tuples for start, position, odometry and attitude, 2-D uint8 arrays for map and "
                            "frame, a string or trnkit.Backend for backend: see help(trnkit.Localizer))") from None
    return call


def load_gray(path):
    """An image file (PNG, JPEG, TIFF ...) as a 2-D uint8 array, grey (trnkit.Error naming the file otherwise).
    It drops an alpha channel: for a map, load_map keeps its no-data as `trnkit localize` does."""
    return _trnkit._load_gray(path)


def load_map(path, nodata=None):
    """A map image as `trnkit localize` reads it: (map, valid), the grey 2-D uint8 array and its
    no-data (2-D uint8, 255 valid, 0 where alpha is 0, a GeoTIFF's mask or nodata, or where every
    colour channel equals nodata 0..255), or None when every pixel is valid: Localizer(map, ...,
    valid=valid) then leaves no-data out of every score, as the CLI does."""
    return _trnkit._load_map(path, nodata)


def load_validity(path, nodata=None):
    """An image file's no-data as a 2-D uint8 array (255 valid, 0 where alpha is 0 or, with nodata
    0..255, every colour channel equals it), or None when every pixel is valid: the map's `valid`."""
    return _trnkit._load_validity(path, nodata)


def read_air_folder(folder):
    """The rows of an AIR flight folder (metadata.csv + frames) as a robot's sensors would feed a Localizer.

    A list of dicts: row (0-based), filename, image_error ("" when the frame loaded), truth ((x, y)
    map pixels, or None) and step: the keyword arguments of Localizer.step for that row (frame as
    taken, odometry since the previous row in metres, heading_rad, altitude_agl_m, attitude in
    radians), so `loc.step(**row["step"])` feeds it; step_without_compass: the same for a
    Localizer(heading="none") (no heading, odometry in the previous frame's axes, odometry_yaw_rad
    from the ImuX..W heading's change)."""
    return _trnkit._read_air_folder(folder)


def localize(*, dataset, map="", backend=_trnkit.DEFAULT_BACKEND, metres_per_pixel=0.0, hfov_deg=0.0, fps=0.0,
             rate_hz=_trnkit.DEFAULT_RATE_HZ, start=None, start_heading_rad=None, odometry="recorded", max_tilt_deg=_D["max_tilt_deg"],
             template_width=_D["template_width"], sparse=_D["sparse"], seed=_D["seed"], conversion=_D["conversion"],
             sampling=_D["sampling"], min_particles=None, max_particles=None, particles=None, init_radius_m=None,
             reinit_radius_m=None, out="", plots=False, heading=_D["heading"], start_heading_sd_deg=None, nodata=None, profile="ours",
             lock_monitor=None, compassless_max_particles=None):
    """Localizes a whole AIR folder as `trnkit localize` does, with the same defaults
    (localizer_defaults(): a 50 m start prior under profile "ours", the text's 300 m under "dissertation").

    dataset: the AIR folder; map: the map image (default: the one flight.json names); backend: a
    trnkit.Backend or a spec string (then made for this flight and closed after it);
    metres_per_pixel, hfov_deg (degrees), fps: when flight.json does not say them (0: not given);
    rate_hz: filter steps per second; start: (x, y) map pixels (None: the first row's ground truth);
    start_heading_rad: RADIANS (None: the first heading); odometry: "recorded" (the folder's
    SvoX/SvoY) or "visual" (from the frames); out: a folder for localization.csv and summary.json
    ("" none; plots=True adds the gnuplot plots); heading="none": no compass (`trnkit localize
    --heading none`; start_heading_rad / start_heading_sd_deg then the yaw prior; the rows add
    estimate_yaw_sd and truth_yaw, the summary the heading figures). nodata: a map grey level
    (0..255) marking no-data besides the map's transparency (None: alpha only). The other keywords are
    Localizer's.

    Returns {"rows": dict of NumPy columns (frame, time_s, distance_m, truth_x, truth_y, odometry_x,
    odometry_y, estimate_x, estimate_y, estimate_yaw, error_m, odometry_error_m, particles,
    score_ms, estimate_lat, estimate_lon, cov_nn_m2, cov_ne_m2, cov_ee_m2, error_sigmas), "summary": summary.json's numbers, "backend",
    "metres_per_pixel", "start"}. Errors name the keyword (ValueError "dataset: ...")."""
    own = Backend(backend) if isinstance(backend, str) else None  # made for this flight, closed after it
    try:
        return _trnkit._localize(dataset=dataset, map=map, backend=backend if own is None else own, metres_per_pixel=metres_per_pixel,
                                 hfov_deg=hfov_deg, fps=fps, rate_hz=rate_hz, start=None if start is None else tuple(start), start_heading_rad=start_heading_rad,
                                 odometry=odometry, max_tilt_deg=max_tilt_deg, template_width=template_width, sparse=sparse, seed=seed,
                                 conversion=conversion, sampling=sampling, min_particles=min_particles, max_particles=max_particles,
                                 particles=particles, init_radius_m=init_radius_m, reinit_radius_m=reinit_radius_m, out=out,
                                 plots=plots, heading=heading, start_heading_sd_deg=start_heading_sd_deg,
                                 nodata=-1 if nodata is None else nodata, profile=profile, lock_monitor=lock_monitor,
                                 compassless_max_particles=compassless_max_particles)
    finally:
        if own is not None:
            own.close()


def localizer_defaults(profile="ours", heading="compass"):
    """The settings a Localizer(profile=..., heading=...) takes when no other keyword is given, under
    the names of docs/EMBEDDING.md's defaults table, as a dict (None where a value is unset: NaN).
    They come from the library's one home (trn/localize/localizer_defaults.hpp), which `trnkit
    localize --print-config` and the C API's trn_localizer_config_for_profile print too."""
    params = inspect.signature(Localizer.__init__).parameters
    keywords = {k: p.default for k, p in params.items()
                if p.kind == p.KEYWORD_ONLY and p.default is not p.empty and k not in ("valid", "map_origin")}
    keywords.update(profile=profile, heading=heading)
    settings = json.loads(_trnkit._localizer_settings(**keywords))
    settings.update(backend=params["backend"].default, profile=profile,
                    rate_hz=inspect.signature(localize).parameters["rate_hz"].default)
    return settings
