"""Errors are Python exceptions with the CLI's messages; the interpreter survives bad input."""
from __future__ import annotations

import numpy as np
import pytest

import filmgrain
from conftest import Case


def test_version():
    assert filmgrain.__version__.count(".") == 2


def test_malformed_fgc_payload_names_the_field():
    # film_grain_model_id 3 parses (2 bits) and is refused when the set is used
    s = filmgrain.Session()
    s.push_fgc_sei(bytes([0b0110_0000, 0, 0, 0]), "hevc")
    with pytest.raises(ValueError, match=r"film_grain_model_id = 3 .*allowed 0\.\.0"):
        s.apply(np.zeros((16, 16), np.uint8))


def test_truncated_fgc_payload():
    payload = (Case("rdd5_352x288_420p8").dir / "frame0.fgc.bin").read_bytes()
    with pytest.raises(ValueError, match="truncated while reading"):
        filmgrain.Session().push_fgc_sei(payload[:3], "hevc")


def test_malformed_afgs1_payload_names_the_field():
    with pytest.raises(ValueError, match="payload_less_than_4byte_flag"):
        filmgrain.Session().push_afgs1(bytes([0xB5, 0x58, 0x90, 0x01, 0xFF]))


def test_invalid_parameter_dict():
    c = Case("rdd5_352x288_420p8")
    p = dict(c.frame_info(0)["params"]["fgc"])
    p["log2_scale_factor"] = 99
    with pytest.raises(ValueError, match=r"log2_scale_factor = 99 is out of range \(allowed 0\.\.15\)"):
        filmgrain.Session().push_fgc_params(p)
    # a set the flavour refuses when it is used: an error, or the picture unchanged
    p = dict(c.frame_info(0)["params"]["fgc"])
    p["film_grain_model_id"] = 1
    s = filmgrain.Session()
    s.push_fgc_params(p)
    with pytest.raises(ValueError, match="film_grain_model_id = 1"):
        s.apply(c.input_planes(0))
    passthrough = filmgrain.Session(on_invalid="passthrough")
    passthrough.push_fgc_params(p)
    out = passthrough.apply(c.input_planes(0))
    assert passthrough.last_result["parameters_refused"]
    assert "film_grain_model_id" in passthrough.last_result["message"]
    assert all((a == b).all() for a, b in zip(out, c.input_planes(0)))


@pytest.mark.parametrize("planes, message", [
    ([np.zeros((16, 16), np.float32)], "dtype"),
    ([np.zeros((16, 16), np.uint8)] * 2, "1 or 3 planes"),
    ([np.zeros((16, 16), np.uint8), np.zeros((5, 5), np.uint8), np.zeros((5, 5), np.uint8)], "fit no chroma format"),
    ([np.zeros((16, 16), np.uint16)], "bit_depth"),
    ([np.zeros((4, 4, 4), np.uint8)], "dimensions"),
])
def test_bad_planes(planes, message):
    with pytest.raises(ValueError, match=message):
        filmgrain.Session().apply(planes)


def test_bad_options():
    with pytest.raises(ValueError, match="flavour"):
        filmgrain.Session(flavour="nope")
    with pytest.raises(ValueError, match="threads"):
        filmgrain.Session(threads=100000)
    with pytest.raises(ValueError, match="--radius"):
        filmgrain.render(np.full((8, 8), 0.5, np.float32), radius="abc")


def test_missing_file_is_oserror(tmp_path):
    with pytest.raises(OSError):
        filmgrain.params.read(str(tmp_path / "absent.json"))


def test_strided_and_inplace_input():
    c = Case("rdd5_352x288_420p8")
    p = c.frame_info(0)["params"]["fgc"]
    planes = [np.array(a) for a in c.input_planes(0)]
    s1, s2, s3 = filmgrain.Session(), filmgrain.Session(), filmgrain.Session()
    for s in (s1, s2, s3):
        s.push_fgc_params(p, poc=0)
    want = s1.apply(planes, poc=0)
    # rows of a larger array (row stride != width): used in place, not copied
    wide = [np.zeros((a.shape[0], a.shape[1] + 7), np.uint8) for a in planes]
    views = []
    for w, a in zip(wide, planes):
        w[:, :a.shape[1]] = a
        views.append(w[:, :a.shape[1]])
    got = s2.apply(views, poc=0)
    assert all((a == b).all() for a, b in zip(want, got))
    # in place
    copies = [a.copy() for a in planes]
    s3.apply(copies, poc=0, inplace=True)
    assert all((a == b).all() for a, b in zip(want, copies))
    # Fortran order: copied once, same result
    s4 = filmgrain.Session()
    s4.push_fgc_params(p, poc=0)
    got = s4.apply([np.asfortranarray(a) for a in planes], poc=0)
    assert all((a == b).all() for a, b in zip(want, got))
