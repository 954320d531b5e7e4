"""One table of the online Localizer's defaults (docs/EMBEDDING.md, "Defaults"): C++, the C API,
Python and `trnkit localize` must give every one the same, by the same name. Each front end is read
its own way (C++ and C: tests/capi/print_defaults.cpp; Python: trnkit.localizer_defaults(), which
reads Localizer's own signature; the CLI: --print-config), so a default changed in one of them alone
fails here."""
import json
import os
import subprocess

import numpy as np
import pytest

import trnkit

CLI = os.environ.get("TRNKIT_EXE")
PRINTER = os.environ.get("TRN_PRINT_DEFAULTS")
# Every name of the table; those the C API has no field for: it takes a backend object and steps
# one observation at a time.
NAMES = ["seed", "conversion", "sampling", "heading", "min_particles", "max_particles", "particles", "compassless_max_particles",
         "init_radius_m", "reinit_radius_m", "start_heading_sd_deg", "compassless_yaw_sd_deg", "lock_monitor", "max_tilt_deg",
         "template_width", "sparse", "camera_hfov_deg", "start_heading_rad", "visual_odometry"]
NOT_IN_C = ["backend", "rate_hz"]


def cli(*args):
    if not CLI:
        pytest.skip("TRNKIT_EXE not set (ctest sets it)")
    out = subprocess.run([CLI, "localize", "--print-config", *args], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def native(profile):
    if not PRINTER:
        pytest.skip("TRN_PRINT_DEFAULTS not set (ctest sets it)")
    out = subprocess.run([PRINTER, profile], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


@pytest.mark.parametrize("profile", ["ours", "dissertation"])
def test_every_front_end_has_the_same_defaults(profile):
    both = native(profile)
    cxx, c = both["cxx"], both["c"]
    py = trnkit.localizer_defaults(profile)
    command = cli("--profile", profile)
    for name in NAMES + NOT_IN_C:
        assert py[name] == cxx[name], f"{name}: Python {py[name]!r}, C++ {cxx[name]!r}"
        assert command[name] == cxx[name], f"{name}: trnkit localize {command[name]!r}, C++ {cxx[name]!r}"
    for name in NAMES:
        # NULL strings in the C struct mean the library's default (trnkit.h says which).
        got = c[name] if c[name] is not None or name not in ("conversion", "sampling", "heading") else cxx[name]
        assert got == cxx[name], f"{name}: C {c[name]!r}, C++ {cxx[name]!r}"
    assert c["profile"] == cxx["profile"] == py["profile"] == command["profile"] == profile


def test_the_cli_defaults_are_the_handover_ones():
    # The values docs/RESULTS.md's real-flight figures were measured with (the CLI's since issue 24).
    d = trnkit.localizer_defaults()
    assert (d["init_radius_m"], d["compassless_max_particles"], d["compassless_yaw_sd_deg"], d["backend"]) == (50, 6000, 10, "fastest")
    assert trnkit.localizer_defaults("dissertation")["init_radius_m"] == 300


def test_without_a_compass_the_same_settings_and_the_same_rule():
    py, command = trnkit.localizer_defaults(heading="none"), cli("--heading", "none")
    for name in NAMES + NOT_IN_C:
        assert py[name] == command[name], f"{name} (heading none): Python {py[name]!r}, trnkit localize {command[name]!r}"
    # A count given is the count, in both.
    assert trnkit.localizer_defaults(heading="none")["compassless_max_particles"] == 6000
    given = cli("--heading", "none", "--max-particles", "3000")
    assert (given["max_particles"], given["compassless_max_particles"]) == (3000, 0)
    # The rule runs in the library: a uniform yaw prior starts with the raised set.
    rng = np.random.default_rng(1)
    ortho = rng.integers(0, 256, (200, 200), dtype=np.uint8)
    with trnkit.Localizer(ortho, 1.0, "cpu", start=(100, 100), heading="none") as loc:
        assert loc.step(None, odometry=(0.0, 0.0))["particles"] == 6000
    with trnkit.Localizer(ortho, 1.0, "cpu", start=(100, 100), heading="none", max_particles=3000) as loc:
        assert loc.step(None, odometry=(0.0, 0.0))["particles"] == 3000


def test_visual_odometry_is_off_unless_asked_and_the_cli_names_it_odometry_visual():
    assert trnkit.localizer_defaults()["visual_odometry"] is False
    assert cli()["visual_odometry"] is False
    assert cli("--odometry", "visual")["visual_odometry"] is True


def test_the_doc_table_names_every_default():
    with open(os.environ["TRN_EMBEDDING_DOC"]) as f:
        doc = f.read()
    table = doc[doc.index("## Defaults"):doc.index("## ", doc.index("## Defaults") + 3)]
    for name in NAMES:
        assert f"`{name}`" in table, f"{name}: not in docs/EMBEDDING.md's defaults table"


def test_print_config_reads_nothing():
    # No --dataset needed; without --print-config it is required, as before.
    assert cli()["backend"] == "fastest"
    out = subprocess.run([CLI, "localize"], capture_output=True, text=True)
    assert out.returncode != 0 and "--dataset is required" in out.stderr
