#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
"""Linearised modes of a first-order DDA block sliding on two compliant corner contacts.

The block (2a x 2b, density rho, E, nu, plane stress) slides down a fixed face on its two
base corners (-a, -b) and (a, -b). Unknowns d = (u, v, r, ex, ey, gxy) about the centroid,
in the face's frame (x down the slope, y out of the face), with DDA's first-order
displacement T(X, Y) = [[1, 0, -Y, X, 0, Y/2], [0, 1, X, 0, Y, X/2]].

Each corner carries N = kn * penetration and, sliding down the slope, the friction -mu*N
along x: the contact stiffness  K_c = kn * sum T(p)^T [-mu, 1]^T T_y(p)  is not symmetric
(friction couples the normal motion into the tangential and moment rows). Linearised about
steady sliding (the sliding direction does not change):

  full:    M d'' + (K_e + K_c) d = 0, M = rho * int T^T T dA (strain inertia included);
  qs:      strains quasi-static: the strain rows condensed, rigid-body inertia only;
  rigid:   strains zero (E -> infinity), rigid-body inertia only.

Prints the largest growth rate (max Re of the eigenvalues, 1/s) over phi and g0 = kn/E,
and the per-step growth of Shi's scheme (the step (2M/dt^2 + K) d = 2M v0/dt - K x0,
x1 = x0 + d, v1 = 2d/dt - v0) and of Newmark's average acceleration at the given steps:
ln(spectral radius)/dt. A scheme that converges tends to the model's rate as dt -> 0.

  python3 scripts/dev/sliding_block_modes.py      (needs python3-numpy; not used by the build or tests)

docs/friction_flutter.md has the rates it prints and what they rule out.
"""
import numpy as np

RHO, E, NU = 2600.0, 5e9, 0.25
A, B = 0.5, 0.25  # half-sides of the 1 m x 0.5 m block


def t_matrix(x, y):
    return np.array([[1, 0, -y, x, 0, y / 2], [0, 1, x, 0, y, x / 2]], dtype=float)


def mass():
    # rho * int T^T T over the rectangle, by Gauss quadrature (exact: T is linear).
    g, w = np.polynomial.legendre.leggauss(3)
    m = np.zeros((6, 6))
    for xi, wi in zip(g, w):
        for yj, wj in zip(g, w):
            t = t_matrix(A * xi, B * yj)
            m += wi * wj * A * B * t.T @ t
    return RHO * m


def elastic():
    c = E / (1 - NU * NU)
    d = c * np.array([[1, NU, 0], [NU, 1, 0], [0, 0, (1 - NU) / 2]])
    k = np.zeros((6, 6))
    k[3:, 3:] = 4 * A * B * d
    return k


def contact(kn, mu):
    k = np.zeros((6, 6))
    for x in (-A, A):
        t = t_matrix(x, -B)
        # force on the block: [-mu, 1] * kn * (pen0 - T_y d)  =>  stiffness kn * T^T [-mu, 1]^T T_y
        k += kn * np.outer(t.T @ np.array([-mu, 1.0]), t[1])
    return k


def growth_continuous(m, k):
    # M d'' + K d = 0: lambda^2 = -eig(M^-1 K); the rate is max Re(lambda).
    mu2 = np.linalg.eigvals(np.linalg.solve(m, k))
    lam = np.sqrt(-mu2.astype(complex))
    return np.max(np.abs(lam.real))  # +-lambda both roots


def condense(m, k, keep):
    """Strains quasi-static: K_rr - K_rs K_ss^-1 K_sr on the rigid rows, M_rr."""
    drop = [i for i in range(k.shape[0]) if i not in keep]
    kk = k[np.ix_(keep, keep)] - k[np.ix_(keep, drop)] @ np.linalg.solve(k[np.ix_(drop, drop)], k[np.ix_(drop, keep)])
    return m[np.ix_(keep, keep)], kk


def growth_shi(m, k, dt):
    n = m.shape[0]
    s = np.linalg.inv(2 * m / dt**2 + k)
    # d = S (2M/dt v0 - K x0); state (x, v)
    dx = -s @ k
    dv = s @ (2 * m / dt)
    step = np.block([[np.eye(n) + dx, dv], [2 / dt * dx, 2 / dt * dv - np.eye(n)]])
    rho = np.max(np.abs(np.linalg.eigvals(step)))
    return np.log(rho) / dt


def growth_newmark(m, k, dt):
    """Newmark's average acceleration (beta = 1/4, gamma = 1/2): ln(spectral radius)/dt."""
    n = m.shape[0]
    s = np.linalg.inv(m + dt * dt / 4 * k)
    # a1 = -S K (x0 + dt v0 + dt^2/4 a0); state (x, v, a)
    a1 = -s @ k @ np.hstack([np.eye(n), dt * np.eye(n), dt * dt / 4 * np.eye(n)])
    x1 = np.hstack([np.eye(n), dt * np.eye(n), dt * dt / 4 * np.eye(n)]) + dt * dt / 4 * a1
    v1 = np.hstack([np.zeros((n, n)), np.eye(n), dt / 2 * np.eye(n)]) + dt / 2 * a1
    rho = np.max(np.abs(np.linalg.eigvals(np.vstack([x1, v1, a1]))))
    return np.log(rho) / dt


def variants(g0, phi_deg):
    """(M, K) of the three models. The sliding direction u has no stiffness while sliding (K's u
    column is zero) and no mass coupling (the first moments vanish): a driven zero mode, left out."""
    m, k = mass(), elastic() + contact(g0 * E, np.tan(np.radians(phi_deg)))
    m, k = m[1:, 1:], k[1:, 1:]  # (v, r, ex, ey, gxy)
    return {
        "full": (m, k),
        "qs": condense(m, k, [0, 1]),
        "rigid": (m[:2, :2], k[:2, :2]),
    }


def static_friction_gain(g0, phi_deg):
    """The successive Tresca bounds (tau = mu * N of the last solve) on a block whose rigid motion a
    small step freezes and whose strains carry no inertia: the gain of N -> tau -> strain -> N."""
    mu, kn = np.tan(np.radians(phi_deg)), g0 * E
    ty = np.array([t_matrix(x, -B)[1, 3:] for x in (-A, A)])  # normal motion of the corners per strain
    tx = np.array([t_matrix(x, -B)[0, 3:] for x in (-A, A)])
    k = elastic()[3:, 3:] + kn * ty.T @ ty
    dn_dtau = -kn * ty @ np.linalg.solve(k, tx.T)
    return np.max(np.abs(np.linalg.eigvals(-mu * dn_dtau)))


def main():
    print("continuous growth rate max Re(lambda), 1/s (u dropped: it has no stiffness while sliding)")
    print(f"{'g0/E':>6} {'phi':>5} {'full':>10} {'qs':>10} {'rigid':>10}")
    for g0 in (0.5, 5, 50):
        for phi in (10, 20, 25, 30, 45):
            v = variants(g0, phi)
            print(f"{g0:6g} {phi:5g} " + " ".join(f"{growth_continuous(*v[k]):10.3g}" for k in ("full", "qs", "rigid")))
    print()
    print("Shi's scheme: ln(spectral radius)/dt, 1/s, g0 = 50E")
    print(f"{'dt':>7} {'phi':>5} {'full':>10} {'qs':>10} {'rigid':>10}")
    for dt in (1e-3, 1e-4, 1e-5, 1e-6, 1e-7):
        for phi in (20, 25, 45):
            v = variants(50, phi)
            print(f"{dt:7g} {phi:5g} " + " ".join(f"{growth_shi(*v[k], dt):10.3g}" for k in ("full", "qs", "rigid")))
    print()
    print("Newmark's average acceleration: ln(spectral radius)/dt, 1/s, g0 = 50E, phi = 25")
    print("  " + ", ".join(f"dt {dt:g}: {growth_newmark(*variants(50, 25)['full'], dt):.0f}" for dt in (1e-3, 1e-4, 1e-5, 1e-6)))
    print()
    print("the full model's modes at g0 = 50E: frequency (Hz) + growth (1/s), lowest first")
    for phi in (0, 10, 20, 25):
        m, k = variants(50, phi)["full"]
        lam = sorted(np.sqrt(-np.linalg.eigvals(np.linalg.solve(m, k)).astype(complex)), key=lambda z: abs(z.imag))
        print(f"  phi {phi:2g}: " + ", ".join(f"{abs(z.imag) / (2 * np.pi):.0f} Hz {abs(z.real):+.0f}" for z in lam))
    print()
    print("flutter threshold: the smallest g0/E at which the block grows")
    g = np.geomspace(0.01, 1000, 400)
    for phi in (10, 20, 25, 30, 45):
        row = []
        for name in ("full", "qs", "rigid"):
            grows = [growth_continuous(*variants(x, phi)[name]) > 1e-6 for x in g]
            row.append(f"{name} {g[grows.index(True)]:.3g}" if any(grows) else f"{name} none")
        print(f"  phi {phi}: " + ", ".join(row))
    print()
    print("successive Tresca bounds, rigid motion frozen, strains without inertia: loop gain (< 1 converges)")
    for g0 in (0.5, 5, 50):
        print(f"  g0 = {g0:4g} E: " + "  ".join(f"phi {p}: {static_friction_gain(g0, p):.3g}" for p in (10, 20, 25, 45)))


if __name__ == "__main__":
    main()


