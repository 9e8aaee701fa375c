#!/usr/bin/env python3
# Alpha textures for the STSV scaling bench: square plates of N x N texels perforated by a k x k grid of round holes
# (gray PNG, 255 = opaque, 0 = hole), written beside this script. `mesh_alpha` turns each opaque texel into two
# triangles, so the meshed plate's triangle count grows as N^2 while the perforated plate stays 2 S-triangles.
# Pure Python (zlib + struct): no imaging library needed. Prints name, size, holes, opaque texels, triangles.
import os, struct, sys, zlib

HERE = os.path.dirname(os.path.abspath(__file__))
# (texels per side, holes per side): sizes 8..256 with holes every 8 texels, plus hole counts at 64^2.
PLATES = [(8, 1), (16, 2), (32, 4), (64, 8), (128, 16), (256, 32), (64, 2), (64, 16)]


def png_gray(path, rows):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    height, width = len(rows), len(rows[0])
    raw = b"".join(b"\x00" + bytes(row) for row in rows)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def plate(n, holes):
    pitch = n / holes
    radius = 0.3 * pitch  # holes take about 28 % of the plate
    rows = []
    for y in range(n):
        row = []
        for x in range(n):
            cx = (int(x / pitch) + 0.5) * pitch
            cy = (int(y / pitch) + 0.5) * pitch
            inside = (x + 0.5 - cx) ** 2 + (y + 0.5 - cy) ** 2 < radius ** 2
            row.append(0 if inside else 255)
        rows.append(row)
    return rows


print("texture,texels,holes,opaque_texels,mesh_triangles")
for n, holes in PLATES:
    rows = plate(n, holes)
    name = f"plate-{n}-h{holes}.png"
    png_gray(os.path.join(HERE, name), rows)
    opaque = sum(v > 127 for row in rows for v in row)
    print(f"{name},{n},{holes * holes},{opaque},{2 * opaque}")
