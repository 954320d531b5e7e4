"""Device work runs without the GIL: another Python thread progresses during a long score, and
threads sharing one backend are serialised (a trn::Backend is not thread-safe)."""
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import trnkit
from conftest import texture

MAP = texture(600, 600, seed=2)
TEMPLATE = MAP[200:264, 250:314]


def random_poses(n, seed=1):
    rng = np.random.default_rng(seed)
    return np.column_stack([rng.uniform(50, 550, (n, 2)), rng.uniform(-3, 3, n), rng.uniform(0.8, 1.2, n)])


def test_a_thread_progresses_during_a_long_score():
    b = trnkit.Backend("cpu-ref")  # one thread, so the call is long and leaves the other core free
    m = b.upload_map(MAP)
    n = 1000
    while True:  # a call of at least 0.3 s, whatever the machine
        poses = random_poses(n)
        t0 = time.perf_counter()
        b.score(m, TEMPLATE, poses)
        call_s = time.perf_counter() - t0
        if call_s > 0.3 or n >= 1 << 20:
            break
        n *= 2
    ticks, stop = [], threading.Event()

    def spin():
        while not stop.is_set():
            ticks.append(time.perf_counter())

    t = threading.Thread(target=spin)
    t.start()
    time.sleep(0.05)
    t0 = time.perf_counter()
    b.score(m, TEMPLATE, poses)
    t1 = time.perf_counter()
    stop.set()
    t.join()
    # Holding the GIL, the call would leave the spinner no tick from the first switch interval
    # (5 ms) until the call returns (and the spinner may run on while the caller waits for the GIL
    # afterwards, so only the first half of the calibrated call time counts).
    during = [x for x in ticks if t0 + 0.02 < x < t0 + call_s / 2]
    assert t1 - t0 > 0.2
    assert len(during) > 1000, f"{len(during)} ticks in the first {call_s / 2:.2f} s of scoring: the GIL was held"


def test_threads_sharing_a_backend_get_serial_results():
    b = trnkit.Backend("cpu")
    m = b.upload_map(MAP)
    batches = [random_poses(2000, seed=s) for s in range(6)]
    serial = [b.score(m, TEMPLATE, p) for p in batches]
    with ThreadPoolExecutor(4) as pool:
        parallel = list(pool.map(lambda p: b.score(m, TEMPLATE, p), batches))
    for s, p in zip(serial, parallel):
        np.testing.assert_array_equal(s, p)
