#!/usr/bin/env python3
"""A small finite-difference solver of its own for beltcheck's `string-hanging` scene,
written as an outside code would be, and the result files `beltcheck check` reads.

The belt is a closed chain of N nodes joined by N elastic links (the finite-difference
form of the extensible string: unstretched spacing l0 = L/N, axial force
N = EA (l/l0 - 1) in each link, weight rho*g*l0 lumped at each node). A link's length l
is its chord, or where the chord would cut into a pulley (the circle of radius R of the
centreline contour), the taut path round it: tangent, arc, tangent. So a node-to-node
link on a pulley is an arc of it, and the link across a lift-off point is arc plus
tangent: the belt length a pulley takes up is exact wherever between two nodes the span
leaves it. (A chain of chords instead rests on the pulley as a polygon, whose free spans
leave it from a vertex: their line misses the circle by up to R (l0/R)^2 / 12, with a
sign that depends on where the lift-off point falls between nodes, and the span's sag
error oscillates with N instead of converging.) The pulleys push on the nodes by a
penalty, k (rc - |p - c|) when a node is inside the circle rc = R (1 + 1e-7), with
k = 50 EA/l0. Equilibrium is the minimum of the total energy, found by Newton's method
with a line search on the energy; the Hessian is banded after numbering the nodes
0, 1, N-1, 2, N-2, ... . Node 0 is held at x = 0 on the upper span (the mirror line of
the symmetric scene): a frictionless loop could otherwise slide round the pulleys.

Usage:  fd_string.py SCENE OUTDIR [N ...]     (default N: 128 256 512)
Pure Python 3 (no numpy). Each mesh starts from the previous one where it has half
the links, so a sequence of doublings takes a few Newton steps a mesh.
"""

import json
import math
import os
import sys
import time


class Contour:
    """The compound contour of DESIGN.md: sigma from the top of the driver (left
    pulley), clockwise; the point (x, y) -> (sigma, nu) map of drive::Contour."""

    def __init__(self, r, h):
        self.r, self.h = r, h
        self.length = 2.0 * h + 2.0 * math.pi * r

    def wrap(self, s):
        s = math.fmod(s, self.length)
        return s + self.length if s < 0.0 else s

    def sigma_nu(self, x, y):
        h, r, half = self.h, self.r, 0.5 * self.h
        if x > half:
            dx, dy = x - half, y
            return self.wrap(h + r * math.atan2(dx, dy)), math.hypot(dx, dy) - r
        if x < -half:
            dx, dy = x + half, y
            return self.wrap(2.0 * h + math.pi * r + r * math.atan2(-dx, -dy)), math.hypot(dx, dy) - r
        if y >= 0.0:
            return self.wrap(x + half), y - r
        return self.wrap(h + math.pi * r + half - x), -y - r


def banded_solve(a, b, n, w):
    """Solves A x = b for a symmetric band matrix stored as rows {col: value} with
    |i - j| <= w, by Gaussian elimination without pivoting (A is positive definite at
    and near a stable equilibrium)."""
    a = [dict(row) for row in a]
    b = list(b)
    for k in range(n):
        piv = a[k][k]
        for i in range(k + 1, min(n, k + w + 1)):
            f = a[i].get(k, 0.0) / piv
            if f == 0.0:
                continue
            for j in range(k, min(n, k + w + 1)):
                v = a[k].get(j, 0.0)
                if v != 0.0:
                    a[i][j] = a[i].get(j, 0.0) - f * v
            b[i] -= f * b[k]
    x = [0.0] * n
    for i in range(n - 1, -1, -1):
        s = b[i] - sum(v * x[j] for j, v in a[i].items() if j > i)
        x[i] = s / a[i][i]
    return x


def solve(scene, n, guess=None):
    """Equilibrium of the chain of n links; `guess`: the solution on n/2 links (node i
    at node 2i, midpoints between), else a start from the contour with sagging spans."""
    d, belt = scene["drive"], scene["belt"]
    r, h = d["pulley_radius"], d["centre_distance"]
    length, ea, rho = belt["length"], belt["axial_stiffness"], belt["mass_per_length"]
    g = scene["effects"].get("gravity", 0.0)
    l0 = length / n
    k = 50.0 * ea / l0
    # a link whose chord would cut into a pulley is the taut path round it (tangent,
    # arc, tangent: `wrapped` below), so the belt length a pulley takes up does not depend
    # on where between two nodes the span lifts off; the penalty holds the nodes on the
    # circle 1e-7 R outside the pulley, clear of the square-root kink of the tangent
    # length at its surface (the path round costs 1e-12 R a link for it)
    rc = r * (1.0 + 1e-7)
    centres = [(-0.5 * h, 0.0), (0.5 * h, 0.0)]
    weight = rho * g * l0

    # start: both spans sag as parabolas, the loop 1e-4 longer than the belt, the arcs
    # pressed 1e-9 R into the penalty circle (so that the contact holds them from the first step)
    ra = rc * (1.0 - 1e-9)

    def start(sag):
        pts = []
        m = 400
        for i in range(m + 1):  # upper span, left to right
            x = -0.5 * h + h * i / m
            pts.append((x, r - sag * (1.0 - (2.0 * x / h) ** 2)))
        for i in range(1, m):  # driven arc, top to bottom
            phi = math.pi * i / m
            pts.append((0.5 * h + ra * math.sin(phi), ra * math.cos(phi)))
        for i in range(m + 1):  # lower span, right to left
            x = 0.5 * h - h * i / m
            pts.append((x, -r - sag * (1.0 - (2.0 * x / h) ** 2)))
        for i in range(1, m):  # driver arc, bottom to top
            phi = math.pi * i / m
            pts.append((-0.5 * h - ra * math.sin(phi), -ra * math.cos(phi)))
        return pts

    def polyline_length(pts):
        return sum(math.dist(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts)))

    lo, hi = 0.0, 0.5 * h
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if polyline_length(start(mid)) < length * (1.0 + 1e-4) else (lo, mid)
    curve = start(0.5 * (lo + hi))
    # resample n nodes equally spaced along the curve, node 0 at the middle of the upper span
    seg = [math.dist(curve[i], curve[(i + 1) % len(curve)]) for i in range(len(curve))]
    total = sum(seg)
    first = 200  # x = 0 on the upper span (point m/2 of its m + 1)
    nodes, acc, j, target = [], 0.0, first, 0.0
    while len(nodes) < n:
        target = total * len(nodes) / n
        while acc + seg[j % len(curve)] < target:
            acc += seg[j % len(curve)]
            j += 1
        p, q = curve[j % len(curve)], curve[(j + 1) % len(curve)]
        t = (target - acc) / seg[j % len(curve)]
        nodes.append((p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])))
    pos = [list(p) for p in nodes]
    if guess is not None and 2 * len(guess) == n:
        m = len(guess)
        pos = []
        for i in range(m):
            a, b = guess[i], guess[(i + 1) % m]
            pos += [list(a), [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]]
    pos[0][0] = 0.0

    # unknown numbering: node order 0, 1, n-1, 2, n-2, ... ; x of node 0 is held
    order = [0]
    for i in range(1, n // 2 + 1):
        order.append(i)
        if n - i != i:
            order.append(n - i)
    slot = {}
    for rank, node in enumerate(order):
        slot[node] = rank
    def dofs(node):
        base = 2 * slot[node] - 1  # node 0 has its y only, at index 0
        return (None, 0) if node == 0 else (base, base + 1)
    nu = 2 * n - 1
    band = 9

    def wrapped(p, q):
        """Length of link p -> q and its gradient: the chord, or where the chord cuts into
        the pulley next to it, the taut path round it (tangent, arc, tangent)."""
        cx = 0.5 * h if p[0] + q[0] > 0.0 else -0.5 * h
        px, py, qx, qy = p[0] - cx, p[1], q[0] - cx, q[1]
        dp, dq = math.hypot(px, py), math.hypot(qx, qy)
        dth = math.atan2(py, px) - math.atan2(qy, qx)  # clockwise angle from p to q
        dth = dth - 2.0 * math.pi * round(dth / (2.0 * math.pi))
        # tangent lengths and their angles, free of cancellation near the surface
        tp, tq = math.sqrt(max((dp - r) * (dp + r), 0.0)), math.sqrt(max((dq - r) * (dq + r), 0.0))
        ap, aq = math.atan2(tp, r), math.atan2(tq, r)
        beta = dth - ap - aq
        if dth > 0.0 and beta > 0.0:
            gp = [(tp * px / dp - r * py / dp) / dp, (tp * py / dp + r * px / dp) / dp]
            gq = [(tq * qx / dq + r * qy / dq) / dq, (tq * qy / dq - r * qx / dq) / dq]
            return tp + tq + r * beta, gp, gq, True
        dx, dy = q[0] - p[0], q[1] - p[1]
        l = math.hypot(dx, dy)
        if l == 0.0:
            return 0.0, [0.0, 0.0], [0.0, 0.0], False
        return l, [-dx / l, -dy / l], [dx / l, dy / l], False

    def link(p, q, with_hessian):
        w, gp, gq, wrap = wrapped(p, q)
        if not with_hessian or w == 0.0:
            return w, gp, gq, None
        if not wrap:
            dx, dy = q[0] - p[0], q[1] - p[1]
            ex, ey = dx / w, dy / w
            b = [[(1 - ex * ex) / w, -ex * ey / w], [-ex * ey / w, (1 - ey * ey) / w]]
            hw = [[b[a % 2][c % 2] * (1 if (a < 2) == (c < 2) else -1) for c in range(4)] for a in range(4)]
            return w, gp, gq, hw
        # round the pulley: the second derivatives by central differences of the gradient
        x0 = [p[0], p[1], q[0], q[1]]
        # (the step stays on one side of the pulley surface, where the path's length
        # changes its law)
        cx = 0.5 * h if p[0] + q[0] > 0.0 else -0.5 * h
        gap = min(abs(math.hypot(p[0] - cx, p[1]) - r), abs(math.hypot(q[0] - cx, q[1]) - r))
        d = min(1e-7 * r, 0.5 * gap) if gap > 0.0 else 1e-7 * r
        hw = [[0.0] * 4 for _ in range(4)]
        for c in range(4):
            up, dn = x0[:], x0[:]
            up[c] += d
            dn[c] -= d
            _, a1, b1, _ = wrapped(up[0:2], up[2:4])
            _, a2, b2, _ = wrapped(dn[0:2], dn[2:4])
            col = [(u - v) / (2.0 * d) for u, v in zip(a1 + b1, a2 + b2)]
            for a in range(4):
                hw[a][c] = col[a]
        for a in range(4):
            for c in range(a):
                hw[a][c] = hw[c][a] = 0.5 * (hw[a][c] + hw[c][a])
        return w, gp, gq, hw

    def energy_parts(pos):
        e, grad, hess = 0.0, [0.0] * nu, [dict() for _ in range(nu)]
        def add_g(node, gx, gy):
            ix, iy = dofs(node)
            if ix is not None:
                grad[ix] += gx
            grad[iy] += gy
        def add_h(a, b, kk):
            da, db = dofs(a), dofs(b)
            for p in range(2):
                for q in range(2):
                    if da[p] is not None and db[q] is not None and kk[p][q] != 0.0:
                        hess[da[p]][db[q]] = hess[da[p]].get(db[q], 0.0) + kk[p][q]
        for i in range(n):
            j = (i + 1) % n
            w, gi, gj, hw = link(pos[i], pos[j], True)
            if w == 0.0:
                return math.inf, grad, hess
            f = ea * (w / l0 - 1.0)
            e += 0.5 * ea / l0 * (w - l0) ** 2
            add_g(i, f * gi[0], f * gi[1])
            add_g(j, f * gj[0], f * gj[1])
            # a link in compression is given no transverse stiffness (a string has
            # none), so the Newton matrix stays positive definite on the way; at the
            # solution every link is in tension and the matrix is the exact Hessian
            g4 = gi + gj
            kl, kg = ea / l0, max(f, 0.0)
            m4 = [[kl * g4[a] * g4[b] + kg * hw[a][b] for b in range(4)] for a in range(4)]
            add_h(i, i, [row[0:2] for row in m4[0:2]])
            add_h(i, j, [row[2:4] for row in m4[0:2]])
            add_h(j, i, [row[0:2] for row in m4[2:4]])
            add_h(j, j, [row[2:4] for row in m4[2:4]])
        for i in range(n):
            e += weight * pos[i][1]
            add_g(i, 0.0, weight)
            for cx, cy in centres:
                dx, dy = pos[i][0] - cx, pos[i][1] - cy
                dist = math.hypot(dx, dy)
                gap = rc - dist
                if gap > 0.0:
                    ux, uy = dx / dist, dy / dist
                    e += 0.5 * k * gap * gap
                    add_g(i, -k * gap * ux, -k * gap * uy)
                    kr, kt = k, -k * gap / dist
                    add_h(i, i, [[kr * ux * ux + kt * (1 - ux * ux), kr * ux * uy - kt * ux * uy],
                                 [kr * ux * uy - kt * ux * uy, kr * uy * uy + kt * (1 - uy * uy)]])
        return e, grad, hess

    def moved(pos, step, alpha):
        out = [p[:] for p in pos]
        for node in range(n):
            ix, iy = dofs(node)
            if ix is not None:
                out[node][0] -= alpha * step[ix]
            out[node][1] -= alpha * step[iy]
        return out

    iterations = 0
    e, grad, hess = energy_parts(pos)
    scale = weight * n
    while max(abs(v) for v in grad) > 1e-9 * scale:
        iterations += 1
        if iterations > 200:
            raise RuntimeError(f"Newton did not converge at N = {n}")
        # Newton step with a backtracking line search on the energy; where it finds no
        # descent, the matrix is shifted by mu*I (mu growing tenfold) and the step retried
        diag = max(hess[i][i] for i in range(nu))
        mu, done = 1e-14 * diag, False
        while True:
            shifted = [dict(row) for row in hess]
            for i in range(nu):
                shifted[i][i] += mu
            step = banded_solve(shifted, grad, nu, band)
            if mu <= 1e-14 * diag and max(abs(v) for v in step) < 1e-13 * h:
                done = True  # the residual is at its round-off floor (k |x| eps): converged
                break
            # no node moves more than R/20 in one step: a node may not jump through a pulley
            longest = max(abs(v) for v in step)
            alpha, accepted = min(1.0, 0.05 * r / longest) if longest > 0.0 else 1.0, False
            while alpha >= 1e-4:
                trial = moved(pos, step, alpha)
                e_trial, g_trial, h_trial = energy_parts(trial)
                # near the solution the energy changes below its round-off: there a step
                # that reduces the residual is taken
                if e_trial < e or (e_trial <= e + 1e-12 * abs(e) and max(abs(v) for v in g_trial) < max(abs(v) for v in grad)):
                    accepted = True
                    break
                alpha *= 0.5
            if accepted:
                break
            mu = max(10.0 * mu, 1e-8 * diag)
            if mu > 1e3 * diag:
                raise RuntimeError(f"no descent direction at N = {n}")
        if done:
            break
        pos, e, grad, hess = trial, e_trial, g_trial, h_trial

    tension_links = [ea * (wrapped(pos[i], pos[(i + 1) % n])[0] / l0 - 1.0) for i in range(n)]
    tension_nodes = [0.5 * (tension_links[i - 1] + tension_links[i]) for i in range(n)]
    # a node is on a pulley where a link next to it is a path round that pulley
    contact = [None] * n
    for i in range(n):
        j = (i + 1) % n
        if wrapped(pos[i], pos[j])[3]:
            name = "driven" if pos[i][0] + pos[j][0] > 0.0 else "driver"
            contact[i] = contact[j] = name
    return pos, tension_nodes, iterations, nu, contact


def lift_off(pos, centre, contact, pulley):
    """Polar angles (first, last in the direction of sigma) of the two points where the
    belt leaves the pulley. The free span is smooth up to the lift-off point and leaves
    the pulley tangentially, so the point is where the span, continued backwards by the
    parabola through its first three free nodes, passes closest to the pulley centre
    (there its direction is normal to the radius)."""
    n = len(pos)
    inside = [i for i in range(n) if contact[i] == pulley]
    ends = []
    for end, step in ((min(inside, key=lambda i: (i - inside[0]) % n), -1), (max(inside, key=lambda i: (i - inside[0]) % n), 1)):
        f = [pos[(end + step * (j + 1)) % n] for j in range(3)]

        def q(t):  # the parabola through f[0], f[1], f[2] at t = 0, 1, 2
            return [f[0][c] + t * (f[1][c] - f[0][c]) + 0.5 * t * (t - 1.0) * (f[2][c] - 2.0 * f[1][c] + f[0][c]) for c in range(2)]

        def dist(t):
            p = q(t)
            return math.hypot(p[0] - centre[0], p[1] - centre[1])

        lo, hi = -2.0, 0.5  # golden-section search for the closest point
        for _ in range(80):
            m1, m2 = lo + 0.382 * (hi - lo), lo + 0.618 * (hi - lo)
            if dist(m1) < dist(m2):
                hi = m2
            else:
                lo = m1
        p = q(0.5 * (lo + hi))
        ends.append(math.atan2(p[1] - centre[1], p[0] - centre[0]))
    return ends


def result(scene, n, guess=None):
    t0 = time.perf_counter()
    pos, tension, iterations, unknowns, contact = solve(scene, n, guess)
    wall = time.perf_counter() - t0
    d = scene["drive"]
    r, h = d["pulley_radius"], d["centre_distance"]
    contour = Contour(r, h)
    centres = {"driver": (-0.5 * h, 0.0), "driven": (0.5 * h, 0.0)}
    summary = {
        "y_upper_mid": pos[0][1],
        "y_lower_mid": pos[n // 2][1],
        "tension_upper_mid": tension[0],
        "tension_lower_mid": tension[n // 2],
    }
    # nodes run clockwise from the upper mid: on each pulley the first contact node
    # in node order is also the first in the direction of sigma
    for name in ("driver", "driven"):
        start, end = lift_off(pos, centres[name], contact, name)
        # the arc sweeps clockwise (decreasing polar angle) from start to end
        summary[name] = {"contact_arc": (start - end) % (2.0 * math.pi), "contact_start": start, "contact_end": end}
    sigma = [contour.sigma_nu(x, y)[0] for x, y in pos]
    return {
        "scene": scene["name"],
        "method": "fd-string",
        "converged": True,
        "summary": summary,
        "cost": {"wall_seconds": wall, "newton_iterations": iterations, "unknowns": unknowns},
        "fields": {"sigma": sigma, "x": [p[0] for p in pos], "y": [p[1] for p in pos], "tension": tension},
        "discretisation": {"elements": n},
    }, pos


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    with open(argv[1]) as f:
        scene = json.load(f)
    os.makedirs(argv[2], exist_ok=True)
    guess = None
    for n in [int(a) for a in argv[3:]] or [128, 256, 512]:
        res, guess = result(scene, n, guess)
        path = os.path.join(argv[2], f"fd-string-{n}.json")
        with open(path, "w") as f:
            json.dump(res, f, indent=1, allow_nan=False)
        s = res["summary"]
        print(f"N = {n:4d}: y_upper_mid = {s['y_upper_mid']:.9f} m, tension_upper_mid = {s['tension_upper_mid']:.9f} N, "
              f"driver arc = {s['driver']['contact_arc']:.6f} rad, {res['cost']['newton_iterations']} Newton iterations -> {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
