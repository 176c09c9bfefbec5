//! `fmi2GetRealOutputDerivatives` through the C API against the run itself:
//!
//! - every Real output's orders 1 and 2 against 5-point central differences
//!   (error O(h^4)) of the outputs read with `fmi2GetReal` after tiny
//!   `fmi2DoStep`s, with the ground acceleration given as a line through
//!   `fmi2SetRealInputDerivatives` (the FMU extrapolates it, so `ag` and
//!   `dag/dt` are those of the steps); rigid, elastic and crushing laws,
//!   both formulations, moving and at rest, at samples with no impact or
//!   regime change in the stencil. The differenced `Fx`, `Fz` are written
//!   here from their definition (docs/model.md §5), `Fx = m (ag + hg theta''
//!   + s hg' omega²)`, `Fz = m (g + s hW theta'' + hW' omega²)`, from the
//!   FMU's `theta`, `omega`, `angularAcceleration` and the levers of the
//!   `rocking` crate, and `frictionDemand` as `|Fx| / Fz` of those (samples
//!   where `Fx` changes sign in the stencil are skipped: `|Fx|` has a kink
//!   there); for the rigid law the FMU's own `Fx`, `Fz` are that;
//! - a request the standard refuses (order 0 or 3, a parameter, an input,
//!   an unknown value reference) is `fmi2Error` with a logger message
//!   naming the variable and the order; the instance is then in the error
//!   state (FMI 2.0, section 2.1.3): `fmi2SetFMUstate` to a state saved
//!   before restores it, and the run goes on bit for bit as one that never
//!   made the request.

mod host;

use fmu_rocking::fmi2GetRealOutputDerivatives;
use host::*;
use rocking::model::LawKind;
use rocking::{Formulation, Law, Model, Params};

/// The Real outputs, in the order of the tables.
const OUTPUTS: [&str; N] = [
    "theta",
    "omega",
    "thetaOverAlpha",
    "angularAcceleration",
    "af",
    "contactLength",
    "MR",
    "Fx",
    "Fz",
    "frictionDemand",
];

/// How many Real outputs [`OUTPUTS`] has.
const N: usize = 10;

/// `fmi2GetRealOutputDerivatives` of several variables at one order each.
fn derivatives(h: &Host, names: &[&str], orders: &[i32]) -> (fmi2Status, Vec<f64>) {
    let vrs: Vec<u32> = names.iter().map(|n| vr_of(n)).collect();
    let mut out = vec![f64::NAN; vrs.len()];
    // SAFETY: n value references, n orders and room for n values.
    let s = unsafe {
        fmi2GetRealOutputDerivatives(
            h.c,
            vrs.as_ptr(),
            vrs.len(),
            orders.as_ptr(),
            out.as_mut_ptr(),
        )
    };
    (s, out)
}

/// `Fx`, `Fz` of docs/model.md §5 from the FMU's state and `theta''`.
fn support_forces(
    m: &Model,
    theta: f64,
    omega: f64,
    ag: f64,
    theta_dd: f64,
    at_rest: bool,
) -> (f64, f64) {
    let b = &m.body;
    if at_rest {
        return (b.mass * ag, b.weight);
    }
    let rigid = m.interface.law() == Law::Rigid;
    let s = if theta != 0.0 {
        theta.signum()
    } else if omega != 0.0 {
        omega.signum()
    } else {
        -ag.signum()
    };
    let phi = if rigid { s * theta } else { theta.abs() };
    let c = m.interface.contact(if rigid {
        phi.max(f64::MIN_POSITIVE)
    } else {
        phi
    });
    let l = m.levers(phi, &c);
    let (sp, cp) = phi.sin_cos();
    let dhg = l.hw - c.daf * sp;
    let dhw = -l.hg - c.daf * cp;
    let w2 = omega * omega;
    (
        b.mass * (ag + l.hg * theta_dd + s * dhg * w2),
        b.mass * (b.g + s * l.hw * theta_dd + dhw * w2),
    )
}

struct Case {
    name: &'static str,
    params: Params,
    ag0: f64,
    dag: f64,
    /// Step of the differences (= the communication step), s.
    h: f64,
    /// Run length, s.
    t_end: f64,
}

/// An initialized instance with the parameters of `p` (those the cases change).
fn instance(p: &Params, ag0: f64, dag: f64) -> Host {
    let h = Host::new();
    let law = match p.interface {
        LawKind::Rigid => enums::RIGID,
        LawKind::Elastic => enums::ELASTIC,
        LawKind::ElastoPlastic => enums::ELASTO_PLASTIC,
    };
    let formulation = match p.formulation {
        Formulation::Costa => enums::COSTA,
        Formulation::ShiftingPivot => enums::SHIFTING_PIVOT,
    };
    assert_eq!(h.setup(Some(1e-12), 0.0, None), fmi2OK);
    assert_eq!(h.set_integer("interface", law), fmi2OK);
    assert_eq!(h.set_integer("formulation", formulation), fmi2OK);
    for (n, x) in [("kn", p.kn), ("fm", p.fm), ("theta", p.theta0), ("ag", ag0)] {
        assert_eq!(h.set_real(n, x), fmi2OK);
    }
    assert_eq!(h.set_input_derivative("ag", 1, dag), fmi2OK);
    assert_eq!(h.enter_init(), fmi2OK);
    assert_eq!(h.exit_init(), fmi2OK, "{:?}", h.messages());
    h
}

/// One sample: the outputs (Fx, Fz from their definition), regime,
/// impacts, the FMU's own Fx, Fz.
struct Sample {
    y: [f64; N],
    regime: i32,
    impacts: i32,
    theta: f64,
    own_forces: (f64, f64),
}

fn sample(h: &Host, m: &Model) -> Sample {
    let v = h.reals(&OUTPUTS);
    let ag = h.real("ag");
    let at_rest = v[0] == 0.0 && v[1] == 0.0;
    let (fx, fz) = support_forces(m, v[0], v[1], ag, v[3], at_rest);
    let mut y = [0.0; N];
    y.copy_from_slice(&v);
    y[7] = fx;
    y[8] = fz;
    // |Fx| / Fz from the forces written here (docs/model.md §5)
    y[9] = fx.abs() / fz;
    Sample {
        y,
        regime: h.integer("regime"),
        impacts: h.integer("impacts"),
        theta: v[0],
        own_forces: (v[7], v[8]),
    }
}

/// Worst relative errors `[order 1, order 2]` per output (relative to the
/// largest magnitude of that derivative along the run, floor 1e-3 of the
/// output's size per s^order), and the number of samples.
fn run(c: &Case) -> ([[f64; 2]; N], usize) {
    let model = c.params.build().unwrap();
    let fmu = instance(&c.params, c.ag0, c.dag);
    let rigid = model.interface.law() == Law::Rigid;
    let mut t = 0.0;
    let mut samples = Vec::new();
    let centres = 30;
    let mut found = Vec::new();
    for k in 1..=centres {
        let tc = c.t_end * k as f64 / (centres + 1) as f64;
        // to tc - 2h in one step, then four steps of h
        let first = tc - 2.0 * c.h - t;
        assert_eq!(fmu.do_step(t, first), fmi2OK);
        t += first;
        let mut pts = vec![sample(&fmu, &model)];
        let mut d = None;
        for j in 0..4 {
            assert_eq!(fmu.do_step(t, c.h), fmi2OK, "{:?}", fmu.messages());
            t += c.h;
            pts.push(sample(&fmu, &model));
            if j == 1 {
                let (s1, d1) = derivatives(&fmu, &OUTPUTS, &[1; N]);
                let (s2, d2) = derivatives(&fmu, &OUTPUTS, &[2; N]);
                assert_eq!(
                    (s1, s2),
                    (fmi2OK, fmi2OK),
                    "{}: {:?}",
                    c.name,
                    fmu.messages()
                );
                d = Some((d1, d2));
            }
        }
        let (d1, d2) = d.unwrap();
        if rigid {
            for p in &pts {
                let (fx, fz) = p.own_forces;
                assert!((fx - p.y[7]).abs() <= 1e-9 * p.y[7].abs().max(fz.abs()));
                assert!((fz - p.y[8]).abs() <= 1e-9 * fz.abs());
            }
        }
        let p0 = &pts[2];
        if pts.iter().any(|p| {
            p.regime != p0.regime
                || p.impacts != p0.impacts
                || p.theta.signum() != p0.theta.signum()
                || p.y[7].signum() != p0.y[7].signum()
        }) {
            continue;
        }
        samples.push(pts);
        found.push((d1, d2));
    }
    let mut scale = [[0.0f64; 2]; N];
    let mut fds = Vec::new();
    for (pts, (d1, d2)) in samples.iter().zip(&found) {
        let mut fd = [[0.0; 2]; N];
        for i in 0..N {
            let y: Vec<f64> = pts.iter().map(|p| p.y[i]).collect();
            fd[i][0] = (-y[4] + 8.0 * y[3] - 8.0 * y[1] + y[0]) / (12.0 * c.h);
            fd[i][1] =
                (-y[4] + 16.0 * y[3] - 30.0 * y[2] + 16.0 * y[1] - y[0]) / (12.0 * c.h * c.h);
            scale[i][0] = scale[i][0]
                .max(d1[i].abs())
                .max(fd[i][0].abs())
                .max(1e-3 * y[2].abs());
            scale[i][1] = scale[i][1]
                .max(d2[i].abs())
                .max(fd[i][1].abs())
                .max(1e-3 * y[2].abs());
        }
        fds.push(fd);
    }
    let mut err = [[0.0f64; 2]; N];
    for (fd, (d1, d2)) in fds.iter().zip(&found) {
        for i in 0..N {
            err[i][0] = err[i][0].max((d1[i] - fd[i][0]).abs() / scale[i][0]);
            err[i][1] = err[i][1].max((d2[i] - fd[i][1]).abs() / scale[i][1]);
        }
    }
    (err, samples.len())
}

fn block(law: LawKind, formulation: Formulation, theta0: f64) -> Params {
    Params {
        interface: law,
        formulation,
        theta0,
        ..Params::default()
    }
}

#[test]
fn output_derivatives_match_differences_through_the_c_api() {
    let mut cases = Vec::new();
    for f in [Formulation::ShiftingPivot, Formulation::Costa] {
        cases.push(Case {
            name: "rigid, moving",
            params: block(LawKind::Rigid, f, 0.1),
            ag0: 0.3,
            dag: -0.4,
            h: 1e-3,
            t_end: 2.0,
        });
        cases.push(Case {
            name: "elastic, moving",
            params: block(LawKind::Elastic, f, 0.08),
            ag0: 0.3,
            dag: -0.4,
            h: 3e-5,
            t_end: 2.0,
        });
        cases.push(Case {
            name: "crushing, moving",
            params: Params {
                fm: 1e6,
                ..block(LawKind::ElastoPlastic, f, 0.08)
            },
            ag0: 0.3,
            dag: -0.4,
            h: 3e-5,
            t_end: 2.0,
        });
    }
    cases.push(Case {
        name: "rigid, at rest",
        params: block(LawKind::Rigid, Formulation::ShiftingPivot, 0.0),
        ag0: 0.5,
        dag: 0.7,
        h: 1e-3,
        t_end: 1.0,
    });
    let mut failures = Vec::new();
    for c in &cases {
        let (err, n) = run(c);
        println!(
            "{} ({:?}), h = {:e} s: {n} samples",
            c.name, c.params.formulation, c.h
        );
        for (i, e) in err.iter().enumerate() {
            println!("  {:<20} d1 {:8.1e}  d2 {:8.1e}", OUTPUTS[i], e[0], e[1]);
            // measured worst: see docs/dynamics.md, "Output derivatives"
            if !(e[0] < 1e-8 && e[1] < 2e-6) {
                failures.push(format!("{}: {} errors {e:?}", c.name, OUTPUTS[i]));
            }
        }
        if n < 15 {
            failures.push(format!("{}: only {n} samples", c.name));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn refused_requests_name_the_variable_and_a_saved_state_restores_the_instance() {
    let p = block(LawKind::ElastoPlastic, Formulation::ShiftingPivot, 0.05);
    let reference = instance(&p, 0.2, 0.0);
    let h = instance(&p, 0.2, 0.0);
    for fmu in [&reference, &h] {
        assert_eq!(fmu.do_step(0.0, 0.01), fmi2OK);
    }
    let mut saved = h.get_state();
    let bad: [(&str, i32, &str); 5] = [
        ("theta", 3, "order 3 outside 1..=2"),
        ("Fx", 0, "order 0 outside 1..=2"),
        ("B", 1, "B is no output"),
        ("ag", 1, "ag is no output"),
        ("kn", 2, "kn is no output"),
    ];
    for (name, order, why) in bad {
        h.clear_log();
        let (s, _) = derivatives(&h, &[name], &[order]);
        assert_eq!(s, fmi2Error, "{name} order {order}");
        let errors = h.errors();
        assert!(
            errors
                .iter()
                .any(|m| m.contains("fmi2GetRealOutputDerivatives") && m.contains(why)),
            "{name} order {order}: {errors:?}"
        );
        // FMI 2.0: after fmi2Error only a restart (saved state, reset) goes on
        assert_eq!(h.do_step(0.01, 0.01), fmi2Error);
        assert_eq!(h.set_state(saved), fmi2OK);
    }
    // an unknown value reference
    let mut out = [f64::NAN];
    let r = 9999u32;
    // SAFETY: one value reference, order and value.
    let s = unsafe { fmi2GetRealOutputDerivatives(h.c, &r, 1, &1, out.as_mut_ptr()) };
    assert_eq!(s, fmi2Error);
    assert!(
        h.errors().iter().any(|m| m.contains("9999")),
        "{:?}",
        h.errors()
    );
    assert_eq!(h.set_state(saved), fmi2OK);
    // the restored instance goes on as one that never made a bad request
    let mut t = 0.01;
    for _ in 0..50 {
        assert_eq!(h.do_step(t, 0.01), fmi2OK);
        assert_eq!(reference.do_step(t, 0.01), fmi2OK);
        t += 0.01;
    }
    let names = ["theta", "omega", "af", "Fx"];
    assert_eq!(h.reals(&names), reference.reals(&names));
    let (s1, d1) = derivatives(&h, &OUTPUTS, &[2; N]);
    let (s2, d2) = derivatives(&reference, &OUTPUTS, &[2; N]);
    assert_eq!((s1, s2), (fmi2OK, fmi2OK));
    assert_eq!(d1, d2);
    assert_eq!(h.free_state(&mut saved), fmi2OK);
}
