"""python3 -m filmgrain.distributed on a LocalCluster of 2 worker processes: render, apply
(parameter files and coded streams) and analyze equal the single-process commands byte for
byte, whatever the split, and a worker killed mid-run changes nothing."""
from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import filmgrain
from filmgrain import distributed
from conftest import CONFORMANCE, ROOT, SEI_STREAM_TOOL, md5_of, run_tool


@pytest.fixture(scope="module")
def client():
    from distributed import Client, LocalCluster
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    c = Client(cluster)
    yield c
    c.close()
    cluster.close()


def write_y4m(path, frames, w, h):
    with open(path, "wb") as f:
        f.write(f"YUV4MPEG2 W{w} H{h} F25:1 Ip A1:1 C420jpeg\n".encode())
        for y, u, v in frames:
            f.write(b"FRAME\n" + y.tobytes() + u.tobytes() + v.tobytes())


def clip(w, h, n, seed=0, scenes=1):
    rng = np.random.default_rng(seed)
    frames = []
    for k in range(n):
        s = k * scenes // n
        xx, yy = np.meshgrid(np.arange(w), np.arange(h))
        base = (40 + 60 * s + 0.5 * (xx + 2 * k) % 120 + 0.3 * yy).clip(16, 235)
        y = (base + rng.normal(0, 1, (h, w))).clip(0, 255).astype(np.uint8)
        u = np.full((h // 2, w // 2), 100 + 20 * s, np.uint8)
        v = np.full((h // 2, w // 2), 150 - 10 * s, np.uint8)
        frames.append((y, u, v))
    return frames


def test_render_clip_tiles_equal_cli(client, tmp_path):
    src = tmp_path / "in.y4m"
    write_y4m(src, clip(96, 64, 4), 96, 64)
    args = [str(src), "-o", str(tmp_path / "dist.y4m"), "--samples", "48", "--radius", "0.25", "--planes", "all", "-q"]
    distributed.render_job(args, client, tile=32)
    run_tool("render", str(src), "-o", str(tmp_path / "cli.y4m"), "--samples", "48", "--radius", "0.25",
             "--planes", "all", "-q")
    assert (tmp_path / "dist.y4m").read_bytes() == (tmp_path / "cli.y4m").read_bytes()
    assert not (tmp_path / "dist.y4m.parts").exists()


def test_render_roi_and_zoom_equal_cli(client, tmp_path):
    src = tmp_path / "in.y4m"
    write_y4m(src, clip(64, 48, 2, seed=5), 64, 48)
    opts = ["--samples", "32", "--zoom", "2", "--roi", "10,6,90,70", "--seed", "9", "-q"]
    distributed.render_job([str(src), "-o", str(tmp_path / "dist.y4m"), *opts], client, tile=24)
    run_tool("render", str(src), "-o", str(tmp_path / "cli.y4m"), *opts)
    assert (tmp_path / "dist.y4m").read_bytes() == (tmp_path / "cli.y4m").read_bytes()


def sparse_sei_files(tmp_path):
    # SEIs on pictures 0, 17 and 41, a cancel on 50: the state at a range's start comes
    # from pictures that other ranges own
    payload = (CONFORMANCE / "rdd5_352x288_420p8" / "frame0.fgc.bin").read_bytes()
    other = (CONFORMANCE / "rdd5_352x288_420p8_rand" / "frame3.fgc.bin").read_bytes()
    (tmp_path / "sei").mkdir()
    for k, p in {0: payload, 17: other, 41: payload, 50: bytes([0x80])}.items():
        (tmp_path / "sei" / f"f{k}.bin").write_bytes(p)
    return str(tmp_path / "sei" / "f%d.bin")


@pytest.mark.parametrize("persistence, per_task", [("reference", 7), ("semantic", 13), ("reference", 60)])
def test_apply_parameter_files_equal_cli(client, tmp_path, persistence, per_task):
    src = tmp_path / "in.y4m"
    write_y4m(src, clip(64, 48, 60, seed=2), 64, 48)
    pattern = sparse_sei_files(tmp_path)
    opts = ["--sei", pattern, "--persistence", persistence, "-q"]
    distributed.apply_job(["-i", str(src), "-o", str(tmp_path / "dist.y4m"), *opts], client, frames_per_task=per_task)
    run_tool("apply", "-i", str(src), "-o", str(tmp_path / "cli.y4m"), *opts)
    assert (tmp_path / "dist.y4m").read_bytes() == (tmp_path / "cli.y4m").read_bytes()


def test_apply_vfgs_ranges_equal_cli(client, tmp_path):
    # VersatileFilmGrain's random state runs through every picture: each range jumps it to
    # where the pictures before it leave it (Session.skip_picture with the picture size)
    src = tmp_path / "in.y4m"
    write_y4m(src, clip(200, 130, 9, seed=4), 200, 130)
    opts = ["--sei", sparse_sei_files(tmp_path), "--flavour", "vfgs", "-q"]
    distributed.apply_job(["-i", str(src), "-o", str(tmp_path / "dist.y4m"), *opts], client, frames_per_task=2)
    run_tool("apply", "-i", str(src), "-o", str(tmp_path / "cli.y4m"), *opts)
    assert (tmp_path / "dist.y4m").read_bytes() == (tmp_path / "cli.y4m").read_bytes()
    assert (tmp_path / "cli.y4m").read_bytes() != src.read_bytes()


def test_apply_afgs1_payloads_equal_cli(client, tmp_path):
    case = CONFORMANCE / "afgs1-176x144-420p8-single"
    import lzma
    (tmp_path / "in.yuv").write_bytes(lzma.decompress((case / "input.yuv.xz").read_bytes()))
    opts = ["--afgs1", str(case / "afgs1_%d.bin"), "--size", "176x144", "-q"]
    distributed.apply_job(["-i", str(tmp_path / "in.yuv"), "-o", str(tmp_path / "dist.yuv"), *opts], client,
                          frames_per_task=2)
    run_tool("apply", "-i", str(tmp_path / "in.yuv"), "-o", str(tmp_path / "cli.yuv"), *opts)
    assert (tmp_path / "dist.yuv").read_bytes() == (tmp_path / "cli.yuv").read_bytes()


def _run(cmd, **kw):
    subprocess.run(cmd, check=True, capture_output=True, **kw)


@pytest.fixture(scope="module")
def hevc_stream(tmp_path_factory):
    d = tmp_path_factory.mktemp("hevc")
    _run(["ffmpeg", "-v", "error", "-f", "lavfi", "-i", "testsrc2=size=128x96:rate=25", "-frames:v", "60",
          "-pix_fmt", "yuv420p", "-f", "rawvideo", str(d / "clean.yuv")])
    # an IDR in the middle (keyint 30) and B-frames: output order differs from decode order
    _run(["x265", "--log-level", "error", "--input", str(d / "clean.yuv"), "--input-res", "128x96", "--fps", "25",
          "--preset", "ultrafast", "--keyint", "30", "--min-keyint", "30", "--no-scenecut", "--bframes", "2",
          "--no-open-gop", "-o", str(d / "plain.hevc")])
    _run([SEI_STREAM_TOOL, str(d / "plain.hevc"), str(d / "grain.hevc"),
          str(CONFORMANCE / "ffmpeg71-350x198-420p8" / "fgc.json"), "hevc"])
    return d / "grain.hevc"


@pytest.mark.parametrize("per_task", [7, 30])
def test_apply_hevc_stream_equals_decode(client, tmp_path, hevc_stream, per_task):
    assert filmgrain._filmgrain.stream_picture_count(str(hevc_stream)) == 60
    distributed.apply_job([str(hevc_stream), "-o", str(tmp_path / "dist.y4m"), "--threads", "1"], client,
                          frames_per_task=per_task)
    run_tool("decode", str(hevc_stream), "-o", str(tmp_path / "cli.y4m"), "--threads", "1", "-q")
    assert (tmp_path / "dist.y4m").read_bytes() == (tmp_path / "cli.y4m").read_bytes()


@pytest.fixture(scope="module")
def hevc_sparse_streams(tmp_path_factory, hevc_stream):
    # the same pictures with a persistent FGC SEI (film_grain_characteristics_persistence_flag
    # 1: it holds until the next one) in every EVERY-th access unit only (decode order), so
    # that the pictures between, and the ranges that start among them, take their grain from
    # an SEI of an earlier picture. EVERY 5: the IDR (access unit 30) brings its own SEI, a
    # restart point; EVERY 7: it does not, and the SEI of access unit 28 persists into it
    d = tmp_path_factory.mktemp("hevc_sparse")
    fgc = json.loads((CONFORMANCE / "ffmpeg71-350x198-420p8" / "fgc.json").read_text())
    assert fgc["film_grain_characteristics_persistence_flag"] == 0
    fgc["film_grain_characteristics_persistence_flag"] = 1
    (d / "fgc_persistent.json").write_text(json.dumps(fgc))
    streams = {}
    for every in (5, 7):
        streams[every] = d / f"grain_every{every}.hevc"
        _run([SEI_STREAM_TOOL, str(hevc_stream.parent / "plain.hevc"), str(streams[every]),
              str(d / "fgc_persistent.json"), "hevc", str(every)])
    return streams


def _frame_digests(path):
    reader, out = filmgrain.VideoReader(str(path)), []
    while (planes := reader.read()) is not None:
        out.append(md5_of(planes))
    return out


@pytest.mark.parametrize("every, restarts, per_task", [(5, [30], 4), (5, [30], 11), (5, [30], 0),
                                                      (7, [], 9), (7, [], 0)])
def test_apply_hevc_sparse_persistent_sei_equals_decode(client, tmp_path, hevc_sparse_streams, every, restarts,
                                                        per_task):
    stream = hevc_sparse_streams[every]
    assert filmgrain._filmgrain.stream_picture_count(str(stream)) == 60
    assert filmgrain._filmgrain.stream_restart_points(str(stream)) == restarts
    run_tool("decode", str(stream), "-o", str(tmp_path / "cli.y4m"), "--threads", "1", "-q")
    # persistence is exercised: pictures without an SEI of their own have grain (12 or 9 SEIs
    # for 60 pictures; with persistence_flag 0 only those 12 or 9 would), so most range starts
    # fall where the grain comes from an earlier picture. (EVERY 7: decoding from the IDR
    # instead changes output pictures 30-33 and 36, which take the SEI of access unit 28.)
    run_tool("decode", str(stream), "-o", str(tmp_path / "clean.y4m"), "--threads", "1", "--no-grain", "-q")
    grainy = [a != b for a, b in zip(_frame_digests(tmp_path / "cli.y4m"), _frame_digests(tmp_path / "clean.y4m"))]
    assert len(grainy) == 60 and sum(grainy) == 60
    distributed.apply_job([str(stream), "-o", str(tmp_path / "dist.y4m"), "--threads", "1"], client,
                          frames_per_task=per_task)
    assert (tmp_path / "dist.y4m").read_bytes() == (tmp_path / "cli.y4m").read_bytes()


@pytest.fixture(scope="module")
def av1_stream(tmp_path_factory):
    d = tmp_path_factory.mktemp("av1")
    _run(["ffmpeg", "-v", "error", "-f", "lavfi", "-i", "testsrc2=size=96x64:rate=25", "-frames:v", "20",
          "-pix_fmt", "yuv420p", str(d / "clean.y4m")])
    # libaom's test grain 3 changes with update_grain and reference slots between frames
    _run(["aomenc", "--quiet", "--cpu-used=8", "--limit=20", "--kf-max-dist=12", "--film-grain-test=3",
          "--ivf", "-o", str(d / "grain.ivf"), str(d / "clean.y4m")])
    return d / "grain.ivf"


def test_apply_av1_stream_equals_decode(client, tmp_path, av1_stream):
    distributed.apply_job([str(av1_stream), "-o", str(tmp_path / "dist.y4m")], client, frames_per_task=3)
    run_tool("decode", str(av1_stream), "-o", str(tmp_path / "cli.y4m"), "-q")
    assert (tmp_path / "dist.y4m").read_bytes() == (tmp_path / "cli.y4m").read_bytes()


@pytest.mark.skipif(not filmgrain._filmgrain.have_analysis, reason="built without OpenCV")
@pytest.mark.parametrize("per_task, model", [(8, "av1"), (5, "av1"), (8, "fgc")])
def test_analyze_three_scenes_equals_cli(client, tmp_path, per_task, model):
    src = tmp_path / "clean.y4m"
    write_y4m(src, clip(128, 96, 24, seed=3, scenes=3), 128, 96)
    grainy = tmp_path / "grainy.y4m"
    # one AV1 set of libaom's test vectors, a new seed per picture
    first = filmgrain.params.read(str(CONFORMANCE / "av1_tv01_176x144_420p8" / "case.json"))["frames"][0]
    frames = []
    for k in range(24):
        f = json.loads(json.dumps(first))
        f["av1"]["grain_seed"] = 1000 + 37 * k
        frames.append(f)
    (tmp_path / "grain.json").write_text(json.dumps({"frames": frames}))
    run_tool("apply", "-i", str(src), "-o", str(grainy), "--params", str(tmp_path / "grain.json"), "-q")
    opts = ["--model", model, "--frame-step", "2", "-q"]
    distributed.analyze_job([str(grainy), "-o", str(tmp_path / "dist.json"), *opts, "--report",
                             str(tmp_path / "dist" / "report.html")], client, frames_per_task=per_task)
    run_tool("analyze", str(grainy), "-o", str(tmp_path / "cli.json"), *opts, "--report",
             str(tmp_path / "cli" / "report.html"))
    assert (tmp_path / "dist.json").read_bytes() == (tmp_path / "cli.json").read_bytes()
    # the report too: its picture (the first analysed one with all its neighbours) analysed
    # again on the driver is the one-pass analyser's, and its plots come from the same sums
    names = sorted(p.name for p in (tmp_path / "cli").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "dist").iterdir()) and "report.html" in names
    for n in names:
        assert (tmp_path / "dist" / n).read_bytes() == (tmp_path / "cli" / n).read_bytes(), n


def test_worker_killed_mid_run(tmp_path):
    from distributed import Client, LocalCluster
    src = tmp_path / "in.y4m"
    write_y4m(src, clip(96, 64, 6, seed=7), 96, 64)
    args = [str(src), "-o", str(tmp_path / "dist.y4m"), "--samples", "200", "--radius", "0.2", "-q"]
    run_tool("render", str(src), "-o", str(tmp_path / "cli.y4m"), "--samples", "200", "--radius", "0.2", "-q")
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as c:
        pids = list(c.run(os.getpid).values())
        killed = threading.Event()
        parts_at_kill = []
        parts = tmp_path / "dist.y4m.parts"

        def kill_one():
            # once the first parts are written, a worker process dies; its tasks run again
            # elsewhere (the cluster's nanny starts a new worker)
            deadline = time.monotonic() + 60
            while time.monotonic() < deadline:
                done = [p for p in parts.glob("*.npz")] if parts.exists() else []
                if len(done) >= 2:
                    parts_at_kill.append(len(done))
                    os.kill(pids[0], signal.SIGKILL)
                    killed.set()
                    return
                time.sleep(0.01)
        t = threading.Thread(target=kill_one)
        t.start()
        distributed.render_job(args, c, tile=16)
        t.join()
    assert killed.is_set()
    assert parts_at_kill[0] < 6 * 24  # killed mid-run: 6 frames of 24 tiles
    assert (tmp_path / "dist.y4m").read_bytes() == (tmp_path / "cli.y4m").read_bytes()


def test_command_line(tmp_path):
    src = tmp_path / "in.y4m"
    write_y4m(src, clip(64, 48, 3, seed=1), 64, 48)
    env = dict(os.environ)
    r = subprocess.run([sys.executable, "-m", "filmgrain.distributed", "render", "--workers", "2", "--no-progress",
                        str(src), "-o", str(tmp_path / "dist.y4m"), "--samples", "16", "-q"], env=env,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    run_tool("render", str(src), "-o", str(tmp_path / "cli.y4m"), "--samples", "16", "-q")
    assert (tmp_path / "dist.y4m").read_bytes() == (tmp_path / "cli.y4m").read_bytes()
    bad = subprocess.run([sys.executable, "-m", "filmgrain.distributed", "render", "--workers", "1", str(src), "-o",
                          str(tmp_path / "x.y4m"), "--radius", "-1"], env=env, capture_output=True, text=True)
    assert bad.returncode == 2 and "radius" in bad.stderr and not (tmp_path / "x.y4m").exists()


def test_stream_ranges_begin_at_restart_points(hevc_stream):
    # the fixture's IDR at 30 brings its own FGC SEI: decoding can begin there
    assert filmgrain._filmgrain.stream_restart_points(str(hevc_stream)) == [30]
    assert distributed._stream_ranges(60, 7, [30]) == [(0, 30), (30, 60)]
    assert distributed._stream_ranges(60, 40, [30]) == [(0, 60)]
    assert distributed._stream_ranges(90, 20, [30, 60]) == [(0, 30), (30, 60), (60, 90)]
    assert distributed._stream_ranges(20, 7, []) == [(0, 7), (7, 14), (14, 20)]


def test_apply_hevc_stream_default_ranges_equal_decode(client, tmp_path, hevc_stream):
    distributed.apply_job([str(hevc_stream), "-o", str(tmp_path / "dist.y4m"), "--threads", "1"], client)
    run_tool("decode", str(hevc_stream), "-o", str(tmp_path / "cli.y4m"), "--threads", "1", "-q")
    assert (tmp_path / "dist.y4m").read_bytes() == (tmp_path / "cli.y4m").read_bytes()
