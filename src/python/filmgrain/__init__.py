"""filmgrain: film grain bit-exact with the FGC SEI (RDD 5, HM/VTM, VersatileFilmGrain) and
AV1 / AFGS1 references, a physically based renderer, grain analysis and statistics.

The stream session (Session) adds grain to numpy pictures; render, analyze, stats, apply and
decode run the command line's subcommands in-process with its options as keyword arguments
(``radius_sigma=0.02`` is ``--radius-sigma 0.02``; ``True`` is a flag); ``params`` reads,
writes and converts every parameter form; ``filmgrain.distributed`` runs render, apply and
analyze on a Dask cluster. Errors are ValueError (invalid arguments, parameters, malformed
payloads) or OSError (files), with the command line's messages.
"""
from __future__ import annotations

import json
import os
import tempfile
from typing import Any, Iterable, Mapping, Sequence


def _find_image_module() -> None:
    # Stills go through OpenImageIO in a module the library loads on first use; the tool
    # finds it beside itself, Python beside this package (build tree) or in lib/filmgrain.
    if os.environ.get("FILMGRAIN_IMAGE_MODULE"):
        return
    here = os.path.dirname(os.path.abspath(__file__))
    candidates = [os.path.join(here, "..", "..", "filmgrain-oiio.so")]
    prefix_lib = os.path.normpath(os.path.join(here, "..", "..", ".."))
    for root, _dirs, files in os.walk(prefix_lib):
        if "filmgrain-oiio.so" in files and root.endswith("filmgrain"):
            candidates.append(os.path.join(root, "filmgrain-oiio.so"))
        if root.count(os.sep) - prefix_lib.count(os.sep) >= 2:
            _dirs[:] = []
    for c in candidates:
        if os.path.exists(c):
            os.environ["FILMGRAIN_IMAGE_MODULE"] = os.path.normpath(c)
            return


_find_image_module()

from . import _filmgrain  # noqa: E402
from ._filmgrain import Session, VideoInfo, VideoReader, VideoWriter  # noqa: E402,F401

__version__: str = _filmgrain.__version__
__all__ = ["Session", "VideoReader", "VideoWriter", "VideoInfo", "params", "render", "analyze", "stats",
           "apply", "decode", "run", "__version__"]


def command_arguments(positional: Sequence[Any] = (), options: Mapping[str, Any] | None = None) -> list[str]:
    """The command line for positional arguments and keyword options: ``name=value`` becomes
    ``--name value`` (underscores as dashes), ``True`` a flag, ``False``/``None`` nothing, and a
    list or tuple the option followed by each value."""
    args = [str(p) for p in positional]
    for key, value in (options or {}).items():
        flag = "--" + key.replace("_", "-")
        if value is None or value is False:
            continue
        if value is True:
            args.append(flag)
        elif isinstance(value, (list, tuple)):
            args.append(flag)
            args.extend(str(v) for v in value)
        else:
            args += [flag, str(value)]
    return args


def run(*args: str) -> None:
    """Runs one ``filmgrain`` command line in-process, e.g. ``run("apply", "-i", "a.y4m", ...)``."""
    _filmgrain.run_command(list(args))


def _is_array(x: Any) -> bool:
    return hasattr(x, "__array_interface__")


def render(input: Any, output: str | None = None, *, frame: int = 0, plane: int = 0, bit_depth: int | None = None,
           **options: Any) -> Any:
    """Physically based grain (the Boolean model), as ``filmgrain render``.

    With file names (a still or a .y4m/.yuv clip) it writes ``output`` and returns None. With a
    2-D numpy array (grey levels: float in [0, 1], uint8, or uint16 with ``bit_depth``) it
    returns the rendered float32 plane, seeded as plane ``plane`` of frame ``frame`` of a clip.
    Options: radius, radius_sigma, filter_sigma, zoom, samples, tolerance, seed, algorithm,
    threads (the CLI's)."""
    if _is_array(input):
        import numpy as np
        a = np.asarray(input)
        depth = bit_depth if bit_depth is not None else (8 if a.dtype == np.uint8 else 16)
        return _filmgrain.render_array(a, command_arguments(["-", "-o", "-"], options), depth, frame, plane)
    if output is None:
        raise ValueError("render: give output= for a file input")
    _filmgrain.run_command(command_arguments(["render", input, "-o", output], options))
    return None


def stats(clean: Any, grainy: Any, *, bit_depth: int | None = None, **options: Any) -> dict:
    """Grain statistics of a clean and a grainy picture, as ``filmgrain stats --json`` (a dict).
    Inputs are file names (stills or clips) or 2-D numpy arrays of the same size."""
    if _is_array(clean) or _is_array(grainy):
        import numpy as np
        c, g = np.asarray(clean), np.asarray(grainy)
        depth = bit_depth if bit_depth is not None else (8 if c.dtype == np.uint8 else 16)
        return _filmgrain.stats_arrays(c, g, command_arguments(["-", "-"], options), depth)
    return _filmgrain.stats_files(command_arguments([clean, grainy], options))


def _pix_fmt_of(planes: Sequence[Any], bit_depth: int) -> str:
    """The pix_fmt of a picture given as its planes (Y only: gray)."""
    suffix = "" if bit_depth == 8 else f"{bit_depth}le"
    if len(planes) == 1:
        return "gray" + suffix
    (h, w), (ch, cw) = planes[0].shape, planes[1].shape
    sub_x, sub_y = cw < w, ch < h
    base = "yuv420p" if sub_x and sub_y else "yuv422p" if sub_x else "yuv444p"
    return base + suffix


def _write_frames(path: str, frames: Iterable[Any], bit_depth: int | None) -> None:
    """A Y4M clip of pictures, each its planes (Y, Cb, Cr) or one 2-D array (grey)."""
    import numpy as np
    writer = None
    for frame in frames:
        planes = [np.asarray(frame)] if _is_array(frame) else [np.asarray(p) for p in frame]
        depth = bit_depth if bit_depth is not None else (8 if planes[0].dtype == np.uint8 else 10)
        if writer is None:
            h, w = planes[0].shape
            writer = _filmgrain.VideoWriter(path, _filmgrain.VideoInfo(w, h, _pix_fmt_of(planes, depth)), True)
        writer.write(planes, bit_depth=depth)
    if writer is None:
        raise ValueError("analyze: no picture given")
    writer.commit()


def analyze(input: Any, model: str, output: str | None = None, *, bit_depth: int | None = None,
            **options: Any) -> dict:
    """Estimates FGC SEI (model="fgc") or AV1 (model="av1") grain parameters from a grainy
    clip, as ``filmgrain analyze``; returns the parameters (the JSON form) and writes them to
    ``output`` when given. ``input`` is a file name, or the pictures themselves: a sequence of
    pictures, each its planes (Y, Cb, Cr) as uint8 / uint16 numpy arrays (the chroma format
    from their sizes) or one 2-D array (grey); uint16 samples are ``bit_depth`` bits (default
    10). Options: denoised, table, afgs1, sei, sei_codec, report, flavour, max_frames,
    frame_step, temporal_radius, spatial, accuracy, max_lag, size, pix_fmt, fps."""
    options.setdefault("quiet", True)
    with tempfile.TemporaryDirectory(prefix="filmgrain-") as tmp:
        if not isinstance(input, (str, os.PathLike)):
            # the pictures go through the same reader as a file (a Y4M in a temporary directory):
            # the same analysis, so the same parameters as `filmgrain analyze` on that file
            clip = os.path.join(tmp, "input.y4m")
            _write_frames(clip, input, bit_depth)
            input = clip
        target = output or os.path.join(tmp, "params.json")
        _filmgrain.run_command(command_arguments(["analyze", input, "--model", model, "-o", target], options))
        with open(target, encoding="utf-8") as f:
            return json.load(f)


def apply(input: str, output: str, **options: Any) -> None:
    """Adds grain to a Y4M / raw YUV file from parameter files, as ``filmgrain apply``
    (params, sei, afgs1, sei_codec, flavour, on_invalid, persistence, threads, ...)."""
    _filmgrain.run_command(command_arguments(["apply", "-i", input, "-o", output], options))


def decode(input: str, output: str, **options: Any) -> None:
    """Decodes a video file through FFmpeg's libraries and adds grain from its metadata, as
    ``filmgrain decode`` (flavour, threads, no_grain, strict, first_frame, frames)."""
    _filmgrain.run_command(command_arguments(["decode", input, "-o", output], options))


from . import params  # noqa: E402,F401
