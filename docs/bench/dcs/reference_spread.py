#!/usr/bin/env python3
"""The spread of visibility over the penumbra of every ray-traced reference in a bench cache, for the pattern
table's "i.i.d." column (run from the repository root):
    python3 docs/bench/dcs/reference_spread.py /tmp/slcache-dcs > docs/bench/dcs/reference-spread.json
For a pixel whose true visible fraction is v, N independent uniform light samples give an estimate with variance
v (1 - v) / N; the reference (1024 stratified samples) adds at most v (1 - v) / 1024. So
    sqrt(mean over penumbra pixels of v (1 - v)) * sqrt(1/N + 1/1024)
is the penumbra RMSE that i.i.d. sampling would reach: a pattern below it gains from its stratification.
The penumbra is ErrorMetrics.h's: 0 < reference < 1 strictly. Reads buffers.vti (zlib-compressed appended raw
data, UInt32 headers, as VTK 9.1 writes it) with the standard library only."""
import json
import os
import re
import struct
import sys
import zlib


def read_array(path, name):
    data = open(path, "rb").read()
    header = data[:data.index(b"<AppendedData")].decode("latin-1")
    match = re.search(r'<DataArray type="Float32" Name="%s"[^>]*offset="(\d+)"' % re.escape(name), header)
    if not match or 'compressor="vtkZLibDataCompressor"' not in header or 'header_type="UInt32"' not in header:
        sys.exit(f"{path}: no zlib-compressed Float32 array {name} with UInt32 headers")
    start = data.index(b"_", data.index(b"<AppendedData")) + 1 + int(match.group(1))
    blocks = struct.unpack_from("<I", data, start)[0]
    sizes = struct.unpack_from("<%dI" % (3 + blocks), data, start)[3:]
    offset = start + 4 * (3 + blocks)
    raw = b""
    for size in sizes:
        raw += zlib.decompress(data[offset:offset + size])
        offset += size
    return struct.unpack("<%df" % (len(raw) // 4), raw)


rows = []
cache = sys.argv[1]
for entry in sorted(os.listdir(cache)):
    directory = os.path.join(cache, entry)
    stats_path = os.path.join(directory, "stats.json")
    if not os.path.isfile(stats_path):
        continue
    stats = json.load(open(stats_path))
    visibility = read_array(os.path.join(directory, "buffers.vti"), "visibility")
    coverage = read_array(os.path.join(directory, "buffers.vti"), "coverage")
    penumbra = [v for v, c in zip(visibility, coverage) if c > 0 and 0.0 < v < 1.0]
    spread = (sum(v * (1.0 - v) for v in penumbra) / len(penumbra)) ** 0.5 if penumbra else 0.0
    rows.append({"scene": stats["scene"], "scene_overrides": stats.get("scene_overrides", []),
                 "resolution": stats["resolution"], "samples": stats["samples"], "sampling": stats["sampling"],
                 "penumbra_pixels": len(penumbra), "penumbra_rms_v_1_minus_v": spread})
print(json.dumps(rows, indent=1))
