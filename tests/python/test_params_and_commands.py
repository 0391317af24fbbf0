"""filmgrain.params (every form the CLI converts) and the commands with keyword options."""
from __future__ import annotations

import json

import numpy as np
import pytest

import filmgrain
from conftest import CONFORMANCE, Case, run_tool


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


@pytest.mark.skipif(not filmgrain._filmgrain.have_analysis, reason="built without OpenCV")
@pytest.mark.parametrize("pix_fmt, depth", [("yuv420p", 8), ("yuv422p10le", 10), ("gray", 8)])
def test_analyze_pictures_in_memory_equal_cli_on_the_file(tmp_path, pix_fmt, depth):
    # grain from the library itself on a smooth picture, read back as numpy planes: the
    # pictures analysed from memory give what `filmgrain analyze` gives on their file
    w, h, frames = 192, 128, 6
    yy, xx = np.mgrid[0:h, 0:w]
    scale = 1 << (depth - 8)
    clean = tmp_path / "clean.y4m"
    info = filmgrain.VideoInfo(w, h, pix_fmt)
    writer = filmgrain.VideoWriter(str(clean), info, True)
    dtype = np.uint8 if depth == 8 else np.uint16
    for k in range(frames):
        y = ((40 + 150 * xx / w + 10 * np.sin(yy / 17 + k)) * scale).astype(dtype)
        planes = [y]
        if pix_fmt != "gray":
            ch = h // 2 if pix_fmt.startswith("yuv420") else h
            planes += [np.full((ch, w // 2), 128 * scale, dtype), np.full((ch, w // 2), 120 * scale, dtype)]
        writer.write(planes, bit_depth=depth)
    writer.commit()
    # libaom's test grain 1 (its first frame's set; luma only on grey pictures)
    case = json.loads((CONFORMANCE / "av1_tv01_176x144_420p8" / "case.json").read_text())
    av1 = dict(case["frames_info"][0]["params"]["av1"])
    if pix_fmt == "gray":
        av1.update(num_cb_points=0, num_cr_points=0, point_cb_value=[], point_cb_scaling=[], point_cr_value=[],
                   point_cr_scaling=[])
    (tmp_path / "p.json").write_text(json.dumps({"av1": av1}))
    grainy = tmp_path / "grainy.y4m"
    run_tool("apply", "-i", str(clean), "-o", str(grainy), "--params", str(tmp_path / "p.json"), "-q")
    reader = filmgrain.VideoReader(str(grainy))
    pictures = []
    while (p := reader.read()) is not None:
        pictures.append(p if pix_fmt != "gray" else p[0])
    assert len(pictures) == frames
    got = filmgrain.analyze(pictures, "av1", bit_depth=depth, spatial=True)
    run_tool("analyze", str(grainy), "--model", "av1", "-o", str(tmp_path / "cli.json"), "--spatial", "-q")
    assert got == json.loads((tmp_path / "cli.json").read_text())
    assert '"apply_grain": 1' in json.dumps(got)  # grain found, not an empty estimate


def test_analyze_refuses_an_empty_picture_list():
    with pytest.raises(ValueError, match="no picture"):
        filmgrain.analyze([], "av1")


def test_video_writer_refuses_a_picture_of_another_format(tmp_path):
    w = filmgrain.VideoWriter(str(tmp_path / "o.y4m"), filmgrain.VideoInfo(64, 32, "yuv420p"), True)
    y = np.zeros((32, 64), np.uint8)
    with pytest.raises(ValueError, match="64x32 yuv422p picture .* which holds 64x32 yuv420p"):
        w.write([y, np.zeros((32, 32), np.uint8), np.zeros((32, 32), np.uint8)])
    assert not (tmp_path / "o.y4m").exists()
