//! Imports the packaged `target/fmu/RockingBlock.fmu` the way a co-simulation
//! master does, independently of the FMU's own crates: unzip, read
//! `modelDescription.xml`, `dlopen` the binary, resolve every FMI 2.0
//! co-simulation function, and run a free-rocking case, which must equal the
//! engine run directly (crate `rocking`) bit for bit. It uses neither
//! `fmu_rocking` nor `fmi2-export`.
//!
//! The test packages the FMU itself first (`cargo xtask fmu`, a no-op when
//! it is up to date), so it never runs against a stale archive and needs no
//! particular order in the test command.
//!
//! The `fmi` crate's FMI 2.0 importer is a second host, in `fmi-import/`
//! (rigid free rocking against the exact solution, FMU states, error
//! messages). It is a package of its own, outside this workspace: `fmi` 0.8
//! depends on `fmi-sys`, whose build script runs bindgen and needs libclang
//! (`tools/test.sh` installs Debian's libclang-dev), and it would add bindgen,
//! clang-sys, its own zip and an XML stack to every `cargo test` of the
//! workspace. This libloading host stays: it runs without libclang,
//! checks that every FMI 2.0 co-simulation function is exported (the `fmi`
//! crate's binding tolerates a missing symbol until it is called, and it
//! wraps neither `fmi2SetRealInputDerivatives`, `fmi2GetRealOutputDerivatives`
//! nor `fmi2GetIntegerStatus`), passes its own callbacks and a wrong GUID (the
//! crate always passes its own logger and the parsed GUID), and compares the
//! FMU with the engine run directly, bit for bit.

mod packaged;

use std::collections::HashMap;
use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::fs;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use libloading::{Library, Symbol};
use rocking::dynamics::{GroundInput, Simulator};
use rocking::model::LawKind;
use rocking::{Params, Restitution};

// The C types, declared here again on purpose (independent host).
type Component = *mut c_void;
type Status = c_int;
const OK: Status = 0;
const DISCARD: Status = 2;
const ERROR: Status = 3;
const CO_SIMULATION: c_int = 1;
const LAST_SUCCESSFUL_TIME: c_int = 2;

/// The logger, declared without the variadic part: the FMU formats its
/// messages itself and passes no arguments after the message (on x86-64
/// System V a non-variadic callee receives such a call unchanged).
type Logger = extern "C" fn(*mut c_void, *const c_char, Status, *const c_char, *const c_char);

#[repr(C)]
struct Callbacks {
    logger: Option<Logger>,
    allocate: Option<extern "C" fn(usize, usize) -> *mut c_void>,
    free: Option<extern "C" fn(*mut c_void)>,
    step_finished: Option<extern "C" fn(*mut c_void, Status)>,
    environment: *mut c_void,
}

extern "C" fn logger(
    env: *mut c_void,
    _name: *const c_char,
    status: Status,
    category: *const c_char,
    message: *const c_char,
) {
    // SAFETY: env is the &Mutex<Vec<..>> given at instantiation; the strings are valid.
    let log = unsafe { &*(env as *const Mutex<Vec<(Status, String, String)>>) };
    let c = unsafe { CStr::from_ptr(category) }
        .to_string_lossy()
        .into_owned();
    let m = unsafe { CStr::from_ptr(message) }
        .to_string_lossy()
        .replace("%%", "%");
    log.lock().unwrap().push((status, c, m));
}

/// Extracts the archive into a fresh temporary directory.
fn unzip(fmu: &Path) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fmu_import_{}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    let mut zip = zip::ZipArchive::new(fs::File::open(fmu).unwrap()).unwrap();
    for i in 0..zip.len() {
        let mut f = zip.by_index(i).unwrap();
        let out = dir.join(f.enclosed_name().expect("safe entry names"));
        fs::create_dir_all(out.parent().unwrap()).unwrap();
        let mut data = Vec::new();
        f.read_to_end(&mut data).unwrap();
        fs::write(out, data).unwrap();
    }
    dir
}

fn attribute<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let i = tag.find(&key)? + key.len();
    Some(&tag[i..i + tag[i..].find('"')?])
}

/// GUID, model identifier and the value references by name.
fn read_description(xml: &str) -> (String, String, HashMap<String, u32>) {
    let root = &xml[xml.find("<fmiModelDescription").unwrap()..];
    let guid = attribute(&root[..root.find('>').unwrap()], "guid").unwrap();
    let cs = &xml[xml.find("<CoSimulation").unwrap()..];
    let id = attribute(&cs[..cs.find('>').unwrap()], "modelIdentifier").unwrap();
    let mut vrs = HashMap::new();
    for chunk in xml.split("<ScalarVariable").skip(1) {
        let tag = &chunk[..chunk.find('>').unwrap()];
        let name = attribute(tag, "name").unwrap();
        let vr = attribute(tag, "valueReference").unwrap().parse().unwrap();
        vrs.insert(name.to_string(), vr);
    }
    (guid.to_string(), id.to_string(), vrs)
}

const CO_SIMULATION_FUNCTIONS: &[&str] = &[
    "fmi2GetTypesPlatform",
    "fmi2GetVersion",
    "fmi2SetDebugLogging",
    "fmi2Instantiate",
    "fmi2FreeInstance",
    "fmi2SetupExperiment",
    "fmi2EnterInitializationMode",
    "fmi2ExitInitializationMode",
    "fmi2Terminate",
    "fmi2Reset",
    "fmi2GetReal",
    "fmi2GetInteger",
    "fmi2GetBoolean",
    "fmi2GetString",
    "fmi2SetReal",
    "fmi2SetInteger",
    "fmi2SetBoolean",
    "fmi2SetString",
    "fmi2GetFMUstate",
    "fmi2SetFMUstate",
    "fmi2FreeFMUstate",
    "fmi2SerializedFMUstateSize",
    "fmi2SerializeFMUstate",
    "fmi2DeSerializeFMUstate",
    "fmi2GetDirectionalDerivative",
    "fmi2SetRealInputDerivatives",
    "fmi2GetRealOutputDerivatives",
    "fmi2DoStep",
    "fmi2CancelStep",
    "fmi2GetStatus",
    "fmi2GetRealStatus",
    "fmi2GetIntegerStatus",
    "fmi2GetBooleanStatus",
    "fmi2GetStringStatus",
];

type Instantiate = unsafe extern "C" fn(
    *const c_char,
    c_int,
    *const c_char,
    *const c_char,
    *const Callbacks,
    c_int,
    c_int,
) -> Component;
type Call0 = unsafe extern "C" fn(Component) -> Status;
type Setup = unsafe extern "C" fn(Component, c_int, f64, f64, c_int, f64) -> Status;
type SetReal = unsafe extern "C" fn(Component, *const u32, usize, *const f64) -> Status;
type GetReal = unsafe extern "C" fn(Component, *const u32, usize, *mut f64) -> Status;
type SetInteger = unsafe extern "C" fn(Component, *const u32, usize, *const c_int) -> Status;
type GetInteger = unsafe extern "C" fn(Component, *const u32, usize, *mut c_int) -> Status;
type DoStep = unsafe extern "C" fn(Component, f64, f64, c_int) -> Status;
type RealStatus = unsafe extern "C" fn(Component, c_int, *mut f64) -> Status;
type Free = unsafe extern "C" fn(Component);

#[test]
fn free_rocking_through_the_packaged_fmu() {
    let dir = unzip(packaged::rocking_block_fmu());
    let xml = fs::read_to_string(dir.join("modelDescription.xml")).unwrap();
    let (guid, id, vr) = read_description(&xml);
    assert_eq!(id, "RockingBlock");
    let so = dir.join("binaries/linux64").join(format!("{id}.so"));
    // SAFETY: loading the FMU's binary runs no initialisers with preconditions.
    let lib = unsafe { Library::new(&so) }.unwrap();
    for f in CO_SIMULATION_FUNCTIONS {
        let s: Result<Symbol<*const c_void>, _> = unsafe { lib.get(f.as_bytes()) };
        assert!(s.is_ok(), "{f} is not exported");
    }
    unsafe {
        let version: Symbol<unsafe extern "C" fn() -> *const c_char> =
            lib.get(b"fmi2GetVersion").unwrap();
        assert_eq!(CStr::from_ptr(version()).to_str().unwrap(), "2.0");
        let instantiate: Symbol<Instantiate> = lib.get(b"fmi2Instantiate").unwrap();
        let setup: Symbol<Setup> = lib.get(b"fmi2SetupExperiment").unwrap();
        let enter: Symbol<Call0> = lib.get(b"fmi2EnterInitializationMode").unwrap();
        let exit: Symbol<Call0> = lib.get(b"fmi2ExitInitializationMode").unwrap();
        let set_real: Symbol<SetReal> = lib.get(b"fmi2SetReal").unwrap();
        let get_real: Symbol<GetReal> = lib.get(b"fmi2GetReal").unwrap();
        let set_integer: Symbol<SetInteger> = lib.get(b"fmi2SetInteger").unwrap();
        let get_integer: Symbol<GetInteger> = lib.get(b"fmi2GetInteger").unwrap();
        let do_step: Symbol<DoStep> = lib.get(b"fmi2DoStep").unwrap();
        let real_status: Symbol<RealStatus> = lib.get(b"fmi2GetRealStatus").unwrap();
        let terminate: Symbol<Call0> = lib.get(b"fmi2Terminate").unwrap();
        let free: Symbol<Free> = lib.get(b"fmi2FreeInstance").unwrap();

        let log: Mutex<Vec<(Status, String, String)>> = Mutex::new(Vec::new());
        let callbacks = Callbacks {
            logger: Some(logger),
            allocate: None,
            free: None,
            step_finished: None,
            environment: &log as *const _ as *mut c_void,
        };
        let name = CString::new("import test").unwrap();
        let resources = CString::new(format!("file://{}/resources", dir.display())).unwrap();

        // a wrong GUID is refused, with a message
        let wrong = CString::new("{wrong}").unwrap();
        let c = instantiate(
            name.as_ptr(),
            CO_SIMULATION,
            wrong.as_ptr(),
            resources.as_ptr(),
            &callbacks,
            0,
            0,
        );
        assert!(c.is_null());
        assert!(log.lock().unwrap().last().unwrap().2.contains("GUID"));

        let g = CString::new(guid).unwrap();
        let c = instantiate(
            name.as_ptr(),
            CO_SIMULATION,
            g.as_ptr(),
            resources.as_ptr(),
            &callbacks,
            0,
            0,
        );
        assert!(!c.is_null());

        // a rigid block released from theta0 at rest, eta given
        let (theta0, eta, dt, n) = (0.1, 0.9, 0.01, 300);
        assert_eq!(setup(c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(set_integer(c, &vr["interface"], 1, &1), OK); // rigid
        assert_eq!(set_integer(c, &vr["restitution"], 1, &2), OK); // given
        assert_eq!(set_real(c, &vr["eta"], 1, &eta), OK);
        assert_eq!(set_real(c, &vr["theta"], 1, &theta0), OK);
        assert_eq!(enter(c), OK);
        assert_eq!(exit(c), OK);
        let get = |name: &str| {
            let mut x = f64::NAN;
            assert_eq!(get_real(c, &vr[name], 1, &mut x), OK, "{name}");
            x
        };
        let (alpha, io, weight, r0) = (get("alpha"), get("IO"), get("weight"), get("R0"));

        // the engine, run directly with the same parameters
        let params = Params {
            interface: LawKind::Rigid,
            restitution: Restitution::Given,
            eta,
            theta0,
            ..Params::default()
        };
        let sim = Simulator::new(params.build().unwrap(), rocking::dynamics::DEFAULT_RTOL);
        let mut s = sim.initial_state(theta0, 0.0);

        let mut first_impact = None;
        for k in 0..n {
            let t = k as f64 * dt;
            assert_eq!(do_step(c, t, dt, 1), OK);
            sim.advance(&mut s, t + dt, GroundInput::default());
            let (theta, omega) = (get("theta"), get("omega"));
            assert_eq!(theta.to_bits(), s.theta.to_bits(), "theta at step {k}");
            assert_eq!(omega.to_bits(), s.omega.to_bits(), "omega at step {k}");
            let mut impacts = -1;
            assert_eq!(get_integer(c, &vr["impacts"], 1, &mut impacts), OK);
            assert_eq!(impacts as u64, s.impacts);
            if impacts > 0 && first_impact.is_none() {
                first_impact = Some(t + dt);
            }
        }
        let mut last = 0.0;
        assert_eq!(real_status(c, LAST_SUCCESSFUL_TIME, &mut last), OK);
        assert!((last - n as f64 * dt).abs() < 1e-9);

        // first impact near the linearised closed form t1 = acosh(alpha/(alpha-theta0))/p
        let p = (weight * r0 / io).sqrt();
        let t1 = (alpha / (alpha - theta0)).acosh() / p;
        let t_fmu = first_impact.expect("the block hits the base");
        assert!(
            (t_fmu - t1).abs() < 0.05 * t1 + dt,
            "first impact at {t_fmu}, linearised {t1}"
        );

        // a step from the wrong time is an error with a message
        assert_eq!(do_step(c, 99.0, dt, 1), ERROR);
        assert!(log
            .lock()
            .unwrap()
            .iter()
            .any(|(st, _, m)| *st == ERROR && m.contains("does not match")));
        assert_ne!(terminate(c), DISCARD);
        free(c);
    }
    let _ = fs::remove_dir_all(&dir);
}
