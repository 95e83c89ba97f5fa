"""Small oscillations about the static equilibrium, and the full nonlinear motion.

Linearised about the equilibrium q_e (where the rates vanish, so the
convective terms drop out), Lagrange's equations of the free coordinates x are

    M x'' + R x' + K x = f e^{i Omega t} - (K_fs - Omega^2 M_fs + i Omega R_fs) S e^{i Omega t}

with M, R, K the matrices of ``forces.lagrange`` at q_e restricted to the free
coordinates, f the harmonic loads' generalised forces, S the complex
amplitudes of the imposed coordinates (moving supports, road profiles) and the
_fs blocks coupling the two.

- Natural frequencies and modes: K u = omega^2 M u (scipy.linalg.eigh); a
  negative eigenvalue means the equilibrium is unstable and is reported so.
- Damped: the eigenvalues s of [[0, I], [-M^-1 K, -M^-1 R]], two per undamped mode,
  paired with the modes through their eigenvectors (``damped``); a mode's roots give
  omega_n = sqrt(s1 s2), zeta = -(s1 + s2) / (2 omega_n) and, for a conjugate pair,
  omega_d = |Im s|; two real roots are an overdamped mode (two decay rates), one double
  root (to within CRITICAL of its size) a critically damped one (zeta = 1).
- Steady state: X = (K - Omega^2 M + i Omega R)^-1 F, vectorised over Omega.
- Free response: z(t) = expm(A t) z0 for the state z = (x, x').
- Nonlinear: M(q) q'' = Q(q) - R(q) q' - c(q, q') + forcing(t), integrated by
  scipy's solve_ivp with the imposed coordinates following their motion.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkcli.errors import SolveError
from linkcli.forces.equilibrium import Equilibrium, equilibrium
from linkcli.forces.lagrange import Lagrangian, energy_units, require_mass
from linkcli.model.units import DIMENSIONS

#: an eigenvalue of K below -UNSTABLE times the largest is a loss of stability
UNSTABLE = 1e-9
#: a dynamic matrix whose Hadamard ratio is below this is singular (resonance)
SINGULAR = 1e-13


@dataclass
class Linear:
    """The linearised system of the free coordinates about the equilibrium."""

    lag: Lagrangian
    eq: Equilibrium
    free: list
    imposed: list
    M: np.ndarray
    K: np.ndarray
    R: np.ndarray
    forces: np.ndarray           # complex generalised harmonic forces (free coordinates)
    supports: np.ndarray         # complex amplitudes of the imposed coordinates
    frequency: float | None      # Omega (rad/s) of the excitation

    @property
    def names(self) -> list:
        return [self.lag.mech.coordinates[j].name for j in self.free]

    def coupling(self, omega):
        """The blocks K_fs - Omega^2 M_fs + i Omega R_fs (free rows, imposed columns)."""
        t = self.eq.terms
        ix = np.ix_(self.free, self.imposed)
        return t.K[ix] - omega ** 2 * t.M[ix] + 1j * omega * t.R[ix]

    def load(self, omega):
        """Complex generalised force amplitude at Omega (harmonic loads and supports)."""
        f = self.forces.astype(complex)
        if self.imposed:
            f = f - np.einsum("...ij,j->...i", self.coupling(np.asarray(omega)[..., None, None]),
                              self.supports)
        return f


def linearise(lag: Lagrangian) -> Linear:
    """The equilibrium and the linear system about it."""
    eq = equilibrium(lag)
    mech = lag.mech
    free = eq.free
    imposed = [j for j in range(lag.n) if j not in free]
    if not free:
        raise SolveError("every coordinate is imposed: nothing is free to vibrate",
                         file=mech.file, hint="leave at least one coordinate without a support motion")
    t = eq.terms
    ix = np.ix_(free, free)
    require_mass(mech, t.M, free, lag.scales)
    elements = mech.elements
    supports = np.zeros(len(imposed), dtype=complex)
    for s in (elements.supports.values() if elements else ()):
        supports[imposed.index(s.coordinate)] += s.amplitude * np.exp(1j * s.phase)
    forces = lag.forcing(t.jet)[free]
    return Linear(lag, eq, free, imposed, t.M[ix], t.K[ix], t.R[ix], forces, supports,
                  elements.frequency if elements else None)


@dataclass
class Modes:
    """The undamped modes, ascending in frequency.

    ``vectors`` are mass-normalised (u^T M u = 1); ``shapes`` the same columns scaled so
    that the reference coordinate (the first free one, index ``REFERENCE``) is 1, or, in a
    mode where it does not move, so that the largest component is.  ``size[i, k]`` is how
    much coordinate i moves in mode k against the mode's largest component, in energy:
    |u_ik| sqrt(M_ii) over the largest such term (1 for the largest, 0 for a coordinate that
    does not move); components below ``still[k]`` (the accuracy of the computed
    eigenvector, from its frequency's gap to the others) are zero.  ``repeated[k]`` names the
    other modes sharing mode k's frequency (their shapes are any combination)."""

    omega: np.ndarray        # natural frequencies (rad/s), ascending
    shapes: np.ndarray       # columns: mode shapes, the reference coordinate 1
    eigenvalues: np.ndarray  # omega^2
    vectors: np.ndarray      # columns: mass-normalised mode shapes
    size: np.ndarray         # |u_ik| sqrt(M_ii) against the mode's largest
    still: np.ndarray        # per mode: the size below which a component is zero
    repeated: list           # per mode: the other modes of the same frequency

    def moves(self, i, k) -> bool:
        """Whether coordinate i moves in mode k (above the eigenvector's accuracy)."""
        return bool(self.size[i, k] > self.still[k])


#: the reference coordinate of the mode shapes: the first free coordinate
REFERENCE = 0
#: omega^2 below ZERO times the largest is a mode without stiffness (omega = 0): a free body
ZERO = 1e-12
#: eigenvalues closer than REPEATED times the largest are one repeated frequency
REPEATED = 1e-8


def modes(lin: Linear) -> Modes:
    """Undamped natural frequencies and modes (K u = omega^2 M u); refuses an unstable
    equilibrium."""
    from scipy.linalg import eigh
    values, vectors = eigh(lin.K, lin.M)
    top = max(float(np.max(np.abs(values))), 1e-300)
    if values[0] < -UNSTABLE * top:
        worst = lin.names[int(np.argmax(np.abs(vectors[:, 0])))]
        kind = "a maximum" if values[-1] < -UNSTABLE * top else "a saddle point"
        raise SolveError(f"the static equilibrium is unstable ({kind} of the potential energy): "
                         f"K has the negative eigenvalue omega^2 = {values[0]:.6g} 1/s^2 (mode "
                         f"mostly along {worst}), so there is no natural frequency",
                         file=lin.lag.mech.file,
                         hint="stiffen the springs or check gravity's direction and the "
                         "equilibrium position")
    values = np.where(values <= ZERO * top, 0.0, values)
    n = len(values)
    gaps = np.abs(values[:, None] - values[None, :]) + np.diag(np.full(n, np.inf))
    repeated = [[j for j in range(n) if gaps[k, j] <= REPEATED * top] for k in range(n)]
    # an eigenvector's error is about eps ||M^-1 K|| / gap (Davis-Kahan), relative to its size
    gap = np.min(gaps, axis=1) if n > 1 else np.full(1, np.inf)
    # (at most a half: a repeated frequency's shapes, refused as answers, are still drawn)
    still = np.minimum(64 * np.finfo(float).eps * top / np.maximum(gap, 1e-300), 0.5)
    still = np.maximum(still, 64 * np.finfo(float).eps)
    weighted = np.abs(vectors) * np.sqrt(np.diag(lin.M))[:, None]
    size = weighted / np.max(weighted, axis=0)
    vectors = np.where(size > still, vectors, 0.0)
    return Modes(np.sqrt(values), _normalise(vectors, size, still), values, vectors, size,
                 still, repeated)


def _normalise(vectors, size, still):
    """Each column scaled so its reference component is 1, or, in a mode where the
    reference does not move, its largest component (in energy)."""
    out = np.array(vectors, dtype=float)
    for k in range(out.shape[1]):
        ref = REFERENCE if size[REFERENCE, k] > still[k] else int(np.argmax(size[:, k]))
        out[:, k] = out[:, k] / out[ref, k]
    return out + 0.0               # no -0: a coordinate that does not move is 0


#: a mode whose two roots are CRITICAL of their size apart, |s1 - s2| <= CRITICAL (|s1| +
#: |s2|), is critically damped: a double root s = -omega_n split by rounding (a double root
#: of the state matrix is known to about sqrt(eps) = 1.5e-8 of its size) into a conjugate
#: pair or two real roots.  Dimensionless; as zeta, |zeta - 1| below about 1e-15, since
#: |s1 - s2| / (|s1| + |s2|) = sqrt(zeta^2 - 1) / zeta for two real roots
CRITICAL = 1e-7


def critical(roots) -> np.ndarray:
    """Per mode (a row of ``roots``, its two roots), whether it is critically damped: its
    roots one double root to within :data:`CRITICAL`."""
    size = np.abs(roots[:, 0]) + np.abs(roots[:, 1])
    return (size > 0) & (np.abs(roots[:, 0] - roots[:, 1]) <= CRITICAL * size)


@dataclass
class Damped:
    """The roots s of det(M s^2 + R s + K) = 0, two per undamped mode (see ``damped``).

    ``roots[k]``: mode k's two roots, a conjugate pair (Im > 0 first) or two real ones (the
    slower decay first).  From them: omega_n = sqrt(s1 s2) (|s| for a pair), zeta =
    -(s1 + s2) / (2 omega_n), and, where the mode oscillates, omega_d = |Im s|."""

    roots: np.ndarray        # (n, 2) complex
    oscillates: np.ndarray   # per mode: a conjugate pair of roots (not critically damped)
    share: np.ndarray        # per mode: its roots' share of that undamped mode (1: proportional)

    @property
    def critical(self):
        """Per mode: critically damped (zeta = 1, one double root: :func:`critical`)."""
        return critical(self.roots)

    @property
    def omega_n(self):
        return np.sqrt(np.abs(self.roots[:, 0] * self.roots[:, 1]))

    @property
    def zeta(self):
        """-(s1 + s2) / (2 omega_n); 0/0 is left to the caller (a mode without stiffness)."""
        wn = self.omega_n
        return 0.0 - np.real(self.roots.sum(axis=1)) / (2 * np.where(wn > 0, wn, np.inf))

    @property
    def omega_d(self):
        return np.where(self.oscillates, np.abs(self.roots[:, 0].imag), 0.0)

    def decay(self, k):
        """The decay rates -s of a mode that does not oscillate, the slower first (1/s)."""
        return -np.real(self.roots[k])


def damped(lin: Linear, found: Modes) -> Damped:
    """Roots of det(M s^2 + R s + K) = 0, paired with the undamped modes ``found``.

    The roots are the eigenvalues s of the state matrix [[0, I], [-M^-1 K, -M^-1 R]], with
    eigenvectors (phi, s phi).  Each root's phi is expanded on the mass-normalised undamped
    modes, c = U^T M phi, and its share of mode k is |c_k|^2 / sum |c|^2.  A conjugate
    pair is one mode (it oscillates); the pairs are given the modes that maximise the sum
    of their shares (Hungarian method), and then the real roots the remaining modes, two
    each, by the same rule.  With damping proportional to the modes (R = a M + b K, or
    uncoupled elements) each share is 1 and the pairing exact; where damping couples the
    modes, a root goes to the undamped mode its motion is most made of.  Undamped (R = 0):
    the roots are +-i omega exactly."""
    n = len(lin.free)
    if not np.any(lin.R):
        roots = np.stack([1j * found.omega, -1j * found.omega], axis=1)
        return Damped(roots, found.omega > 0, np.ones(n))
    A = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-np.linalg.solve(lin.M, lin.K), -np.linalg.solve(lin.M, lin.R)]])
    s, vectors = np.linalg.eig(A)
    c = found.vectors.T @ lin.M @ vectors[:n]
    weight = np.abs(c) ** 2
    share = (weight / np.maximum(np.sum(weight, axis=0), 1e-300)).T     # (2n roots, n modes)
    pairs = [r for r in range(2 * n) if s[r].imag > 0]
    reals = [r for r in range(2 * n) if s[r].imag == 0]
    roots = np.zeros((n, 2), dtype=complex)
    got = np.zeros(n)
    modes_left = list(range(n))
    if pairs:
        rows, cols = _assign(share[pairs])
        for r, k in zip(rows, cols):
            root = s[pairs[r]]
            roots[k] = (root, np.conj(root))
            got[k] = share[pairs[r], k]
        modes_left = [k for k in range(n) if k not in set(cols)]
    if reals:
        slots = np.repeat(modes_left, 2)
        rows, cols = _assign(share[np.ix_(reals, slots)])
        taken = {k: [] for k in modes_left}
        for r, col in zip(rows, cols):
            taken[int(slots[col])].append(reals[r])
        for k, two in taken.items():
            two.sort(key=lambda r: abs(s[r]))
            roots[k] = s[two].real
            got[k] = float(np.mean(share[two, k]))
    oscillates = (roots[:, 0].imag != 0) & ~critical(roots)
    return Damped(roots, oscillates, got)


def _assign(share):
    """Rows and columns of the assignment that maximises the sum of ``share`` (each row to
    its own column)."""
    from scipy.optimize import linear_sum_assignment
    return linear_sum_assignment(-share)


def dynamic_matrix(lin: Linear, omega):
    """D(Omega) = K - Omega^2 M + i Omega R for each Omega, and where D is singular:
    |det D| against the product over the rows of the magnitudes of their terms
    (sum_j |K_ij| + Omega^2 |M_ij| + Omega |R_ij|) below SINGULAR, an undamped resonance.
    Both are taken in energy units (``lagrange.energy_units``: a row's terms of a length
    and of an angle coordinate in one unit), so the ratio is dimensionless whatever the
    length unit, and sees the cancellation of K against Omega^2 M."""
    w = np.asarray(omega, dtype=float)[..., None, None]
    D = lin.K - w ** 2 * lin.M + 1j * w * lin.R
    d = np.asarray(lin.lag.scales, float)[lin.free]
    scale = energy_units(np.abs(lin.K) + w ** 2 * np.abs(lin.M) + w * np.abs(lin.R), d)
    rows = np.sum(scale, axis=-1)[..., None]       # each row over its magnitude before the
    ratio = np.abs(np.linalg.det(energy_units(D, d) / np.where(rows > 0, rows, 1.0)))
    return D, ratio < SINGULAR                      # determinant: no power of the size in it


def response(lin: Linear, omega):
    """Steady-state complex amplitudes X (..., n_free) at the forcing frequency (ies) omega."""
    omega = np.asarray(omega, dtype=float)
    D, singular = dynamic_matrix(lin, omega)
    if np.any(singular):
        bad = float(np.atleast_1d(omega)[np.argmax(np.atleast_1d(singular))])
        units = lin.lag.mech.units
        unit, factor = units.show(DIMENSIONS["frequency"], "frequency")
        raise SolveError(f"the undamped system is at resonance at Omega = {bad / factor:.6g} "
                         f"{unit}: the steady-state amplitude is unbounded", file=lin.lag.mech.file,
                         hint="add damping, or move the forcing frequency away from the natural "
                         "frequencies")
    F = np.broadcast_to(lin.load(omega), D.shape[:-1])
    return np.linalg.solve(D, F[..., None])[..., 0]


def full_amplitudes(lin: Linear, X):
    """Complex amplitudes of every coordinate (free from X, imposed from the supports)."""
    n = lin.lag.n
    out = np.zeros(np.shape(X)[:-1] + (n,), dtype=complex)
    out[..., lin.free] = X
    if lin.imposed:
        out[..., lin.imposed] = lin.supports
    return out


def free_response(lin: Linear, x0, v0, times):
    """x(t) of the linear system from offsets x0 and rates v0 (free coordinates)."""
    from scipy.linalg import expm
    n = len(lin.free)
    Minv = np.linalg.inv(lin.M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ lin.K, -Minv @ lin.R]])
    z0 = np.concatenate([x0, v0])
    times = np.atleast_1d(np.asarray(times, dtype=float))
    return np.array([(expm(A * t) @ z0)[:n] for t in times])


def simulate(lin: Linear, x0, v0, times, forced=False, rtol=1e-10, atol=1e-13):
    """The nonlinear equations of motion integrated from q_e + x0 with rates v0 (free
    coordinates), free or (``forced``) under the excitation; returns x(t), the offsets
    from equilibrium, at ``times``."""
    from scipy.integrate import solve_ivp
    lag = lin.lag
    free = lin.free
    imposed = lin.imposed if forced else []
    q_e = lin.eq.q
    omega = (lin.frequency or 0.0) if forced else 0.0
    forces = lag.elements.forces if forced and lag.elements else {}
    supports = lin.supports if forced else np.zeros(0)

    def rhs(t, z):
        nf = len(free)
        q = q_e.copy()
        qd = np.zeros(lag.n)
        qdd_s = np.zeros(len(imposed))
        q[free], qd[free] = q_e[free] + z[:nf], z[nf:]
        if imposed:
            e = np.exp(1j * omega * t)
            q[imposed] += np.real(supports * e)
            qd[imposed] = np.real(1j * omega * supports * e)
            qdd_s = np.real(-omega ** 2 * supports * e)
        terms = lag.terms(q)
        rhs_q = terms.Q - terms.R @ qd - lag.convective(terms, qd)
        if forces:
            rhs_q = rhs_q + np.real(lag.forcing(terms.jet) * np.exp(1j * omega * t))
        rhs_f = rhs_q[free] - (terms.M[np.ix_(free, imposed)] @ qdd_s if imposed else 0.0)
        acc = np.linalg.solve(terms.M[np.ix_(free, free)], rhs_f)
        return np.concatenate([z[nf:], acc])

    times = np.asarray(times, dtype=float)
    z0 = np.concatenate([np.asarray(x0, float), np.asarray(v0, float)])
    sol = solve_ivp(rhs, (0.0, float(times[-1])), z0, t_eval=times, rtol=rtol, atol=atol,
                    method="DOP853")
    if not sol.success:
        raise SolveError(f"the time integration stopped: {sol.message}",
                         file=lag.mech.file, hint="shorten the time or reduce the initial offsets")
    return sol.y[:len(free)].T
