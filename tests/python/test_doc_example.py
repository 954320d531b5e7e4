"""docs/EMBEDDING.md's Python examples, read from the doc and run: five lines score 1000 particles
on OpenCL, and the results equal cpu-ref's on the same inputs."""
import os
import re

import numpy as np
import pytest

import trnkit
from conftest import backend_or_skip


def doc_example(name):
    with open(os.environ["TRN_EMBEDDING_DOC"]) as f:
        text = f.read()
    m = re.search(r"<!-- example: " + re.escape(name) + r" -->\n```python\n(.*?)\n```", text, re.S)
    assert m, f"no example {name} in {os.environ['TRN_EMBEDDING_DOC']}"
    return m.group(1)


def test_five_lines_score_1000_particles_on_opencl(capsys):
    backend_or_skip("opencl")  # skips (or fails when required) without a device, before running the doc
    five = doc_example("five_lines.py")
    assert len([l for l in five.splitlines() if l.strip()]) == 5, five
    ns = {}
    exec(compile(five, "EMBEDDING.md:five_lines.py", "exec"), ns)
    scores, poses, ortho = ns["scores"], ns["poses"], ns["ortho"]
    assert ns["backend"].name.startswith("opencl")
    assert scores.shape == (1000,) and scores.dtype == trnkit.SCORE_DTYPE
    ref = trnkit.Backend("cpu-ref")
    want = ref.score(ref.upload_map(ortho), ortho[300:348, 400:464], poses)
    np.testing.assert_array_equal(scores["valid_samples"], want["valid_samples"])
    np.testing.assert_array_equal(scores["flags"], want["flags"])
    np.testing.assert_allclose(scores["ncc"], want["ncc"], atol=1e-4)

    exec(compile(doc_example("more.py"), "EMBEDDING.md:more.py", "exec"), ns)
    out = capsys.readouterr().out
    assert "true pose: ncc 1.000" in out, out
    assert ns["gx"].shape == ortho.shape and len(ns["valid"]) == (scores["flags"] == 0).sum()

    exec(compile(doc_example("keywords.py"), "EMBEDDING.md:keywords.py", "exec"), ns)
    assert ns["scores"] is ns["out"] and ns["cpu"].closed
    np.testing.assert_array_equal(ns["out"], ref.score(ref.upload_map(ortho), ns["plan"], poses))
    assert "execute" in capsys.readouterr().out


def test_live_energy_example(tmp_path, capsys):
    """The live-energy example on a fake hwmon rail instead of RAPL (the doc's source string replaced)."""
    chip = tmp_path / "class" / "hwmon" / "hwmon0"
    chip.mkdir(parents=True)
    (chip / "name").write_text("ina226\n")
    (chip / "power1_input").write_text("4000000\n")
    text = doc_example("live_energy.py")
    assert '"rapl:package-0"' in text
    text = text.replace('"rapl:package-0"', f'"hwmon:ina226", sysfs_root={str(tmp_path)!r}')
    ortho = np.random.default_rng(0).integers(0, 256, (300, 300), dtype=np.uint8)
    backend = trnkit.Backend("cpu")
    # calls long enough for several polls at 5 ms (fewer than 3 samples flag a frame unusable)
    ns = {"trnkit": trnkit, "backend": backend, "map_on_gpu": backend.upload_map(ortho), "plan": trnkit.plan(ortho[:100, :100]),
          "batches": [np.array([[150.0, 150.0, 0.0, 1.0]] * 4000)] * 3}
    exec(compile(text, "EMBEDDING.md:live_energy.py", "exec"), ns)
    report = ns["report"]
    assert len(report["net_j"]) == 3 and report["usable"].all(), report["flag"]
    assert report["idle_w"] == pytest.approx(4.0) and np.all(np.abs(report["net_j"]) < 1e-9)  # a constant rail: nothing above idle
    assert "J above idle per call" in capsys.readouterr().out
