#!/usr/bin/env python3
"""Compares two 8-bit RGB(A) PNGs of one frame (before and after a shader change): max and mean absolute
channel difference and PSNR over the pixels that are terrain in both (pixels equal to a background
colour in either image are left out, since the background colour itself may differ).
Usage: png-diff.py A.png B.png [--background R,G,B ...]   (default background: 255,0,255)"""
import struct, sys, zlib, math

def read_png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path}: not a PNG"
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and ctype in (2, 6) and interlace == 0, f"{path}: only 8-bit RGB/RGBA"
            bpp = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, stride = zlib.decompress(idat), w * bpp
    out, prev = bytearray(), bytearray(stride)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], (prev[i - bpp] if i >= bpp else 0)
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out += line
        prev = line
    return w, h, bpp, out

def main():
    args = sys.argv[1:]
    bg = [(255, 0, 255)]
    if "--background" in args:
        i = args.index("--background")
        bg = [tuple(int(v) for v in c.split(",")) for c in args[i + 1:]]
        args = args[:i]
    (w, h, pa, a), (w2, h2, pb, b) = read_png(args[0]), read_png(args[1])
    assert (w, h) == (w2, h2), "sizes differ"
    n = worst = total = sq = 0
    for p in range(w * h):
        ca, cb = tuple(a[p * pa:p * pa + 3]), tuple(b[p * pb:p * pb + 3])
        if ca in bg or cb in bg:
            continue
        n += 1
        for k in range(3):
            d = abs(ca[k] - cb[k])
            worst, total, sq = max(worst, d), total + d, sq + d * d
    mse = sq / max(1, 3 * n)
    psnr = 100.0 if mse == 0 else 10 * math.log10(255 ** 2 / mse)
    print(f"{args[0]} vs {args[1]}: {n} terrain pixels of {w * h}, max {worst}, mean {total / max(1, 3 * n):.3f}, PSNR {psnr:.1f} dB")

main()
