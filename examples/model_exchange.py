"""Co-simulation against Model Exchange: RockingBlock.fmu run by fmpy both ways.

    .venv/bin/python examples/model_exchange.py [--out DIR]

Three panels: (a) rigid free rocking of a 0.25 m x 1 m block released from
0.5 alpha, ME with CVode (rtol 1e-10) and explicit Euler (step 1e-4 s) beside
CS and the exact impact times; (b) the Dharahara tower on the 15 GPa/m, 2 MPa
joint (I15_fm2) under the KATNP stand-in record, CS and ME (CVode rtol 1e-8)
to overturning; (c) a 0.5 m x 2.5 m block on an elastic and on a crushing
(fm = 0.3 MPa) bed of 100 MPa/m under a one-sine pulse, CS and ME.
Writes DIR/model_exchange.png (default docs/img) and prints the figures the
docs quote (about 30 s).
"""

import argparse
import math
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "fmpy-tests"))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from test_model_exchange import (  # noqa: E402
    Exact, crossing_times, cs, cvode_applies_inputs, dharahara, me, rigid_block)

FMU = str(REPO / "target" / "fmu" / "RockingBlock.fmu")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=str(REPO / "docs" / "img"))
    out = Path(ap.parse_args().out)
    out.mkdir(parents=True, exist_ok=True)
    setattr(*cvode_applies_inputs())  # fmpy's CVode and time-varying inputs
    fig, ax = plt.subplots(3, 1, figsize=(9, 10))

    ex = Exact(0.25, 1.0)
    exact = ex.impact_times(0.5 * ex.alpha, 10)
    stop = exact[-1] + 0.05
    p = rigid_block()
    ref, _ = cs(FMU, p, stop, interval=1e-3)
    cv = me(FMU, p, stop, rtol=1e-10, interval=1e-3)
    eu = me(FMU, p, stop, solver="Euler", step=1e-4, interval=1e-3)
    err = np.abs(crossing_times(cv)[:10] - exact) / np.asarray(exact)
    eu_err = np.abs(crossing_times(eu)[:10] - exact)
    print(f"rigid free rocking: CVode rtol 1e-10 impact times, worst relative error {err.max():.1e}; "
          f"Euler 1e-4 s: worst absolute error {eu_err.max():.1e} s")
    a = ax[0]
    a.plot(ref["time"], ref["theta"] / ex.alpha, "k-", lw=2.5, alpha=0.35, label="co-simulation")
    a.plot(cv["time"], cv["theta"] / ex.alpha, "C0-", lw=1, label="ME, CVode rtol 1e-10")
    a.plot(eu["time"], eu["theta"] / ex.alpha, "C3--", lw=1, label="ME, Euler h = 1e-4 s")
    a.plot(exact, np.zeros(len(exact)), "kx", label="exact impact times")
    a.set_title("(a) rigid block 0.25 m x 1 m from 0.5 alpha, no input")
    a.set_ylabel("theta / alpha")
    a.legend(fontsize=8, loc="upper right")

    params, record = dharahara("I15_fm2", 26.0)
    ref, run = cs(FMU, params, 26.0, record=record)
    res = me(FMU, params, 26.0, rtol=1e-8, record=record)
    alpha = math.atan(3.99 / params["hG"])
    t_cs = run.t_overturn
    print(f"Dharahara I15_fm2: overturns at {t_cs:.4f} s (CS), {res['time'][-1]:.4f} s (ME, CVode 1e-8)")
    a = ax[1]
    a.plot(ref["time"], ref["theta"] / alpha, "k-", lw=2.5, alpha=0.35, label=f"co-simulation (overturns {t_cs:.2f} s)")
    a.plot(res["time"], res["theta"] / alpha, "C0-", lw=1,
           label=f"ME, CVode rtol 1e-8 (overturns {res['time'][-1]:.2f} s)")
    a.set_xlim(18, 26)
    a.set_title("(b) Dharahara tower, joint 15 GPa/m, fm = 2 MPa, KATNP stand-in record")
    a.set_ylabel("theta / alpha")
    a.legend(fontsize=8, loc="upper left")

    a = ax[2]
    alpha = math.atan(0.5 / 2.5)
    t = np.arange(0, 3.0001, 0.01)
    ag = np.where(t < 0.5, -1.3 * 9.81 * math.tan(alpha) * np.sin(2 * math.pi * t / 0.5), 0.0)
    for law, c in (("elastic", "C0"), ("elastoPlastic", "C2")):
        p = dict(shape="solidRectangle", B=0.5, L=1.0, massModel="prism", H=2.5, rho=1800.0,
                 interface=law, kn=1e8, fm=3e5, g=9.81)
        ref, _ = cs(FMU, p, 3.0, record=(t, ag))
        res = me(FMU, p, 3.0, rtol=1e-10, record=(t, ag), events=False)
        d = np.max(np.abs(res["theta"] - ref["theta"])) / alpha
        print(f"{law}: max |theta_ME - theta_CS| / alpha = {d:.1e}")
        a.plot(ref["time"], ref["theta"] / alpha, "k-", lw=2.5, alpha=0.35)
        a.plot(res["time"], res["theta"] / alpha, c + "-", lw=1, label=f"{law}: ME (CVode 1e-10) on CS (grey)")
    a.set_title("(c) block 0.5 m x 2.5 m, kn = 100 MPa/m, elastic and fm = 0.3 MPa, one-sine pulse")
    a.set_xlabel("t (s)")
    a.set_ylabel("theta / alpha")
    a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "model_exchange.png", dpi=110)
    print(f"wrote {out / 'model_exchange.png'}")


if __name__ == "__main__":
    main()
