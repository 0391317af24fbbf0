#!/usr/bin/python3
"""Throughput of python3 -m filmgrain.distributed with 1 and 2 local workers (docs/SCALE.md).
Runs render / apply / analyze on clips it makes, alternating 1 and 2 workers, and prints the
median and range of each, and the same-run speed-up. Not a test: no time is asserted.

    PYTHONPATH=build/python /usr/bin/python3 bench/distributed_scale.py [repeats]
"""
import statistics
import subprocess
import sys
import tempfile
import time
import os

import numpy as np

from filmgrain import distributed

TOOL = os.environ.get("FILMGRAIN_TOOL", "build/filmgrain")


def y4m(path, w, h, n, seed=0):
    rng = np.random.default_rng(seed)
    with open(path, "wb") as f:
        f.write(f"YUV4MPEG2 W{w} H{h} F25:1 Ip A1:1 C420jpeg\n".encode())
        for k in range(n):
            f.write(b"FRAME\n" + rng.integers(30, 220, (h, w), np.uint8).tobytes()
                    + np.full((h // 2, w // 2), 128, np.uint8).tobytes() * 2)


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    d = tempfile.mkdtemp(prefix="fg-scale-")
    y4m(f"{d}/render.y4m", 256, 256, 4)
    y4m(f"{d}/apply.y4m", 1920, 1080, 60, seed=1)
    sei = "conformance/rdd5_352x288_420p8/frame0.fgc.bin"
    jobs = {
        "render 4 x 256x256, N=800, whole frames": (distributed.render_job,
                                                   [f"{d}/render.y4m", "-o", f"{d}/r.y4m", "--samples", "800",
                                                    "--threads", "1", "-q"], {"tile": 256}),
        "render 4 x 256x256, N=800, 128-pixel tiles": (distributed.render_job,
                                                      [f"{d}/render.y4m", "-o", f"{d}/r.y4m", "--samples", "800",
                                                       "--threads", "1", "-q"], {"tile": 128}),
        "apply 60 x 1080p rdd5": (distributed.apply_job,
                                  ["-i", f"{d}/apply.y4m", "-o", f"{d}/a.y4m", "--sei", sei, "--threads", "1", "-q"],
                                  {"frames_per_task": 8}),
    }
    from distributed import Client, LocalCluster
    clients = {n: Client(LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None))
               for n in (1, 2)}
    for name, (fn, args, kw) in jobs.items():
        times = {1: [], 2: []}
        for _ in range(repeats):
            for n in (1, 2):
                t0 = time.perf_counter()
                fn(args, clients[n], **kw)
                times[n].append(time.perf_counter() - t0)
        ratios = [a / b for a, b in zip(times[1], times[2])]
        print(f"{name}: 1 worker median {statistics.median(times[1]):.2f} s "
              f"[{min(times[1]):.2f}, {max(times[1]):.2f}], 2 workers {statistics.median(times[2]):.2f} s "
              f"[{min(times[2]):.2f}, {max(times[2]):.2f}], speed-up median {statistics.median(ratios):.2f} "
              f"[{min(ratios):.2f}, {max(ratios):.2f}]")
    t0 = time.perf_counter()
    subprocess.run([TOOL, "render", f"{d}/render.y4m", "-o", f"{d}/cli.y4m", "--samples", "800", "--threads", "1", "-q"],
                   check=True)
    print(f"filmgrain render (one process, 1 thread): {time.perf_counter() - t0:.2f} s")


if __name__ == "__main__":
    main()
