#!/usr/bin/env python3
"""scipy.integrate.solve_bvp on the Bratu and elastica problems of the `bvp` crate.

Not part of CI. Needs numpy and scipy (`pip install scipy`). Run:

    python3 bvp/examples/scipy_compare.py

Prints, per tolerance 1e-3 ... 1e-10, the final mesh nodes, the max error against the
exact solution (measured exactly as the Rust examples do), the solver's iteration
count (scipy reports none: '-'), and the best-of-3 wall time, so the numbers can be
quoted beside `cargo run --release -p bvp --example elastica`.

Problems (same data as bvp::analytical):
- Bratu y'' + lam e^y = 0, y(0) = y(1) = 0, lam = 1, lower branch; exact
  y = -2 ln[cosh((x - 1/2) th/2) / cosh(th/4)], th = sqrt(2 lam) cosh(th/4).
  Guess y = 0 on 11 nodes. Error: max over 2001 points of |y - y_ex| and |y' - y'_ex|
  (`bratu::Exact::max_dense_error`).
- Elastica x' = cos t, y' = sin t, t' = m, m' = -P sin t - Q cos t, x(0)=y(0)=t(0)=0,
  x(1) = a, y(1) = 0, t(1) = 0, unknown (P, Q); k = 1/sqrt 2, exact P = 16 K^2, Q = 0,
  a = 2E/K - 1. Guess theta = sin 2 pi s, P = 4 pi^2 on 11 nodes. Error:
  `elastica::Exact::max_error` (component-wise relative to max(1, max|y_i|) on 2001
  points, |P - P_ex| / P_ex, |Q| / P_ex).

Then the elastica once more with analytic Jacobians (fun_jac, bc_jac), best process CPU
time of 5 runs at 1e-7 and 1e-8: the side of `cargo run --release -p bvp --example speed`
(docs/bvp-engine.md, "Speed").

scipy's tol is its relative residual tolerance (the same definition the Rust collocation
uses); bc_tol is set equal to tol; max_nodes = 10^5 (status 1 = node cap reached).
"""
import time
import warnings

import numpy as np
from scipy.integrate import solve_bvp
from scipy.optimize import brentq
from scipy.special import ellipe, ellipeinc, ellipj, ellipk

TOLERANCES = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10]
REPEATS = 3
S = np.linspace(0.0, 1.0, 2001)


def best_time(run, repeats, clock=time.process_time):
    """Best time by `clock` (default: process CPU time) of `repeats` calls of `run`,
    and the last result."""
    best, out = np.inf, None
    for _ in range(repeats):
        t0 = clock()
        out = run()
        best = min(best, clock() - t0)
    return best, out


def timed(run):
    best, sol = best_time(run, REPEATS, time.perf_counter)
    return sol, best


# ---------------------------------------------------------------- Bratu
LAM = 1.0


def bratu_exact():
    th_c = brentq(lambda t: t / 4 * np.tanh(t / 4) - 1, 1.0, 10.0)
    th = brentq(lambda t: t - np.sqrt(2 * LAM) * np.cosh(t / 4), 1e-12, th_c)
    y = -2 * np.log(np.cosh((S - 0.5) * th / 2) / np.cosh(th / 4))
    dy = -th * np.tanh((S - 0.5) * th / 2)
    return np.vstack([y, dy])


def bratu(tol):
    x = np.linspace(0, 1, 11)
    return solve_bvp(
        lambda x, y: np.vstack([y[1], -LAM * np.exp(y[0])]),
        lambda ya, yb: np.array([ya[0], yb[0]]),
        x,
        np.zeros((2, x.size)),
        tol=tol,
        bc_tol=tol,
        max_nodes=10**5,
    )


def bratu_error(sol, exact):
    return np.max(np.abs(sol.sol(S) - exact))


# ---------------------------------------------------------------- elastica
K_MOD = 1 / np.sqrt(2)
M_PAR = K_MOD**2
KK, EE = ellipk(M_PAR), ellipe(M_PAR)
A_END = 2 * EE / KK - 1
P_EX = 16 * KK**2


def elastica_exact():
    u = 4 * KK * S
    sn, cn, dn, am = ellipj(u, M_PAR)
    x = (2 * ellipeinc(am, M_PAR) - u) / (4 * KK)
    y = K_MOD * (1 - cn) / (2 * KK)
    th = 2 * np.arcsin(K_MOD * sn)
    m = 8 * K_MOD * KK * cn
    return np.vstack([x, y, th, m])


def elastica_guess(nodes=11):
    s = np.linspace(0, 1, nodes)
    fine = np.linspace(0, 1, (nodes - 1) * 32 + 1)
    th = np.sin(2 * np.pi * fine)
    h = fine[1] - fine[0]
    cx = np.concatenate([[0], np.cumsum(0.5 * h * (np.cos(th[1:]) + np.cos(th[:-1])))])
    cy = np.concatenate([[0], np.cumsum(0.5 * h * (np.sin(th[1:]) + np.sin(th[:-1])))])
    y = np.vstack([cx[::32], cy[::32], np.sin(2 * np.pi * s), 2 * np.pi * np.cos(2 * np.pi * s)])
    return s, y


def elastica(tol):
    s, y0 = elastica_guess()

    def fun(s, y, p):
        P, Q = p
        return np.vstack([np.cos(y[2]), np.sin(y[2]), y[3], -P * np.sin(y[2]) - Q * np.cos(y[2])])

    def bc(ya, yb, p):
        return np.array([ya[0], ya[1], ya[2], yb[0] - A_END, yb[1], yb[2]])

    return solve_bvp(fun, bc, s, y0, p=[4 * np.pi**2, 0.0], tol=tol, bc_tol=tol, max_nodes=10**5)


def elastica_analytic(tol):
    """The same elastica with analytic Jacobians (fun_jac, bc_jac), as the peers in
    ../shared/peers/ run scipy: the fair side of a CPU-time comparison."""
    s, y0 = elastica_guess()

    def fun(s, y, p):
        P, Q = p
        return np.vstack([np.cos(y[2]), np.sin(y[2]), y[3], -P * np.sin(y[2]) - Q * np.cos(y[2])])

    def fun_jac(s, y, p):
        P, Q = p
        dy, dp = np.zeros((4, 4, s.size)), np.zeros((4, 2, s.size))
        dy[0, 2], dy[1, 2], dy[2, 3] = -np.sin(y[2]), np.cos(y[2]), 1.0
        dy[3, 2] = -P * np.cos(y[2]) + Q * np.sin(y[2])
        dp[3, 0], dp[3, 1] = -np.sin(y[2]), -np.cos(y[2])
        return dy, dp

    def bc(ya, yb, p):
        return np.array([ya[0], ya[1], ya[2], yb[0] - A_END, yb[1], yb[2]])

    def bc_jac(ya, yb, p):
        da, db = np.zeros((6, 4)), np.zeros((6, 4))
        da[0, 0] = da[1, 1] = da[2, 2] = 1.0
        db[3, 0] = db[4, 1] = db[5, 2] = 1.0
        return da, db, np.zeros((6, 2))

    return solve_bvp(fun, bc, s, y0, p=[4 * np.pi**2, 0.0], fun_jac=fun_jac, bc_jac=bc_jac,
                     tol=tol, bc_tol=tol, max_nodes=10**5)


def cpu_table(name, run, error, exact, tolerances=(1e-7, 1e-8), repeats=5):
    """Best process CPU time of `repeats` runs per tolerance (compare with
    `cargo run --release -p bvp --example speed`, which reports CPU time too)."""
    print(f"{name:<22} {'tol':>8} {'nodes':>7} {'max error':>11} {'status':>6} {'cpu [ms]':>11}")
    for tol in tolerances:
        best, sol = best_time(lambda: run(tol), repeats)
        err = error(sol, exact) if sol.success else float("nan")
        print(f"{name:<22} {tol:>8.0e} {sol.x.size:>7} {err:>11.3e} {sol.status:>6} {best * 1e3:>11.3f}")
    print()


def elastica_error(sol, exact):
    num = sol.sol(S)
    scale = np.maximum(1.0, np.max(np.abs(exact), axis=1))
    err = np.max(np.abs(num - exact).max(axis=1) / scale)
    return max(err, abs(sol.p[0] - P_EX) / P_EX, abs(sol.p[1]) / P_EX)


def table(name, run, error, exact):
    print(f"{name:<22} {'tol':>8} {'nodes':>7} {'max error':>11} {'status':>6} {'time [ms]':>11}")
    for tol in TOLERANCES:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            sol, secs = timed(lambda: run(tol))
        err = error(sol, exact) if sol.success else float("nan")
        print(f"{name:<22} {tol:>8.0e} {sol.x.size:>7} {err:>11.3e} {sol.status:>6} {secs * 1e3:>11.3f}")
    print()


if __name__ == "__main__":
    import scipy

    print(f"scipy {scipy.__version__}, numpy {np.__version__}; best of {REPEATS} runs\n")
    print(f"Bratu lam = {LAM}, lower branch, guess y = 0 (11 nodes)")
    table("scipy solve_bvp", bratu, bratu_error, bratu_exact())
    print(f"elastica k = 1/sqrt2: a = {A_END:.12f}, P = {P_EX:.12f}; guess theta = sin 2 pi s (11 nodes)")
    table("scipy solve_bvp", elastica, elastica_error, elastica_exact())
    print("elastica k = 1/sqrt2 with analytic Jacobians; best CPU time of 5 runs")
    cpu_table("scipy analytic", elastica_analytic, elastica_error, elastica_exact())
