#!/usr/bin/env python3
"""Issue 17's side-by-side in one run: scipy's solve_bvp (the peers in ../shared/peers/,
analytic Jacobians, tol 1e-8) and beltcheck's collocation (`--example speed`), CPU
times and the ratios scipy / beltcheck.

Run from the repository root (needs numpy and scipy, `python3 -m pip install scipy`):

    python3 bvp/examples/speed_vs_scipy.py [--wp] [SCENE] [REPEATS] [PEERS_DIR]

SCENE defaults to scenes/string-hanging.json, REPEATS to 5 (best process CPU time of
that many scipy runs; beltcheck's `speed` example takes the best of REPEATS batches of
>= 0.2 s of CPU time of its thread), PEERS_DIR to ../shared/peers (the directory of
string_hanging_scipy.py and bench_solve_bvp.py).

Problems (accuracy matched as in `--example speed`: beltcheck's tolerance is the
loosest power of ten whose error against the closed form is at most scipy's):
- the string-hanging scene from its file, scipy by string_hanging_scipy.py at tol 1e-8,
  beltcheck `solve_scene` at tol 1e-8 with the scene's scheme;
- Bratu lambda = 3.51, lower branch, guess y = 0 on 11 nodes (bench_solve_bvp.py's
  problem), error max |y - y_exact| on 2001 points;
- the clamped elastica k = 1/sqrt 2 of scipy_compare.py (beltcheck's own elastica),
  error of `elastica::Exact::max_error`.

With --wp (work-precision) it also sweeps the tolerance on both sides for Bratu and the
elastica (scipy 10^(-4 - k/2) down to 1e-11, beltcheck's `speed ... wp` down to 1e-12;
a sweep stops at a failure or after a solve of > 0.5 s on beltcheck's side, > 1 s on
scipy's) with the same error measure on both sides (Bratu: max over 2001 points of
|y - y_exact| and |y' - y'_exact|, beltcheck's `max_dense_error`; elastica: as above),
and prints the CPU time of each side at equal error: per side the points no other point
of that side beats in both error and time (its Pareto front), log time interpolated
linearly in log error between the two front points around the target error (no
extrapolation: outside a side's measured errors the ratio is left out). Targets: the
powers of ten 1e-5 ... 1e-14 that both sides reach and scipy's own error at tol 1e-8.
The scene is swept too (scipy by string_hanging_scipy.py at tol 1e-5 ... 1e-11, beltcheck
`solve_scene` with gauss6 and gauss8 at 1e-5 ... 1e-12); there is no closed form, so its
error is the largest relative deviation of the four mid-span values (heights and axial
forces of both spans) from beltcheck's gauss8 at its tightest tolerance, whose distance
to gauss6's and scipy's tightest is printed as a check. The mid-span values are node
values (superconvergent), so this error is far below the tolerance on both sides.
Tests of the arithmetic: `python3 -m unittest bvp/examples/test_speed_vs_scipy.py`.
"""
import os
import re
import subprocess
import sys

import numpy as np
from scipy.integrate import solve_bvp

HERE = os.path.dirname(os.path.abspath(__file__))


def import_peers(peers):
    """The peer modules, imported with an empty argument list (bench_solve_bvp reads
    its repeat count from sys.argv at import)."""
    sys.path[:0] = [peers, HERE]
    argv, sys.argv = sys.argv, sys.argv[:1]
    try:
        import bench_solve_bvp
        import scipy_compare
        import string_hanging_scipy
    finally:
        sys.argv = argv
    return bench_solve_bvp, scipy_compare, string_hanging_scipy


def scipy_side(scene_path, repeats, peers):
    bench, compare, hanging = import_peers(peers)
    best_cpu = compare.best_time
    rows = {}
    # string-hanging from the file, as string_hanging_scipy.py's main does
    import json
    scene = json.load(open(scene_path))
    d, b, e = scene["drive"], scene["belt"], scene.get("effects", {})
    args = (d["pulley_radius"], d["centre_distance"], b["axial_stiffness"], b["mass_per_length"],
            e.get("gravity", 0.0), b["length"])
    cpu, res = best_cpu(lambda: hanging.solve(*args, 1e-8), repeats)
    rows["string-hanging"] = (cpu, res["nodes"], float("nan"))
    # Bratu 3.51, lower branch, analytic Jacobians
    f, fj, bc, bcj = bench.bratu_problem(3.51)
    th_lo, _ = bench.bratu_theta(3.51)
    x0 = np.linspace(0, 1, 11)
    cpu, sol = best_cpu(lambda: solve_bvp(f, bc, x0, np.zeros((2, 11)), tol=1e-8, max_nodes=10**5,
                                          fun_jac=fj, bc_jac=bcj), repeats)
    err = np.max(np.abs(sol.sol(bench.XE)[0] - bench.bratu_exact(bench.XE, th_lo)))
    rows["bratu 3.51"] = (cpu, sol.x.size, err)
    # beltcheck's elastica, analytic Jacobians
    exact = compare.elastica_exact()
    cpu, sol = best_cpu(lambda: compare.elastica_analytic(1e-8), repeats)
    rows["elastica"] = (cpu, sol.x.size, compare.elastica_error(sol, exact))
    return rows


WP_TOLS = [10.0 ** (-4 - k / 2) for k in range(15)]  # 1e-4 ... 1e-11


def bratu_state_exact(x, th):
    """Exact (y, y') of Bratu's lower branch with parameter theta: the state beltcheck's
    `bratu::Exact::max_dense_error` compares against."""
    y = -2 * np.log(np.cosh((x - 0.5) * th / 2) / np.cosh(th / 4))
    dy = -th * np.tanh((x - 0.5) * th / 2)
    return np.vstack([y, dy])


SCENE_KEYS = ("y_upper_mid", "y_lower_mid", "tension_upper_mid", "tension_lower_mid")


def scene_error(values, reference):
    """Largest relative error of the four mid-span values (heights and tensions)."""
    return max(abs(v - r) / abs(r) for v, r in zip(values, reference))


def scipy_scene_sweep(scene_path, repeats, peers):
    """scipy's sweep of the scene (string_hanging_scipy.py, tol 1e-5 ... 1e-11):
    [(tol, nodes, values, cpu_s), ...] with the four mid-span values."""
    _, compare, hanging = import_peers(peers)
    import json
    scene = json.load(open(scene_path))
    d, b, e = scene["drive"], scene["belt"], scene.get("effects", {})
    args = (d["pulley_radius"], d["centre_distance"], b["axial_stiffness"], b["mass_per_length"],
            e.get("gravity", 0.0), b["length"])
    rows = []
    for tol in WP_TOLS[2:]:
        cpu, res = compare.best_time(lambda: hanging.solve(*args, tol), repeats)
        if res["status"] != 0:
            print(f"scipy scene tol {tol:.3e}: status {res['status']}, sweep stopped")
            break
        rows.append((tol, res["nodes"], [res[k] for k in SCENE_KEYS], cpu))
        if cpu > 1.0:
            break
    return rows


def add_scene_sweeps(their_sweeps, our_sweeps, scipy_rows, scene_rows):
    """Errors of both sides' scene sweeps against the reference, beltcheck's gauss8 at
    its tightest tolerance (printed with its distance to the tightest of gauss6 and of
    scipy, an independent check of the reference)."""
    ref_tol, _, _, ref, _ = min(scene_rows[("scene", "gauss8")], key=lambda r: r[0])
    print(f"scene reference: beltcheck gauss8 at tol {ref_tol:.1e}: {ref}")
    g6 = min(scene_rows[("scene", "gauss6")], key=lambda r: r[0])
    sp = min(scipy_rows, key=lambda r: r[0])
    print(f"  relative distance of gauss6 at tol {g6[0]:.1e}: {scene_error(g6[3], ref):.2e}, "
          f"of scipy at tol {sp[0]:.1e}: {scene_error(sp[2], ref):.2e}")
    their_sweeps["scene"] = [(tol, nodes, scene_error(v, ref), cpu) for tol, nodes, v, cpu in scipy_rows]
    for key, rows in scene_rows.items():
        our_sweeps[key] = [(tol, nodes, newton, scene_error(v, ref), cpu) for tol, nodes, newton, v, cpu in rows]


def scipy_sweeps(repeats, peers):
    """scipy's work-precision sweeps: {problem: [(tol, nodes, error, cpu_s), ...]}."""
    bench, compare, _ = import_peers(peers)
    f, fj, bc, bcj = bench.bratu_problem(3.51)
    th_lo, _ = bench.bratu_theta(3.51)
    bratu_exact = bratu_state_exact(bench.XE, th_lo)
    x0 = np.linspace(0, 1, 11)
    elastica_exact = compare.elastica_exact()
    problems = {
        "bratu": (lambda tol: solve_bvp(f, bc, x0, np.zeros((2, 11)), tol=tol, max_nodes=10**5,
                                        fun_jac=fj, bc_jac=bcj),
                  lambda sol: float(np.max(np.abs(sol.sol(bench.XE) - bratu_exact)))),
        "elastica": (compare.elastica_analytic, lambda sol: compare.elastica_error(sol, elastica_exact)),
    }
    out = {}
    for name, (solve, error) in problems.items():
        rows = out.setdefault(name, [])
        for tol in WP_TOLS:
            cpu, sol = compare.best_time(lambda: solve(tol), repeats)
            if sol.status != 0:
                print(f"scipy {name} tol {tol:.3e}: status {sol.status}, sweep stopped")
                break
            rows.append((tol, sol.x.size, error(sol), cpu))
            if cpu > 1.0:
                break
    return out


def pareto(points):
    """The (error, time) points no other point beats in both, by increasing error (and
    so decreasing time); non-finite and non-positive points are left out."""
    pts = sorted((e, t) for e, t in points if np.isfinite(e) and np.isfinite(t) and e > 0 and t > 0)
    front, fastest = [], np.inf
    for e, t in pts:
        if t < fastest:
            front.append((e, t))
            fastest = t
    return front


def time_at_error(front, error):
    """Time to reach `error` on a Pareto front (increasing error): log time linear in
    log error between the two points around it; None outside the front's errors."""
    if not front or error < front[0][0] or error > front[-1][0]:
        return None
    for (e0, t0), (e1, t1) in zip(front, front[1:]):
        if e0 <= error <= e1:
            if e1 == e0:
                return t0
            w = (np.log(error) - np.log(e0)) / (np.log(e1) - np.log(e0))
            return float(np.exp((1 - w) * np.log(t0) + w * np.log(t1)))
    return front[0][1]  # a front of one point, error equal to it


def print_work_precision(theirs, ours, own_errors):
    """The sweeps of both sides and the ratio scipy / beltcheck of CPU time at equal error."""
    for name, rows in theirs.items():
        print(f"\nwork-precision, {name}: scipy (analytic Jacobians)")
        print(f"  {'tol':>9} {'nodes':>6} {'error':>10} {'cpu [ms]':>10}")
        for tol, nodes, err, cpu in rows:
            print(f"  {tol:>9.2e} {nodes:>6} {err:>10.3e} {cpu * 1e3:>10.3f}")
        for (pname, scheme), brows in ours.items():
            if pname != name:
                continue
            print(f"  beltcheck {scheme}")
            for tol, nodes, newton, err, cpu in brows:
                print(f"  {tol:>9.2e} {nodes:>6} {err:>10.3e} {cpu * 1e3:>10.3f}   newton {newton}")
        sfront = pareto([(e, t) for _, _, e, t in rows])
        schemes = [s for (p, s) in ours if p == name]
        fronts = {s: pareto([(e, t) for _, _, _, e, t in ours[(name, s)]]) for s in schemes}
        targets = [(f"{10.0 ** -k:.0e}", 10.0 ** -k) for k in range(5, 15)]
        if name in own_errors:
            targets.append((f"{own_errors[name]:.2e} (scipy tol 1e-8)", own_errors[name]))
        head = "".join(f" {s + ' [ms]':>12} {'ratio':>7}" for s in schemes)
        print(f"  CPU time at equal error (log-log interpolation on each side's Pareto front)")
        print(f"  {'error':<26} {'scipy [ms]':>10}{head}")
        for label, target in targets:
            ts = time_at_error(sfront, target)
            if ts is None or all(time_at_error(fronts[s], target) is None for s in schemes):
                continue
            line = f"  {label:<26} {'-' if ts is None else f'{ts * 1e3:.3f}':>10}"
            for s in schemes:
                tb = time_at_error(fronts[s], target)
                ratio = "-" if tb is None or ts is None else f"{ts / tb:.1f}x"
                line += f" {'-' if tb is None else f'{tb * 1e3:.3f}':>12} {ratio:>7}"
            print(line)


def beltcheck_side(scene_path, repeats, sweep=False):
    cmd = ["cargo", "run", "--release", "--quiet", "-p", "bvp", "--example", "speed", "--", scene_path, str(repeats)]
    if sweep:
        cmd.append("wp")
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    print(out)
    rows = {}
    m = re.search(r"tol 1e-8 \((\w+)\): nodes (\d+), Newton (\d+), cpu ([\d.]+) ms", out)
    rows[("string-hanging", m.group(1))] = (float(m.group(4)) * 1e-3, int(m.group(2)), float("nan"))
    for m in re.finditer(r"^(bratu 3\.51|elastica)\s+(\w+)\s+tol (\S+)\s+nodes\s+(\d+)\s+newton\s+\d+\s+error (\S+)\s+cpu\s+([\d.]+) ms",
                         out, re.M):
        rows[(m.group(1), m.group(2))] = (float(m.group(6)) * 1e-3, int(m.group(4)), float(m.group(5)))
    if not sweep:
        return rows, {}, {}
    sweeps, scene = {}, {}
    for m in re.finditer(r"^wp (\w+) (\w+) tol (\S+) nodes (\d+) newton (\d+) error (\S+) cpu (\S+) ms", out, re.M):
        sweeps.setdefault((m.group(1), m.group(2)), []).append(
            (float(m.group(3)), int(m.group(4)), int(m.group(5)), float(m.group(6)), float(m.group(7)) * 1e-3))
    for m in re.finditer(r"^wp scene (\w+) tol (\S+) nodes (\d+) newton (\d+) values (.+) cpu (\S+) ms", out, re.M):
        scene.setdefault(("scene", m.group(1)), []).append(
            (float(m.group(2)), int(m.group(3)), int(m.group(4)), [float(v) for v in m.group(5).split()],
             float(m.group(6)) * 1e-3))
    return rows, sweeps, scene


def main():
    args = [a for a in sys.argv[1:] if a != "--wp"]
    sweep = len(args) < len(sys.argv) - 1
    scene = args[0] if len(args) > 0 else "scenes/string-hanging.json"
    repeats = int(args[1]) if len(args) > 1 else 5
    peers = args[2] if len(args) > 2 else os.path.join(HERE, "..", "..", "..", "shared", "peers")
    if not os.path.isdir(peers):
        peers = "/work/shared/peers"
    print(f"load before: {os.getloadavg()}")
    theirs = scipy_side(scene, repeats, peers)
    their_sweeps = scipy_sweeps(repeats, peers) if sweep else {}
    their_scene = scipy_scene_sweep(scene, repeats, peers) if sweep else []
    ours, our_sweeps, our_scene = beltcheck_side(scene, repeats, sweep)
    print(f"load after: {os.getloadavg()}\n")
    print(f"{'problem':<16} {'scipy [ms]':>10} {'nodes':>6} {'error':>9} | {'scheme':<7} {'beltcheck [ms]':>14} {'nodes':>6} {'error':>9} {'ratio':>7}")
    for name, (cpu, nodes, err) in theirs.items():
        for (pname, scheme), (bcpu, bnodes, berr) in ours.items():
            if pname == name:
                print(f"{name:<16} {cpu * 1e3:>10.2f} {nodes:>6} {err:>9.2e} | {scheme:<7} {bcpu * 1e3:>14.3f} {bnodes:>6} "
                      f"{berr:>9.2e} {cpu / bcpu:>6.1f}x")
    if sweep:
        add_scene_sweeps(their_sweeps, our_sweeps, their_scene, our_scene)
        own = {name: e for name, rows in their_sweeps.items() for tol, _, e, _ in rows if abs(tol / 1e-8 - 1) < 1e-9}
        print_work_precision(their_sweeps, our_sweeps, own)


if __name__ == "__main__":
    main()
