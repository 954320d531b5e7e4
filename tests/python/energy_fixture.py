"""A synthetic measurement run: a marker file as `trnkit frames` writes it and a power log in
trnkit's own format, with 2 W idle and 5 W while a sync burst or frame runs, sampled every
millisecond on a clock `offset_ms` ahead of the markers'. Every frame's true net energy is 0.6 J."""

T0_S = 1_700_000_000
FRAMES = 8


def timeline():
    rows, t, idle = [], 0, 0

    def add(kind, i, length):
        nonlocal t
        rows.append((kind, i, t, t + length))
        t += length

    add("idle", 0, 500)
    idle = 1
    for i, length in enumerate([300, 100, 200]):
        add("sync", i, length)
        add("idle", idle, 100)
        idle += 1
    for i in range(FRAMES):
        add("frame", i, 200)
        add("idle", idle, 100 if i + 1 < FRAMES else 500)
        idle += 1
    return rows


def write_run(folder, offset_ms=0):
    rows = timeline()
    markers = folder / "markers.csv"
    with open(markers, "w") as f:
        f.write("# trnkit-frames v1 backend=synthetic kernel=sobel\n"
                "kind,id,mono_start_ns,mono_end_ns,real_start_ns,real_end_ns,write_ms,exec_ms,read_ms\n")
        for kind, i, s, e in rows:
            f.write(f"{kind},{i},{s * 10**6},{e * 10**6},{T0_S * 10**9 + s * 10**6},{T0_S * 10**9 + e * 10**6},0,0,0\n")
    busy = [(s, e) for kind, _, s, e in rows if kind != "idle"]
    log = folder / f"power-{offset_ms}.csv"
    with open(log, "w") as f:
        f.write("# trnkit-power v1 kind=instant wall_clock=1\nt_s,power_w\n")
        for k in range(-200, rows[-1][3] + 200):
            ms = k + offset_ms + 1000  # from T0 - 1 s, never negative
            w = 5.0 if any(s <= k < e for s, e in busy) else 2.0
            f.write(f"{T0_S - 1 + ms // 1000}.{ms % 1000:03d},{w:.3f}\n")
    return log, markers
