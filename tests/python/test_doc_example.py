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
