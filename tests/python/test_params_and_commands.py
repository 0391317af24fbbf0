"""filmgrain.params (every form the CLI converts) and the commands with keyword options."""
from __future__ import annotations

import json

import numpy as np
import pytest

import filmgrain
from conftest import Case, run_tool


def test_fgc_sei_round_trip():
    c = Case("rdd5_352x288_420p8")
    payload = (c.dir / "frame0.fgc.bin").read_bytes()
    d = filmgrain.params.from_sei(payload, "hevc")
    fgc = d["fgc"] if "fgc" in d else d["frames"][0]["fgc"]
    want = c.frame_info(0)["params"]["fgc"]
    assert {k: fgc[k] for k in want} == want
    assert filmgrain.params.to_sei(d, "hevc") == payload


def test_av1_forms_round_trip(tmp_path):
    c = Case("av1_tv01_176x144_420p8")
    d = filmgrain.params.read(str(c.dir / "case.json"))
    filmgrain.params.write(d, str(tmp_path / "g.tbl"), quiet=True)
    via_table = filmgrain.params.read(str(tmp_path / "g.tbl"), frames=c.frames)
    payload = filmgrain.params.to_afgs1(d, size="176x144", pix_fmt="yuv420p")
    via_afgs1 = filmgrain.params.from_afgs1(payload, size="176x144", pix_fmt="yuv420p")
    key = lambda f: {k: v for k, v in f["av1"].items() if k not in ("update_grain", "grain_seed",
                                                                                  "clip_to_restricted_range")}
    assert key(via_table["frames"][0]) == key(d["frames"][0])
    assert key(via_afgs1["frames"][0]) == key(d["frames"][0])
    # the same as the CLI's conversion
    run_tool("params", "convert", str(c.dir / "case.json"), "-o", str(tmp_path / "cli.tbl"), "-q")
    assert (tmp_path / "cli.tbl").read_bytes() == (tmp_path / "g.tbl").read_bytes()


def test_render_array_equals_cli_still(tmp_path):
    import lzma
    plane = np.linspace(0.1, 0.9, 48 * 40, dtype=np.float32).reshape(40, 48)
    a = filmgrain.render(plane, radius=0.2, samples=64, seed=3)
    b = filmgrain.render(plane, radius=0.2, samples=64, seed=3, threads=1)
    assert a.shape == (40, 48) and a.dtype == np.float32
    assert (a == b).all()
    assert abs(float(a.mean()) - float(plane.mean())) < 0.05
    c = filmgrain.render(plane, radius=0.2, samples=64, seed=4)
    assert not (a == c).all()


def test_render_file_equals_cli(tmp_path):
    src = tmp_path / "in.y4m"
    run_tool("demo", "--help")  # the tool is there
    y = np.tile(np.linspace(20, 230, 32, dtype=np.uint8), (24, 1))
    with open(src, "wb") as f:
        f.write(b"YUV4MPEG2 W32 H24 F25:1 Ip A1:1 C420jpeg\n")
        for _ in range(2):
            f.write(b"FRAME\n" + y.tobytes() + np.full((12, 16), 128, np.uint8).tobytes() * 2)
    filmgrain.render(str(src), str(tmp_path / "py.y4m"), samples=32, radius=0.3, quiet=True)
    run_tool("render", str(src), "-o", str(tmp_path / "cli.y4m"), "--samples", "32", "--radius", "0.3", "-q")
    assert (tmp_path / "py.y4m").read_bytes() == (tmp_path / "cli.y4m").read_bytes()


def test_stats_arrays_and_files(tmp_path):
    rng = np.random.default_rng(0)
    clean = np.full((64, 64), 0.5, np.float32)
    grainy = clean + rng.normal(0, 0.02, clean.shape).astype(np.float32)
    s = filmgrain.stats(clean, grainy, max_lag=2)
    sd = np.sqrt(s["variance_vs_intensity"][0]["variance"])
    assert abs(sd - 0.02) < 0.002
    assert len(s["autocovariance"]["rows_dy_from_minus_max"]) == 5


@pytest.mark.skipif(not filmgrain._filmgrain.have_analysis, reason="built without OpenCV")
def test_analyze_equals_cli(tmp_path):
    c = Case("av1_tv01_176x144_420p8")
    import lzma
    grainy = tmp_path / "grainy.yuv"
    run_tool("apply", "-i", "-", "-o", str(grainy), "--params", str(c.dir / "case.json"), "--size", "176x144", "-q",
             check=False)
    data = lzma.decompress((c.dir / "input.yuv.xz").read_bytes())
    (tmp_path / "clean.yuv").write_bytes(data)
    run_tool("apply", "-i", str(tmp_path / "clean.yuv"), "-o", str(grainy), "--params", str(c.dir / "case.json"),
             "--size", "176x144", "-q")
    got = filmgrain.analyze(str(grainy), "av1", size="176x144", spatial=True)
    run_tool("analyze", str(grainy), "--model", "av1", "-o", str(tmp_path / "cli.json"), "--size", "176x144",
             "--spatial", "-q")
    assert got == json.loads((tmp_path / "cli.json").read_text())
