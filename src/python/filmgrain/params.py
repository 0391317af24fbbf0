"""Parameter files in every form ``filmgrain params convert`` knows, as Python dicts named
after the syntax elements (the project's JSON forms):

- FGC SEI: JSON <-> the SEI payload (payloadType 19 body), for avc / hevc / vvc syntax;
- AV1: JSON (film_grain_params per frame) <-> libaom grain table (.tbl) <-> AFGS1 T.35 payload.

The conversions are the command line's (one implementation); its notes about what a form
cannot carry go to stderr unless quiet=True.
"""
from __future__ import annotations

import json
import os
import tempfile
from typing import Any

from . import _filmgrain, command_arguments

__all__ = ["read", "write", "convert", "from_sei", "to_sei", "from_afgs1", "to_afgs1"]


def convert(input: str | list[str], output: str, **options: Any) -> None:
    """``filmgrain params convert``: options to, from_, sei_codec, size, pix_fmt, fps, frames, quiet."""
    if "from_" in options:
        options["from"] = options.pop("from_")
    inputs = [input] if isinstance(input, str) else list(input)
    _filmgrain.run_command(command_arguments(["params", "convert", *inputs, "-o", output], options))


def read(path: str | list[str], **options: Any) -> dict:
    """Reads parameters in any form (JSON, .tbl, SEI or AFGS1 payload files) as a dict."""
    options.setdefault("quiet", True)
    with tempfile.TemporaryDirectory(prefix="filmgrain-") as tmp:
        target = os.path.join(tmp, "params.json")
        convert(path, target, to="json", **options)
        with open(target, encoding="utf-8") as f:
            return json.load(f)


def write(params: dict, path: str, **options: Any) -> None:
    """Writes a parameter dict in the form ``path`` names (.json, .tbl, .sei, else AFGS1), or ``to=``."""
    with tempfile.TemporaryDirectory(prefix="filmgrain-") as tmp:
        source = os.path.join(tmp, "params.json")
        with open(source, "w", encoding="utf-8") as f:
            json.dump(params, f)
        convert(source, path, **options)


def _via_file(data: bytes, name: str, **options: Any) -> dict:
    with tempfile.TemporaryDirectory(prefix="filmgrain-") as tmp:
        source = os.path.join(tmp, name)
        with open(source, "wb") as f:
            f.write(bytes(data))
        return read(source, **options)


def _to_bytes(params: dict, name: str, **options: Any) -> bytes:
    options.setdefault("quiet", True)
    with tempfile.TemporaryDirectory(prefix="filmgrain-") as tmp:
        target = os.path.join(tmp, name)
        write(params, target, **options)
        with open(target, "rb") as f:
            return f.read()


def from_sei(payload: bytes, codec: str = "hevc") -> dict:
    """An FGC SEI payload as a dict (ValueError naming the syntax element if malformed)."""
    return _via_file(payload, "payload.sei", sei_codec=codec, from_="sei")


def to_sei(params: dict, codec: str = "hevc") -> bytes:
    """FGC parameters (a dict as from_sei gives) as an SEI payload."""
    return _to_bytes(params, "payload.sei", sei_codec=codec, to="sei")


def from_afgs1(payload: bytes, **options: Any) -> dict:
    """An AFGS1 T.35 payload as AV1 parameters (size=, pix_fmt= select its set)."""
    return _via_file(payload, "payload.afgs1", from_="afgs1", **options)


def to_afgs1(params: dict, **options: Any) -> bytes:
    """AV1 parameters as an AFGS1 T.35 payload (size=, pix_fmt= give the target)."""
    return _to_bytes(params, "payload.afgs1", to="afgs1", **options)
