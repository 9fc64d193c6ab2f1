#!/usr/bin/env python3
"""TestParaViewGui: the real ParaView GUI loads the CBC3D plugin and renders a lattice.

Runs (system Python, standard library only)
    xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" paraview --dr --script=gui_script.py --exit
with a time limit, then judges only the exit code and the picture (the GUI may print
warnings): the script's marker file says it ran to the end with a non-empty lattice, and the
PNG, decoded here with zlib and struct, is 800 x 600 with many colours and no single colour
covering almost all of it. Skips (77) when xvfb-run or paraview is missing or Xvfb cannot
start. Environment: CBC3D_PLUGIN, CBC3D_SOURCE_DIR, CBC3D_TEST_OUTPUT.
"""
import collections
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

TIME_LIMIT = 120


def skip(message):
    print("SKIP: " + message)
    sys.exit(77)


def read_png(path):
    """(width, height, rows of (r, g, b) tuples) of an 8-bit RGB/RGBA/grey PNG, not interlaced."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG file")
    position, idat, header = 8, [], None
    while position < len(data):
        length, kind = struct.unpack(">I4s", data[position:position + 8])
        body = data[position + 8:position + 8 + length]
        if zlib.crc32(kind + body) & 0xFFFFFFFF != struct.unpack(">I", data[position + 8 + length:position + 12 + length])[0]:
            raise ValueError("bad CRC in chunk %r" % kind)
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
        position += 12 + length
    width, height, depth, colour_type, _, _, interlace = header
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(colour_type)
    if depth != 8 or channels is None or interlace:
        raise ValueError("unsupported PNG: depth %d, colour type %d, interlace %d" % (depth, colour_type, interlace))
    raw = zlib.decompress(b"".join(idat))
    stride = width * channels
    previous = bytearray(stride)
    rows = []
    for y in range(height):
        start = y * (stride + 1)
        kind, line = raw[start], bytearray(raw[start + 1:start + 1 + stride])
        if kind == 1:
            for i in range(channels, stride):
                line[i] = (line[i] + line[i - channels]) & 0xFF
        elif kind == 2:
            line = bytearray((a + b) & 0xFF for a, b in zip(line, previous))
        elif kind == 3:
            for i in range(stride):
                left = line[i - channels] if i >= channels else 0
                line[i] = (line[i] + ((left + previous[i]) >> 1)) & 0xFF
        elif kind == 4:
            for i in range(stride):
                a = line[i - channels] if i >= channels else 0
                b = previous[i]
                c = previous[i - channels] if i >= channels else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 0xFF
        elif kind != 0:
            raise ValueError("bad PNG filter %d" % kind)
        if channels >= 3:
            rows.append([tuple(line[i:i + 3]) for i in range(0, stride, channels)])
        else:
            rows.append([(line[i],) * 3 for i in range(0, stride, channels)])
        previous = line
    return width, height, rows


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    plugin = os.environ["CBC3D_PLUGIN"]
    source = os.environ["CBC3D_SOURCE_DIR"]
    work = os.path.join(os.environ["CBC3D_TEST_OUTPUT"], "TestParaViewGui")
    xvfb_run = shutil.which("xvfb-run")
    paraview = shutil.which("paraview")
    if xvfb_run is None:
        skip("xvfb-run is not installed (apt-get install xvfb xauth)")
    if paraview is None:
        skip("the paraview GUI is not on PATH")

    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    screenshot = os.path.join(work, "gui.png")
    environment = dict(os.environ, CBC3D_GUI_SCREENSHOT=screenshot)
    environment.setdefault("XDG_RUNTIME_DIR", tempfile.mkdtemp(prefix="runtime-", dir=work))
    # -noreset: see Testing/Python/TestExampleScript.py (Xvfb resets when a client leaves).
    command = [xvfb_run, "-a", "-s", "-screen 0 1280x1024x24 -noreset", paraview, "--dr",
               "--script=" + os.path.join(here, "gui_script.py"), "--exit"]
    print(" ".join(command))
    try:
        # start_new_session: on a timeout the whole group (xvfb-run, Xvfb, paraview) is killed.
        process = subprocess.Popen(command, env=environment, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                   text=True, start_new_session=True)
        output, _ = process.communicate(timeout=TIME_LIMIT)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, 9)
        process.communicate()
        print("FAIL: paraview did not exit within %d s" % TIME_LIMIT)
        return 1
    print(output)
    if process.returncode != 0 and "Xvfb failed to start" in output:
        skip("the X server (Xvfb) could not start")

    failures = []

    def check(condition, message):
        print(("ok   " if condition else "FAIL ") + message)
        if not condition:
            failures.append(message)
        return condition

    check(process.returncode == 0, "paraview exits 0 (got %d)" % process.returncode)
    marker = screenshot + ".txt"
    if check(os.path.isfile(marker), "the script ran to the end (%s)" % marker):
        lines = open(marker).read().split()
        cells = int(lines[-1]) if lines and lines[-1].isdigit() else 0
        check(cells > 1000, "the lattice has %d tets" % cells)
    if check(os.path.isfile(screenshot), "the screenshot exists: " + screenshot):
        width, height, rows = read_png(screenshot)
        check((width, height) == (800, 600), "the screenshot is 800 x 600 (got %d x %d)" % (width, height))
        counts = collections.Counter(pixel for row in rows for pixel in row)
        commonest, share = counts.most_common(1)[0]
        share /= float(width * height)
        print("%d colours; the commonest, %s, covers %.0f%%" % (len(counts), commonest, 100 * share))
        check(len(counts) > 50, "the screenshot has many colours (%d)" % len(counts))
        check(share < 0.95, "no single colour covers 95% of the screenshot")
    print("%d failed checks" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
