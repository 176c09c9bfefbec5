"""The parameter sets of `rocking.cases` by name, for `rocking simulate --preset`
and the `preset` key of a sweep's CASES.toml.

Names:
- `dharahara-rigid`: the Dharahara Tower on a rigid interface (docs/model.md §4);
- `dharahara-F<kn>-<fm>`: on a flexible foundation, kn in MPa/m (85, 170, 340,
  680, 1350, 13500), fm the crushing strength `fm2`, `fm5`, `fm15` (MPa) or
  `elastic` (no crushing);
- `dharahara-I<kn>-<fm>`: on a flexible interface, kn in GPa/m (2, 5, 15, 200,
  500, 1500), fm as above;
  (the case ids of `rocking.cases.dharahara_cases` with `_` written `-`);
- `fig15-alpha<alpha>-<formulation>`: a block of the paper's Fig. 15, free
  rocking from theta0 = 0.9 alpha, alpha one of 0.10, 0.15, 0.20, 0.24, 0.30,
  0.35 rad, formulation `costa` or `shiftingPivot`.
"""

import math

from .cases import FIG15_ALPHAS, FIG15_KN, case_info, dharahara_cases, fig15_block

FIG15_FORMULATIONS = ("costa", "shiftingPivot")

#: How the names are built, for --help.
NAMING = ("dharahara-rigid; dharahara-F{85,170,340,680,1350,13500}-{fm2,fm5,fm15,elastic} "
          "(foundation kn in MPa/m, crushing strength fm in MPa or none); "
          "dharahara-I{2,5,15,200,500,1500}-{fm2,fm5,fm15,elastic} (interface kn in GPa/m); "
          "fig15-alpha{" + ",".join(f"{a:.2f}" for a in FIG15_ALPHAS) + "}-{costa,shiftingPivot} "
          "(free rocking of the paper's Fig. 15 blocks from theta0 = 0.9 alpha)")


def dharahara_name(case_id):
    """Preset name of a case id of `dharahara_cases` ("F170_fm5" -> "dharahara-F170-fm5")."""
    return "dharahara-" + case_id.replace("_", "-")


def _dharahara_text(case_id):
    group, kn, fm = case_info(case_id)
    if group == "rigid":
        return "Dharahara Tower, rigid interface (Housner)"
    kn_text = f"kn = {kn / 1e6:g} MPa/m" if group == "foundation" else f"kn = {kn / 1e9:g} GPa/m"
    fm_text = "no crushing" if math.isinf(fm) else f"fm = {fm / 1e6:g} MPa"
    return f"Dharahara Tower, flexible {group}: {kn_text}, {fm_text}"


def presets():
    """{name: (description, start values)}, in a stable order."""
    out = {}
    for case_id, params in dharahara_cases().items():
        out[dharahara_name(case_id)] = (_dharahara_text(case_id), params)
    for alpha in FIG15_ALPHAS:
        for formulation in FIG15_FORMULATIONS:
            out[f"fig15-alpha{alpha:.2f}-{formulation}"] = (
                f"Fig. 15 block: solid prism, alpha = {alpha:g} rad, R0 = 3 m, elastic kn = "
                f"{FIG15_KN / 1e6:g} MPa/m, {formulation}, released at theta0 = 0.9 alpha",
                fig15_block(alpha, formulation))
    return out


def preset(name):
    """Start values of the preset `name`; KeyError (with close matches) if there is none."""
    table = presets()
    if name not in table:
        import difflib
        close = difflib.get_close_matches(name, table, n=3, cutoff=0.6)
        hint = f"; did you mean {', '.join(close)}?" if close else ""
        raise KeyError(f"unknown preset {name!r}{hint} (`rocking info --presets` lists them)")
    return dict(table[name][1])
