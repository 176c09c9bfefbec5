//! The macroblock as a rocking body: a pure-rocking mechanism (no dissipation) must have the
//! multiplier tan(alpha_eq) = b / hG of its body; the paper's pi/2 optimum against the
//! independent reference implementation; the FMU parameter set.

use std::f64::consts::FRAC_PI_2;

use corner::{
    body_direction, corner_multiplier, rocking_body, BodyKind, CornerModel, Direction, Geometry,
    Options, ParamValue, Specimen,
};

fn pure_rocking() -> (CornerModel, Geometry) {
    // m = 0 with every crack at the running-bond step (8 half blocks over 8 courses): the
    // friction weight 1 - alpha_c/alpha_b vanishes, so D = Lambda = 0.
    let model = CornerModel::new(Specimen::paper(), 0, 0.3, Options::default()).unwrap();
    let v = model.specimen.v();
    let x = Geometry {
        x1: v,
        x2: 8.0 * v,
        x3: v,
        y1: 8.0 * v,
        y2: v,
        y3: v,
        z1: model.specimen.h,
    };
    (model, x)
}

#[test]
fn pure_rocking_multiplier_is_tan_alpha_of_its_body() {
    let (model, x) = pure_rocking();
    for dir in [Direction::X, Direction::Y] {
        let w = model.direction_terms(&x, dir);
        assert!(w.dissipation.abs() < 1e-12 * w.stabilising, "{w:?}");
        let body = rocking_body(&model, &x, dir).unwrap();
        let tan_alpha = body.b / body.h_g;
        assert!((w.lambda - tan_alpha).abs() <= 4.0 * f64::EPSILON * tan_alpha);
        assert!((body.lambda - body.lambda_rock).abs() <= 4.0 * f64::EPSILON * tan_alpha);
        assert!((body.theta_u - tan_alpha.atan()).abs() <= 4.0 * f64::EPSILON);
        // The reference implementation: 0.284844.
        assert!((w.lambda - 0.284844).abs() < 1e-6, "{}", w.lambda);
        // The same value through the orientation combination (any alpha: both directions agree).
        let e = model.evaluate(&x, 0.3).unwrap();
        assert!((e.lambda_alpha - tan_alpha).abs() <= 4.0 * f64::EPSILON * tan_alpha);
    }
}

#[test]
fn pi_2_optimum_body_matches_the_reference() {
    let model = CornerModel::paper(1, 0.3).unwrap();
    let r = corner_multiplier(&model, FRAC_PI_2).unwrap();
    assert_eq!(body_direction(FRAC_PI_2), Direction::Y);
    let b = rocking_body(&model, &r.grid.geometry, Direction::Y).unwrap();
    let close = |a: f64, e: f64, tol: f64| assert!((a - e).abs() <= tol, "{a} vs {e}");
    close(b.weight, 511.1, 0.05);
    close(b.h_g, 0.2812, 5e-5);
    close(b.b, 0.0427, 5e-5);
    close(b.i_o, 5.680, 5e-4);
    close(b.i_c, 1.465, 5e-4);
    close(b.lambda, 0.2230, 5e-5);
    close(b.lambda_rock, 0.1519, 5e-5);
    close(b.b_eq, 0.0627, 5e-5);
    // Ic from its definition, and IO = Ic + m R0^2 as the FMU computes it.
    let m = b.weight / model.specimen.g;
    close(b.i_o, b.i_c + m * (b.b * b.b + b.h_g * b.h_g), 1e-12);
    // The body's uplift threshold lambda_rock g is below the limit-analysis lambda g:
    // dissipation carries about a third of the static capacity.
    close(1.0 - b.lambda_rock / b.lambda, 0.32, 0.01);
}

#[test]
fn fmu_parameters_of_both_bodies() {
    let model = CornerModel::paper(1, 0.3).unwrap();
    let r = corner_multiplier(&model, FRAC_PI_2).unwrap();
    let b = rocking_body(&model, &r.grid.geometry, Direction::Y).unwrap();
    let get = |kind, name: &str| {
        b.fmu_parameters(kind, 9.81)
            .into_iter()
            .find(|(n, _)| *n == name)
            .map(|(_, v)| v)
            .unwrap()
    };
    let real = |v: ParamValue| match v {
        ParamValue::Real(x) => x,
        ParamValue::Enum(e) => panic!("{e}"),
    };
    // The FMU's rigid-interface threshold is tan(alpha) = (B/2) / hG.
    let geo = real(get(BodyKind::Geometric, "B")) / 2.0 / real(get(BodyKind::Geometric, "hG"));
    let thr = real(get(BodyKind::Threshold, "B")) / 2.0 / real(get(BodyKind::Threshold, "hG"));
    assert!((geo - b.lambda_rock).abs() < 1e-15);
    assert!((thr - b.lambda).abs() < 1e-15);
    assert_eq!(
        get(BodyKind::Geometric, "massModel"),
        ParamValue::Enum("lumped")
    );
    assert_eq!(
        get(BodyKind::Geometric, "interface"),
        ParamValue::Enum("rigid")
    );
    // L is the base of the out-of-plane wall's part along the hinge: X3 for direction Y.
    assert_eq!(real(get(BodyKind::Geometric, "L")), r.grid.geometry.x3);
}
