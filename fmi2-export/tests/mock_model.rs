//! The generic layer with a model of its own (x' = k u, y = x), to show it
//! needs nothing of rocking, and to test what the real model never does:
//! panics inside the model.

use std::ffi::CString;
use std::ptr;

use fmi2_export::bytes::{ByteReader, ByteWriter, ReadError};
use fmi2_export::model_description::*;
use fmi2_export::test_host::Host;
use fmi2_export::types::*;
use fmi2_export::{EventLog, Inputs, Setup, Slave, StepEnd, Values};

static VARIABLES: &[Variable] = &[
    Variable {
        name: "k",
        vr: 0,
        description: "gain",
        causality: Causality::Parameter,
        variability: Variability::Fixed,
        initial: Some(Initial::Exact),
        ty: Type::Real {
            unit: None,
            display_unit: None,
            start: Some(2.0),
            min: None,
            max: None,
        },
        depends_on: &[],
        derivative: None,
        run_depends_on: &[],
    },
    Variable {
        name: "u",
        vr: 1,
        description: "input; 13 makes the model panic",
        causality: Causality::Input,
        variability: Variability::Continuous,
        initial: None,
        ty: Type::Real {
            unit: None,
            display_unit: None,
            start: Some(0.0),
            min: None,
            max: None,
        },
        depends_on: &[],
        derivative: None,
        run_depends_on: &[],
    },
    Variable {
        name: "x",
        vr: 2,
        description: "state",
        causality: Causality::Output,
        variability: Variability::Continuous,
        initial: Some(Initial::Exact),
        ty: Type::Real {
            unit: None,
            display_unit: None,
            start: Some(1.0),
            min: None,
            max: None,
        },
        depends_on: &[],
        derivative: None,
        run_depends_on: &[],
    },
];

static MD: ModelDescription = ModelDescription {
    model_name: "Mock",
    description: "x' = k u",
    author: "",
    version: "1",
    copyright: "",
    license: "",
    generation_tool: "",
    // the layer's capabilities, but output derivatives to order 1 only: the
    // mock answers x' = k u and nothing higher
    co_simulation: CoSimulation {
        max_output_derivative_order: 1,
        ..common::co_simulation("Mock")
    },
    model_exchange: None,
    units: &[],
    types: &[],
    log_categories: &[
        LogCategory {
            name: "logEvents",
            description: "",
        },
        LogCategory {
            name: "logStatusWarning",
            description: "",
        },
        LogCategory {
            name: "logStatusError",
            description: "",
        },
        LogCategory {
            name: "logAll",
            description: "",
        },
    ],
    default_experiment: DefaultExperiment {
        start_time: 0.0,
        stop_time: 1.0,
        tolerance: 1e-6,
        step_size: 0.1,
    },
    variables: VARIABLES,
    documentation: "",
    arrays3: None,
};

const GUID: &str = "{mock-model}";

struct Mock {
    k: f64,
    x: f64,
}

impl Slave for Mock {
    type State = f64;
    fn description() -> &'static ModelDescription {
        &MD
    }
    fn guid() -> &'static str {
        GUID
    }
    fn new(v: Values<'_>, _setup: &Setup) -> Result<Self, String> {
        let k = v.real(0);
        if k < 0.0 {
            return Err(format!("k = {k}: must be >= 0"));
        }
        Ok(Mock { k, x: v.real(2) })
    }
    fn get_real(&mut self, vr: u32, inputs: Inputs<'_>) -> Result<f64, String> {
        match vr {
            2 if inputs.real(1) == -13.0 => panic!("get_real exploded"),
            2 => Ok(self.x),
            _ => Err("no such".into()),
        }
    }
    fn output_derivative(&mut self, _vr: u32, _o: i32, inputs: Inputs<'_>) -> Result<f64, String> {
        Ok(self.k * inputs.real(1))
    }
    fn do_step(
        &mut self,
        _t: f64,
        h: f64,
        inputs: Inputs<'_>,
        log: &mut EventLog,
    ) -> Result<StepEnd, String> {
        let u = inputs.real(1);
        let x0 = self.x;
        // half-way corrupt the state, then panic: the layer must restore it
        self.x = f64::NAN;
        if u == 13.0 {
            panic!("the model exploded at u = {u}");
        }
        let du = inputs.derivative(1);
        self.x = x0 + self.k * (u * h + 0.5 * du * h * h);
        log.event(format!("x = {}", self.x));
        Ok(StepEnd::Completed)
    }
    fn state(&self) -> f64 {
        self.x
    }
    fn set_state(&mut self, s: f64) {
        self.x = s;
    }
    fn write_state(s: &f64, w: &mut ByteWriter) {
        w.f64(*s);
    }
    fn read_state(r: &mut ByteReader<'_>) -> Result<f64, ReadError> {
        r.f64("x")
    }
}

fmi2_export::export_fmi2!(Mock);

fn instantiate() -> Host<Mock> {
    Host::named("mock")
}

#[test]
fn a_panicking_model_is_an_error_and_the_state_is_kept() {
    let host = instantiate();
    let c = host.c;
    unsafe {
        assert_eq!(fmi2EnterInitializationMode(c), fmi2OK);
        assert_eq!(fmi2ExitInitializationMode(c), fmi2OK);
        let u = 13.0;
        assert_eq!(fmi2SetReal(c, &1, 1, &u), fmi2OK);
        assert_eq!(fmi2DoStep(c, 0.0, 0.1, 1), fmi2Error);
        assert!(host
            .logged("internal error in the model during fmi2DoStep: the model exploded at u = 13"));
        // x was corrupted inside the model, then restored
        let mut x = 0.0;
        assert_eq!(fmi2GetReal(c, &2, 1, &mut x), fmi2OK);
        assert_eq!(x, 1.0);
        // error state: no stepping until reset
        assert_eq!(fmi2DoStep(c, 0.0, 0.1, 1), fmi2Error);
        assert_eq!(fmi2Reset(c), fmi2OK);
        // a panic while evaluating an output
        assert_eq!(fmi2EnterInitializationMode(c), fmi2OK);
        let u = -13.0;
        assert_eq!(fmi2SetReal(c, &1, 1, &u), fmi2OK);
        assert_eq!(fmi2GetReal(c, &2, 1, &mut x), fmi2Error);
        assert!(host.logged("get_real exploded"));
    }
}

#[test]
fn invalid_parameters_and_null_pointers() {
    let host = instantiate();
    let c = host.c;
    unsafe {
        let k = -1.0;
        assert_eq!(fmi2SetReal(c, &0, 1, &k), fmi2OK);
        assert_eq!(fmi2EnterInitializationMode(c), fmi2OK);
        assert_eq!(fmi2ExitInitializationMode(c), fmi2Error);
        assert!(host.logged("k = -1: must be >= 0"));
        assert_eq!(fmi2Reset(c), fmi2OK);
        assert_eq!(fmi2SetReal(c, ptr::null(), 1, &k), fmi2Error);
        assert!(host.logged("vr is NULL"));
        assert_eq!(fmi2Reset(c), fmi2OK);
        assert_eq!(fmi2GetFMUstate(c, ptr::null_mut()), fmi2Error);
        host.free();
        fmi2FreeInstance(ptr::null_mut()); // harmless
    }
}

#[test]
fn no_callbacks_at_all() {
    let name = CString::new("silent").unwrap();
    let guid = CString::new(GUID).unwrap();
    unsafe {
        let c = fmi2Instantiate(
            name.as_ptr(),
            fmi2CoSimulation,
            guid.as_ptr(),
            ptr::null(),
            ptr::null(),
            0,
            1,
        );
        assert!(!c.is_null());
        assert_eq!(fmi2DoStep(c, 0.0, 0.1, 1), fmi2Error); // logged nowhere, no crash
        fmi2FreeInstance(c);
    }
}
