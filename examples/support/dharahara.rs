//! The Dharahara Tower of docs/dharahara.md, shared by the examples that
//! run it (`#[path = "support/dharahara.rs"] mod dharahara;`): the hollow
//! circular base Ro = 3.99 m, Ri = 2.12 m, W = 24003.94 kN.
//!
//! Geometry (stated in docs/dharahara.md): the paper's R0 = 30.44 m and
//! alpha = 0.125 put the pivot 3.80 m from G's vertical, not at Ro = 3.99 m;
//! this model needs G above the section centroid, so hG = R0 cos(alpha) =
//! 30.20 m and alpha = atan(3.99 / 30.20) = 0.131. Ic is an assumption: a
//! hollow cylinder of height 2 hG, Ic = m (H²/12 + (Ro² + Ri²)/4).

#![allow(dead_code)] // each example uses part of it

use rocking::model::{MassKind, ShapeKind};
use rocking::Params;

/// Outer radius, m.
pub const RO: f64 = 3.99;
/// Inner radius, m.
pub const RI: f64 = 2.12;
/// Weight, N.
pub const W: f64 = 24003.94e3;
/// The paper's R0 (m) and alpha (rad).
pub const R0_PAPER: f64 = 30.44;
pub const ALPHA_PAPER: f64 = 0.125;
/// Gravity, m/s².
pub const G: f64 = 9.81;

/// The tower, its interface left at the default: `hg` (m) defaults to R0
/// cos(alpha) of the paper, `ic` (kg m²) to the hollow cylinder of height
/// 2 hG.
pub fn tower(hg: Option<f64>, ic: Option<f64>) -> Params {
    let hg = hg.unwrap_or(R0_PAPER * ALPHA_PAPER.cos());
    let m = W / G;
    let h = 2.0 * hg;
    Params {
        shape: ShapeKind::HollowCircle,
        ro: RO,
        ri: RI,
        mass_model: MassKind::Lumped,
        w: W,
        hg,
        ic: ic.unwrap_or(m * (h * h / 12.0 + (RO * RO + RI * RI) / 4.0)),
        g: G,
        ..Params::default()
    }
}

/// Foundation stiffnesses of the paper's Table 1, MPa/m.
pub const FOUNDATION_MPA: [f64; 6] = [85.0, 170.0, 340.0, 680.0, 1350.0, 13500.0];
/// Interface stiffnesses of the paper's Table 1, GPa/m.
pub const INTERFACE_GPA: [f64; 6] = [2.0, 5.0, 15.0, 200.0, 500.0, 1500.0];
/// Compressive strengths of Table 1, MPa (and none: infinity).
pub const FM_MPA: [f64; 4] = [2.0, 5.0, 15.0, f64::INFINITY];

/// The 49 cases of docs/model.md §4 as the planar study runs them
/// (`python/rocking/cases.py`, `dharahara_cases`: the same ids, the
/// elastic law where fm is infinite, the default formulation
/// shiftingPivot): `(id, params)`, rigid first.
pub fn cases() -> Vec<(String, Params)> {
    use rocking::model::LawKind;
    let base = tower(None, None);
    let mut out = vec![(
        "rigid".to_string(),
        Params {
            interface: LawKind::Rigid,
            ..base
        },
    )];
    for (prefix, unit, kns) in [("F", 1e6, FOUNDATION_MPA), ("I", 1e9, INTERFACE_GPA)] {
        for kn in kns {
            for fm in FM_MPA {
                let (interface, label) = if fm.is_finite() {
                    (LawKind::ElastoPlastic, format!("fm{fm}"))
                } else {
                    (LawKind::Elastic, "elastic".to_string())
                };
                let params = Params {
                    interface,
                    kn: kn * unit,
                    fm: if fm.is_finite() { fm * 1e6 } else { base.fm },
                    ..base
                };
                out.push((format!("{prefix}{kn}_{label}"), params));
            }
        }
    }
    out
}
