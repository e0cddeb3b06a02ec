#!/usr/bin/env python3
"""Prints the coefficients of core/math/portable_atan2.h: a Chebyshev fit (mpmath.chebyfit, 60 digits)
of P(s) = (atan √s − √s) / s^(3/2) on [0, tan²(π/8)], highest degree first, with its error, and the
low parts of π, π/2 and π/4."""
import mpmath as mp

mp.mp.dps = 60
LIMIT = mp.tan(mp.pi / 8) ** 2


def p(s):
    if s == 0:
        return mp.mpf(-1) / 3
    r = mp.sqrt(s)
    return (mp.atan(r) - r) / (s * r)


coefficients, error = mp.chebyfit(p, [0, LIMIT], 11, error=True)
print("kP =", ", ".join(repr(float(c)) for c in coefficients))
print("fit error", mp.nstr(error, 5), "(relative error of atan z at most tan²(π/8) times that)")
print("kTanPiOver8 =", repr(float(mp.tan(mp.pi / 8))))
for name, value in (("kPi", mp.pi), ("kPiOver2", mp.pi / 2), ("kPiOver4", mp.pi / 4)):
    high = float(value)
    print(f"{name} = {high!r}, low = {float(value - mp.mpf(high))!r}")
