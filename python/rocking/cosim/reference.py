"""The monolithic reference: frame and block as one system of ODEs, one
integrator at tight tolerance (docs/cosimulation.md §2).

Independent of the FMUs on purpose: the interface law is the closed form of an
elastic solid rectangle (docs/model.md §2, "Solid rectangle in closed form"),
the equations of motion and the support force are written here from
docs/model.md §3 and §5, the frame's matrices from docs/shear-frame.md, and
SciPy's DOP853 integrates them with its own event location. None of the Rust
code (contact solve, integrator, exact frame step) is on this path, so an
agreement between master and reference checks both.

    ref = Reference(frame_params(...), {"interface": "elastic", "kn": 1e8, ...},
                    floor=3, ground=sine_ground(4.0, 2.0, cycles=3), stop_time=3.0)
    ref.at(times)["theta"], ref.peak("a_floor")

Supported: shape solidRectangle, massModel prism or lumped, interface elastic,
formulation shiftingPivot or costa, restitution housner or given.
"""

import math

import numpy as np
from scipy.integrate import quad, solve_ivp
from scipy.linalg import eigh
from scipy.optimize import brentq

#: The block's defaults (docs/model.md §5), for the parameters a dict leaves out.
BLOCK_DEFAULTS = {"shape": "solidRectangle", "B": 0.5, "L": 1.0, "massModel": "prism", "H": 2.5,
                  "rho": 1800.0, "W": 1e5, "hG": 1.25, "Ic": 1e4, "interface": "elastoPlastic",
                  "kn": 5e9, "formulation": "shiftingPivot", "restitution": "housner", "eta": 0.9,
                  "g": 9.81, "theta": 0.0, "omega": 0.0}


class ElasticRectangle:
    """An elastic solid rectangle: the closed-form af(phi) and the levers (docs/model.md §2, §3)."""

    def __init__(self, params):
        p = {**BLOCK_DEFAULTS, **params}
        for key, allowed in (("shape", "solidRectangle"), ("interface", "elastic")):
            if p[key] != allowed:
                raise ValueError(f"reference: {key} = {p[key]!r}: only {allowed!r} has a closed form here")
        self.B, self.L, self.g, self.kn = float(p["B"]), float(p["L"]), float(p["g"]), float(p["kn"])
        if p["massModel"] == "prism":
            H = float(p["H"])
            self.m = float(p["rho"]) * self.B * self.L * H
            self.hG, self.Ic = H / 2, self.m * (H**2 + self.B**2) / 12
        elif p["massModel"] == "lumped":
            self.m = float(p["W"]) / self.g
            self.hG, self.Ic = float(p["hG"]), float(p["Ic"])
        else:
            raise ValueError(f"reference: massModel = {p['massModel']!r}")
        self.W = self.m * self.g
        self.b = self.B / 2
        self.R0 = math.hypot(self.b, self.hG)
        self.alpha = math.atan2(self.b, self.hG)
        self.IO = self.Ic + self.m * self.R0**2
        self.Is = self.L * self.B**3 / 12
        self.thetaJo = 2 * self.W / (self.kn * self.L * self.B**2)
        self.eta = 1 - 2 * self.m * self.b**2 / self.IO if p["restitution"] == "housner" else float(p["eta"])
        self.shifting = p["formulation"] == "shiftingPivot"
        self.theta0, self.omega0 = float(p["theta"]), float(p["omega"])
        self.thetaOv = brentq(lambda x: self.levers(x)[0], 1e-9, self.alpha, xtol=1e-15)

    def af(self, phi):
        """(af, d af/d phi), m and m/rad: full contact below thetaJo, a = sqrt(2W/(kn phi L))
        above. phi: a float (the integrator's path, in plain floats for speed) or an array."""
        if np.ndim(phi) == 0:
            if phi <= self.thetaJo:
                return self.B / 2 - self.kn * phi * self.Is / self.W, -self.kn * self.Is / self.W
            a = math.sqrt(2 * self.W / (self.kn * phi * self.L))
            return a / 3, -a / (6 * phi)
        full = phi <= self.thetaJo
        a = np.sqrt(2 * self.W / (self.kn * np.maximum(phi, self.thetaJo) * self.L))
        af = np.where(full, self.B / 2 - self.kn * phi * self.Is / self.W, a / 3)
        daf = np.where(full, -self.kn * self.Is / self.W, -a / (6 * np.maximum(phi, self.thetaJo)))
        return af, daf

    def levers(self, phi):
        """hW, hg, their phi-derivatives, I and dI/dphi (docs/model.md §3, §5); phi: float or array."""
        sin, cos = (math.sin, math.cos) if np.ndim(phi) == 0 else (np.sin, np.cos)
        af, daf = self.af(phi)
        s, c = sin(phi), cos(phi)
        hW = self.R0 * sin(self.alpha - phi) - af * c
        hg = self.R0 * cos(self.alpha - phi) - af * s
        I = self.Ic + self.m * (self.R0**2 + af**2 - 2 * self.R0 * af * math.sin(self.alpha))
        dI = -2 * self.m * (self.R0 * math.sin(self.alpha) - af) * daf
        return hW, hg, hW - daf * s, -hg - daf * c, I, dI

    def potential(self, theta):
        """W * integral of hW from 0 to |theta| (J)."""
        return self.W * quad(lambda x: self.levers(x)[0], 0.0, abs(theta), epsabs=0, epsrel=1e-13)[0]


class Reference:
    """The coupled system integrated from 0 to stop_time (see the module's docstring)."""

    def __init__(self, frame, block, floor, ground, stop_time, rtol=1e-12, coupling="two-way",
                 u0=None, v0=None):
        n = int(frame.get("n", 3))
        self.n, self.j = n, int(floor) - 1
        self.mass = np.array([float(frame[f"m[{i}]"]) for i in range(1, n + 1)])
        k = np.array([float(frame[f"k[{i}]"]) for i in range(1, n + 1)])
        K = np.diag(k)
        K[:-1, :-1] += np.diag(k[1:])
        K -= np.diag(k[1:], 1) + np.diag(k[1:], -1)
        self.K = K
        M = np.diag(self.mass)
        w2, phi = eigh(K, M)                     # mass-normalised modes
        omega_n = np.sqrt(w2)
        if frame.get("damping", "modal") != "modal":
            raise ValueError("reference: only modal damping")
        zeta = float(frame.get("zeta", 0.05))
        self.C = M @ phi @ np.diag(2 * zeta * omega_n) @ phi.T @ M
        self.periods = 2 * np.pi / omega_n
        self.body = ElasticRectangle(block)
        self.ground = ground
        self.two_way = coupling == "two-way"
        y0 = np.zeros(2 * n + 2)
        if u0 is not None:
            y0[:n] = u0
        if v0 is not None:
            y0[n:2 * n] = v0
        y0[2 * n], y0[2 * n + 1] = self.body.theta0, self.body.omega0
        self._integrate(y0, float(stop_time), rtol)

    # -- the equations ------------------------------------------------------------
    def _accelerations(self, t, y):
        """(u'' of every floor, A = absolute acceleration of floor j, theta'', Fx) at t for
        the state y = (u, v, theta, omega); t: float or array, y: (2n + 2,) or (len(t), 2n + 2)."""
        n, j, bd = self.n, self.j, self.body
        y = np.asarray(y)
        u, v, th, om = y[..., :n], y[..., n:2 * n], y[..., 2 * n], y[..., 2 * n + 1]
        ag = self.ground(t)
        f = -(v @ self.C.T + u @ self.K.T)
        if np.ndim(th) == 0:
            th, om, ag = float(th), float(om), float(ag)
            s, phi = math.copysign(1.0, th) if th != 0 else 0.0, abs(th)
        else:
            s, phi = np.sign(th), np.abs(th)
        hW, hg, dhg, _, I, dI = bd.levers(phi)
        gyro = 0.5 * s * dI * om**2 if bd.shifting else 0.0
        mb, mj = bd.m, self.mass[j]
        fj = f[..., j]
        if self.two_way:
            # [(mj + mb)  mb hg] [A     ]   [f_j - mb s hg' om^2    ]
            # [ mb hg     I    ] [theta''] = [-s W hW - (1/2) s I' om^2]
            a11, a12, a22 = mj + mb, mb * hg, I
            r1, r2 = fj - mb * s * dhg * om**2, -s * bd.W * hW - gyro
            det = a11 * a22 - a12 * a12
            A, thdd = (r1 * a22 - a12 * r2) / det, (a11 * r2 - a12 * r1) / det
        else:
            A = fj / mj
            thdd = (-s * bd.W * hW - gyro - mb * A * hg) / I
        Fx = mb * (A + hg * thdd + s * dhg * om**2)
        udd = f / self.mass - np.asarray(ag)[..., None]
        udd[..., j] = A - ag
        return udd, A, thdd, Fx

    def _rhs(self, t, y):
        n = self.n
        udd, _, thdd, _ = self._accelerations(t, y)
        out = np.empty_like(y)
        out[:n], out[n:2 * n] = y[n:2 * n], udd
        out[2 * n], out[2 * n + 1] = y[2 * n + 1], thdd
        return out

    # -- integration with the impacts and overturning as events -----------------
    def _integrate(self, y0, stop, rtol):
        n, bd = self.n, self.body
        ith = 2 * n
        overturn = lambda t, y: abs(y[ith]) - bd.thetaOv  # noqa: E731
        overturn.terminal, overturn.direction = True, 1
        self.segments, self.impact_times = [], []
        self.overturned, self.t_overturn = False, math.nan
        t, y = 0.0, y0.copy()
        atol = 1e-14
        while t < stop:
            if y[ith] == 0.0 and y[ith + 1] == 0.0:
                # from rest: no crossing is possible before the body has moved off 0
                sol = solve_ivp(self._rhs, (t, min(stop, t + 1e-3)), y, method="DOP853",
                                rtol=rtol, atol=atol, dense_output=True)
                self.segments.append(sol)
                t, y = sol.t[-1], sol.y[:, -1].copy()
                continue
            side = math.copysign(1.0, y[ith] if y[ith] != 0 else y[ith + 1])
            cross = lambda t, y: y[ith]  # noqa: E731
            cross.terminal, cross.direction = True, -side
            sol = solve_ivp(self._rhs, (t, stop), y, method="DOP853", rtol=rtol, atol=atol,
                            dense_output=True, events=[cross, overturn])
            self.segments.append(sol)
            t, y = sol.t[-1], sol.y[:, -1].copy()
            if sol.status == 1 and len(sol.t_events[1]):
                self.overturned, self.t_overturn = True, t
                break
            if sol.status == 1:
                y[ith] = 0.0
                y[ith + 1] *= bd.eta
                self.impact_times.append(t)
        self.t_end = t

    # -- results --------------------------------------------------------------------
    def at(self, times, accelerations=True):
        """Values at `times` (within the run): theta, omega, u (len x n), v and, with
        accelerations, a_floor (absolute, floor j) and Fx (the block's support force)."""
        times = np.asarray(times, dtype=float)
        y = np.empty((len(times), 2 * self.n + 2))
        starts = np.array([s.t[0] for s in self.segments])
        # the segment that ends at or after t (before an impact: its pre-impact value)
        seg = np.maximum(0, np.searchsorted(starts, times, side="left") - 1)
        for k in np.unique(seg):
            sel = seg == k
            y[sel] = self.segments[k].sol(times[sel]).T
        out = {"time": times, "theta": y[:, 2 * self.n], "omega": y[:, 2 * self.n + 1],
               "u": y[:, :self.n], "v": y[:, self.n:2 * self.n]}
        if accelerations:
            _, out["a_floor"], _, out["Fx"] = self._accelerations(times, y)
        return out

    def peak(self, name, dt=2e-4):
        """max |name| over the run, on a grid of dt plus the solver's own steps."""
        grid = np.union1d(np.arange(0.0, self.t_end, dt), np.concatenate([s.t for s in self.segments]))
        grid = grid[grid <= self.t_end]
        return float(np.max(np.abs(self.at(grid, name not in ("theta", "omega", "u", "v"))[name])))

    def energy(self, times):
        """Mechanical energy of frame and block (J) on a fixed ground (ag = 0): the kinetic
        energies (docs/model.md §3 "Energy" with the floor's velocity) plus the strain
        energy of the storeys and the block's potential."""
        r = self.at(times)
        bd = self.body
        out = []
        for k in range(len(times)):
            u, v, th, om = r["u"][k], r["v"][k], r["theta"][k], r["omega"][k]
            _, hg, _, _, I, _ = bd.levers(abs(th))
            vj = v[self.j]
            e = 0.5 * v @ (self.mass * v) + 0.5 * u @ self.K @ u
            e += 0.5 * bd.m * vj**2 + bd.m * vj * hg * om + 0.5 * I * om**2 + bd.potential(th)
            out.append(e)
        return np.array(out)
