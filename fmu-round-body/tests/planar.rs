//! The planar limit through both FMUs in one process: RoundBody under `agx`
//! alone (and `av`), started in the x-z plane, against RockingBlock's
//! circle of the same parameters under `ag = agx`, on the rigid bed and on
//! the flexible ones (the same `interface`, `kn`, `fm`, `formulation`). Each FMU is driven
//! through its own FMI 2.0 functions (the generic layer's, instantiated for
//! each model), with the same inputs and input derivatives.

use fmi2_export::test_host::Host;
use fmi2_export::types::fmi2OK;
use fmu_rocking::RockingSlave;
use fmu_round_body::RoundBodySlave;

/// Tight enough that both integrators are far below the comparison's 1e-10 rad.
const RTOL: f64 = 1e-12;
const DT: f64 = 0.01;

/// A decaying train that rocks the drum (tan alpha = 1/3) hard without
/// overturning it, m/s2 at t s; and a vertical input.
fn ag(t: f64) -> f64 {
    1.6 * 9.81 / 3.0 * (2.0 * std::f64::consts::PI * 1.3 * t).sin() * (-0.25 * t).exp()
}

fn av(t: f64) -> f64 {
    2.0 * (2.0 * std::f64::consts::PI * 3.1 * t).sin()
}

/// The bed both FMUs stand on: `interface`, `formulation` (codes, the
/// same in both), `kn` (Pa/m), `fm` (Pa).
#[derive(Clone, Copy, Debug)]
struct Bed {
    interface: i32,
    formulation: i32,
    kn: f64,
    fm: f64,
}

const RIGID: Bed = Bed {
    interface: 1,
    formulation: 2,
    kn: 5e9,
    fm: 5e6,
};

/// What a comparison measured.
#[derive(Debug, Default)]
struct Compared {
    /// Largest |theta_planar - asin(ex)|, rad.
    worst: f64,
    /// Peak |theta|, rad.
    peak: f64,
    /// (RockingBlock's, RoundBody's) impacts; on a flexible bed
    /// RockingBlock's zero crossings, the returns through upright that
    /// RoundBody counts as impacts.
    impacts: (i32, i32),
    /// Largest |af_planar - af_space|, m.
    af: f64,
    /// Samples whose regimes differ (RockingBlock's code + 3 against
    /// RoundBody's), and the samples with crushing.
    regimes_differ: usize,
    crushing: usize,
}

/// The run of `t_end` s on `bed` through both FMUs.
fn compare(bed: Bed, restitution: i32, with_av: bool, theta0: f64, t_end: f64) -> Compared {
    let planar = Host::<RockingSlave>::named("planar");
    let space = Host::<RoundBodySlave>::named("space");
    for host in [&planar as &dyn SetBed, &space] {
        host.bed(bed);
    }
    // the same drum: a solid circle of radius 0.5 m, prism 3 m high, 2000 kg/m3
    for (name, x) in [("Ro", 0.5), ("H", 3.0), ("rho", 2000.0), ("eta", 0.8)] {
        assert_eq!(planar.set_real(name, x), fmi2OK);
        assert_eq!(space.set_real(name, x), fmi2OK);
    }
    assert_eq!(planar.set_integer("shape", 3), fmi2OK);
    assert_eq!(planar.set_integer("restitution", restitution), fmi2OK);
    assert_eq!(space.set_integer("restitution", restitution), fmi2OK);
    assert_eq!(planar.set_real("theta", theta0), fmi2OK);
    assert_eq!(space.set_real("theta0", theta0), fmi2OK);
    planar.init_with(Some(RTOL));
    space.init_with(Some(RTOL));
    let v = |t: f64| if with_av { av(t) } else { 0.0 };
    let mut c = Compared::default();
    let flexible = bed.interface != RIGID.interface;
    let n = (t_end / DT).round() as usize;
    for k in 0..n {
        let (t0, t1) = (k as f64 * DT, (k + 1) as f64 * DT);
        let (a, da) = (ag(t0), (ag(t1) - ag(t0)) / DT);
        let (b, db) = (v(t0), (v(t1) - v(t0)) / DT);
        for (host_set, ag_name) in [(&planar as &dyn SetInputs, "ag"), (&space, "agx")] {
            host_set.inputs(ag_name, a, da, b, db);
        }
        planar.check("planar step", planar.do_step(t0, DT));
        space.check("spatial step", space.do_step(t0, DT));
        let theta = planar.real("theta");
        let [ex, ey] = [space.real("ex"), space.real("ey")];
        assert_eq!(ey, 0.0, "the motion stays in its plane");
        c.worst = c.worst.max((theta - ex.asin()).abs());
        c.peak = c.peak.max(theta.abs());
        if flexible {
            c.af = c.af.max((planar.real("af") - space.real("af")).abs());
            let regime = planar.integer("regime");
            c.regimes_differ += (regime + 3 != space.integer("regime")) as usize;
            c.crushing += (regime == 2 || regime == 3) as usize;
        }
    }
    let planar_impacts = if flexible { "zeroCrossings" } else { "impacts" };
    c.impacts = (planar.integer(planar_impacts), space.integer("impacts"));
    c
}

/// Sets the bed of either FMU (the same names and codes in both).
trait SetBed {
    fn bed(&self, bed: Bed);
}

impl<S: fmi2_export::Slave> SetBed for Host<S> {
    fn bed(&self, bed: Bed) {
        assert_eq!(self.set_integer("interface", bed.interface), fmi2OK);
        assert_eq!(self.set_integer("formulation", bed.formulation), fmi2OK);
        assert_eq!(self.set_real("kn", bed.kn), fmi2OK);
        assert_eq!(self.set_real("fm", bed.fm), fmi2OK);
    }
}

/// Sets the inputs of either FMU (RockingBlock's `ag` or RoundBody's `agx`).
trait SetInputs {
    fn inputs(&self, ag: &str, a: f64, da: f64, v: f64, dv: f64);
}

impl<S: fmi2_export::Slave> SetInputs for Host<S> {
    fn inputs(&self, ag: &str, a: f64, da: f64, v: f64, dv: f64) {
        assert_eq!(self.set_real(ag, a), fmi2OK);
        assert_eq!(self.set_real("av", v), fmi2OK);
        assert_eq!(self.set_input_derivative(ag, 1, da), fmi2OK);
        assert_eq!(self.set_input_derivative("av", 1, dv), fmi2OK);
    }
}

#[test]
fn along_x_roundbody_is_rockingblocks_rigid_circle() {
    for restitution in [1, 2] {
        for with_av in [false, true] {
            for theta0 in [0.0, 0.15, -0.1] {
                let Compared {
                    worst,
                    peak,
                    impacts,
                    ..
                } = compare(RIGID, restitution, with_av, theta0, 6.0);
                eprintln!(
                    "restitution {restitution}, av {with_av}, theta0 {theta0}: worst {worst:.2e} rad, peak {peak:.3} rad, impacts {impacts:?}"
                );
                assert!(peak > 0.05, "the run must rock: peak {peak}");
                assert!(impacts.0 >= 2, "impacts {impacts:?}");
                assert_eq!(impacts.0, impacts.1);
                assert!(worst <= 1e-10, "{worst:e} rad");
            }
        }
    }
}

/// On the elastic and the crushing bed (kn = 1e8 Pa/m, fm = 0.3 MPa: the
/// heel opens at 1.2e-3 rad, the toe crushes at 6.9e-3 rad), both
/// formulations, with and without av: RoundBody along x is RockingBlock's
/// circle to 1e-10 rad, the resultant's place `af` to 1.2e-8 m (its slope
/// reaches kn Is/N = 118 m/rad near upright: 1e-10 rad of it), the same
/// regime at every sample and the same returns through upright.
#[test]
fn along_x_roundbody_is_rockingblocks_circle_on_flexible_beds() {
    for interface in [2, 3] {
        for formulation in [1, 2] {
            for with_av in [false, true] {
                let bed = Bed {
                    interface,
                    formulation,
                    kn: 1e8,
                    fm: 3e5,
                };
                let c = compare(bed, 1, with_av, 0.0, 4.0);
                eprintln!(
                    "interface {interface}, formulation {formulation}, av {with_av}: worst {:.2e} rad, af {:.2e} m, peak {:.3} rad, crossings {:?}, {} samples crushing, {} regimes differ",
                    c.worst, c.af, c.peak, c.impacts, c.crushing, c.regimes_differ
                );
                assert!(c.peak > 0.05, "the run must rock: peak {}", c.peak);
                assert!(c.impacts.0 >= 2, "{:?}", c.impacts);
                assert_eq!(c.impacts.0, c.impacts.1);
                assert!(interface == 2 || c.crushing > 10, "the toe must crush");
                assert!(c.worst <= 1e-10, "{:e} rad", c.worst);
                assert!(c.af <= 1.2e-8, "af {:e} m", c.af);
                assert_eq!(c.regimes_differ, 0);
            }
        }
    }
}
