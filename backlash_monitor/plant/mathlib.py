"""Math helpers for effect terms: one name, two implementations (docs/effects.md).

A term function (see :mod:`backlash_monitor.plant.effects`) is written once and runs

- compiled, inside the generated SIMD stage and the scalar right-hand side: there the helpers below
  are numba functions inlined into the loop. They avoid libm calls (numba's LLVM has no vectorised
  ``exp``, ``log``, ``pow``, ``sin``: one libm call turns the whole SIMD loop back into scalar code)
  and branches (``where`` is a select);
- on numpy arrays, in the numpy backend and the solve_ivp reference: there the same names are bound
  to numpy functions (``NUMPY_NAMESPACE``).

The polynomial ``exp``/``log`` are those the hand-written SIMD kernel used (relative error < 1e-13,
tested); ``sin``/``cos`` reduce the argument by Cody-Waite in three parts of pi/2 (exact to ~1e-16
relative for |x| < 1e5 rad, i.e. 10 minutes of motor angle; beyond that the error grows ~|x|*1e-21)
and evaluate Taylor polynomials to degree 17/18 on |r| <= pi/4 (truncation < 1e-19).
"""
from __future__ import annotations

import math

import numpy as np

from ._numba import HAVE_NUMBA, numba

__all__ = ["where", "fabs", "fmax", "fmin", "sign", "smooth_sign", "sqrt", "exp", "log", "power", "sin", "cos"]

_LN2_HI = 6.93147180369123816490e-01
_LN2_LO = 1.90821492927058770002e-10
_INV_LN2 = 1.44269504088896338700e+00
_SQRT2 = 1.4142135623730951
_MANT = 0x000FFFFFFFFFFFFF
_ONE_BITS = 0x3FF0000000000000
_TINY = 1e-290
_TWO_OVER_PI = 0.63661977236758134308
_PIO2_1 = 1.57079632673412561417e+00     # first 33 bits of pi/2
_PIO2_2 = 6.07710050650619224932e-11     # next 33 bits
_PIO2_3 = 2.02226624879595063154e-21     # the rest


def _where_py(cond, a, b):
    return a if cond else b


def _sign_py(x):
    return 1.0 if x > 0.0 else (-1.0 if x < 0.0 else 0.0)


def _smooth_sign_py(x, eps):
    return x / math.sqrt(x * x + eps * eps)


if HAVE_NUMBA:
    from numba.core import types
    from numba.extending import intrinsic

    @intrinsic
    def _f2i(typingctx, x):
        """float64 -> int64 bit pattern (an LLVM bitcast: free, vectorises)."""
        sig = types.int64(types.float64)

        def codegen(context, builder, signature, args):
            return builder.bitcast(args[0], context.get_value_type(types.int64))
        return sig, codegen

    @intrinsic
    def _i2f(typingctx, x):
        """int64 bit pattern -> float64."""
        sig = types.float64(types.int64)

        def codegen(context, builder, signature, args):
            return builder.bitcast(args[0], context.get_value_type(types.float64))
        return sig, codegen

    _jit = numba.njit(inline="always", fastmath=True, error_model="numpy", cache=False)

    @_jit
    def where(cond, a, b):
        """``a`` where ``cond`` else ``b`` (a select; both are evaluated)."""
        return a if cond else b

    @_jit
    def fabs(x):
        return abs(x)

    @_jit
    def fmax(x, y):
        return x if x > y else y

    @_jit
    def fmin(x, y):
        return x if x < y else y

    @_jit
    def sign(x):
        """+1, -1, or 0 at 0."""
        return 1.0 if x > 0.0 else (-1.0 if x < 0.0 else 0.0)

    @_jit
    def smooth_sign(x, eps):
        """x/sqrt(x^2 + eps^2): sign(x) to a relative error eps^2/(2 x^2) for |x| >> eps, smooth at 0."""
        return x / math.sqrt(x * x + eps * eps)

    @_jit
    def sqrt(x):
        return math.sqrt(x)

    @_jit
    def log(x):
        """Natural log for x > 0 (x is clamped to >= 1e-290), polynomial, relative error < 1e-13."""
        b = _f2i(max(x, _TINY))
        m = _i2f((b & _MANT) | _ONE_BITS)
        e = np.float64((b >> 52) - 1023)
        big = m > _SQRT2
        m = m * 0.5 if big else m
        e = e + 1.0 if big else e
        t = (m - 1.0) / (m + 1.0)
        t2 = t * t
        pl = 2.0 * t * (1.0 + t2 * (1.0 / 3 + t2 * (1.0 / 5 + t2 * (1.0 / 7 + t2 * (1.0 / 9 + t2 * (
            1.0 / 11 + t2 * (1.0 / 13 + t2 * (1.0 / 15 + t2 * (1.0 / 17)))))))))
        return e * _LN2_HI + (e * _LN2_LO + pl)

    @_jit
    def exp(y):
        """exp(y) for -690 < y < 709 (clamped), polynomial, relative error < 1e-13."""
        kf = math.floor(y * _INV_LN2 + 0.5)
        kf = max(min(kf, 1000.0), -1000.0)
        r = (y - kf * _LN2_HI) - kf * _LN2_LO
        ex = 1.0 + r * (1.0 + r * (0.5 + r * (1.0 / 6 + r * (1.0 / 24 + r * (1.0 / 120 + r * (1.0 / 720 + r * (
            1.0 / 5040 + r * (1.0 / 40320 + r * (1.0 / 362880 + r * (1.0 / 3628800 + r * (
                1.0 / 39916800 + r * (1.0 / 479001600))))))))))))
        return ex * _i2f((np.int64(kf) + 1023) << 52)

    @_jit
    def power(x, n):
        """x**n for x >= 0 (0 for x = 0 when n > 0), as exp(n*log x) with the polynomial forms."""
        return exp(n * log(x)) if x > 0.0 else 0.0

    # libm forms for the scalar right-hand side (codegen renames exp -> s_exp ... there)
    @_jit
    def s_exp(y):
        return math.exp(y)

    @_jit
    def s_log(x):
        return math.log(x)

    @_jit
    def s_power(x, n):
        return math.exp(n * math.log(x)) if x > 0.0 else 0.0

    @_jit
    def s_sin(x):
        return math.sin(x)

    @_jit
    def s_cos(x):
        return math.cos(x)

    @_jit
    def _sincos_kernel(x):
        k = math.floor(x * _TWO_OVER_PI + 0.5)
        r = ((x - k * _PIO2_1) - k * _PIO2_2) - k * _PIO2_3
        r2 = r * r
        s = r * (1.0 + r2 * (-1.0 / 6 + r2 * (1.0 / 120 + r2 * (-1.0 / 5040 + r2 * (1.0 / 362880 + r2 * (
            -1.0 / 39916800 + r2 * (1.0 / 6227020800 + r2 * (-1.0 / 1307674368000 + r2 * (
                1.0 / 355687428096000)))))))))
        c = 1.0 + r2 * (-0.5 + r2 * (1.0 / 24 + r2 * (-1.0 / 720 + r2 * (1.0 / 40320 + r2 * (
            -1.0 / 3628800 + r2 * (1.0 / 479001600 + r2 * (-1.0 / 87178291200 + r2 * (
                1.0 / 20922789888000 + r2 * (-1.0 / 6402373705728000)))))))))
        q = np.int64(k) & 3
        return s, c, q

    @_jit
    def sin(x):
        """sin(x), vectorisable (no libm call)."""
        s, c, q = _sincos_kernel(x)
        v = s if (q & 1) == 0 else c
        return -v if q >= 2 else v

    @_jit
    def cos(x):
        """cos(x), vectorisable (no libm call)."""
        s, c, q = _sincos_kernel(x)
        v = c if (q & 1) == 0 else -s
        return -v if q >= 2 else v
else:  # pragma: no cover - without numba the helpers are the numpy ones
    def where(cond, a, b):
        return np.where(cond, a, b)
    fabs, fmax, fmin, sign, sqrt = np.abs, np.maximum, np.minimum, np.sign, np.sqrt
    exp, log, sin, cos = np.exp, np.log, np.sin, np.cos

    def smooth_sign(x, eps):
        return x / np.sqrt(x * x + eps * eps)

    def power(x, n):
        return np.power(x, n)
    s_exp, s_log, s_power, s_sin, s_cos = exp, log, power, sin, cos


def _np_power(x, n):
    # ``**`` (not np.power): on numpy scalars it is libm's pow, as the former numpy form used; np.power on
    # 0-d input goes through numpy's SIMD loop, 1 ulp apart, and the solve_ivp reference is sensitive to
    # ulps at the zone crossing (measured: 6e-5 vs 8e-7 of a window peak from a 1-ulp change)
    return np.maximum(x, 0.0) ** n


def _np_smooth_sign(x, eps):
    return x / np.sqrt(x * x + eps * eps)


# the numpy forms (array arguments): the namespace the numpy backend runs the term sources in
NUMPY_NAMESPACE = {
    "where": np.where, "fabs": np.abs, "fmax": np.maximum, "fmin": np.minimum, "sign": np.sign,
    "smooth_sign": _np_smooth_sign, "sqrt": np.sqrt, "exp": np.exp, "log": np.log, "power": _np_power,
    "sin": np.sin, "cos": np.cos, "abs": np.abs, "max": np.maximum, "min": np.minimum, "math": math, "np": np,
}
