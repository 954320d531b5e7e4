#!/usr/bin/env bash
# scripts/bench-report on fixed bench.json files (tests/bench/data): each speed target of issue 14
# is reported as a ratio of two rates from the same run with met / not met, and as "not measured"
# when the run lacks one side (here: no old cpu path, no filter case); issue 28's CUDA ratio; and
# issue 43's frame-to-MAVLink latency table.
# usage: report_issue14_targets.sh REPO_ROOT WORK_DIR
set -uo pipefail
repo=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
fail=0
report() {  # fixture -> $work/<name>/report.md
  local out="$work/${1%.json}"
  if ! "$repo/scripts/bench-report" --from-json "$repo/tests/bench/data/$1" --out "$out" > "$out.log" 2>&1; then
    echo "FAIL $1: bench-report exited non-zero:"; cat "$out.log"; fail=1
  fi
}
expect() {  # fixture, text the report must hold on one line
  if grep -qF -- "$2" "$work/${1%.json}/report.md"; then echo "ok   $1: $2"
  else echo "FAIL $1: no line with: $2"; fail=1; fi
}
report ncc_issue14_targets.json
expect ncc_issue14_targets.json "NCC cpu 640x480 dense >= 1.5x the old cpu backend: **met** — 12.0 vs 6.00 particles/s = 2.00x"
expect ncc_issue14_targets.json "NCC cpu 640x480 dense >= 30x particle_match: **not met** — 12.0 vs 0.500 particles/s = 24.00x"
expect ncc_issue14_targets.json "the filter's case, >= 2x the old cpu backend: **not met** — 400 vs 250 particles/s = 1.60x"
expect ncc_issue14_targets.json "NCC on PoCL (opencl:0) >= 0.6x cpu: **met** — 9.00 vs 12.0 particles/s = 0.75x"
expect ncc_issue14_targets.json "NCC on lavapipe (vulkan:0) >= 0.5x cpu: **not met** — 5.00 vs 12.0 particles/s = 0.42x"
expect ncc_issue14_targets.json "the filter's case (160x120 dense N1000): 0.25x cpu"
report ncc_without_old_path.json
expect ncc_without_old_path.json "NCC cpu 640x480 dense >= 1.5x the old cpu backend: not measured in this run"
expect ncc_without_old_path.json "NCC cpu 160x120 dense (the filter's case) >= 2x the old cpu backend: not measured in this run"
# Issue 28: CUDA against the faster of OpenCL and Vulkan on the same GPU (by device name).
report ncc_cuda_beside_peers.json
expect ncc_cuda_beside_peers.json "NCC filter case on cuda:0 (NVIDIA H200) >= 1.0x the faster of OpenCL and Vulkan on the same device: **not met** — 360 vs vulkan:0 400 particles/s = 0.90x"
expect ncc_cuda_beside_peers.json "random-gather limit: not measured"
# The machine and the cpu loop the cpu rows measured (a board's run names its NEON loop).
expect ncc_cuda_beside_peers.json "Architecture: aarch64; cpu backend: 12 threads (TRN_CPU_THREADS), 12 hardware threads, inner loop NEON"
expect ncc_issue14_targets.json "No CUDA device in this run: the CUDA targets were not measured."
# Issue 43: the frame-to-MAVLink latency table, ratios to cpu as the bench computed them, an error row kept.
report latency_frame_to_mavlink.json
expect latency_frame_to_mavlink.json "## Frame to MAVLink message, realflight3 (issue 43 item 5)"
expect latency_frame_to_mavlink.json "| cpu | 50.0 | 100 | 55.0 | 120 | 0.0200 | 167 | — | — |"
expect latency_frame_to_mavlink.json "| opencl:0 | 125 | 300 | 130 | 310 | 0.0300 | 167 | 2.50 | 3.00 |"
expect latency_frame_to_mavlink.json "| vulkan:0 | error: fixture error ||||||||"
exit $fail
