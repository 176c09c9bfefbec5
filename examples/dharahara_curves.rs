//! Moment-rotation curves of the Dharahara Tower (docs/model.md §4; the paper's
//! Figs. 17 and 18): the hollow circular base Ro = 3.99 m, Ri = 2.12 m,
//! W = 24003.94 kN, on the foundation and interface stiffnesses of the paper's
//! Table 1 with fm = 2, 5, 15 MPa and without crushing, and on the rigid
//! interface.
//!
//! Geometry and mass: examples/support/dharahara.rs.
//!
//! `cargo run --release --example dharahara_curves [-- OUT_DIR [HG [IC]]]`
//! (default `out/dharahara`; HG in m and IC in kg m² replace the choices above,
//! for sensitivity studies) writes
//! - `OUT_DIR/dharahara_mr_curves.csv`: MR (N m) of every case against theta;
//! - `OUT_DIR/dharahara_mr_cases.csv`: one row per case: thresholds,
//!   overturning rotation, peak MR, overturning energy, their ratios to the
//!   rigid interface, and the stability margin kn Is / (W hG);
//!
//! and prints the cases and the rest-stability check (docs/model.md §2) for the
//! softest foundation, including what the model does when it fails.
//! `examples/dharahara.py` runs it and plots the curves.

use std::fmt::Write as _;

use rocking::model::LawKind;
use rocking::{Model, Params};

#[path = "support/dharahara.rs"]
mod dharahara;
use dharahara::{tower, ALPHA_PAPER, FM_MPA, FOUNDATION_MPA, INTERFACE_GPA, R0_PAPER, RI, RO};

struct Case {
    id: String,
    group: &'static str,
    kn: f64,
    fm: f64,
    model: Model,
}

fn fm_label(fm: f64) -> String {
    if fm.is_finite() {
        format!("fm{}", fm / 1e6)
    } else {
        "elastic".to_string()
    }
}

/// Composite 8-point Gauss-Legendre of `f` over the partition `nodes`.
fn integrate(f: impl Fn(f64) -> f64, nodes: &[f64]) -> f64 {
    const X: [f64; 4] = [
        0.183_434_642_495_649_8,
        0.525_532_409_916_329,
        0.796_666_477_413_626_7,
        0.960_289_856_497_536_3,
    ];
    const WT: [f64; 4] = [
        0.362_683_783_378_362,
        0.313_706_645_877_887_3,
        0.222_381_034_453_374_5,
        0.101_228_536_290_376_3,
    ];
    let mut sum = 0.0;
    for w in nodes.windows(2) {
        let (c, h) = ((w[0] + w[1]) / 2.0, (w[1] - w[0]) / 2.0);
        for (x, wt) in X.iter().zip(WT) {
            sum += wt * h * (f(c - h * x) + f(c + h * x));
        }
    }
    sum
}

/// A partition of `[0, end]`: geometric from `1e-10 end` to `0.01 end`, then
/// linear, with the interface thresholds inserted (MR is only C1 there).
fn partition(end: f64, extra: &[f64]) -> Vec<f64> {
    let mut nodes = vec![0.0];
    let (lo, n_geo) = (1e-10 * end, 80);
    for i in 0..=n_geo {
        nodes.push(lo * (0.01 / 1e-10_f64).powf(i as f64 / n_geo as f64));
    }
    for i in 1..=400 {
        nodes.push(0.01 * end + (end - 0.01 * end) * i as f64 / 400.0);
    }
    nodes.extend(extra.iter().copied().filter(|&x| x > 0.0 && x < end));
    nodes.sort_by(f64::total_cmp);
    nodes.dedup();
    nodes
}

/// The peak of MR on `(0, theta_ov)`: the largest sampled value, refined by
/// bisection on the sign change of dMR/dtheta around it.
fn peak(model: &Model, grid: &[f64]) -> (f64, f64) {
    let (mut best, mut at) = (f64::NEG_INFINITY, 0usize);
    for (i, &th) in grid.iter().enumerate() {
        let (mr, _) = model.restoring_moment(th);
        if mr > best {
            best = mr;
            at = i;
        }
    }
    if at == 0 || at + 1 == grid.len() {
        return (grid[at], best);
    }
    let (mut lo, mut hi) = (grid[at - 1], grid[at + 1]);
    if model.restoring_moment(lo).1 < 0.0 || model.restoring_moment(hi).1 > 0.0 {
        return (grid[at], best);
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if model.restoring_moment(mid).1 > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let th = 0.5 * (lo + hi);
    (th, model.restoring_moment(th).0.max(best))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let out = args
        .get(1)
        .cloned()
        .unwrap_or_else(|| "out/dharahara".to_string());
    let number = |i: usize| -> Result<Option<f64>, Box<dyn std::error::Error>> {
        match args.get(i) {
            Some(s) => Ok(Some(s.parse::<f64>()?)),
            None => Ok(None),
        }
    };
    std::fs::create_dir_all(&out)?;
    let base = tower(number(2)?, number(3)?);

    let mut cases = vec![Case {
        id: "rigid".into(),
        group: "rigid",
        kn: f64::INFINITY,
        fm: f64::INFINITY,
        model: Params {
            interface: LawKind::Rigid,
            ..base
        }
        .build()?,
    }];
    for (group, prefix, unit, kns) in [
        ("foundation", "F", 1e6, FOUNDATION_MPA),
        ("interface", "I", 1e9, INTERFACE_GPA),
    ] {
        for kn in kns {
            for fm in FM_MPA {
                let fm = fm * 1e6;
                let model = Params {
                    interface: LawKind::ElastoPlastic,
                    kn: kn * unit,
                    fm,
                    ..base
                }
                .build()?;
                cases.push(Case {
                    id: format!("{prefix}{kn}_{}", fm_label(fm)),
                    group,
                    kn: kn * unit,
                    fm,
                    model,
                });
            }
        }
    }

    let rigid = cases[0].model;
    let body = rigid.body;
    let alpha = body.alpha;
    let shape = rigid.interface.shape();
    let (area, is) = (shape.area(), shape.second_moment());
    println!("Dharahara Tower (docs/model.md §4), lumped body on a hollow circle:");
    println!(
        "  Ro = {RO} m, Ri = {RI} m, A = {area:.4} m², Is = {is:.3} m⁴, W = {:.2} kN, m = {:.6e} kg",
        body.weight / 1e3,
        body.mass
    );
    println!(
        "  paper: R0 = {R0_PAPER} m, alpha = {ALPHA_PAPER} (pivot half-width R0 sin(alpha) = {:.3} m, not Ro = {RO} m)",
        R0_PAPER * ALPHA_PAPER.sin()
    );
    println!(
        "  here:  hG = {} = {:.4} m, R0 = {:.4} m, alpha = atan(Ro/hG) = {:.5}",
        if args.len() > 2 {
            "(given)"
        } else {
            "R0 cos(alpha)"
        },
        body.hg,
        body.r0,
        alpha
    );
    println!(
        "  Ic = {} = {:.6e} kg m², IO = {:.6e} kg m², Housner eta = {:.5}",
        if args.len() > 3 {
            "(given)"
        } else {
            "m ((2 hG)²/12 + (Ro² + Ri²)/4) (assumed: hollow cylinder of height 2 hG)"
        },
        body.ic,
        body.io,
        body.eta_housner()
    );

    // Rest stability (docs/model.md §2): kn Is > W hG.
    let kn_min = body.weight * body.hg / is;
    let soft = FOUNDATION_MPA[0] * 1e6;
    println!(
        "  stability of the rest position, kn Is > W hG: softest foundation kn = {:.0} MPa/m: kn Is = {:.4e} N m, W hG = {:.4e} N m, margin {:.1}x (holds for every case; the limit is kn = {:.3} MPa/m)",
        soft / 1e6,
        soft * is,
        body.weight * body.hg,
        soft * is / (body.weight * body.hg),
        kn_min / 1e6
    );
    match (Params {
        interface: LawKind::Elastic,
        kn: 0.9 * kn_min,
        ..base
    })
    .build()
    {
        Ok(_) => println!("  UNEXPECTED: kn = 0.9 x the limit was accepted"),
        Err(e) => println!("  with kn = 0.9 x the limit the model refuses the parameters: {e}"),
    }

    // The rotation grid: geometric below 1 % of alpha (the thresholds of the
    // stiff interfaces are 1e-7 rad), linear above, up to alpha.
    let mut grid: Vec<f64> = (0..=120)
        .map(|i| alpha * 1e-9 * (0.01_f64 / 1e-9).powf(i as f64 / 120.0))
        .collect();
    grid.extend((1..=990).map(|i| alpha * (0.01 + 0.99 * i as f64 / 990.0)));

    let mut cases_csv = String::from(
        "case,group,kn_Pa_per_m,fm_Pa,alpha,R0_m,thetaJo,thetaC,thetaOv,thetaOv_over_alpha,theta_at_peak,MR_peak_Nm,E_ov_J,thetaOv_ratio_to_rigid,MR_peak_ratio_to_rigid,E_ov_ratio_to_rigid,crushes_before_overturning,stability_margin_knIs_over_WhG\n",
    );
    let e_rigid_exact = body.weight * body.r0 * (1.0 - alpha.cos());
    let mut reference = (0.0, 0.0, 0.0);
    println!(
        "\n{:14} {:>11} {:>9} {:>11} {:>11} {:>9} {:>9} {:>9} {:>9} {:>8}",
        "case",
        "kn Pa/m",
        "fm MPa",
        "thetaJo",
        "thetaC",
        "thOv/alp",
        "MRpk/rig",
        "Eov/rig",
        "thOv/rig",
        "crushes"
    );
    for (k, c) in cases.iter().enumerate() {
        let m = &c.model;
        let (jo, tc, tov) = (m.interface.theta_jo(), m.interface.theta_c(), m.theta_ov);
        let (th_pk, mr_pk) = if m.interface.law() == rocking::Law::Rigid {
            (0.0, body.weight * body.r0 * alpha.sin())
        } else {
            let g: Vec<f64> = grid.iter().copied().filter(|&x| x < tov).collect();
            peak(m, &g)
        };
        let e_ov = integrate(|th| m.restoring_moment(th).0, &partition(tov, &[jo, tc]));
        if k == 0 {
            reference = (tov, mr_pk, e_ov);
            let err = (e_ov / e_rigid_exact - 1.0).abs();
            assert!(err < 1e-9, "rigid overturning energy off by {err:e}");
        }
        let crushes = tc < tov;
        let margin = if c.kn.is_finite() {
            c.kn * is / (body.weight * body.hg)
        } else {
            f64::INFINITY
        };
        writeln!(
            cases_csv,
            "{},{},{:e},{:e},{:.10},{:.10},{:.10e},{:.10e},{:.10e},{:.10},{:.10e},{:.10e},{:.10e},{:.6},{:.6},{:.6},{},{:.6}",
            c.id,
            c.group,
            c.kn,
            c.fm,
            alpha,
            body.r0,
            jo,
            tc,
            tov,
            tov / alpha,
            th_pk,
            mr_pk,
            e_ov,
            tov / reference.0,
            mr_pk / reference.1,
            e_ov / reference.2,
            crushes,
            margin
        )?;
        println!(
            "{:14} {:>11.3e} {:>9} {:>11.3e} {:>11.3e} {:>9.4} {:>9.4} {:>9.4} {:>9.4} {:>8}",
            c.id,
            c.kn,
            if c.fm.is_finite() {
                format!("{}", c.fm / 1e6)
            } else {
                "inf".into()
            },
            jo,
            tc,
            tov / alpha,
            mr_pk / reference.1,
            e_ov / reference.2,
            tov / reference.0,
            crushes
        );
    }

    let mut curves = String::new();
    writeln!(
        curves,
        "# Dharahara Tower moment-rotation curves (examples/dharahara_curves.rs): MR = W hW(theta) in N m"
    )?;
    writeln!(
        curves,
        "# hollow circle Ro = {RO} m, Ri = {RI} m, W = {} N, hG = {:.6} m, R0 = {:.6} m, alpha = {:.8} rad, Ic = {:.6e} kg m2 (assumed)",
        body.weight, body.hg, body.r0, alpha, body.ic
    )?;
    writeln!(
        curves,
        "# case ids: rigid; F<kn MPa/m>_<fm MPa|elastic> foundation; I<kn GPa/m>_<fm MPa|elastic> interface; see dharahara_mr_cases.csv"
    )?;
    write!(curves, "theta,theta_over_alpha")?;
    for c in &cases {
        write!(curves, ",{}", c.id)?;
    }
    curves.push('\n');
    for &th in &grid {
        write!(curves, "{th:.10e},{:.10e}", th / alpha)?;
        for c in &cases {
            write!(curves, ",{:.10e}", c.model.restoring_moment(th).0)?;
        }
        curves.push('\n');
    }
    let p1 = format!("{out}/dharahara_mr_curves.csv");
    let p2 = format!("{out}/dharahara_mr_cases.csv");
    std::fs::write(&p1, curves)?;
    std::fs::write(&p2, cases_csv)?;
    println!("\nwrote {p1} and {p2}");
    Ok(())
}
