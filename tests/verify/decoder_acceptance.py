#!/usr/bin/python3
"""`filmgrain verify` against real decoders and real streams (CTest: verify.decoder_acceptance).

1. dav1d's own output of aomenc --film-grain-test 1..16 streams, 8-bit (the conformance
   streams) and 10-bit (encoded here), is reported bit-exact (exit 0), as Y4M and as a
   per-frame .md5 list; `filmgrain decode` output of FGC (H.265) and AFGS1 streams too.
2. For every mistake verify knows, a "broken decoder" output is made from a real stream
   (`verify --simulate ID`: the reference with exactly that mistake injected) and verify
   must name that mistake first. Where it names another, both mistakes must give the
   identical pictures on that stream (checked byte for byte, and printed). Every mistake
   must be exercised; the stream-state ones on streams made for them (aomenc alt-ref with
   show_existing_frame, aomenc grain table with update_grain = 0, H.264 with an SEI every
   third picture, checked with --persistence reference). `filmgrain decode`, which follows
   FFmpeg's persistence, is bit-exact there by default (verify reads a stream as decode does)
   and diagnosed as fgc.semantic_persistence against --persistence reference.
3. A decoder that dropped pictures: the missing ones are named and the rest stays aligned.
4. dav1d --filmgrain 0 (grain not applied) is diagnosed as such.
5. A real decoder whose grain no known mistake describes: Debian 12's FFmpeg 5.1 applies
   H.274 grain itself (its early h274 synthesis: the same level, other noise). verify must
   not claim a diagnosis: every picture mismatching, no mistake reproducing any, and the
   line saying that no known mistake explains it.

usage: decoder_acceptance.py FILMGRAIN SOURCE_DIR WORK_DIR FILMGRAIN_FGC_SEI_STREAM
"""
import hashlib
import json
import lzma
import os
import shutil
import subprocess
import sys

TOOL, SRC, WORK, SEI_TOOL = (os.path.abspath(a) for a in sys.argv[1:5])
CONF = os.path.join(SRC, "conformance")
failures = []


def run(args, check=None):
    p = subprocess.run(args, capture_output=True, text=True)
    if check is not None and p.returncode != check:
        raise SystemExit(f"FAIL: {' '.join(args)} exited {p.returncode} (expected {check})\n{p.stdout[-3000:]}{p.stderr[-3000:]}")
    return p


def expect(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what)


def y4m_frames(path):
    """(header, [frame bytes]) of a Y4M file."""
    data = open(path, "rb").read()
    head_end = data.index(b"\n")
    header = data[:head_end].decode()
    w = int(next(t[1:] for t in header.split() if t.startswith("W")))
    h = int(next(t[1:] for t in header.split() if t.startswith("H")))
    c = next((t[1:] for t in header.split() if t.startswith("C")), "420jpeg")
    bps = 2 if "p" in c and any(d in c for d in ("p10", "p12", "p16")) else 1
    cw, ch = ((w + 1) // 2, (h + 1) // 2) if c.startswith("420") else ((w + 1) // 2, h) if c.startswith("422") else (w, h)
    size = (w * h + (2 * cw * ch if not c.startswith("mono") else 0)) * bps
    frames, pos = [], head_end + 1
    while pos < len(data):
        line_end = data.index(b"\n", pos)
        frames.append(data[line_end + 1:line_end + 1 + size])
        pos = line_end + 1 + size
    return header, frames


def write_y4m(path, header, frames):
    with open(path, "wb") as f:
        f.write(header.encode() + b"\n")
        for fr in frames:
            f.write(b"FRAME\n" + fr)


def verify_json(stream, decoded, *extra):
    out = os.path.join(WORK, "result.json")
    p = run([TOOL, "verify", stream, "--decoded", decoded, "--json", out, "-q", *extra])
    if p.returncode == 2:
        raise SystemExit(f"FAIL: verify {stream} {decoded}: {p.stderr}")
    return p.returncode, json.load(open(out))


os.makedirs(WORK, exist_ok=True)
os.chdir(WORK)

# ---- 1. real decoders' correct output is bit-exact --------------------------------------
av1_8bit = [os.path.join(CONF, f"av1_tv{n:02d}_176x144_420p8", "stream.ivf") for n in range(1, 17)]
raw10 = os.path.join(WORK, "input10.yuv")
with open(raw10, "wb") as f:
    f.write(lzma.open(os.path.join(CONF, "av1_tv01_352x288_420p10", "input.yuv.xz")).read())
av1_10bit = []
for n in range(1, 17):
    out = os.path.join(WORK, f"tv{n:02d}_10bit.ivf")
    run(["aomenc", "--ivf", "-w", "352", "-h", "288", "--fps=25/1", "--i420", "--profile=0", "--bit-depth=10",
         "--input-bit-depth=10", "--lossless=1", "--passes=1", "--cpu-used=8", "--limit=3",
         f"--film-grain-test={n}", "-o", out, raw10, "-q"], check=0)
    av1_10bit.append(out)
for stream in av1_8bit + av1_10bit:
    run(["dav1d", "-q", "-i", stream, "-o", "dav1d.y4m"], check=0)
    rc, r = verify_json(stream, "dav1d.y4m")
    expect(rc == 0 and r["summary"]["all_exact"], f"dav1d output of {stream} bit-exact (rc {rc})")
    header, frames = y4m_frames("dav1d.y4m")
    with open("dav1d.md5", "w") as f:
        f.write("# per-frame MD5s of dav1d's output\n")
        for i, fr in enumerate(frames):
            f.write(f"{hashlib.md5(fr).hexdigest()}  frame{i}\n")
    rc, r = verify_json(stream, "dav1d.md5")
    expect(rc == 0 and r["summary"]["exact"] == len(frames), f"dav1d MD5 list of {stream} bit-exact (rc {rc})")
print(f"dav1d: {len(av1_8bit)} 8-bit and {len(av1_10bit)} 10-bit film-grain-test streams checked")

fgc_streams = [os.path.join(CONF, d, "stream.hevc") for d in sorted(os.listdir(CONF))
               if d.startswith("ffmpeg71-") and os.path.exists(os.path.join(CONF, d, "stream.hevc"))]
# the one AFGS1 case with a coded stream (H.265, B-frames; the others are payload files)
afgs1_streams = [os.path.join(CONF, "afgs1-352x288-420p8-bframes", "stream.hevc")]
for stream in fgc_streams + afgs1_streams:
    run([TOOL, "decode", stream, "-o", "decoded.y4m", "-q"], check=0)
    rc, r = verify_json(stream, "decoded.y4m")
    expect(rc == 0, f"filmgrain decode output of {stream} bit-exact (rc {rc})")

# ---- 2. every known mistake, injected into a real stream, is named first -----------------
raw8 = os.path.join(WORK, "input8.yuv")
# moving content: repeated pictures could make a mistaken picture equal a later reference one
run(["ffmpeg", "-v", "error", "-y", "-f", "lavfi", "-i", "testsrc2=size=176x144:rate=25", "-frames:v", "12",
     "-pix_fmt", "yuv420p", "-f", "rawvideo", raw8], check=0)
# An AV1 stream with hidden frames shown later (show_existing_frame): aomenc's alt-ref in
# fixed golden-frame groups of 8 with a 3-level pyramid and no overlay frames, so the
# alt-ref and the pyramid's hidden frames are shown by show_existing_frame headers.
raw17 = os.path.join(WORK, "input8_17.yuv")
run(["ffmpeg", "-v", "error", "-y", "-f", "lavfi", "-i", "testsrc2=size=176x144:rate=25", "-frames:v", "17",
     "-pix_fmt", "yuv420p", "-f", "rawvideo", raw17], check=0)
altref = os.path.join(WORK, "altref.ivf")
run(["aomenc", "--ivf", "-w", "176", "-h", "144", "--fps=25/1", "--i420", "--passes=1", "--cpu-used=6",
     "--end-usage=q", "--cq-level=20", "--lag-in-frames=16", "--auto-alt-ref=1", "--enable-overlay=0",
     "--arnr-strength=0", "--min-gf-interval=8", "--max-gf-interval=8", "--gf-max-pyr-height=3", "--limit=17",
     "--film-grain-test=2", "-o", altref, raw17, "-q"], check=0)


def av1_show_existing_frames(path):
    """Temporal units (IVF frames) of an AV1 IVF file whose frame header OBU has
    show_existing_frame = 1 (AV1 5.9.2: its first bit; aomenc streams have no
    reduced_still_picture_header)."""
    data, found, pos, tu = open(path, "rb").read(), [], 32, 0
    while pos + 12 <= len(data):
        end = pos + 12 + int.from_bytes(data[pos:pos + 4], "little")
        p = pos + 12
        while p < end:
            header = data[p]
            obu_type, has_ext, has_size = (header >> 3) & 15, (header >> 2) & 1, (header >> 1) & 1
            p += 1 + has_ext
            size, shift = 0, 0
            if has_size:
                while True:
                    b = data[p]
                    p += 1
                    size |= (b & 0x7f) << shift
                    shift += 7
                    if not b & 0x80:
                        break
            else:
                size = end - p
            if obu_type == 3 and size and data[p] & 0x80:  # OBU_FRAME_HEADER, show_existing_frame
                found.append(tu)
            p += size
        pos, tu = end, tu + 1
    return found


altref_shown_existing = av1_show_existing_frames(altref)
print(f"{os.path.basename(altref)}: show_existing_frame = 1 in temporal units {altref_shown_existing}")
expect(len(altref_shown_existing) >= 2, f"{altref} has frame headers with show_existing_frame = 1 "
                                        f"(got {altref_shown_existing})")
# dav1d's output of it is the reference: the shown frames take their slots' grain and seed
run(["dav1d", "-q", "-i", altref, "-o", "dav1d.y4m"], check=0)
rc, r = verify_json(altref, "dav1d.y4m")
expect(rc == 0 and r["summary"]["all_exact"], f"dav1d output of {altref} bit-exact (rc {rc})")
# AV1 with update_grain = 0 (film_grain_params_ref_idx): aomenc --film-grain-table writes it for
# entries whose update flag is 0. libaom reads no parameters for such an entry (all zero but
# apply_grain and the seed) and must find a reference frame holding that same set, else it
# aborts (bitstream.c: assert ref_frame < REF_FRAMES). So picture 0 takes set A (tv01's),
# picture 1 a set without scaling points (grain on, nothing added) and pictures 2.. update
# nothing: they load picture 1's set while A stays in another of their reference slots,
# which a decoder loading the wrong slot applies.
lines = open(os.path.join(CONF, "av1_tv01_176x144_420p8", "grain.tbl")).read().split("\n")
tick = 10000000 // 25
table = ["filmgrn1", f"E 0 {tick} 1 1000 1", *lines[2:9],
         f"E {tick} {2 * tick} 1 2000 1", "\tp 0 0 0 0 0 0 0 0 0 0 0 0", "\tsY 0 ", "\tsCb 0", "\tsCr 0", "\tcY",
         "\tcCb 0", "\tcCr 0"]
table += [f"E {k * tick} {(k + 1) * tick} 1 {3000 + 111 * k} 0" for k in range(2, 12)]
open("update0.tbl", "w").write("\n".join(table) + "\n")
update0 = os.path.join(WORK, "update0.ivf")
run(["aomenc", "--ivf", "-w", "176", "-h", "144", "--fps=25/1", "--i420", "--passes=1", "--cpu-used=6",
     "--end-usage=q", "--cq-level=20", "--lag-in-frames=0", "--limit=12", "--film-grain-table=update0.tbl",
     "-o", update0, raw8, "-q"], check=0)
run(["dav1d", "-q", "-i", update0, "-o", "dav1d.y4m"], check=0)
rc, r = verify_json(update0, "dav1d.y4m")
expect(rc == 0 and r["summary"]["all_exact"], f"dav1d output of {update0} bit-exact (rc {rc})")
# H.264 with an FGC SEI every third access unit (persistence ends with its picture:
# repetition_period 0) and IDR pictures with idr_pic_id 1, 2... (x264 counts them)
fgc_json = json.load(open(os.path.join(CONF, "ffmpeg71-352x288-420p8-gaps", "fgc.json")))
fgc_json["film_grain_characteristics_repetition_period"] = 0
json.dump(fgc_json, open("h264_fgc.json", "w"))
run(["x264", "--input-res", "176x144", "--fps", "25", "--keyint", "3", "--min-keyint", "1", "--bframes", "0",
     "--qp", "20", "-o", "plain.264", raw8, "--quiet"], check=0)
h264 = os.path.join(WORK, "fgc_every3.264")
run([SEI_TOOL, "plain.264", h264, "h264_fgc.json", "h264", "3"], check=0)
ids = run([TOOL, "verify", "--list-mistakes"], check=0).stdout.split()
expect(len(ids) == 30, f"30 mistakes known (got {len(ids)})")
# H.265 coded at 1920x1088 showing 1920x1080: HM/VTM size the grain blocks by the coded
# picture (deriveFGSBlkSize: over 1920x1080 samples, 16x16); a decoder sizing them by the
# visible 1920x1080 takes 8x8 (fgc.block_size_8)
coded1088 = os.path.join(CONF, "ffmpeg71-1920x1080-420p8-coded1088")
case1088 = json.load(open(os.path.join(coded1088, "case.json")))
expect((case1088["width"], case1088["height"], case1088["coded_width"], case1088["coded_height"]) == (1920, 1080, 1920, 1088),
       f"{coded1088}: shown 1920x1080, coded 1920x1088 (case.json)")
vtm_1088 = (os.path.join(coded1088, "stream.hevc"),
            ["--flavour", "vtm", "--coded-size", f"{case1088['coded_width']}x{case1088['coded_height']}"])
# (stream, extra arguments: the reference flavour the decoder is checked against)
candidates = {"av1": [(s, []) for s in av1_8bit + [os.path.join(CONF, "av1_tv01_352x288_420p10", "stream.ivf"), altref,
                                          update0]],
              "fgc": [(s, []) for s in fgc_streams] + [(h264, ["--persistence", "reference"])]
                     + [(s, ["--flavour", "vtm"]) for s in fgc_streams if "1280x720" in s]
                     + [vtm_1088],
              "any": [(s, []) for s in av1_8bit[:1] + fgc_streams[:1] + afgs1_streams]}
exercised, not_exercised = [], []
for mistake in ids:
    family = "av1" if mistake.startswith("av1.") else "fgc" if mistake.startswith("fgc.") else "any"
    done = False
    for stream, extra in candidates[family]:
        p = run([TOOL, "verify", stream, "--simulate", mistake, "-o", "broken.y4m", *extra], check=0)
        changed = int(p.stderr.split(", ")[-1].split(" changed")[0])
        if changed == 0:
            continue
        rc, r = verify_json(stream, "broken.y4m", *extra)
        named = r["diagnosis"][0]["id"] if r["diagnosis"] else None
        expect(rc == 1, f"{mistake} on {stream}: exit 1 (got {rc})")
        expect(r["diagnosis"] and r["diagnosis"][0]["frames_exact"] == changed,
               f"{mistake} on {stream}: the first diagnosis reproduces all {changed} changed pictures")
        if named != mistake:
            # allowed only when the named mistake gives the identical pictures on this stream
            run([TOOL, "verify", stream, "--simulate", named, "-o", "other.y4m", *extra], check=0)
            same = open("broken.y4m", "rb").read() == open("other.y4m", "rb").read()
            expect(same, f"{mistake} on {stream}: named {named}, whose pictures differ")
            if same:
                print(f"note: {mistake} and {named} give identical pictures on {os.path.relpath(stream, SRC)}; "
                      f"verify names {named} first")
        exercised.append((mistake, (os.path.relpath(stream, SRC) if stream.startswith(SRC) else os.path.basename(stream))
                          + " " + " ".join(extra), changed))
        done = True
        break
    if not done:
        not_exercised.append(mistake)
for m, s, c in exercised:
    print(f"named: {m:45s} {s} ({c} picture(s))")
# the seed-reuse mistake changes show_existing_frame pictures only, on aomenc's alt-ref stream
sef = [(s, c) for m, s, c in exercised if m == "av1.show_existing_frame_reuses_previous"]
expect(sef and os.path.basename(sef[0][0].split()[0]) == "altref.ivf" and 1 <= sef[0][1] <= len(altref_shown_existing),
       f"av1.show_existing_frame_reuses_previous exercised on altref.ivf's {len(altref_shown_existing)} "
       f"show_existing_frame pictures (got {sef})")
# the wrong slot exists only for update_grain = 0 pictures (the scan lists the other slots of
# those alone): on update0.ivf, where A stays in a slot the picture does not load from
slot = [(s, c) for m, s, c in exercised if m == "av1.update_grain_wrong_slot"]
expect(slot and os.path.basename(slot[0][0].split()[0]) == "update0.ivf",
       f"av1.update_grain_wrong_slot exercised on update0.ivf (got {slot})")
print("no candidate stream exercises:", ", ".join(not_exercised) or "none")
# every mistake, the stream-state ones included, is exercised on a real stream
for m in not_exercised:
    expect(False, f"{m}: no real stream exercised it")
# FFmpeg's own persistence (which `filmgrain decode` follows, taking the grain libav exports):
# an H.264 SEI with repetition_period 0 ends with its picture. By default verify reads the
# stream as decode does, so decode's output is bit-exact; checked against the reference's
# persistence (HM reuses the last SEI) it is a real decoder making fgc.semantic_persistence.
run([TOOL, "decode", h264, "-o", "decoded.y4m", "-q"], check=0)
rc, r = verify_json(h264, "decoded.y4m")
expect(rc == 0, f"filmgrain decode of {h264} bit-exact by default, the stream read as decode reads it (rc {rc})")
rc, r = verify_json(h264, "decoded.y4m", "--persistence", "reference")
expect(rc == 1 and r["diagnosis"] and r["diagnosis"][0]["id"] == "fgc.semantic_persistence" and
       r["diagnosis"][0]["frames_exact"] == r["summary"]["mismatching"] > 0,
       f"filmgrain decode of {h264} (FFmpeg's persistence) against --persistence reference: "
       f"fgc.semantic_persistence (rc {rc})")
rc, r = verify_json(h264, "decoded.y4m", "--persistence", "semantic")
expect(rc == 0, f"filmgrain decode of {h264} bit-exact with --persistence semantic (rc {rc})")

# ---- 3. a decoder that dropped pictures ----------------------------------------------------
stream = afgs1_streams[0]
run([TOOL, "decode", stream, "-o", "full.y4m", "-q"], check=0)
header, frames = y4m_frames("full.y4m")
write_y4m("dropped.y4m", header, [f for i, f in enumerate(frames) if i not in (2, 5)])
rc, r = verify_json(stream, "dropped.y4m")
missing = [f["index"] for f in r["frames"] if f["missing"]]
expect(rc == 1 and missing == [2, 5], f"dropped pictures 2 and 5 reported missing (got {missing}, rc {rc})")
expect(r["summary"]["exact"] == len(frames) - 2, f"the other {len(frames) - 2} pictures stay aligned and bit-exact "
                                                  f"(got {r['summary']['exact']})")
write_y4m("short.y4m", header, frames[:-3])
rc, r = verify_json(stream, "short.y4m")
missing = [f["index"] for f in r["frames"] if f["missing"]]
expect(missing == list(range(len(frames) - 3, len(frames))), f"the last 3 pictures missing at the end (got {missing})")

# ---- 4. dav1d without grain ------------------------------------------------------------------
run(["dav1d", "-q", "--filmgrain", "0", "-i", av1_8bit[0], "-o", "nograin.y4m"], check=0)
rc, r = verify_json(av1_8bit[0], "nograin.y4m")
expect(rc == 1 and r["diagnosis"][0]["id"] == "grain_not_applied", "dav1d --filmgrain 0 diagnosed as grain not applied")

# ---- 5. a decoder no known mistake describes ---------------------------------------------
ff_stream = os.path.join(CONF, "ffmpeg71-350x198-420p8", "stream.hevc")
run(["ffmpeg", "-v", "error", "-y", "-i", ff_stream, "-f", "yuv4mpegpipe", "-pix_fmt", "yuv420p", "ffmpeg51.y4m"], check=0)
p = run([TOOL, "verify", ff_stream, "--decoded", "ffmpeg51.y4m", "--json", "ffmpeg51.json", "-q"])
r = json.load(open("ffmpeg51.json"))
expect(p.returncode == 1 and r["summary"]["exact"] == 0, f"FFmpeg 5.1's own grain mismatches (rc {p.returncode})")
expect(all(d["frames_exact"] == 0 for d in r["diagnosis"]), "no known mistake reproduces FFmpeg 5.1's grain")
expect("no known mistake explains it" in p.stdout + p.stderr, "the summary says no known mistake explains it: " +
       (p.stdout + p.stderr).strip()[-300:])

if failures:
    print(f"{len(failures)} failure(s)")
    sys.exit(1)
print("all decoder acceptance checks passed")
