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
- Damped: the eigenvalues s of [[0, I], [-M^-1 K, -M^-1 R]]; for each
  conjugate pair zeta = -Re(s)/|s| and omega_d = |Im(s)|.
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
from linkcli.forces.lagrange import Lagrangian, require_mass

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
    require_mass(mech, t.M, free)
    elements = mech.elements
    supports = np.zeros(len(imposed), dtype=complex)
    for s in (elements.supports.values() if elements else ()):
        supports[imposed.index(s.coordinate)] += s.amplitude * np.exp(1j * s.phase)
    forces = lag.forcing(t.jet)[free]
    return Linear(lag, eq, free, imposed, t.M[ix], t.K[ix], t.R[ix], forces, supports,
                  elements.frequency if elements else None)


@dataclass
class Modes:
    omega: np.ndarray        # natural frequencies (rad/s), ascending
    shapes: np.ndarray       # columns: mode shapes, normalised (see ``normalise``)
    eigenvalues: np.ndarray  # omega^2


def modes(lin: Linear) -> Modes:
    """Undamped natural frequencies and modes; refuses an unstable equilibrium."""
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
    values = np.where(values < 0, 0.0, values)
    return Modes(np.sqrt(values), normalise(vectors), values)


def normalise(vectors):
    """Each column scaled so its first component is 1 (or, when that is ~0, its largest)."""
    out = np.array(vectors, dtype=complex if np.iscomplexobj(vectors) else float)
    for k in range(out.shape[1]):
        col = out[:, k]
        ref = col[0] if abs(col[0]) > 1e-9 * np.max(np.abs(col)) else col[np.argmax(np.abs(col))]
        out[:, k] = col / ref
    return out


@dataclass
class Damped:
    omega_n: np.ndarray      # |s| per mode
    zeta: np.ndarray         # damping ratios
    omega_d: np.ndarray      # damped frequencies (0 when overdamped)


def damped(lin: Linear) -> Damped:
    """Damping ratios and damped frequencies from the state matrix's eigenvalues."""
    n = len(lin.free)
    Minv = np.linalg.inv(lin.M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ lin.K, -Minv @ lin.R]])
    s = np.linalg.eigvals(A)
    # a conjugate pair per underdamped mode, two real roots per overdamped one
    s = s[np.argsort(np.abs(s))]
    wn, zeta, wd, used = [], [], [], np.zeros(len(s), bool)
    for i, root in enumerate(s):
        if used[i]:
            continue
        used[i] = True
        if abs(root.imag) > 1e-12 * max(abs(root), 1e-300):
            j = next(k for k in range(len(s)) if not used[k] and abs(s[k] - np.conj(root))
                     <= 1e-8 * max(abs(root), 1e-300))
            used[j] = True
            wn.append(abs(root))
            zeta.append(-root.real / abs(root))
            wd.append(abs(root.imag))
        else:
            j = next((k for k in range(len(s)) if not used[k] and abs(s[k].imag) <=
                      1e-12 * max(abs(s[k]), 1e-300)), None)
            other = root if j is None else s[j]
            if j is not None:
                used[j] = True
            w = np.sqrt(abs(root * other))
            wn.append(w)
            zeta.append(-(root.real + other.real) / (2 * w) if w > 0 else 1.0)
            wd.append(0.0)
    return Damped(np.array(wn), np.array(zeta), np.array(wd))


def dynamic_matrix(lin: Linear, omega):
    """D(Omega) = K - Omega^2 M + i Omega R for each Omega, and where D is singular:
    |det D| against the product over the rows of the magnitudes of their terms
    (sum_j |K_ij| + Omega^2 |M_ij| + Omega |R_ij|) below SINGULAR, an undamped resonance.
    The ratio is dimensionless and sees the cancellation of K against Omega^2 M."""
    w = np.asarray(omega, dtype=float)[..., None, None]
    D = lin.K - w ** 2 * lin.M + 1j * w * lin.R
    scale = np.abs(lin.K) + w ** 2 * np.abs(lin.M) + w * np.abs(lin.R)
    rows = np.prod(np.sum(scale, axis=-1), axis=-1)
    ratio = np.abs(np.linalg.det(D)) / np.where(rows > 0, rows, 1.0)
    return D, ratio < SINGULAR


def response(lin: Linear, omega):
    """Steady-state complex amplitudes X (..., n_free) at the forcing frequency (ies) omega."""
    omega = np.asarray(omega, dtype=float)
    D, singular = dynamic_matrix(lin, omega)
    if np.any(singular):
        bad = float(np.atleast_1d(omega)[np.argmax(np.atleast_1d(singular))])
        raise SolveError(f"the undamped system is at resonance at Omega = {bad:.6g} rad/s: the "
                         "steady-state amplitude is unbounded", file=lin.lag.mech.file,
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
