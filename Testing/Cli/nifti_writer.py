"""Writes small NIfTI-1 files with the standard library only, for tests of the cbc3d command."""
import gzip
import struct

# NIfTI-1 datatype codes and their struct formats.
DATATYPES = {"uint8": (2, "B"), "int16": (4, "h"), "int32": (8, "i"), "float32": (16, "f"),
             "rgb24": (128, "BBB")}


def write_nifti(path, dims, values, dtype="int16", spacing=(1.0, 1.0, 1.0)):
    """dims: (nx, ny, nz); values: flat list, x fastest (tuples for rgb24)."""
    code, fmt = DATATYPES[dtype]
    bitpix = 8 * struct.calcsize("<" + fmt)
    header = bytearray(348)
    struct.pack_into("<i", header, 0, 348)
    struct.pack_into("<8h", header, 40, 3, dims[0], dims[1], dims[2], 1, 1, 1, 1)
    struct.pack_into("<hh", header, 70, code, bitpix)
    struct.pack_into("<8f", header, 76, 1.0, spacing[0], spacing[1], spacing[2], 0, 0, 0, 0)
    struct.pack_into("<f", header, 108, 352.0)  # vox_offset
    struct.pack_into("<f", header, 112, 1.0)  # scl_slope
    header[344:348] = b"n+1\0"
    body = bytearray()
    for v in values:
        body += struct.pack("<" + fmt, *(v if isinstance(v, tuple) else (v,)))
    data = bytes(header) + b"\0\0\0\0" + bytes(body)
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "wb") as f:
        f.write(data)
