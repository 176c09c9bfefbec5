//! `target/fmu/RockingBlock.fmu` imported through the `fmi` crate's FMI 2.0
//! API, a host written by others: the crate unzips the archive, parses
//! `modelDescription.xml` (`fmi-schema`), loads the binary through its
//! bindgen-generated binding (`fmi-sys`) and drives a co-simulation instance.
//! Value references and start values come from the model description as the
//! crate parsed it, not from this project's `model-description` crate.
//!
//! The case: a rigid solid block released from `theta0 = 0.8 alpha` at rest,
//! Housner's restitution (the default), stepped with `fmi2DoStep` at the
//! model's default communication step and at coarser ones; the first ten
//! impacts are compared with the exact solution of `fmi_import::Housner`
//! (elliptic integrals, this crate's `src/lib.rs`). Also: FMU states and
//! error messages through the crate.
//!
//! The test packages the FMU first (`cargo xtask fmu` in the repository,
//! a no-op when it is up to date).

#[path = "../../fmu-rocking/tests/packaged/mod.rs"]
mod packaged;

use std::sync::{Mutex, OnceLock};

use fmi::fmi2::import::Fmi2Import;
use fmi::fmi2::instance::{CoSimulation, Common, InstanceCS};
use fmi::fmi2::schema::{Causality, Fmi2ModelDescription, ScalarVariableElement, Variability};
use fmi::fmi2::{Fmi2Error, Fmi2Res};
use fmi::traits::{FmiImport, FmiStatus};
use fmi_import::Housner;

/// The FMU's integration tolerance for these runs (`fmi2SetupExperiment`).
const RTOL: f64 = 1e-9;

/// Value of the `rigid` item of the `InterfaceLaw` enumeration. The `fmi`
/// crate's FMI 2.0 schema (0.8) reads `<Enumeration>` as a unit variant, with
/// neither its items nor a variable's start value, so this one number is
/// taken from the FMU's documentation (`documentation/index.html`); it is
/// checked against the text of the extracted `modelDescription.xml`, and
/// that the law is rigid on the outputs (`af = 0` throughout).
const INTERFACE_RIGID: i32 = 1;

/// Imports the FMU: the crate extracts it into a temporary directory that
/// lives as long as the import. Installs the capturing logger on first use.
fn import() -> Fmi2Import {
    static LOGGER: OnceLock<()> = OnceLock::new();
    LOGGER.get_or_init(|| {
        log::set_logger(&LOG).expect("one logger");
        log::set_max_level(log::LevelFilter::Trace);
    });
    fmi::import::from_path(packaged::rocking_block_fmu()).expect("the fmi crate imports the FMU")
}

/// The FMU's messages as the `fmi` crate delivers them: its C logger
/// formats them (`vsnprintf`, so `%%` becomes `%`) and passes them to the
/// `log` crate with the instance name as target.
struct Capture(Mutex<Vec<(log::Level, String, String)>>);

static LOG: Capture = Capture(Mutex::new(Vec::new()));

impl log::Log for Capture {
    fn enabled(&self, _: &log::Metadata) -> bool {
        true
    }
    fn log(&self, r: &log::Record) {
        let m = (r.level(), r.target().to_string(), r.args().to_string());
        self.0.lock().unwrap().push(m);
    }
    fn flush(&self) {}
}

fn messages(instance: &str) -> Vec<(log::Level, String)> {
    LOG.0
        .lock()
        .unwrap()
        .iter()
        .filter(|(_, t, _)| t == instance)
        .map(|(l, _, m)| (*l, m.clone()))
        .collect()
}

/// The value reference of `name`, checking its causality and type as parsed.
fn vr(md: &Fmi2ModelDescription, name: &str, causality: Causality, real: bool) -> u32 {
    let v = md
        .model_variable_by_name(name)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(v.causality, causality, "{name}");
    match (&v.elem, real) {
        (ScalarVariableElement::Real(_), true)
        | (ScalarVariableElement::Integer(_) | ScalarVariableElement::Enumeration, false) => {}
        (e, _) => panic!("{name}: unexpected type {e:?}"),
    }
    v.value_reference
}

/// The start value of a Real parameter.
fn start(md: &Fmi2ModelDescription, name: &str) -> f64 {
    match &md.model_variable_by_name(name).unwrap().elem {
        ScalarVariableElement::Real(r) => r.start.unwrap_or_else(|| panic!("{name} has no start")),
        e => panic!("{name}: {e:?}"),
    }
}

/// Value references used by the tests.
struct Vars {
    interface: u32,
    theta: u32,
    omega: u32,
    af: u32,
    impacts: u32,
    alpha: u32,
    weight: u32,
    r0: u32,
    io: u32,
    eta_housner: u32,
}

impl Vars {
    fn new(md: &Fmi2ModelDescription) -> Vars {
        use Causality::{CalculatedParameter as Calc, Output, Parameter};
        Vars {
            interface: vr(md, "interface", Parameter, false),
            theta: vr(md, "theta", Output, true),
            omega: vr(md, "omega", Output, true),
            af: vr(md, "af", Output, true),
            impacts: vr(md, "impacts", Output, false),
            alpha: vr(md, "alpha", Calc, true),
            weight: vr(md, "weight", Calc, true),
            r0: vr(md, "R0", Calc, true),
            io: vr(md, "IO", Calc, true),
            eta_housner: vr(md, "etaHousner", Calc, true),
        }
    }
}

fn get(inst: &mut InstanceCS, vr: u32) -> f64 {
    let mut x = [f64::NAN];
    assert!(matches!(inst.get_real(&[vr], &mut x), Ok(Fmi2Res::OK)));
    x[0]
}

fn get_int(inst: &mut InstanceCS, vr: u32) -> i32 {
    let mut x = [-1];
    assert!(matches!(inst.get_integer(&[vr], &mut x), Ok(Fmi2Res::OK)));
    x[0]
}

/// `(theta, omega, af, impacts)` at the current communication point.
fn sample(inst: &mut InstanceCS, v: &Vars) -> (f64, f64, f64, i32) {
    let mut x = [f64::NAN; 3];
    assert!(matches!(
        inst.get_real(&[v.theta, v.omega, v.af], &mut x),
        Ok(Fmi2Res::OK)
    ));
    (x[0], x[1], x[2], get_int(inst, v.impacts))
}

/// The default block (solid rectangle `B x L`, prism of height `H`) on the
/// rigid interface, released from `theta0_over_alpha * alpha` at rest, in
/// step mode at t = 0. Returns the instance, the value references and the
/// exact solution built from the parsed start values alone.
fn rigid_block(
    import: &Fmi2Import,
    name: &str,
    theta0_over_alpha: f64,
) -> (InstanceCS, Vars, Housner, f64) {
    let md = import.model_description();
    let v = Vars::new(md);
    // the reference, from the start values as parsed: a prism `B x H` has
    // tan(alpha) = B/H, R0 = hypot(B, H)/2, IO = (4/3) m R0², so p² = W R0/IO = 3 g/(4 R0)
    let (b, h, g) = (start(md, "B"), start(md, "H"), start(md, "g"));
    let r0 = 0.5 * b.hypot(h);
    let hb = Housner {
        p2: 0.75 * g / r0,
        alpha: b.atan2(h),
        eta: Housner::solid_block_eta(b, h),
    };
    let theta0 = theta0_over_alpha * hb.alpha;

    let mut inst = import
        .instantiate_cs(name, false, false)
        .expect("instantiate");
    assert_eq!(Common::get_version(&inst), "2.0");
    assert_eq!(inst.get_types_platform(), "default");
    assert!(matches!(
        inst.setup_experiment(Some(RTOL), 0.0, None),
        Ok(Fmi2Res::OK)
    ));
    assert!(matches!(
        inst.set_integer(&[v.interface], &[INTERFACE_RIGID]),
        Ok(Fmi2Res::OK)
    ));
    assert!(matches!(
        inst.set_real(&[v.theta], &[theta0]),
        Ok(Fmi2Res::OK)
    ));
    assert!(matches!(inst.enter_initialization_mode(), Ok(Fmi2Res::OK)));
    assert!(matches!(inst.exit_initialization_mode(), Ok(Fmi2Res::OK)));

    // the FMU's calculated parameters agree with the reference's
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-14 * b.abs();
    let alpha = get(&mut inst, v.alpha);
    assert!(close(alpha, hb.alpha), "alpha {alpha} vs {}", hb.alpha);
    let p2 = get(&mut inst, v.weight) * get(&mut inst, v.r0) / get(&mut inst, v.io);
    assert!(close(p2, hb.p2), "W R0 / IO = {p2} vs {}", hb.p2);
    assert!(close(get(&mut inst, v.r0), r0));
    let eta = get(&mut inst, v.eta_housner);
    assert!(close(eta, hb.eta), "etaHousner {eta} vs {}", hb.eta);
    (inst, v, hb, theta0)
}

#[test]
fn the_fmi_crate_reads_the_model_description() {
    let import = import();
    let md = import.model_description();
    assert_eq!(md.fmi_version, "2.0");
    assert_eq!(md.model_name, "RockingBlock");
    let cs = md.co_simulation.as_ref().expect("a co-simulation FMU");
    assert_eq!(cs.model_identifier, "RockingBlock");
    assert_eq!(cs.can_get_and_set_fmu_state, Some(true));
    assert_eq!(cs.can_serialize_fmu_state, Some(true));
    assert_eq!(cs.can_handle_variable_communication_step_size, Some(true));
    // Model Exchange in the same archive (docs/model-exchange.md): the same
    // binary, and the 12 event indicators that page lists
    let me = md
        .model_exchange
        .as_ref()
        .expect("a Model Exchange interface");
    assert_eq!(me.model_identifier, "RockingBlock");
    assert_eq!(md.number_of_event_indicators, Some(16));
    let names: Vec<&str> = md.get_model_variables().map(|v| v.name.as_str()).collect();
    for n in [
        "ag",
        "theta",
        "omega",
        "omegaW",
        "impacts",
        "overturned",
        "Fx",
        "Fz",
    ] {
        assert!(names.contains(&n), "{n} missing");
    }
    let ag = md.model_variable_by_name("ag").unwrap();
    assert_eq!(ag.causality, Causality::Input);
    assert_eq!(ag.variability, Some(Variability::Continuous));
    // the one value not available from the crate's parse (see INTERFACE_RIGID)
    let xml = std::fs::read_to_string(import.archive_path().join("modelDescription.xml")).unwrap();
    let item = format!("<Item name=\"rigid\" value=\"{INTERFACE_RIGID}\"");
    assert!(xml.contains(&item), "{item} not in the model description");
    let de = md.default_experiment.as_ref().expect("DefaultExperiment");
    assert!(de.step_size().is_some_and(|h| h > 0.0));
}

/// Worst relative errors of one run: impact times (reconstructed from the
/// state before and after each impact), amplitudes, and the amplitude of
/// every sample between impacts.
#[derive(Debug, Default, Clone, Copy)]
struct Worst {
    time_before: f64,
    time_after: f64,
    amplitude: f64,
    between: f64,
}

/// Steps the block released from `0.8 alpha` with the communication step
/// `h` through its first `n` impacts and compares each with the exact
/// solution.
///
/// Each impact is located from the FMU's outputs without interpolation
/// error: the step `(t_k, t_k + h]` in which the `impacts` output goes up by
/// one holds the crossing (checked against the exact time); from the state
/// sampled at `t_k` (before the impact) the exact time still to fall is
/// `time_to_impact(theta_k, omega_k)`, and from the state at `t_k + h`
/// (after it) the exact time since the crossing is `time_since_impact`.
/// Both use only energy conservation between impacts (exact for the rigid
/// law), so what is measured is the FMU's own error in the sampled states,
/// not the communication step's; likewise the amplitude after an impact,
/// and at every sample between impacts, follows from the sampled state.
fn free_rocking(import: &Fmi2Import, h: f64, n: usize) -> Worst {
    let name = format!("free rocking, h = {h}");
    let (mut inst, v, hb, theta0) = rigid_block(import, &name, 0.8);
    let exact = hb.impacts(theta0, n);
    // at most one impact per communication step: the shortest interval
    // between two impacts, the last one, is longer than h
    assert!(2.0 * hb.fall_time(exact[n - 1].1, 0.0) > h);

    let (mut t, mut k) = (0.0, 0u32);
    let mut prev = sample(&mut inst, &v);
    assert_eq!(prev.0, theta0);
    assert_eq!((prev.1, prev.3), (0.0, 0));
    let mut amplitude = theta0; // the exact amplitude of the current half-cycle
    let mut found = 0;
    let mut w = Worst::default();
    while found < n {
        let status = inst.do_step(t, h, true);
        assert!(matches!(status, Ok(Fmi2Res::OK)), "step at {t}: {status:?}");
        k += 1;
        let t_next = k as f64 * h; // communication points without drift
        let now = sample(&mut inst, &v);
        assert_eq!(
            now.2, 0.0,
            "af = {} at t = {t_next}: not the rigid law",
            now.2
        );
        match now.3 - prev.3 {
            0 => {
                let e = (hb.amplitude(now.0, now.1) - amplitude).abs() / amplitude;
                w.between = w.between.max(e);
            }
            1 => {
                let (te, phi_exact) = exact[found];
                found += 1;
                assert!(
                    t < te && te <= t_next,
                    "impact {found} reported in ({t}, {t_next}], exact time {te}"
                );
                let t_before = t + hb.time_to_impact(prev.0, prev.1);
                let t_after = t_next - hb.time_since_impact(now.0, now.1);
                let phi = hb.amplitude(now.0, now.1);
                let err = [
                    (t_before - te).abs() / te,
                    (t_after - te).abs() / te,
                    (phi - phi_exact).abs() / phi_exact,
                ];
                eprintln!(
                    "h = {h} s, impact {found:2}: t = {te:.12} s (FMU: {t_before:.12} from before, \
                     {t_after:.12} from after), amplitude {phi_exact:.12} rad (FMU {phi:.12}); \
                     relative errors {:.1e} {:.1e} {:.1e}",
                    err[0], err[1], err[2]
                );
                w.time_before = w.time_before.max(err[0]);
                w.time_after = w.time_after.max(err[1]);
                w.amplitude = w.amplitude.max(err[2]);
                amplitude = phi_exact;
            }
            d => panic!("{d} impacts in the step from {t}"),
        }
        prev = now;
        t = t_next;
    }
    let last = inst.last_successful_time().expect("fmi2LastSuccessfulTime");
    assert!(
        (last - t).abs() <= 1e-12 * t,
        "last successful time {last} vs {t}"
    );
    assert!(!inst.terminated().expect("fmi2Terminated"));
    assert!(matches!(inst.terminate(), Ok(Fmi2Res::OK)));
    let msgs = messages(&name);
    assert!(msgs.iter().all(|(l, _)| *l > log::Level::Warn), "{msgs:?}");
    eprintln!("h = {h} s: {n} impacts, worst relative errors {w:?}");
    w
}

/// Ten impacts against the exact solution, at the model's default
/// communication step and at coarser ones.
///
/// Tolerance. The FMU integrates with DOP853 at the relative tolerance
/// `RTOL` (`fmi2SetupExperiment`): each integration step's error estimate is
/// held below `RTOL` relative to `|y| + (thetaOv, p thetaOv)`, and the global
/// error falls in proportion to `RTOL` (`tests/dynamics_convergence.rs`),
/// with a factor of order one for a smooth motion over a few cycles (measured
/// here: 0.33 at most, see below). The reconstruction above
/// removes the communication step's interpolation error, so the bound is
/// `10 RTOL` on relative times and amplitudes, whatever `h`: a margin of ten
/// over the order-one factor, and still far below anything wrong in kind
/// (`eta` off by 1e-6 moves the tenth amplitude by 2e-5 relative; an impact
/// reported a step late is `h / t_n > 1e-3` off). The communication step
/// enters in two ways: at most one impact may fall in a step (asserted), and
/// the integrator's steps end on communication points, so at `h = 0.01 s`
/// and `0.05 s` (`p h = 0.024, 0.12`) the steps are limited by `h`, not by
/// the tolerance, and the errors are at round-off (measured: below 1e-14);
/// at `h = 0.2 s` and `0.5 s` the tolerance governs (measured: up to
/// 3.3e-10, that is 0.33 `RTOL`).
#[test]
fn free_rocking_matches_the_exact_solution() {
    let import = import();
    let h_default = import
        .model_description()
        .default_experiment
        .as_ref()
        .and_then(|d| d.step_size())
        .unwrap();
    let tol = 10.0 * RTOL;
    for h in [h_default, 0.05, 0.2, 0.5] {
        let w = free_rocking(&import, h, 10);
        for (what, e) in [
            ("impact times from the state before", w.time_before),
            ("impact times from the state after", w.time_after),
            ("amplitudes", w.amplitude),
            ("amplitudes between impacts", w.between),
        ] {
            assert!(e < tol, "h = {h}: {what} off by {e:.1e} > {tol:.0e}");
        }
    }
}

/// FMU state through the `fmi` crate: taken, restored, serialized and
/// deserialized mid-run, the continuation is the same bit for bit.
#[test]
fn fmu_state_round_trip_through_the_fmi_crate() {
    let import = import();
    let (mut inst, v, _, _) = rigid_block(&import, "fmu state", 0.5);
    let h = 0.01;
    let run = |inst: &mut InstanceCS, t0: f64, n: usize| {
        (0..n)
            .map(|i| {
                let t = t0 + i as f64 * h;
                assert!(matches!(inst.do_step(t, h, true), Ok(Fmi2Res::OK)));
                let s = sample(inst, &v);
                (s.0.to_bits(), s.1.to_bits(), s.3)
            })
            .collect::<Vec<_>>()
    };
    run(&mut inst, 0.0, 50);
    let t0 = 50.0 * h;
    let state = inst.get_fmu_state().expect("fmi2GetFMUstate");
    let bytes = inst
        .serialize_fmu_state(&state)
        .expect("fmi2SerializeFMUstate");
    assert!(bytes.starts_with(b"FMI2STAT"), "the documented header");
    let first = run(&mut inst, t0, 150); // through at least one impact
    assert!(
        first.last().unwrap().2 > first[0].2,
        "no impact in the window"
    );

    assert!(matches!(inst.set_fmu_state(&state).ok(), Ok(Fmi2Res::OK)));
    assert_eq!(run(&mut inst, t0, 150), first);

    let restored = inst
        .deserialize_fmu_state(&bytes)
        .expect("fmi2DeSerializeFMUstate");
    assert!(matches!(
        inst.set_fmu_state(&restored).ok(),
        Ok(Fmi2Res::OK)
    ));
    assert_eq!(run(&mut inst, t0, 150), first);

    // a corrupted buffer is refused
    let mut bad = bytes.clone();
    let i = bad.len() / 2;
    bad[i] ^= 0x40;
    assert!(matches!(
        inst.deserialize_fmu_state(&bad),
        Err(Fmi2Error::Error)
    ));
}

/// An error returns `fmi2Error` and its message reaches the `fmi` crate's logger.
#[test]
fn errors_reach_the_fmi_crate_logger() {
    let name = "wrong time";
    let import = import();
    let (inst, _, _, _) = rigid_block(&import, name, 0.5);
    assert!(matches!(
        inst.do_step(1.0, 0.01, true),
        Err(Fmi2Error::Error)
    ));
    let msgs = messages(name);
    assert!(
        msgs.iter()
            .any(|(l, m)| *l == log::Level::Error && m.contains("does not match")),
        "{msgs:?}"
    );
}
