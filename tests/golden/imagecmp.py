#!/usr/bin/env python3
"""imagecmp.py - compares two PNGs within a tolerance and writes a diff image; stdlib only (zlib)."""
import struct
import sys
import zlib


def read_png(path):
    """Returns (width, height, rows of RGBA bytes) for 8-bit RGB/RGBA non-interlaced PNGs."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG file")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, color, _, _, interlace = header
    if depth != 8 or color not in (2, 6) or interlace:
        raise ValueError(f"{path}: only 8-bit RGB/RGBA non-interlaced PNGs are supported")
    channels = 4 if color == 6 else 3
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = previous[i]
            c = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        previous = line
        if channels == 3:
            line = bytearray(b for px in range(width) for b in (*line[px * 3:px * 3 + 3], 255))
        rows.append(bytes(line))
    return width, height, rows


def write_png(path, width, height, rows):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + r for r in rows)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def main():
    if len(sys.argv) != 6:
        print("usage: imagecmp.py EXPECTED ACTUAL DIFF_OUT PIXEL_THRESHOLD MAX_FRACTION", file=sys.stderr)
        return 2
    expected, actual, diff_path = sys.argv[1:4]
    threshold, max_fraction = int(sys.argv[4]), float(sys.argv[5])
    w1, h1, a = read_png(expected)
    w2, h2, b = read_png(actual)
    if (w1, h1) != (w2, h2):
        print(f"size differs: expected {w1}x{h1}, got {w2}x{h2}")
        return 1
    over, total_abs, diff_rows = 0, 0, []
    for ra, rb in zip(a, b):
        out = bytearray()
        for x in range(w1):
            d = max(abs(ra[x * 4 + c] - rb[x * 4 + c]) for c in range(4))
            total_abs += d
            over += d > threshold
            out += bytes((255, 0, 0, 255)) if d > threshold else bytes((d * 4 if d * 4 < 255 else 255,) * 3 + (255,))
        diff_rows.append(bytes(out))
    fraction = over / (w1 * h1)
    mean = total_abs / (w1 * h1)
    ok = fraction <= max_fraction
    print(f"{'ok' if ok else 'FAIL'}: {over} pixels ({fraction:.4%}) differ by more than {threshold}, "
          f"allowed {max_fraction:.4%}; mean max-channel difference {mean:.3f}")
    if not ok:
        write_png(diff_path, w1, h1, diff_rows)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
