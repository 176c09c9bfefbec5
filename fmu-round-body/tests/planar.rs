//! The planar limit through both FMUs in one process: RoundBody under `agx`
//! alone (and `av`), started in the x-z plane, against RockingBlock's rigid
//! circle of the same parameters under `ag = agx`. Each FMU is driven
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

/// The largest |theta_planar - asin(ex)| over a run of `t_end` s, the peak
/// |theta| and the impacts of both.
fn compare(restitution: i32, with_av: bool, theta0: f64, t_end: f64) -> (f64, f64, (i32, i32)) {
    let planar = Host::<RockingSlave>::named("planar");
    let space = Host::<RoundBodySlave>::named("space");
    // the same drum: a solid circle of radius 0.5 m, prism 3 m high, 2000 kg/m3
    for (name, x) in [("Ro", 0.5), ("H", 3.0), ("rho", 2000.0), ("eta", 0.8)] {
        assert_eq!(planar.set_real(name, x), fmi2OK);
        assert_eq!(space.set_real(name, x), fmi2OK);
    }
    assert_eq!(planar.set_integer("shape", 3), fmi2OK);
    assert_eq!(planar.set_integer("interface", 1), fmi2OK); // rigid
    assert_eq!(planar.set_integer("restitution", restitution), fmi2OK);
    assert_eq!(space.set_integer("restitution", restitution), fmi2OK);
    assert_eq!(planar.set_real("theta", theta0), fmi2OK);
    assert_eq!(space.set_real("theta0", theta0), fmi2OK);
    planar.init_with(Some(RTOL));
    space.init_with(Some(RTOL));
    let v = |t: f64| if with_av { av(t) } else { 0.0 };
    let (mut worst, mut peak) = (0.0f64, 0.0f64);
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
        worst = worst.max((theta - ex.asin()).abs());
        peak = peak.max(theta.abs());
    }
    let impacts = (planar.integer("impacts"), space.integer("impacts"));
    (worst, peak, impacts)
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
                let (worst, peak, impacts) = compare(restitution, with_av, theta0, 6.0);
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
