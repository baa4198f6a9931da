#!/usr/bin/env python3
"""Issue 17's side-by-side in one run: scipy's solve_bvp (the peers in ../shared/peers/,
analytic Jacobians, tol 1e-8) and beltcheck's collocation (`--example speed`), CPU
times and the ratios scipy / beltcheck.

Run from the repository root (needs numpy and scipy, `python3 -m pip install scipy`):

    python3 bvp/examples/speed_vs_scipy.py [SCENE] [REPEATS] [PEERS_DIR]

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


def beltcheck_side(scene_path, repeats):
    cmd = ["cargo", "run", "--release", "--quiet", "-p", "bvp", "--example", "speed", "--", scene_path, str(repeats)]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    print(out)
    rows = {}
    m = re.search(r"tol 1e-8 \((\w+)\): nodes (\d+), Newton (\d+), cpu ([\d.]+) ms", out)
    rows[("string-hanging", m.group(1))] = (float(m.group(4)) * 1e-3, int(m.group(2)), float("nan"))
    for m in re.finditer(r"^(bratu 3\.51|elastica)\s+(\w+)\s+tol (\S+)\s+nodes\s+(\d+)\s+newton\s+\d+\s+error (\S+)\s+cpu\s+([\d.]+) ms",
                         out, re.M):
        rows[(m.group(1), m.group(2))] = (float(m.group(6)) * 1e-3, int(m.group(4)), float(m.group(5)))
    return rows


def main():
    scene = sys.argv[1] if len(sys.argv) > 1 else "scenes/string-hanging.json"
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    peers = sys.argv[3] if len(sys.argv) > 3 else os.path.join(HERE, "..", "..", "..", "shared", "peers")
    if not os.path.isdir(peers):
        peers = "/work/shared/peers"
    print(f"load before: {os.getloadavg()}")
    theirs = scipy_side(scene, repeats, peers)
    ours = beltcheck_side(scene, repeats)
    print(f"load after: {os.getloadavg()}\n")
    print(f"{'problem':<16} {'scipy [ms]':>10} {'nodes':>6} {'error':>9} | {'scheme':<7} {'beltcheck [ms]':>14} {'nodes':>6} {'error':>9} {'ratio':>7}")
    for name, (cpu, nodes, err) in theirs.items():
        for (pname, scheme), (bcpu, bnodes, berr) in ours.items():
            if pname == name:
                print(f"{name:<16} {cpu * 1e3:>10.2f} {nodes:>6} {err:>9.2e} | {scheme:<7} {bcpu * 1e3:>14.3f} {bnodes:>6} "
                      f"{berr:>9.2e} {cpu / bcpu:>6.1f}x")


if __name__ == "__main__":
    main()
