#!/usr/bin/env python3
"""Pads a NIfTI-1 label image with background on the high side of every axis (plain Python 3).

usage: pad_nifti.py IN.nii[.gz] OUT.nii[.gz] FACTOR [VALUE]
Each axis grows to round(dim * FACTOR ** (1/3)) voxels, so the image holds about FACTOR times
its voxels; the new voxels hold VALUE (default 0). The low side is untouched, so the world frame
(origin, spacing, direction) is the same and a mesh of the padded image can be compared byte for
byte with the unpadded one's.
"""
import gzip
import struct
import sys


def main():
    src, dst, factor = sys.argv[1], sys.argv[2], float(sys.argv[3])
    value = int(sys.argv[4]) if len(sys.argv) > 4 else 0
    data = (gzip.open if src.endswith(".gz") else open)(src, "rb").read()
    dim = list(struct.unpack("<8h", data[40:56]))
    datatype, bitpix = struct.unpack("<hh", data[70:74])
    offset = int(struct.unpack("<f", data[108:112])[0])
    if dim[0] != 3 and not all(d == 1 for d in dim[4:dim[0] + 1]):
        sys.exit("a 3-D image is required")
    size = bitpix // 8
    old = dim[1:4]
    grow = factor ** (1.0 / 3.0)
    new = [max(o, int(round(o * grow))) for o in old]
    codes = {2: "B", 4: "h", 8: "i", 16: "f", 64: "d", 256: "b", 512: "H", 768: "I"}
    fill = struct.pack("<" + codes[datatype], value)
    body = data[offset:offset + old[0] * old[1] * old[2] * size]
    rows = []
    row_pad = fill * (new[0] - old[0])
    slice_pad = fill * (new[0] * (new[1] - old[1]))
    for k in range(old[2]):
        for j in range(old[1]):
            start = (k * old[1] + j) * old[0] * size
            rows.append(body[start:start + old[0] * size])
            rows.append(row_pad)
        rows.append(slice_pad)
    rows.append(fill * (new[0] * new[1] * (new[2] - old[2])))
    header = bytearray(data[:offset])
    header[40:56] = struct.pack("<8h", 3, new[0], new[1], new[2], 1, 1, 1, 1)
    out = (gzip.open if dst.endswith(".gz") else open)(dst, "wb")
    out.write(bytes(header) + b"".join(rows))
    out.close()
    print("%s: %s -> %s voxels (%.3f times)" % (dst, old, new, new[0] * new[1] * new[2] / (old[0] * old[1] * old[2])))


if __name__ == "__main__":
    main()
