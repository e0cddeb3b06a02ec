#!/usr/bin/env python3
"""Signed-error picture of low-spp renders against a reference (docs/images/zsobol-vs-sobol-4spp.png).

usage: tools/error_image.py REFERENCE.pfm OUT.png LABEL=RENDER.pfm ...
Top row: estimate - reference (luminance; blue below, red above, one scale for all); bottom row: the
same error averaged over 4x4 pixel blocks (what is left of it at a quarter of the resolution), on a
4x finer scale; the scale is the 95th percentile of |error| away from the emitter. Prints each
render's RMSE at full and at block resolution over blocks that see no emitter. Standard library only.
"""
import struct, sys, zlib


def read_pfm(path):
    with open(path, 'rb') as f:
        kind = f.readline().strip()
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = f.read()
    ch = 3 if kind == b'PF' else 1
    fmt = ('<' if scale < 0 else '>') + 'f' * (w * h * ch)
    v = struct.unpack(fmt, data[:4 * w * h * ch])
    lum = [0.0] * (w * h)
    for y in range(h):  # PFM rows run bottom to top
        for x in range(w):
            i = ((h - 1 - y) * w + x) * ch
            lum[y * w + x] = (0.212671 * v[i] + 0.715160 * v[i + 1] + 0.072169 * v[i + 2]) if ch == 3 else v[i]
    return w, h, lum


def blocks(err, w, h, b):
    out = []
    for by in range(h // b):
        for bx in range(w // b):
            out.append(sum(err[(by * b + j) * w + bx * b + i] for j in range(b) for i in range(b)) / (b * b))
    return out


def colour(e, s):
    t = max(-1.0, min(1.0, e / s))
    if t >= 0:
        return (255, int(255 * (1 - t)), int(255 * (1 - t)))
    return (int(255 * (1 + t)), int(255 * (1 + t)), 255)


def write_png(path, w, h, rows):
    raw = b''.join(b'\x00' + bytes(c for px in row for c in px) for row in rows)
    def chunk(t, d):
        return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
    png = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 2, 0, 0, 0))
    png += chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b'')
    with open(path, 'wb') as f:
        f.write(png)


def main():
    ref_path, out = sys.argv[1], sys.argv[2]
    w, h, ref = read_pfm(ref_path)
    runs = []
    for arg in sys.argv[3:]:
        label, path = arg.split('=', 1)
        rw, rh, est = read_pfm(path)
        assert (rw, rh) == (w, h), path
        err = [e - r for e, r in zip(est, ref)]
        runs.append((label, err, blocks(err, w, h, 4)))
    # Statistics and colour scale leave out blocks that see an emitter (reference above 1.5 in a block):
    # their filter variance dwarfs everything else.
    bright = [v > 0 for v in blocks([float(r > 1.5) for r in ref], w, h, 4)]
    keep = [not bright[(y // 4) * (w // 4) + x // 4] for y in range(h) for x in range(w)]
    rms = lambda v, m: (sum(x * x for x, k in zip(v, m) if k) / max(1, sum(m))) ** 0.5
    blockKeep = [not b for b in bright]
    for label, err, blk in runs:
        print(f'{label}: RMSE {rms(err, keep):.4g} per pixel, {rms(blk, blockKeep):.4g} over 4x4 blocks '
              f'(blocks that see no emitter)')
    mags = sorted(abs(e) for _, err, _ in runs for e, k in zip(err, keep) if k)
    s = mags[int(0.95 * (len(mags) - 1))]
    zoom, gap = 3, 8
    W = len(runs) * (w * zoom + gap) + gap
    H = 2 * (h * zoom + gap) + gap
    img = [[(245, 245, 245)] * W for _ in range(H)]
    for k, (label, err, blk) in enumerate(runs):
        x0 = gap + k * (w * zoom + gap)
        for y in range(h * zoom):
            for x in range(w * zoom):
                img[gap + y][x0 + x] = colour(err[(y // zoom) * w + x // zoom], s)
                img[2 * gap + h * zoom + y][x0 + x] = colour(blk[(y // (4 * zoom)) * (w // 4) + x // (4 * zoom)], s / 4)
    write_png(out, W, H, img)
    print(f'wrote {out}: columns {", ".join(l for l, _, _ in runs)}; error scale +-{s:.3g} (top), +-{s / 4:.3g} (bottom)')


if __name__ == '__main__':
    main()
