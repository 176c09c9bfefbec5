"""Parameter sets of the paper's examples, as FMU start values (docs/model.md §4, §5).

The Dharahara Tower (docs/model.md §4): hollow circular base Ro = 3.99 m,
Ri = 2.12 m, W = 24003.94 kN. The paper gives R0 = 30.44 m and alpha = 0.125,
which put the pivot R0 sin(alpha) = 3.80 m from G's vertical, not Ro = 3.99 m.
This model needs G over the section centroid, so hG = R0 cos(alpha) = 30.20 m,
and then alpha = atan(3.99 / 30.20) = 0.131 and R0 = 30.46 m. Ic is an
ASSUMPTION (the paper does not give it): a hollow cylinder of height 2 hG,
Ic = m (H²/12 + (Ro² + Ri²)/4). Same values as examples/dharahara_curves.rs.
"""

import math

G = 9.81

# --- Dharahara (docs/model.md §4, the paper's Table 1) ---------------------------
RO, RI, W = 3.99, 2.12, 24003.94e3
R0_PAPER, ALPHA_PAPER = 30.44, 0.125
HG = R0_PAPER * math.cos(ALPHA_PAPER)
IC = W / G * ((2 * HG) ** 2 / 12 + (RO ** 2 + RI ** 2) / 4)  # = tower_inertia(HG)
FOUNDATION_KN_MPA = (85, 170, 340, 680, 1350, 13500)
INTERFACE_KN_GPA = (2, 5, 15, 200, 500, 1500)
FM_MPA = (2, 5, 15, math.inf)


def tower_inertia(hg):
    """The assumed Ic: a hollow cylinder of height 2 hG, m (H²/12 + (Ro² + Ri²)/4)."""
    return W / G * ((2 * hg) ** 2 / 12 + (RO ** 2 + RI ** 2) / 4)


def dharahara_tower(hg=None, ic=None, **overrides):
    """Start values of the tower on a rigid interface; override e.g. interface, kn, fm.
    hg, ic replace hG = R0 cos(alpha) and the assumed Ic (which follows hg)."""
    hg = HG if hg is None else hg
    ic = tower_inertia(hg) if ic is None else ic
    params = dict(shape="hollowCircle", Ro=RO, Ri=RI, massModel="lumped", W=W, hG=hg, Ic=ic,
                  interface="rigid", formulation="shiftingPivot", restitution="housner", g=G)
    params.update(overrides)
    return params


def fm_label(fm_mpa):
    return "elastic" if math.isinf(fm_mpa) else f"fm{fm_mpa:g}"


def dharahara_cases(groups=("rigid", "foundation", "interface"), hg=None, ic=None):
    """{case id: start values}, ids as in examples/dharahara_curves.rs:
    rigid; F<kn MPa/m>_<fm2|fm5|fm15|elastic>; I<kn GPa/m>_<...>. hg, ic as for dharahara_tower."""
    cases = {}
    if "rigid" in groups:
        cases["rigid"] = dharahara_tower(hg, ic)
    for group, prefix, unit, kns in (("foundation", "F", 1e6, FOUNDATION_KN_MPA),
                                     ("interface", "I", 1e9, INTERFACE_KN_GPA)):
        if group not in groups:
            continue
        for kn in kns:
            for fm in FM_MPA:
                law = "elastic" if math.isinf(fm) else "elastoPlastic"
                extra = {} if math.isinf(fm) else {"fm": fm * 1e6}
                cases[f"{prefix}{kn:g}_{fm_label(fm)}"] = dharahara_tower(
                    hg, ic, interface=law, kn=kn * unit, **extra)
    return cases


def case_info(case_id):
    """(group, kn in Pa/m, fm in Pa) of a case id of `dharahara_cases`."""
    if case_id == "rigid":
        return "rigid", math.inf, math.inf
    head, fm = case_id.split("_")
    group, unit = ("foundation", 1e6) if head[0] == "F" else ("interface", 1e9)
    fm_pa = math.inf if fm == "elastic" else float(fm[2:]) * 1e6
    return group, float(head[1:]) * unit, fm_pa


# --- The paper's Fig. 15: free rocking of six solid blocks ------------------
#: Slendernesses of the six blocks, rad (the paper: 0.1 .. 0.35).
FIG15_ALPHAS = (0.10, 0.15, 0.20, 0.24, 0.30, 0.35)
#: Size R0 (toe to G) held fixed, m; density of masonry, kg/m³; width L, m.
FIG15_R0, FIG15_RHO, FIG15_L = 3.0, 1800.0, 1.0
#: Interface (chosen: the paper's text does not give Fig. 15's): Fig. 14c's
#: kn = 340 MPa/m, elastic (no crushing).
FIG15_KN = 340e6


def fig15_block(alpha, formulation, theta0_over_alpha=0.9, kn=FIG15_KN, fm=None, r0=FIG15_R0):
    """A solid rectangular prism of slenderness alpha and size r0 (default FIG15_R0):
    B = 2 R0 sin(alpha), H = 2 R0 cos(alpha), L = 1 m, rho = 1800 kg/m³,
    released from rest at theta0 = theta0_over_alpha * alpha (Housner's eta)."""
    b = 2 * r0 * math.sin(alpha)
    h = 2 * r0 * math.cos(alpha)
    params = dict(shape="solidRectangle", B=b, L=FIG15_L, massModel="prism", H=h, rho=FIG15_RHO,
                  interface="elastic" if fm is None else "elastoPlastic", kn=kn,
                  formulation=formulation, restitution="housner", g=G,
                  theta=theta0_over_alpha * alpha, omega=0.0)
    if fm is not None:
        params["fm"] = fm
    return params
