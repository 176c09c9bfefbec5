//! The round body in space on the flexible and crushing bed (docs/model.md
//! §11.2-§11.4) against independent references: the planar model in a
//! plane, the rigid bed in the stiff limit, rotated inputs, and the energy.

use rocking::dynamics::{GroundInput, Simulator, VerticalInput};
use rocking::interface::Interface;
use rocking::model::{Formulation, LawKind, Restitution};
use rocking::spatial::{PlanInput, Spatial, SpatialState};
use rocking::Params;

mod support;
use support::drum::{drum, on_bed, pulse_train, vertical, DT};
use support::rotated::{assert_rotates, rot, run_rotated};

const RTOL: f64 = 1e-13;

/// The planar run and the spatial run along the azimuth `psi`, sampled
/// every `DT`: the worst `|theta_planar - theta_spatial|`, the peak
/// `|theta|`, the worst off-plane tilt, the zero crossings of each.
fn planar_and_spatial(
    p: &Params,
    with_av: bool,
    theta0: f64,
    psi: f64,
    t_end: f64,
) -> (f64, f64, f64, u64, u64) {
    let mut planar = Simulator::new(p.build().unwrap(), RTOL);
    // the spatial loop has no stiff mode: compare the explicit pair's runs
    planar.stiff_mode = false;
    let spatial = Spatial::new(p, None, RTOL).unwrap();
    let mut a = planar.initial_state(theta0, 0.0);
    let mut b = SpatialState::tilted(&spatial, theta0, psi, [0.0; 3]);
    let av = |t: f64| if with_av { vertical(t) } else { 0.0 };
    let (mut worst, mut peak, mut off) = (0.0f64, 0.0f64, 0.0f64);
    let dir = [psi.cos(), psi.sin()];
    let n = (t_end / DT).round() as usize;
    for k in 0..n {
        let (t0, t1) = (k as f64 * DT, (k + 1) as f64 * DT);
        let dag = (pulse_train(t1) - pulse_train(t0)) / DT;
        let v = VerticalInput {
            av: av(t0),
            dav: (av(t1) - av(t0)) / DT,
        };
        let ga = GroundInput {
            ag: pulse_train(t0),
            dag,
        };
        planar.advance_vertical(&mut a, t1, ga, v);
        let h = PlanInput {
            a: rot([pulse_train(t0), 0.0], psi),
            da: rot([dag, 0.0], psi),
        };
        spatial.advance(&mut b, t1, h, v);
        let along = (b.e[0] * dir[0] + b.e[1] * dir[1]).asin();
        let across = b.e[1] * dir[0] - b.e[0] * dir[1];
        worst = worst.max((a.theta - along).abs());
        peak = peak.max(a.theta.abs());
        off = off.max(across.abs());
        assert_eq!(a.overturned, b.overturned, "t = {t1}");
    }
    (worst, peak, off, a.zero_crossings, b.impacts)
}

#[test]
fn in_a_plane_the_body_on_a_flexible_bed_is_the_planar_model() {
    for crushing in [false, true] {
        for formulation in [Formulation::ShiftingPivot, Formulation::Costa] {
            for with_av in [false, true] {
                for (theta0, psi) in [(0.0, 0.0), (0.05, 0.7)] {
                    let p = on_bed(crushing, formulation);
                    let (worst, peak, off, za, zb) =
                        planar_and_spatial(&p, with_av, theta0, psi, 4.0);
                    eprintln!(
                        "crushing {crushing} {formulation:?} av {with_av} theta0 {theta0} psi {psi}: \
                         worst {worst:.2e} rad, peak {peak:.3}, off-plane {off:.1e}, crossings {za} {zb}"
                    );
                    assert!(peak > 0.05, "the run must rock: peak {peak}");
                    let theta_c = p.build().unwrap().interface.theta_c();
                    assert!(!crushing || peak > 10.0 * theta_c, "crushes: {theta_c}");
                    assert!(worst <= 1e-10, "{worst:e} rad");
                    assert!(off <= 1e-14, "off its plane by {off:e}");
                    assert_eq!(za, zb, "zero crossings");
                }
            }
        }
    }
}

fn two_components(t: f64) -> [f64; 2] {
    [pulse_train(t), 0.7 * pulse_train(1.37 * t + 0.2)]
}

fn no_av(_: f64) -> f64 {
    0.0
}

/// The largest gap in tilt and angular velocity between two runs sampled alike.
fn gap(a: &[SpatialState], b: &[SpatialState]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(a, b)| {
            let de = (a.e[0] - b.e[0]).abs() + (a.e[1] - b.e[1]).abs();
            let dw = (0..3).map(|i| (a.omega[i] - b.omega[i]).abs()).sum::<f64>();
            de.max(dw)
        })
        .fold(0.0, f64::max)
}

#[test]
fn as_the_bed_stiffens_the_motion_tends_to_the_rigid_beds() {
    let rigid = Spatial::new(&drum(Restitution::Housner, false), None, RTOL).unwrap();
    // a wobble started off a plane, under both components, clear of upright
    let start = |s: &Spatial| SpatialState::tilted(s, 0.15, 0.4, [0.1, -0.2, 2.0]);
    let weak = |t: f64| {
        let a = two_components(t);
        [0.3 * a[0], 0.3 * a[1]]
    };
    let reference = run_rotated(&rigid, start(&rigid), (&weak, &no_av), 0.0, 1.5);
    let low = reference.iter().map(|s| s.theta()).fold(1.0, f64::min);
    let mut gaps = vec![];
    for kn in [1e9, 1e10, 1e11, 1e12, 1e13] {
        let p = Params {
            kn,
            ..on_bed(false, Formulation::ShiftingPivot)
        };
        let s = Spatial::new(&p, None, RTOL).unwrap();
        let run = run_rotated(&s, start(&s), (&weak, &no_av), 0.0, 1.5);
        let g = gap(&run, &reference);
        let theta_jo = s.model.interface.theta_jo();
        eprintln!("kn {kn:.0e} (thetaJo {theta_jo:.1e}): gap to the rigid bed {g:.3e}");
        assert_eq!(run.last().unwrap().impacts, 0);
        gaps.push(g);
    }
    let rates: Vec<f64> = gaps.windows(2).map(|w| (w[0] / w[1]).log10()).collect();
    eprintln!("lowest tilt {low:.3} rad; orders per decade of kn: {rates:.3?}");
    assert!(low > 0.02, "the wobble stays clear of upright: {low}");
    // a circle's contact near its toe: the width grows as sqrt(x), so the
    // contact length and af shrink as kn^(-2/5)
    for r in &rates {
        assert!((0.3..0.5).contains(r), "converges at {r} per decade");
    }
}

#[test]
fn a_rotated_input_rotates_the_response_on_a_crushing_bed() {
    let p = on_bed(true, Formulation::ShiftingPivot);
    let spatial = Spatial::new(&p, None, RTOL).unwrap();
    for (name, av) in [
        ("horizontal", &no_av as &dyn Fn(f64) -> f64),
        ("with av", &vertical),
    ] {
        let base = run_rotated(
            &spatial,
            SpatialState::at_rest(),
            (&two_components, av),
            0.0,
            4.0,
        );
        for beta in [0.3, 2.1, -1.0] {
            let turned = run_rotated(
                &spatial,
                SpatialState::at_rest(),
                (&two_components, av),
                beta,
                4.0,
            );
            assert_rotates(name, beta, &base, &turned);
        }
    }
}

/// `omega^T J omega / 2 + W ∫ hW`, J, written from the planar law
/// ([`Interface::contact`]) apart from the code under test: `J` about the
/// resultant at `(R - af) e1` from the base's centre, the potential by
/// Simpson's rule on `[0, thetaJo]`, `[thetaJo, thetaC]` and
/// `[thetaC, theta]`, where `af` is smooth.
fn energy(s: &Spatial, it: &Interface, st: &SpatialState) -> f64 {
    let b = &s.model.body;
    let (ex, ey) = (st.e[0], st.e[1]);
    let sin = ex.hypot(ey);
    let (theta, cos) = (sin.asin(), (1.0 - sin * sin).sqrt());
    let rho = |phi: f64| s.radius - it.contact(phi).af;
    let e3 = [ex, ey, cos];
    let e1 = [cos * ex / sin, cos * ey / sin, -sin];
    let r: Vec<f64> = (0..3).map(|i| b.hg * e3[i] - rho(theta) * e1[i]).collect();
    let w = st.omega;
    let rr: f64 = r.iter().map(|x| x * x).sum();
    let mut kinetic = 0.0;
    for i in 0..3 {
        for j in 0..3 {
            let unit = if i == j { 1.0 } else { 0.0 };
            let ig = b.ic * unit + (s.c_axial - b.ic) * e3[i] * e3[j];
            kinetic += 0.5 * w[i] * w[j] * (ig + b.mass * (rr * unit - r[i] * r[j]));
        }
    }
    let hw = |phi: f64| rho(phi) * phi.cos() - b.hg * phi.sin();
    // phi = a + (c - a) u²: af past thetaJo grows like a power of
    // (phi - thetaJo) (the circle's width is a square root at the heel)
    let simpson = |a: f64, c: f64| {
        let n = 1000;
        let h = 1.0 / n as f64;
        (0..=n)
            .map(|k| {
                let wk = if k == 0 || k == n {
                    1.0
                } else if k % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                let u = k as f64 * h;
                wk * hw(a + (c - a) * u * u) * 2.0 * (c - a) * u
            })
            .sum::<f64>()
            * h
            / 3.0
    };
    let jo = it.theta_jo().min(theta);
    let c = it.theta_c().clamp(jo, theta);
    kinetic + b.weight * (simpson(0.0, jo) + simpson(jo, c) + simpson(c, theta))
}

#[test]
fn energy_is_conserved_on_an_elastic_bed_without_ground_motion() {
    let p = on_bed(false, Formulation::ShiftingPivot);
    let spatial = Spatial::new(&p, None, RTOL).unwrap();
    let it = spatial.model.interface;
    let mut st = SpatialState::tilted(&spatial, 0.15, 0.4, [0.1, -0.2, 2.0]);
    let e0 = energy(&spatial, &it, &st);
    let (mut worst, mut low, mut high) = (0.0f64, 1.0f64, 0.0f64);
    for k in 1..=100 {
        let t = 0.03 * k as f64;
        spatial.advance(&mut st, t, PlanInput::default(), VerticalInput::default());
        worst = worst.max((energy(&spatial, &it, &st) - e0).abs() / e0);
        (low, high) = (low.min(st.theta()), high.max(st.theta()));
    }
    let own = (spatial.energy(&st) - e0).abs() / e0;
    let rolled = st.xg[0].hypot(st.xg[1]);
    eprintln!(
        "free wobble on the elastic bed: |dE|/E {worst:.1e} (Spatial::energy {own:.1e}), \
         tilt {low:.3}..{high:.3} rad, G moved {rolled:.2} m, impacts {}",
        st.impacts
    );
    assert!(
        !st.overturned && low > 0.02 && high > 0.1 && rolled > 0.5,
        "a wobble that rolls"
    );
    assert_eq!(st.impacts, 0, "the wobble stays clear of upright");
    assert!(worst <= 1e-9, "{worst:e}");
    assert!(own <= 1e-9, "Spatial::energy: {own:e}");
}

#[test]
fn the_holonomic_crushing_bed_dissipates_nothing_in_a_free_wobble() {
    // the stress is a function of the present closure (docs/model.md
    // §11.1): the toe that crushed gives its work back as the tilt turns
    // away, so a wobble past thetaC keeps its energy, the crushed zone
    // running round the rim with the lean
    let p = on_bed(true, Formulation::ShiftingPivot);
    let spatial = Spatial::new(&p, None, RTOL).unwrap();
    let it = spatial.model.interface;
    let mut st = SpatialState::tilted(&spatial, 0.15, 0.4, [0.1, -0.2, 2.0]);
    let e0 = energy(&spatial, &it, &st);
    let (mut worst, mut low, mut crushed) = (0.0f64, 1.0f64, 0);
    let mut azimuths = vec![];
    for k in 1..=100 {
        let t = 0.03 * k as f64;
        spatial.advance(&mut st, t, PlanInput::default(), VerticalInput::default());
        worst = worst.max((energy(&spatial, &it, &st) - e0).abs() / e0);
        low = low.min(st.theta());
        if st.theta() > it.theta_c() {
            crushed += 1;
            azimuths.push(st.e[1].atan2(st.e[0]));
        }
    }
    let turned = azimuths
        .windows(2)
        .map(|w| {
            (w[1] - w[0] + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                - std::f64::consts::PI
        })
        .map(f64::abs)
        .sum::<f64>();
    eprintln!(
        "free wobble on the crushing bed: |dE|/E {worst:.1e}, thetaC {:.4} rad, \
         {crushed} of 100 samples past it, the lean turning {turned:.1} rad among them, \
         lowest tilt {low:.3} rad, impacts {}",
        it.theta_c(),
        st.impacts
    );
    assert!(!st.overturned && st.impacts == 0 && low > it.theta_jo());
    assert!(
        crushed >= 20 && turned > std::f64::consts::TAU,
        "the crushed toe runs round the rim"
    );
    assert!(worst <= 1e-9, "{worst:e}");
}

#[test]
fn a_motion_near_a_plane_takes_the_planar_loss_at_each_pass_near_upright() {
    // free rocking along x with a transverse tilt rate eps: the tilt passes
    // upright at a distance of order eps, where it turns a right angle from
    // its side with the heel closed and takes the restitution rule, and the
    // motion tends to the planar one as eps -> 0 (the rule does not need an
    // exact crossing)
    let p = on_bed(false, Formulation::ShiftingPivot);
    let mut planar = Simulator::new(p.build().unwrap(), RTOL);
    planar.stiff_mode = false;
    let spatial = Spatial::new(&p, None, RTOL).unwrap();
    let mut gaps = vec![];
    for eps in [1e-4, 1e-5, 1e-6] {
        let mut a = planar.initial_state(0.06, 0.0);
        let mut b = SpatialState::tilted(&spatial, 0.06, 0.0, [eps, 0.0, 0.0]);
        let mut worst = 0.0f64;
        for k in 1..=300 {
            let t = k as f64 * DT;
            planar.advance(&mut a, t, GroundInput::default());
            spatial.advance(&mut b, t, PlanInput::default(), VerticalInput::default());
            let along = b.e[0].signum() * b.theta();
            worst = worst.max((a.theta - along).abs());
        }
        eprintln!(
            "eps {eps:.0e}: gap to the planar run {worst:.2e} rad, crossings {} and {}, off-plane {:.1e}",
            a.zero_crossings, b.impacts, b.e[1]
        );
        assert_eq!(a.zero_crossings, b.impacts);
        assert!(a.zero_crossings >= 4);
        gaps.push(worst);
    }
    for w in gaps.windows(2) {
        // the gap is of second order in eps (measured: x0.01 per decade)
        assert!(w[1] < 0.02 * w[0], "{gaps:?}");
    }
}

#[test]
fn as_a_crushing_bed_stiffens_the_body_rolls_on_the_crushed_rim() {
    // kn -> infinity at a fixed fm: beyond thetaC -> 0 the resultant sits
    // at af_lim from the toe (the centroid of the crushed segment carrying
    // N at fm), so the limit is the rigid bed's rolling on a rim of radius
    // R - af_lim: a lumped body of the same mass, centre of mass and
    // inertias on a base of that radius
    let start = |s: &Spatial| SpatialState::tilted(s, 0.15, 0.4, [0.1, -0.2, 2.0]);
    let weak = |t: f64| {
        let a = two_components(t);
        [0.3 * a[0], 0.3 * a[1]]
    };
    let crushing = |kn: f64| {
        let p = Params {
            kn,
            fm: 1e6,
            ..on_bed(true, Formulation::ShiftingPivot)
        };
        Spatial::new(&p, None, RTOL).unwrap()
    };
    let soft = crushing(1e9);
    let b = soft.model.body;
    let rim = soft.radius - soft.model.interface.af_limit();
    let lumped = Params {
        shape: rocking::model::ShapeKind::SolidCircle,
        ro: rim,
        mass_model: rocking::model::MassKind::Lumped,
        w: b.weight,
        hg: b.hg,
        ic: b.ic,
        interface: LawKind::Rigid,
        ..drum(Restitution::Housner, false)
    };
    let rigid = Spatial::new(&lumped, Some(soft.c_axial), RTOL).unwrap();
    let reference = run_rotated(&rigid, start(&rigid), (&weak, &no_av), 0.0, 1.5);
    let mut gaps = vec![];
    for kn in [1e9, 1e10, 1e11, 1e12] {
        let s = crushing(kn);
        let run = run_rotated(&s, start(&s), (&weak, &no_av), 0.0, 1.5);
        let g = gap(&run, &reference);
        eprintln!(
            "kn {kn:.0e} (thetaC {:.1e}): gap to rolling on the rim of {rim:.4} m {g:.3e}",
            s.model.interface.theta_c()
        );
        gaps.push(g);
    }
    let rates: Vec<f64> = gaps.windows(2).map(|w| (w[0] / w[1]).log10()).collect();
    eprintln!("orders per decade of kn: {rates:.3?}");
    // af - af_lim shrinks as the elastic zone's square, (fm/(kn theta))²
    for r in &rates {
        assert!((1.8..2.2).contains(r), "converges at {r} per decade");
    }
    assert!(gaps[3] < 1e-8, "{gaps:?}");
}

#[test]
fn a_turning_point_short_of_upright_is_no_crossing() {
    // a steady push holds the drum tilted in full contact; started beyond
    // its equilibrium it oscillates about it, its tilt turning back at
    // half the equilibrium without crossing upright: no restitution
    let p = on_bed(false, Formulation::ShiftingPivot);
    let mut planar = Simulator::new(p.build().unwrap(), RTOL);
    planar.stiff_mode = false;
    let spatial = Spatial::new(&p, None, RTOL).unwrap();
    let b = spatial.model.body;
    let k0 = p.kn * spatial.model.interface.shape().second_moment() - b.weight * b.hg;
    let ag = -0.05;
    let theta_eq = -b.mass * ag * b.hg / k0;
    let (mut a, mut s) = (
        planar.initial_state(1.5 * theta_eq, 0.0),
        SpatialState::tilted(&spatial, 1.5 * theta_eq, 0.3, [0.0; 3]),
    );
    let push = PlanInput {
        a: rot([ag, 0.0], 0.3),
        da: [0.0; 2],
    };
    let (mut worst, mut low) = (0.0f64, 1.0f64);
    for k in 1..=100 {
        let t = k as f64 * DT;
        planar.advance(&mut a, t, GroundInput { ag, dag: 0.0 });
        spatial.advance(&mut s, t, push, VerticalInput::default());
        worst = worst.max((a.theta - s.theta()).abs());
        low = low.min(s.theta());
    }
    eprintln!(
        "held at {theta_eq:.2e} rad: lowest tilt {low:.2e}, gap {worst:.1e} rad, crossings {} {}",
        a.zero_crossings, s.impacts
    );
    assert!(low < 0.6 * theta_eq && low > 0.4 * theta_eq, "{low}");
    assert_eq!((a.zero_crossings, s.impacts), (0, 0));
    assert!(worst <= 1e-12, "{worst:e}");
}
