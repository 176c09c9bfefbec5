//! Moment-rotation curves of the four base shapes with the same size R0 and
//! slenderness alpha (the paper's Fig. 13/14a setting): D = 2 m, hG = 6 m,
//! masonry prisms of H = 12 m and 1800 kg/m³ on an interface of
//! kn = 340 MPa/m, with and without crushing at fm = 0.5 MPa, and the rigid
//! interface for reference.
//!
//! `cargo run --release --example moment_rotation [OUT_DIR]` writes
//! `OUT_DIR/moment_rotation.csv` (default `out/`); `examples/plot_moment_rotation.py`
//! turns it into a PNG.

use std::fmt::Write as _;

use rocking::model::{LawKind, ShapeKind};
use rocking::Params;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args().nth(1).unwrap_or_else(|| "out".to_string());
    std::fs::create_dir_all(&out)?;
    let base = Params {
        b: 2.0,
        l: 2.0,
        t: 0.3,
        ro: 1.0,
        ri: 0.7,
        h: 12.0,
        rho: 1800.0,
        kn: 340e6,
        ..Params::default()
    };
    let shapes = [
        ("solidRectangle", ShapeKind::SolidRectangle),
        ("hollowRectangle", ShapeKind::HollowRectangle),
        ("solidCircle", ShapeKind::SolidCircle),
        ("hollowCircle", ShapeKind::HollowCircle),
    ];
    let laws = [
        ("rigid", LawKind::Rigid, f64::INFINITY),
        ("elastic", LawKind::Elastic, f64::INFINITY),
        ("fm0.5MPa", LawKind::ElastoPlastic, 0.5e6),
    ];
    let mut models = Vec::new();
    let mut header = String::from("theta_over_alpha");
    for (sname, shape) in shapes {
        for (lname, law, fm) in laws {
            let m = Params {
                shape,
                interface: law,
                fm,
                ..base
            }
            .build()?;
            write!(header, ",{sname}_{lname}")?;
            println!(
                "{sname:16} {lname:9} W = {:8.1} kN  alpha = {:.4}  R0 = {:.3} m  thetaJo = {:.3e}  thetaC = {:.3e}  thetaOv/alpha = {:.4}",
                m.body.weight / 1e3,
                m.body.alpha,
                m.body.r0,
                m.interface.theta_jo(),
                m.interface.theta_c(),
                m.theta_ov / m.body.alpha
            );
            models.push(m);
        }
    }
    let alpha = models[0].body.alpha;
    let mut csv = header + "\n";
    let n = 400;
    for i in 0..=n {
        let r = i as f64 / n as f64;
        write!(csv, "{r:.5}")?;
        for m in &models {
            // MR normalised by the rigid restoring moment at rest, W R0 sin(alpha)
            let (mr, _) = m.restoring_moment(r * alpha);
            write!(
                csv,
                ",{:.8e}",
                mr / (m.body.weight * m.body.r0 * alpha.sin())
            )?;
        }
        csv.push('\n');
    }
    let path = format!("{out}/moment_rotation.csv");
    std::fs::write(&path, csv)?;
    println!("wrote {path} (MR / (W R0 sin alpha) against theta/alpha)");
    Ok(())
}
