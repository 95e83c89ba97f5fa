"""What a vibration chapter asks of the linearised system beyond its modes.

With M, K, R the matrices of the free coordinates about the equilibrium (forces.vibration):

- the characteristic polynomial det(K - lambda M) = sum_i c_i lambda^i (lambda = omega^2),
  expanded exactly by the columns: det is linear in each column, so
  det(K - lambda M) = sum over the sets S of columns of (-lambda)^|S| det(M on S, K off S);
- the receptance H(Omega) = (K - Omega^2 M + i Omega R)^-1: the complex response of each
  coordinate to a unit harmonic generalised force on each;
- the peaks of a frequency response y(Omega) = g . X(Omega) (a coordinate, a point's
  displacement): the roots of d|y|^2/dOmega = 2 Re(conj(y) y') where it falls, found by
  Brent's method between samples where its sign changes (the samples only bracket them:
  dense about each damped root s, Im s +- 16 |Re s|, and over the whole range);
  with y' = g . X', X' = D^-1 (F' - D' X), D' = -2 Omega M + i R, F' the derivative of the
  support terms;
- the largest value of a linear function y = c . x of the free vibration from x0, v0: by
  superposition of the modes; undamped, y(t) = sum_k C_k cos(omega_k t - phi_k), whose
  largest value is sum_k C_k (reached when the modes come into phase: at once for one mode,
  at t = 0 for a start in phase, approached without end for incommensurate frequencies); damped,
  the extremes of y(t) (roots of y'(t) = c . v(t) between samples of the motion, by Brent's
  method) until the envelope sum_k |r_k| e^{Re s_k t} of the modal expansion (or the energy
  bound |y| <= sqrt(2 E c^T K^-1 c)) falls below the largest found.

The characteristic polynomial's twin in formulas is ``forces.symbolic.characteristic``
(det(K - omega^2 M) expanded by minors in the parameters).
"""
from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

import numpy as np

from linkcli.errors import SolveError

#: samples of the frequency axis about each damped root, in units of its decay rate |Re s|
NEAR = np.concatenate([-np.geomspace(16, 1 / 16, 25), [0.0], np.geomspace(1 / 16, 16, 25)])
#: samples of the whole frequency axis
SPREAD = 400
#: the free vibration is sampled this many times per shortest period
PER_PERIOD = 48
#: at most this many samples of the free vibration
MOST_SAMPLES = 400_000


def characteristic(M, K) -> np.ndarray:
    """Coefficients c_0 .. c_n of det(K - lambda M) = sum_i c_i lambda^i (exact expansion by
    columns; n at most 12); M and K may be stacks (..., n, n), c is then (..., n + 1)."""
    M, K = np.asarray(M, dtype=float), np.asarray(K, dtype=float)
    n = M.shape[-1]
    if n > 12:
        raise SolveError(f"the characteristic polynomial of {n} coordinates is not expanded "
                         "(at most 12)", hint="ask for the natural frequencies instead")
    c = np.zeros(np.broadcast_shapes(M.shape, K.shape)[:-2] + (n + 1,))
    for size in range(n + 1):
        for columns in combinations(range(n), size):
            mixed = np.array(np.broadcast_to(K, np.broadcast_shapes(M.shape, K.shape)))
            mixed[..., :, list(columns)] = np.broadcast_to(M, mixed.shape)[..., :, list(columns)]
            c[..., size] += (-1) ** size * np.linalg.det(mixed)
    return c


def receptance(M, K, R, omega) -> np.ndarray:
    """H(Omega) = (K - Omega^2 M + i Omega R)^-1 (n x n, complex)."""
    return np.linalg.inv(K - omega ** 2 * M + 1j * omega * R)


# --- peaks of a frequency response -----------------------------------------------------------
@dataclass
class Response:
    """y(Omega) = g . X(Omega) + g_s . S of a linear system forced harmonically: ``g`` over the
    free coordinates, ``offset`` = g_s . S the part of the imposed coordinates (constant)."""

    M: np.ndarray
    K: np.ndarray
    R: np.ndarray
    force: np.ndarray          # the generalised forces' amplitudes (free coordinates)
    Mfs: np.ndarray            # couplings to the imposed coordinates (free x imposed)
    Kfs: np.ndarray
    Rfs: np.ndarray
    supports: np.ndarray       # the imposed coordinates' complex amplitudes
    g: np.ndarray
    offset: complex = 0j

    def values(self, omega):
        """(y, dy/dOmega) at each Omega (arrays)."""
        w = np.asarray(omega, dtype=float)[..., None, None]
        D = self.K - w ** 2 * self.M + 1j * w * self.R
        dD = -2 * w * self.M + 1j * self.R
        F = self.force - ((self.Kfs - w ** 2 * self.Mfs + 1j * w * self.Rfs)
                          @ self.supports)[..., :] if self.supports.size else \
            np.broadcast_to(self.force, D.shape[:-1])
        dF = -((-2 * w * self.Mfs + 1j * self.Rfs) @ self.supports) if self.supports.size \
            else np.zeros(D.shape[:-1], dtype=complex)
        F = np.broadcast_to(F, D.shape[:-1])
        dF = np.broadcast_to(dF, D.shape[:-1])
        X = np.linalg.solve(D, F[..., None])
        dX = np.linalg.solve(D, dF[..., None] - dD @ X)
        return X[..., 0] @ self.g + self.offset, dX[..., 0] @ self.g

    def slope(self, omega):
        """d|y|^2/dOmega."""
        y, dy = self.values(omega)
        return 2 * np.real(np.conj(y) * dy)

    def magnitude(self, omega):
        return np.abs(self.values(omega)[0])


def peaks(response: Response, roots) -> list:
    """[(Omega, |y|)] of every maximum of |y(Omega)| for Omega > 0, ascending, about the
    damped roots ``roots`` (complex, Im >= 0); [] where |y| only falls from Omega = 0."""
    from scipy.optimize import brentq
    roots = np.asarray(roots, dtype=complex)
    top = float(np.max(np.abs(roots))) if roots.size else 1.0
    low = float(np.min(np.abs(roots[np.abs(roots) > 0]))) if np.any(np.abs(roots) > 0) \
        else top
    grid = [np.geomspace(low * 1e-4, top * 20, SPREAD)]
    for s in roots:
        if abs(s.imag) > 0:
            grid.append(abs(s.imag) + abs(s.real) * NEAR)
    grid = np.unique(np.concatenate(grid))
    grid = grid[grid > 0]
    slope = response.slope(grid)
    found = []
    for i in np.nonzero((slope[:-1] > 0) & (slope[1:] <= 0))[0]:
        a, b = grid[i], grid[i + 1]
        w = b if slope[i + 1] == 0 else brentq(lambda x: float(response.slope(x)), a, b,
                                               xtol=1e-14 * b, rtol=4 * np.finfo(float).eps)
        found.append((float(w), float(response.magnitude(w))))
    return found


# --- the largest value of a free vibration ----------------------------------------------------
@dataclass
class Largest:
    """The value of w(t) = offset + c . x(t) of largest magnitude over t >= 0 (its sign kept;
    positive where both signs reach it), whether it is reached (False where it is only
    approached: undamped modes of incommensurate frequencies) and when (None if not)."""

    value: float
    reached: bool
    time: float | None = None


def largest(M, K, R, c, x0, v0, offset: float = 0.0) -> Largest:
    """The largest value of offset + c . x(t) for the free vibration M x'' + R x' + K x = 0
    from x(0) = x0, x'(0) = v0 (see the module's docstring)."""
    c, x0, v0 = (np.asarray(a, dtype=float) for a in (c, x0, v0))
    if not np.any(R):
        return _undamped(M, K, c, x0, v0, offset)
    return _damped(M, K, R, c, x0, v0, offset)


def _signed(offset, amount) -> float:
    return offset + amount if offset >= 0 else offset - amount


#: a mode's share of the largest value below this fraction of it is rounding (a mode the
#: answer does not see), and so is a start this fraction short of the largest value
ROUNDING = 1e-10


def _undamped(M, K, c, x0, v0, offset) -> Largest:
    """By the modes: c . x(t) = sum_k C_k cos(omega_k t - phi_k) (+ what a mode without
    stiffness keeps still), C_k = |c . u_k| sqrt(a_k^2 + (b_k / omega_k)^2).  The largest,
    sum_k C_k, is reached where the modes come into phase: always for one mode (the others'
    C_k below :data:`ROUNDING` of it), at t = 0 where the start is in phase (c . x0 is
    +-sum_k C_k: released from rest in a shape of like-signed modal terms), else only
    approached (incommensurate frequencies)."""
    from scipy.linalg import eigh
    values, vectors = eigh(K, M)          # mass-normalised: U^T M U = I
    top = max(float(np.max(np.abs(values))), 1e-300)
    a, b = vectors.T @ M @ x0, vectors.T @ M @ v0
    reach = c @ vectors
    amplitudes, frequencies, start = [], [], 0.0
    for k, lam in enumerate(values):
        if lam <= 1e-12 * top:            # no stiffness: x stays at a (from rest) or drifts
            if abs(reach[k] * b[k]) > 0:
                raise SolveError("the free vibration drifts without bound: a mode without "
                                 "stiffness (a free body) moves from the initial rates",
                                 hint="hold every mode with a spring or gravity, or start "
                                 "from rest in that mode")
            offset += reach[k] * a[k]
            continue
        w = np.sqrt(lam)
        amplitudes.append(abs(reach[k]) * np.hypot(a[k], b[k] / w))
        frequencies.append(float(w))
        start += reach[k] * a[k]
    total = float(sum(amplitudes))
    if total == 0:
        return Largest(float(offset), True, 0.0)
    distinct = sorted(w for w, amount in zip(frequencies, amplitudes)
                      if amount > ROUNDING * total)
    one = all(f2 - f1 <= 1e-12 * f2 for f1, f2 in zip(distinct, distinct[1:]))
    value = _signed(offset, total)
    at_start = offset + float(np.copysign(total, start))
    if not one and abs(start) >= (1 - ROUNDING) * total and abs(at_start) >= abs(value):
        return Largest(at_start, True, 0.0)
    return Largest(value, one, None)


def _damped(M, K, R, c, x0, v0, offset) -> Largest:
    """The extremes of w(t), between samples of the motion (one propagator expm(A h)),
    until no later value can be larger: the envelope of the modal expansion
    y(t) = sum_i r_i e^{s_i t}, or where the modes are not independent (critical damping)
    the energy bound |y| <= sqrt(2 E(t) c^T K^-1 c), has fallen below the largest found."""
    from scipy.linalg import expm
    from scipy.optimize import brentq
    n = len(M)
    A = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-np.linalg.solve(M, K), -np.linalg.solve(M, R)]])
    s, V = np.linalg.eig(A)
    z0 = np.concatenate([x0, v0])
    scale = float(np.max(np.abs(s)))
    if scale == 0:
        return Largest(float(offset + c @ x0), True, 0.0)
    envelope = None
    if np.linalg.cond(V) < 1e8:
        envelope = (np.abs((c @ V[:n]) * np.linalg.solve(V, z0)), s.real)
    held = np.linalg.eigvalsh(K)[0] > 0
    factor = float(np.sqrt(c @ np.linalg.solve(K, c))) if held else np.inf
    if envelope is None and not held:
        raise SolveError("the largest value of this free vibration is not bounded by its "
                         "energy: a mode without stiffness", hint="hold every mode with a "
                         "spring or gravity")
    fastest = float(np.max(np.abs(s.imag)))
    h = min(2 * np.pi / fastest / PER_PERIOD if fastest > 0 else np.inf, 0.25 / scale)
    step = expm(A * h)

    def bound(t, z):
        energy = 0.5 * z[n:] @ M @ z[n:] + 0.5 * z[:n] @ K @ z[:n]
        limit = factor * np.sqrt(2 * max(float(energy), 0.0))
        if envelope is not None:
            limit = min(limit, float(np.sum(envelope[0] * np.exp(envelope[1] * t))))
        return limit

    best = Largest(float(offset + c @ x0), True, 0.0)
    z, slope = z0, float(c @ v0)
    for i in range(1, MOST_SAMPLES + 1):
        t = i * h
        following = step @ z
        after = float(c @ following[n:])
        if slope * after < 0:
            start = z

            def rate(u):
                return float(c @ (expm(A * (u - t + h)) @ start)[n:])
            root = brentq(rate, t - h, t, xtol=1e-15 * t, rtol=4 * np.finfo(float).eps)
            value = float(offset + c @ (expm(A * (root - t + h)) @ start)[:n])
            if abs(value) > abs(best.value):
                best = Largest(value, True, root)
        z, slope = following, after
        if abs(offset) + bound(t, z) <= abs(best.value):
            return best
    raise SolveError(f"the largest value of the free vibration is not settled within "
                     f"{MOST_SAMPLES} samples: the damping is too light for the search",
                     hint="ask for it without the dampers (the undamped motion's largest "
                     "value bounds it)")
