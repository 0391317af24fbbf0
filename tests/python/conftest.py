"""Shared pieces of the Python module's tests: the conformance cases, the tool, temp clips."""
from __future__ import annotations

import hashlib
import json
import lzma
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
CONFORMANCE = ROOT / "conformance"
TOOL = os.environ.get("FILMGRAIN_TOOL", str(ROOT / "build" / "filmgrain"))
SEI_STREAM_TOOL = os.environ.get("FILMGRAIN_SEI_STREAM_TOOL", str(ROOT / "build" / "filmgrain_fgc_sei_stream"))


class Case:
    def __init__(self, name: str) -> None:
        self.name = name
        self.dir = CONFORMANCE / name
        self.json = json.loads((self.dir / "case.json").read_text())
        self.width, self.height = self.json["width"], self.json["height"]
        self.pix_fmt = self.json["pix_fmt"]
        self.frames = self.json["frames"]
        self.bit_depth = self.json.get("bit_depth", 8)
        self._input = None

    def frame_info(self, k: int) -> dict:
        return self.json["frames_info"][k]

    def input_planes(self, k: int) -> list:
        import numpy as np
        if self._input is None:
            self._input = lzma.decompress((self.dir / "input.yuv.xz").read_bytes())
        return planes_of(self._input, k, self.width, self.height, self.pix_fmt)


def plane_shapes(w: int, h: int, pix_fmt: str) -> list:
    if pix_fmt.startswith("gray"):
        return [(h, w)]
    if pix_fmt.startswith("yuv420"):
        return [(h, w), ((h + 1) // 2, (w + 1) // 2), ((h + 1) // 2, (w + 1) // 2)]
    if pix_fmt.startswith("yuv422"):
        return [(h, w), (h, (w + 1) // 2), (h, (w + 1) // 2)]
    return [(h, w)] * 3


def planes_of(data: bytes, k: int, w: int, h: int, pix_fmt: str) -> list:
    import numpy as np
    dtype = np.uint8 if pix_fmt in ("yuv420p", "yuv422p", "yuv444p", "gray") else np.dtype("<u2")
    shapes = plane_shapes(w, h, pix_fmt)
    frame_samples = sum(a * b for a, b in shapes)
    flat = np.frombuffer(data, dtype, count=frame_samples, offset=k * frame_samples * np.dtype(dtype).itemsize)
    out, at = [], 0
    for s in shapes:
        n = s[0] * s[1]
        out.append(flat[at:at + n].reshape(s))
        at += n
    return out


def md5_of(planes: list) -> str:
    m = hashlib.md5()
    for p in planes:
        m.update(p.tobytes())
    return m.hexdigest()


def run_tool(*args: str, check: bool = True) -> subprocess.CompletedProcess:
    return subprocess.run([TOOL, *args], capture_output=True, text=True, check=check)


@pytest.fixture
def case():
    return Case
