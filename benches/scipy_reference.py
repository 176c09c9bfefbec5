#!/usr/bin/env python3
"""The rocking equations of docs/model.md §3 with scipy.integrate.solve_ivp.

A reference written independently of the Rust code, for the dynamics bench
(benches/dynamics/), which spawns it as

    .venv/bin/python benches/scipy_reference.py '<json>'

and reads one JSON document from stdout. The input names a case and the
tolerances to run; the output has, per tolerance, the wall time of the run
(min over `repeat` runs) and the quantities the bench compares.

Cases:

- "rigid": Housner's rigid block released from theta0 at rest, no ground
  motion; impacts at theta = 0 (solve_ivp event, terminal, then restart
  with omega <- eta omega). Returns the impact times and post-impact omegas.
- "flexible": a hollow circular base on the Winkler bed of docs/model.md §2
  (kn, fm), lumped mass, shiftingPivot, under a piecewise-linear ground
  acceleration given by samples. The reaction position af(phi) is found
  here by brentq on the vertical equilibrium N(a) = W, the stress integrals
  by Gauss-Legendre on panels split at every non-smooth point of the
  integrand (the plastic edge, the contact edge, the circles' edges, where
  the chord has a square-root end: removed by x = edge + L s^2). Its
  derivative follows from differentiating W af = M at constant N:
  af' = -(kn / W) * (second moment of the elastic zone about its centroid).
  Events: theta = 0 (impact), omega = 0 (peaks, recorded), |theta| =
  thetaOv (overturning, terminal), with thetaOv the first root of hW here.
  The input is integrated sample interval by sample interval while the
  ground moves (no step across a kink of ag), as the FMU is driven.
  Returns the impact times, the peaks and the overturning time.

Tolerances: rtol as given, atol = rtol * (thetaOv, p thetaOv) with
p = sqrt(W R0 / IO), the same scales as the Rust code.
"""

import json
import math
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

GL_X, GL_W = np.polynomial.legendre.leggauss(24)


def rigid(p, rtol):
    W, R0, alpha, IO, eta = p["W"], p["R0"], p["alpha"], p["IO"], p["eta"]
    theta_ov = alpha
    pp = math.sqrt(W * R0 / IO)
    atol = [rtol * theta_ov, rtol * pp * theta_ov]

    def make(side):
        def f(t, y):
            phi = side * y[0]
            return [y[1], -side * W * R0 * math.sin(alpha - phi) / IO]

        return f

    def hit(t, y):
        return y[0]

    hit.terminal = True
    t, y = 0.0, [p["theta0"], 0.0]
    side = 1.0 if p["theta0"] > 0 else -1.0
    times, omegas = [], []
    while len(times) < p["impacts"]:
        # the start of a segment is theta = 0: the event must not fire there
        hit.direction = -side
        sol = solve_ivp(make(side), (t, t + 100.0), y, method="DOP853",
                        rtol=rtol, atol=atol, events=hit)
        if not sol.t_events[0].size:
            break
        t = sol.t_events[0][0]
        om = eta * sol.y_events[0][0][1]
        times.append(t)
        omegas.append(om)
        y = [0.0, om]
        side = -side
    return {"impact_times": times, "impact_omegas": omegas}


class Circle:
    """Hollow circular base: the width w(x), x from the toe, and its breaks."""

    def __init__(self, ro, ri):
        self.ro, self.ri, self.d = ro, ri, 2.0 * ro

    def width(self, x):
        u = x - self.ro
        outer = 2.0 * np.sqrt(np.maximum(self.ro**2 - u**2, 0.0))
        inner = 2.0 * np.sqrt(np.maximum(self.ri**2 - u**2, 0.0))
        return outer - inner

    def breaks(self):
        return [0.0, self.ro - self.ri, self.ro + self.ri, self.d]


def panel_integrals(shape, lo, hi, fn):
    """sum over the panel [lo, hi] of fn(x) w(x) dx, each piece mapped so
    that a square-root end at a circle edge becomes smooth."""
    if hi <= lo:
        return 0.0
    edges = shape.breaks()
    total = 0.0
    mid = 0.5 * (lo + hi)
    for a, b, sing_at_a in ((lo, mid, True), (mid, hi, False)):
        L = b - a
        s = 0.5 * (GL_X + 1.0)
        ws = 0.5 * GL_W
        near_a = any(abs(a - e) < 1e-14 for e in edges)
        near_b = any(abs(b - e) < 1e-14 for e in edges)
        if sing_at_a and near_a:
            x = a + L * s**2
            jac = 2.0 * L * s
        elif (not sing_at_a) and near_b:
            x = b - L * s**2
            jac = 2.0 * L * s
        else:
            x = a + L * s
            jac = L * np.ones_like(s)
        total += np.sum(ws * jac * fn(x) * shape.width(x))
    return total


def pieces(shape, lo, hi, extra):
    pts = sorted({lo, hi, *[e for e in shape.breaks() + extra if lo < e < hi]})
    return list(zip(pts[:-1], pts[1:]))


class Interface:
    def __init__(self, shape, W, kn, fm):
        self.s, self.W, self.kn, self.fm = shape, W, kn, fm

    def stress_fn(self, phi, a):
        k, fm = self.kn * phi, self.fm
        return lambda x: np.minimum(k * np.maximum(a - x, 0.0), fm)

    def normal(self, phi, a):
        hi = min(a, self.s.d)
        xp = a - self.fm / (self.kn * phi)
        sig = self.stress_fn(phi, a)
        return sum(panel_integrals(self.s, p, q, sig) for p, q in pieces(self.s, 0.0, hi, [xp]))

    def contact(self, phi):
        """(af, daf) at phi > 0."""
        W, d = self.W, self.s.d
        a1 = self.fm / (self.kn * phi)
        # N grows with a; bracket: N(0) = 0 < W, large a carries W
        hi = d
        while self.normal(phi, hi) < W:
            hi *= 2.0
        a = brentq(lambda x: self.normal(phi, x) - W, 0.0, hi, xtol=1e-15, rtol=1e-15, maxiter=200)
        top = min(a, d)
        xp = max(a - a1, 0.0)
        sig = self.stress_fn(phi, a)
        m = sum(panel_integrals(self.s, p, q, lambda x: sig(x) * x) for p, q in pieces(self.s, 0.0, top, [xp]))
        af = m / W
        # elastic zone [xp, top]: moments about its start
        e = [sum(panel_integrals(self.s, p, q, lambda x, k=k: (x - xp) ** k) for p, q in pieces(self.s, xp, top, []))
             for k in range(3)]
        central = max(e[2] - e[1] ** 2 / e[0], 0.0) if e[0] > 0 else 0.0
        return af, -self.kn * central / W


def flexible(p, rtol):
    shape = Circle(p["ro"], p["ri"])
    W, hg, Ic, g, eta = p["W"], p["hG"], p["Ic"], p["g"], p["eta"]
    m = W / g
    b = shape.ro
    R0 = math.hypot(b, hg)
    alpha = math.atan2(b, hg)
    IO = Ic + m * R0**2
    itf = Interface(shape, W, p["kn"], p["fm"])
    dt = p["dt"]
    ag_s = np.asarray(p["ag"])
    t_end = p["t_end"]

    def ag(t):
        k = int(t / dt)
        if k >= len(ag_s) - 1:
            return 0.0
        return ag_s[k] + (ag_s[k + 1] - ag_s[k]) * (t / dt - k)

    def levers(phi):
        if phi == 0.0:
            af, daf = b, -p["kn"] * math.pi * (shape.ro**4 - shape.ri**4) / 4.0 / W
        else:
            af, daf = itf.contact(phi)
        hw = R0 * math.sin(alpha - phi) - af * math.cos(phi)
        hgl = R0 * math.cos(alpha - phi) - af * math.sin(phi)
        inertia = Ic + m * (R0**2 + af**2 - 2.0 * R0 * af * math.sin(alpha))
        dinertia = -2.0 * m * (R0 * math.sin(alpha) - af) * daf
        return hw, hgl, inertia, dinertia

    # thetaOv: first root of hW on a geometric scan up to alpha
    prev = 1e-9
    theta_ov = alpha
    for k in range(1, 301):
        ph = 1e-9 * (alpha / 1e-9) ** (k / 300)
        if levers(ph)[0] <= 0.0:
            theta_ov = brentq(lambda x: levers(x)[0], prev, ph, xtol=1e-15)
            break
        prev = ph
    pp = math.sqrt(W * R0 / IO)
    atol = [rtol * theta_ov, rtol * pp * theta_ov]

    def make(side0):
        def f(t, y):
            th, om = y
            s = math.copysign(1.0, th) if th != 0.0 else side0
            hw, hgl, inertia, dinertia = levers(abs(th))
            return [om, (-s * W * hw - m * ag(t) * hgl - 0.5 * s * dinertia * om * om) / inertia]

        return f

    def impact(t, y):
        return y[0]

    impact.terminal = True

    def peak(t, y):
        return y[1]

    def over(t, y):
        return abs(y[0]) - theta_ov

    over.terminal = True
    over.direction = 1.0
    t, y = 0.0, [0.0, 0.0]
    # from rest the body moves away from the first push: side -sgn(ag)
    first = next((a for a in ag_s if a != 0.0), 1.0)
    side = -math.copysign(1.0, first)
    times, peaks, t_ov = [], [], None
    # the input is linear between samples: integrate sample interval by
    # sample interval while it moves (as an FMU master would), so that no
    # step straddles a kink of ag; then in one piece to t_end
    last = max((k for k, a in enumerate(ag_s) if a != 0.0), default=0) + 1
    stops = [k * dt for k in range(1, last + 1) if k * dt < t_end] + [t_end]
    h = None
    for stop in stops:
        while t < stop and t_ov is None:
            # theta = 0 at the start of a segment after an impact: only the
            # return counts
            impact.direction = -side
            sol = solve_ivp(make(side), (t, stop), y, method="DOP853", rtol=rtol, atol=atol,
                            events=[impact, peak, over], first_step=h)
            if len(sol.t) > 1:
                h = sol.t[-1] - sol.t[-2]
            for tt, yy in zip(sol.t_events[1], sol.y_events[1]):
                if tt > t:
                    peaks.append(abs(yy[0]))
            if sol.t_events[2].size:
                t_ov = float(sol.t_events[2][0])
                break
            if sol.t_events[0].size and sol.t_events[0][0] > t:
                t = float(sol.t_events[0][0])
                om = eta * sol.y_events[0][0][1]
                times.append(t)
                y = [0.0, om]
                side = math.copysign(1.0, om)
                continue
            t, y = stop, [sol.y[0][-1], sol.y[1][-1]]
            if y[0] != 0.0:
                side = math.copysign(1.0, y[0])
        if t_ov is not None:
            break
    return {"impact_times": times, "peaks": peaks, "overturn": t_ov, "theta_ov": theta_ov}


def main():
    req = json.loads(sys.argv[1])
    case = {"rigid": rigid, "flexible": flexible}[req["case"]]
    out = []
    for rtol in req["rtols"]:
        best, res = math.inf, None
        for _ in range(req.get("repeat", 1)):
            t0 = time.perf_counter()
            res = case(req["params"], rtol)
            best = min(best, time.perf_counter() - t0)
        out.append({"rtol": rtol, "seconds": best, **res})
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    main()
