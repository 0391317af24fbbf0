"""Golden cases of every family through filmgrain.Session (and decode for ffmpeg71), every
picture's MD5: the Python module is the library the goldens test, not a copy."""
from __future__ import annotations

import os

import pytest

import filmgrain
from conftest import Case, md5_of, run_tool, CONFORMANCE

FGC_CASES = ["rdd5_352x288_420p8", "rdd5_352x288_420p10", "rdd5_h264_352x288_420p8_idr", "rdd5_352x288_420p8_rand",
             "vtm_352x288_420p8", "vtm_352x288_420p12", "vtm_352x288_422p8", "vtm_352x288_gray",
             "vtm_352x288_420p8_invalid_mix"]
VFGS_CASES = ["vfgs-gain150-420p8", "vfgs-outdepth8-420p10", "vfgs-ar-444p8-nmv5", "vfgs-ff-422p8-luma"]
AV1_CASES = ["av1_tv01_176x144_420p8", "av1_tv05_176x144_420p12", "av1_tbl_mono_176x144_gray", "av1_tbl_352x288_422p8",
             "av1_tbl_odd_97x61_420p8"]
AFGS1_CASES = ["afgs1-176x144-420p8-single", "afgs1-144x80-420p12", "afgs1-160x96-gray", "afgs1-640x360-422p10",
               "afgs1-352x288-420p8-chroma", "afgs1-200x136-420p8-apply0"]
FFMPEG_CASES = ["ffmpeg71-350x198-420p8", "ffmpeg71-270x150-420p8-gaps", "ffmpeg71-352x288-420p8-nmv1"]


def _bit_depth(c: Case):
    return None if c.bit_depth == 8 else c.bit_depth


@pytest.mark.parametrize("name", FGC_CASES)
def test_fgc_sei_payloads(name):
    c = Case(name)
    codec = "avc" if c.json["codec"] == "h264" else "hevc"
    s = filmgrain.Session(flavour=c.json["family"], on_invalid="passthrough", threads=2)
    for k in range(c.frames):
        fi = c.frame_info(k)
        poc, idr = fi["poc"], fi["idr_pic_id"] or 0
        if fi["sei_present"]:
            s.push_fgc_sei((c.dir / f"frame{k}.fgc.bin").read_bytes(), codec, poc=poc, idr_pic_id=idr)
        out = s.apply(c.input_planes(k), bit_depth=_bit_depth(c), poc=poc, idr_pic_id=idr)
        assert md5_of(out) == fi["expected_md5"], f"{name} frame {k}"


@pytest.mark.parametrize("name", VFGS_CASES)
def test_vfgs(name):
    c = Case(name)
    out_depth = {"yuv420p": 8, "yuv422p": 8, "yuv444p": 8}.get(c.json["output_pix_fmt"], 10)
    s = filmgrain.Session(flavour="vfgs", vfgs_seed=c.json["seed"], vfgs_gain_percent=c.json.get("vfgs_gain_percent", 100),
                          vfgs_output_bit_depth=out_depth if out_depth != c.bit_depth else 0)
    for k in range(c.frames):
        fi = c.frame_info(k)
        payload = c.dir / f"fgc_{k:04d}.bin"
        if payload.exists():
            s.push_fgc_sei(payload.read_bytes(), "hevc")
        out = s.apply(c.input_planes(k), bit_depth=_bit_depth(c))
        assert md5_of(out) == fi["expected_md5"], f"{name} frame {k}"


@pytest.mark.parametrize("name", AV1_CASES)
def test_av1_parameter_file(name):
    c = Case(name)
    s = filmgrain.Session(threads=2)
    s.attach_files(params=str(c.dir / "case.json"))
    for k in range(c.frames):
        out = s.apply(c.input_planes(k), bit_depth=_bit_depth(c))
        assert md5_of(out) == c.frame_info(k)["expected_md5"], f"{name} frame {k}"


@pytest.mark.parametrize("name", AV1_CASES[:3])
def test_av1_parameter_dicts(name):
    # the dicts filmgrain.params reads, pushed per picture
    c = Case(name)
    frames = filmgrain.params.read(str(c.dir / "case.json"))["frames"]
    s = filmgrain.Session()
    for k in range(c.frames):
        p = dict(frames[k]["av1"])
        p["update_grain"] = 1
        s.push_av1_params(p, matrix_coefficients=frames[k].get("matrix_coefficients", 2))
        out = s.apply(c.input_planes(k), bit_depth=_bit_depth(c))
        assert md5_of(out) == c.frame_info(k)["expected_md5"], f"{name} frame {k}"


@pytest.mark.parametrize("name", AFGS1_CASES)
def test_afgs1_payloads(name):
    c = Case(name)
    s = filmgrain.Session(threads=3)
    for k in range(c.frames):
        payload = c.dir / f"afgs1_{k}.bin"
        if payload.exists():
            s.push_afgs1(payload.read_bytes())
        out = s.apply(c.input_planes(k), bit_depth=_bit_depth(c))
        assert md5_of(out) == c.frame_info(k)["expected_md5"], f"{name} frame {k}"


@pytest.mark.parametrize("name", FFMPEG_CASES)
def test_ffmpeg_flavour_decode(name, tmp_path):
    import numpy as np
    c = CONFORMANCE / name
    import json
    j = json.loads((c / "case.json").read_text())
    out = tmp_path / "out.yuv"
    filmgrain.decode(str(c / "stream.hevc"), str(out), flavour="ffmpeg", quiet=True)
    data = out.read_bytes()
    from conftest import planes_of
    for k, want in enumerate(j["expected_md5"]):
        assert md5_of(planes_of(data, k, j["width"], j["height"], "yuv420p")) == want, f"{name} frame {k}"
