"""Runs that outgrow one machine, on Dask: ``python3 -m filmgrain.distributed render|apply|analyze``.

The command line takes the ``filmgrain`` subcommand's own options (parsed by the same code)
plus ``--workers N`` (a local cluster of N worker processes) or ``--scheduler tcp://HOST:PORT``
(an existing Dask cluster). The same runs are the functions render_job, apply_job and
analyze_job, which take the subcommand's argument list and a dask.distributed Client.

- render: every (frame, tile) of a clip, every (channel, tile) of a still, is a task. Grains
  are seeded per cell, so the joined output equals ``filmgrain render`` byte for byte.
- apply: ranges of pictures are tasks. Y4M / raw YUV input with parameter files: a range
  starts in the state the stream has there, found by following the metadata of the pictures
  before it (Session.skip_picture), not by synthesizing them. A coded stream (.265, .264,
  .ivf, .obu, ...) goes through ``filmgrain decode --first-frame --frames``, which decodes a
  range from the random access point before it (an IDR or key frame the metadata scan shows
  is safe to start at; the stream's start where there is none). By default the ranges begin
  at those points, so that each decodes only what it writes; frames_per_task cuts them
  exactly there instead. Either way the output equals ``filmgrain apply`` /
  ``decode`` byte for byte, whatever the split.
- analyze: ranges of pictures are tasks, each reading the temporal neighbours beyond its ends;
  every analysed picture's observations come back and are fitted once in picture order:
  the same observations and sums, so the same parameters as ``filmgrain analyze``.

Each task writes its part under ``OUTPUT.parts/`` (a directory the workers and the driver
share) to a temporary name and renames it when complete; a retried or duplicated task (a
worker lost mid-task) rewrites the same bytes. The driver joins the parts in order, writes
the output through a temporary name and removes the parts.
"""
from __future__ import annotations

import argparse
import os
import shutil
import sys
import time
import uuid
from functools import lru_cache
from typing import Any, Callable, Iterable, Sequence

from . import _filmgrain

__all__ = ["render_job", "apply_job", "analyze_job", "connect", "main"]

_VIDEO_SUFFIXES = (".y4m", ".yuv")


# ----------------------------------------------------------------------------- parts


def _write_part(path: str, write: Callable[[str], Any]) -> Any:
    """Writes a part through a temporary name unique to this attempt, then renames it."""
    tmp = f"{path}.{uuid.uuid4().hex}.tmp"
    try:
        result = write(tmp)
        os.replace(tmp, path)
        return result
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def _parts_dir(output: str) -> str:
    d = os.path.abspath(output) + ".parts"
    os.makedirs(d, exist_ok=True)
    return d


class _Progress:
    def __init__(self, what: str, total: int, enabled: bool) -> None:
        self.what, self.total, self.enabled = what, total, enabled
        self.done, self.start, self.last = 0, time.monotonic(), 0.0

    def step(self) -> None:
        self.done += 1
        now = time.monotonic()
        if self.enabled and (now - self.last > 0.5 or self.done == self.total):
            self.last = now
            sys.stderr.write(f"\rfilmgrain.distributed {self.what}: {self.done}/{self.total} tasks, "
                             f"{now - self.start:.1f} s")
            if self.done == self.total:
                sys.stderr.write("\n")
            sys.stderr.flush()


def _gather_in_order(client: Any, futures: list, progress: _Progress) -> list:
    from distributed import as_completed
    for _ in as_completed(futures):
        progress.step()
    return client.gather(futures)


# ----------------------------------------------------------------------------- render


@lru_cache(maxsize=4)
def _render_job(args: tuple) -> Any:
    return _filmgrain.RenderJob(list(args))


def _render_video_task(args: tuple, k: int, tile: tuple, part: str) -> str:
    import numpy as np
    planes = _render_job(args).render_video_tile(k, *tile)
    _write_part(part, lambda tmp: np.savez(open(tmp, "wb"), *planes))
    return part


def _render_still_task(args: tuple, c: int, tile: tuple, part: str) -> str:
    import numpy as np
    channel = _render_job(args).render_still_tile(c, *tile)
    _write_part(part, lambda tmp: np.save(open(tmp, "wb"), channel))
    return part


def _tiles(width: int, height: int, size: int, align: tuple) -> list:
    size = max(align[0], align[1], size - size % max(align))
    return [(x, y, min(size, width - x), min(size, height - y))
            for y in range(0, height, size) for x in range(0, width, size)]


def render_job(args: Sequence[str], client: Any, *, tile: int = 0, progress: bool = False) -> None:
    """``filmgrain render`` with ``args`` (input, -o OUTPUT, options) on the cluster of ``client``.
    tile: tile size in output pixels (0: whole frames for a clip, 512 for a still)."""
    import numpy as np
    args = tuple(args)
    job = _filmgrain.RenderJob(list(args))
    output = _output_of(args)
    parts = _parts_dir(output)
    try:
        w, h = job.output_width, job.output_height
        if job.video:
            frames = job.frame_count
            if frames < 0:
                raise ValueError("distributed render needs a regular input file (not a pipe)")
            tiles = _tiles(w, h, tile or max(w, h), job.tile_alignment)
            tasks = [(k, t) for k in range(frames) for t in tiles]
            futures = [client.submit(_render_video_task, args, k, t, os.path.join(parts, f"{k}_{t[0]}_{t[1]}.npz"),
                                     pure=False) for k, t in tasks]
            _gather_in_order(client, futures, _Progress("render", len(futures), progress))
            info = job.output_info
            sx = 1 if info.pix_fmt.startswith(("yuv420", "yuv422")) else 0
            sy = 1 if info.pix_fmt.startswith("yuv420") else 0
            dtype = np.uint8 if info.bit_depth == 8 else np.uint16
            writer = _filmgrain.VideoWriter(output, info, job.output_y4m)
            gray = info.pix_fmt.startswith("gray")
            shapes = [(h, w)] if gray else [(h, w), ((h + sy) >> sy, (w + sx) >> sx), ((h + sy) >> sy, (w + sx) >> sx)]
            for k in range(frames):
                planes = [np.empty(s, dtype) for s in shapes]
                for t in tiles:
                    with np.load(os.path.join(parts, f"{k}_{t[0]}_{t[1]}.npz")) as z:
                        for c in range(len(planes)):
                            a = z[f"arr_{c}"]
                            x0, y0 = (t[0] >> sx, t[1] >> sy) if c else (t[0], t[1])
                            planes[c][y0:y0 + a.shape[0], x0:x0 + a.shape[1]] = a
                writer.write(planes, bit_depth=info.bit_depth)
            writer.commit()
        else:
            tiles = _tiles(w, h, tile or 512, (1, 1))
            tasks = [(c, t) for c in range(job.channels) for t in tiles]
            futures = [client.submit(_render_still_task, args, c, t, os.path.join(parts, f"{c}_{t[0]}_{t[1]}.npy"),
                                     pure=False) for c, t in tasks]
            _gather_in_order(client, futures, _Progress("render", len(futures), progress))
            channels = []
            for c in range(job.channels):
                full = np.empty((h, w), np.float32)
                for t in tiles:
                    a = np.load(os.path.join(parts, f"{c}_{t[0]}_{t[1]}.npy"))
                    full[t[1]:t[1] + a.shape[0], t[0]:t[0] + a.shape[1]] = a
                channels.append(full)
            job.write_still(output, channels)
    finally:
        shutil.rmtree(parts, ignore_errors=True)


# ----------------------------------------------------------------------------- apply


def _apply_range_task(args: tuple, first: int, end: int, part: str) -> int:
    job = _filmgrain.ApplyJob(list(args))
    return _write_part(part, lambda tmp: job.run_range(first, end, tmp))


def _decode_range_task(args: tuple, first: int, end: int, part: str) -> int:
    def run(tmp: str) -> int:
        a = list(args)
        if "--format" in a[:-1]:
            del a[a.index("--format"):a.index("--format") + 2]
        o = a.index("-o") if "-o" in a else a.index("--output")
        a[o + 1] = tmp
        _filmgrain.run_command(["decode", *a, "--format", "yuv", "--first-frame", str(first),
                                "--frames", str(end - first), "--quiet"])
        return end - first
    return _write_part(part, run)


def _ranges(count: int, per_task: int) -> list:
    return [(a, min(count, a + per_task)) for a in range(0, count, per_task)]


def _stream_ranges(count: int, per_task: int, restarts: Sequence[int]) -> list:
    """Ranges of at least per_task pictures that begin where decoding can begin (the
    stream's start or a restart point), so that no range decodes pictures it does not
    write. Without restart points, ranges of per_task (each decodes from the start)."""
    if not restarts:
        return _ranges(count, per_task)
    starts, a = [0], 0
    for r in restarts:
        if r >= a + per_task and r < count:
            starts.append(r)
            a = r
    return list(zip(starts, starts[1:] + [count]))


def apply_job(args: Sequence[str], client: Any, *, frames_per_task: int = 0, progress: bool = False,
              workers_hint: int = 2) -> None:
    """``filmgrain apply`` (args: -i INPUT -o OUTPUT options) or, when the first argument is a
    coded stream, ``filmgrain decode`` (args: INPUT -o OUTPUT options), in ranges of pictures."""
    args = tuple(args)
    output = _output_of(args)
    stream = not any(a.startswith("-") for a in args[:1]) and not args[0].lower().endswith(_VIDEO_SUFFIXES)
    parts = _parts_dir(output)
    try:
        if stream:
            count = int(_filmgrain.stream_picture_count(args[0]))
            if count == 0:
                raise ValueError(f"'{args[0]}' holds no picture the stream scanner sees")
            # frames_per_task given: ranges of exactly that many pictures (each decoding from
            # the restart point before it); by default, ranges that begin at restart points
            per = frames_per_task or max(1, -(-count // (4 * workers_hint)))
            ranges = _ranges(count, per) if frames_per_task else \
                _stream_ranges(count, per, _filmgrain.stream_restart_points(args[0]))
            futures = [client.submit(_decode_range_task, args, a, b, os.path.join(parts, f"{a:09d}.yuv"), pure=False)
                       for a, b in ranges]
            _gather_in_order(client, futures, _Progress("decode", len(futures), progress))
            # the size, format and rate of `filmgrain decode`'s output, from its first picture
            head = os.path.join(parts, "head.y4m")
            a = list(args)
            o = a.index("-o") if "-o" in a else a.index("--output")
            a[o + 1] = head
            fmt = a[a.index("--format") + 1] if "--format" in a[:-1] else ""
            if fmt:
                del a[a.index("--format"):a.index("--format") + 2]
            _filmgrain.run_command(["decode", *a, "--format", "y4m", "--frames", "1", "--no-grain", "--quiet"])
            info = _filmgrain.VideoReader(head).info
            y4m = fmt == "y4m" or (not fmt and not output.lower().endswith(".yuv"))
            _join_frames(output, info, y4m, [os.path.join(parts, f"{a:09d}.yuv") for a, _ in ranges])
        else:
            job = _filmgrain.ApplyJob(list(args))
            count = job.frame_count
            if count < 0:
                raise ValueError("distributed apply needs a regular input file (not a pipe)")
            per = frames_per_task or max(1, -(-count // (4 * workers_hint)))
            ranges = _ranges(count, per)
            futures = [client.submit(_apply_range_task, args, a, b, os.path.join(parts, f"{a:09d}.yuv"), pure=False)
                       for a, b in ranges]
            _gather_in_order(client, futures, _Progress("apply", len(futures), progress))
            _join_frames(output, job.output_info, job.output_y4m,
                         [os.path.join(parts, f"{a:09d}.yuv") for a, _ in ranges])
    finally:
        shutil.rmtree(parts, ignore_errors=True)


def _join_frames(output: str, info: Any, y4m: bool, parts: list) -> None:
    # the parts' raw frames, in order, through the writer the commands use (its header, and
    # the output appears only when complete)
    writer = _filmgrain.VideoWriter(output, info, y4m)
    for p in parts:
        with open(p, "rb") as f:
            while chunk := f.read(info.frame_bytes):
                writer.write_raw(chunk, info)
    writer.commit()


# ----------------------------------------------------------------------------- analyze


def _analyze_range_task(args: tuple, first: int, end: int, part: str) -> str:
    import pickle
    records = _filmgrain.AnalysisJob(list(args)).observe_range(first, end)
    _write_part(part, lambda tmp: pickle.dump(records, open(tmp, "wb")))
    return part


def analyze_job(args: Sequence[str], client: Any, *, frames_per_task: int = 0, progress: bool = False,
                workers_hint: int = 2) -> None:
    """``filmgrain analyze`` (args: INPUT --model M -o OUTPUT options) in ranges of pictures."""
    import pickle
    if not _filmgrain.have_analysis:
        raise ValueError("analyze needs OpenCV (libopencv-dev); rebuild after tools/install-deps")
    args = tuple(args)
    job = _filmgrain.AnalysisJob(list(args))
    count = job.frame_count
    if count < 0:
        raise ValueError("distributed analyze needs a regular input file (not a pipe)")
    step = job.frame_step
    per = frames_per_task or max(step, -(-count // (4 * workers_hint)))
    ranges = _ranges(count, per)
    parts = _parts_dir(_output_of(args))
    try:
        futures = [client.submit(_analyze_range_task, args, a, b, os.path.join(parts, f"{a:09d}.obs"), pure=False)
                   for a, b in ranges]
        paths = _gather_in_order(client, futures, _Progress("analyze", len(futures), progress))
        records: list = []
        for p in paths:
            with open(p, "rb") as f:
                records += pickle.load(f)
        job.fit_and_write(records, count)
    finally:
        shutil.rmtree(parts, ignore_errors=True)


# ----------------------------------------------------------------------------- driver


def _output_of(args: Sequence[str]) -> str:
    for i, a in enumerate(args):
        if a in ("-o", "--output") and i + 1 < len(args):
            return args[i + 1]
        if a.startswith("--output="):
            return a.split("=", 1)[1]
    raise ValueError("give the output with -o OUTPUT")


def connect(workers: int = 0, scheduler: str | None = None) -> Any:
    """A Client of an existing cluster (scheduler) or of a local cluster of ``workers`` processes."""
    from distributed import Client, LocalCluster
    if scheduler:
        return Client(scheduler)
    cluster = LocalCluster(n_workers=max(1, workers or os.cpu_count() or 1), threads_per_worker=1, processes=True,
                           dashboard_address=None)
    return Client(cluster)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python3 -m filmgrain.distributed",
        description="filmgrain render / apply / analyze on a Dask cluster; the subcommand's own options follow it.")
    parser.add_argument("command", choices=["render", "apply", "analyze"])
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, default=0, help="a local cluster of N worker processes")
    where.add_argument("--scheduler", help="an existing Dask scheduler, tcp://HOST:PORT")
    parser.add_argument("--tile", type=int, default=0, help="render: tile size in output pixels")
    parser.add_argument("--frames-per-task", type=int, default=0,
                        help="apply, analyze: pictures per task (default: a quarter of the pictures per worker; "
                             "a coded stream's default ranges begin at its random access points)")
    parser.add_argument("--no-progress", action="store_true", help="no progress line on stderr")
    known, rest = parser.parse_known_args(argv)
    if known.workers < 0:
        parser.error(f"--workers {known.workers} is out of range (allowed 1..)")
    try:
        with connect(known.workers, known.scheduler) as client:
            n = len(client.scheduler_info().get("workers", {})) or 1
            if known.command == "render":
                render_job(rest, client, tile=known.tile, progress=not known.no_progress)
            elif known.command == "apply":
                apply_job(rest, client, frames_per_task=known.frames_per_task, progress=not known.no_progress,
                          workers_hint=n)
            else:
                analyze_job(rest, client, frames_per_task=known.frames_per_task, progress=not known.no_progress,
                            workers_hint=n)
    except (ValueError, OSError, RuntimeError) as e:
        sys.stderr.write(f"filmgrain.distributed: error: {e}\n")
        return 2 if isinstance(e, ValueError) else 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
