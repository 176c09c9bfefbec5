//! The driver's FMI calls on one instance: life cycle, get/set, stepping,
//! status.

use crate::*;

impl<M: Model> Driver<M> {
    /// One Model Exchange call; after `fmi2OK` every value written is finite
    /// (the nominals positive), and the driver follows the ME state machine.
    pub(crate) fn model_exchange(&mut self, k: u8, which: u8, x: &[f64], n: usize) {
        let mut out = [f64::from_bits(SENTINEL); 16];
        let n = n.min(out.len());
        let (mut enter, mut terminate) = (-1, -1);
        let mut info = fmi2EventInfo {
            newDiscreteStatesNeeded: -1,
            terminateSimulation: -1,
            nominalsOfContinuousStatesChanged: -1,
            valuesOfContinuousStatesChanged: -1,
            nextEventTimeDefined: -1,
            nextEventTime: f64::NAN,
        };
        let p = out.as_mut_ptr();
        let op = which % 10;
        let (what, allowed): (&str, &[Machine]) = match op {
            0 => ("fmi2SetTime", ME_SET_TIME),
            1 => ("fmi2SetContinuousStates", ME_CONTINUOUS),
            2 => ("fmi2GetContinuousStates", ME_EVALUATE),
            3 => ("fmi2GetDerivatives", ME_EVALUATE),
            4 => ("fmi2GetEventIndicators", ME_EVALUATE),
            5 => ("fmi2GetNominalsOfContinuousStates", ANY),
            6 => ("fmi2EnterEventMode", ME_SET_TIME),
            7 => ("fmi2NewDiscreteStates", ME_EVENT),
            8 => ("fmi2EnterContinuousTimeMode", ME_EVENT),
            _ => ("fmi2CompletedIntegratorStep", ME_CONTINUOUS),
        };
        // SAFETY (every arm): a live instance and arrays of at least `n` values.
        let st = self.call(k, what, allowed, |c| unsafe {
            match op {
                0 => (M::API.fmi2SetTime)(c, x[0]),
                1 => (M::API.fmi2SetContinuousStates)(c, x.as_ptr(), n.min(x.len())),
                2 => (M::API.fmi2GetContinuousStates)(c, p, n),
                3 => (M::API.fmi2GetDerivatives)(c, p, n),
                4 => (M::API.fmi2GetEventIndicators)(c, p, n),
                5 => (M::API.fmi2GetNominalsOfContinuousStates)(c, p, n),
                6 => (M::API.fmi2EnterEventMode)(c),
                7 => (M::API.fmi2NewDiscreteStates)(c, &mut info),
                8 => (M::API.fmi2EnterContinuousTimeMode)(c),
                _ => (M::API.fmi2CompletedIntegratorStep)(c, fmi2True, &mut enter, &mut terminate),
            }
        });
        let Some(st) = st else { return };
        let me = self.slot(k).is_some_and(|s| s.me);
        if !me {
            assert_eq!(st, fmi2Error, "{what} on a co-simulation instance");
            return;
        }
        if st != fmi2OK {
            return;
        }
        self.stats.model_exchange_ok += 1;
        if (2..=5).contains(&op) {
            for (i, v) in out[..n].iter().enumerate() {
                assert!(v.is_finite(), "{what}: value {i} = {v} after fmi2OK");
            }
            if op == 5 {
                assert!(out[..n].iter().all(|v| *v > 0.0), "{what}: {:?}", &out[..n]);
            }
        }
        match op {
            6 => self.set_machine(k, Some(Machine::EventMode)),
            7 => {
                for b in [
                    info.newDiscreteStatesNeeded,
                    info.terminateSimulation,
                    info.valuesOfContinuousStatesChanged,
                ] {
                    assert!(b == fmi2True || b == fmi2False, "{what}: fmi2Boolean {b}");
                }
            }
            8 => self.set_machine(k, Some(Machine::ContinuousTime)),
            9 => assert!(
                [enter, terminate]
                    .iter()
                    .all(|b| *b == fmi2True || *b == fmi2False),
                "{what}: {enter}, {terminate}"
            ),
            _ => {}
        }
    }

    pub(crate) fn instantiate(&mut self, k: u8, spec: &InstSpec) {
        let k = k as usize % M::SLOTS;
        if self.slots[k].is_some() {
            // Instantiating into a used slot would lose the pointer: free first.
            self.free(k as u8);
        }
        let name: Option<Vec<u8>> = match &spec.name {
            Name::Null => None,
            Name::Empty => Some(Vec::new()),
            Name::Plain => Some(format!("fuzz{k}").into_bytes()),
            Name::Odd(b) => Some(b.clone()),
            Name::Long => Some(vec![b'n'; 5000]),
        };
        let name_c = name
            .as_ref()
            .map(|n| CString::new(n.clone()).expect("no NUL"));
        let guid = match spec.guid {
            Guid::Right => Some(CString::new(M::GUID).expect("GUID")),
            Guid::Wrong => Some(c"{00000000-0000-0000-0000-000000000000}".to_owned()),
            Guid::Null => None,
            Guid::Truncated => Some(CString::new(&M::GUID[..M::GUID.len() - 1]).expect("GUID")),
        };
        let resource = spec
            .resource
            .as_ref()
            .map(|r| CString::new(r.clone()).expect("no NUL"));
        // the FMU passes back the lossy UTF-8 of the name
        let name_back = name.as_deref().unwrap_or(b"").to_vec();
        let debug = spec.logging_on != fmi2False;
        let log = new_log(spec.inspect);
        let callbacks = Box::new(log.callbacks(spec.logger));
        let p0 = panics();
        let c = unsafe {
            (M::API.fmi2Instantiate)(
                name_c.as_ref().map_or(ptr::null(), |s| s.as_ptr()),
                spec.fmu_type,
                guid.as_ref().map_or(ptr::null(), |s| s.as_ptr()),
                resource.as_ref().map_or(ptr::null(), |s| s.as_ptr()),
                &*callbacks,
                spec.visible,
                spec.logging_on,
            )
        };
        self.stats.calls += 1;
        assert_eq!(panics(), p0, "fmi2Instantiate: the FMU panicked");
        let recent = log.take();
        if let Some(p) = problem::<M>(&log, [0; 5], &recent, &name_back, debug) {
            panic!("fmi2Instantiate: logger: {p}");
        }
        let valid = name.as_ref().is_some_and(|n| !n.is_empty())
            && (spec.fmu_type == fmi2CoSimulation
                || (spec.fmu_type == fmi2ModelExchange && M::MODEL_EXCHANGE))
            && matches!(spec.guid, Guid::Right);
        assert_eq!(
            !c.is_null(),
            valid,
            "fmi2Instantiate({spec:?}) returned {c:?}"
        );
        if c.is_null() {
            if spec.logger {
                assert!(
                    log.counts()[fmi2Error as usize] > 0,
                    "refused without a message"
                );
            }
            return;
        }
        self.stats.instantiated += 1;
        self.slots[k] = Some(Slot {
            c,
            log,
            callbacks,
            logger: spec.logger,
            name: name_back,
            debug,
            machine: Some(Machine::Instantiated),
            stored: Some(Stored::start::<M>()),
            time: Some(0.0),
            forged: false,
            states: Vec::new(),
            me: spec.fmu_type == fmi2ModelExchange,
            inspect: spec.inspect,
            recent: Vec::new(),
            derivatives: Some(vec![0.0; M::INPUTS.len()]),
        });
    }

    pub(crate) fn free(&mut self, k: u8) {
        let k = k as usize % M::SLOTS;
        if let Some(s) = self.slots[k].take() {
            let before = s.log.counts();
            let p0 = panics();
            // SAFETY: a live instance of ours; its FMU states go with it.
            unsafe { (M::API.fmi2FreeInstance)(s.c) };
            self.stats.calls += 1;
            assert_eq!(panics(), p0, "fmi2FreeInstance: the FMU panicked");
            let recent = s.log.take();
            if let Some(p) = problem::<M>(&s.log, before, &recent, &s.name, s.debug) {
                panic!("fmi2FreeInstance: logger: {p}");
            }
            drop(s);
        }
    }

    pub(crate) fn setup(
        &mut self,
        k: u8,
        tol_def: c_int,
        tol: f64,
        start: f64,
        stop_def: c_int,
        stop: f64,
    ) {
        let before = self.slot(k).and_then(|s| s.machine);
        if let Some(st) = self.call(k, "fmi2SetupExperiment", INSTANTIATED, |c| unsafe {
            (M::API.fmi2SetupExperiment)(c, tol_def, tol, start, stop_def, stop)
        }) {
            let tol_ok = tol_def == fmi2False || (tol.is_finite() && tol > 0.0);
            let stop_ok = stop_def == fmi2False || (stop.is_finite() && stop >= start);
            let s = self.slot(k).expect("called");
            if before == Some(Machine::Instantiated) || st == fmi2OK {
                assert_eq!(
                    st == fmi2OK,
                    tol_ok && start.is_finite() && stop_ok,
                    "fmi2SetupExperiment({tol_def}, {tol}, {start}, {stop_def}, {stop}) = {st}"
                );
            }
            if st == fmi2OK {
                s.time = Some(start);
            }
        }
    }

    pub(crate) fn enter(&mut self, k: u8) {
        if let Some(fmi2OK) =
            self.call(k, "fmi2EnterInitializationMode", INSTANTIATED, |c| unsafe {
                (M::API.fmi2EnterInitializationMode)(c)
            })
        {
            self.set_machine(k, Some(Machine::Init));
        }
    }

    pub(crate) fn exit(&mut self, k: u8) {
        let Some(s) = self.slot(k) else { return };
        let expect = (s.machine == Some(Machine::Init))
            .then(|| s.stored.as_ref().map(|st| M::valid_for(st, s.me)))
            .flatten();
        let stored = s.stored.clone();
        let Some(st) = self.call(k, "fmi2ExitInitializationMode", INIT, |c| unsafe {
            (M::API.fmi2ExitInitializationMode)(c)
        }) else {
            return;
        };
        if let Some(valid) = expect {
            assert_eq!(
                st,
                if valid { fmi2OK } else { fmi2Error },
                "fmi2ExitInitializationMode with parameters {:?}",
                stored.as_ref().and_then(M::params)
            );
            if valid {
                self.stats.exit_init_ok += 1;
            } else {
                self.stats.exit_init_error += 1;
                let s = self.slot(k).expect("called");
                if M::STRICT && s.inspect && s.logger {
                    assert!(
                        names_one_of(&s.recent, &parameter_names::<M>()),
                        "fmi2ExitInitializationMode refused without naming a parameter: {:?}",
                        s.recent
                    );
                }
            }
        }
        if st == fmi2OK {
            let me = self.slot(k).is_some_and(|s| s.me);
            self.set_machine(
                k,
                Some(if me {
                    Machine::EventMode
                } else {
                    Machine::StepComplete
                }),
            );
        }
    }

    pub(crate) fn set_real(&mut self, k: u8, r: &[u32], x: &[f64]) {
        let m = self.machine(k);
        let st = self.call(k, "fmi2SetReal", SET, |c| unsafe {
            (M::API.fmi2SetReal)(c, r.as_ptr(), r.len(), x.as_ptr())
        });
        self.refusal_names_a_target(k, "fmi2SetReal", m, st, r);
        if let Some(fmi2OK) = st {
            let s = self.slot(k).expect("called");
            if let Some(st) = s.stored.as_mut() {
                accept(&mut st.real, r, x);
            }
            // setting an input resets its derivative to 0 (held)
            if let Some(d) = s.derivatives.as_mut() {
                for q in r {
                    if let Some(i) = M::INPUTS.iter().position(|p| p == q) {
                        d[i] = 0.0;
                    }
                }
            }
        }
    }

    pub(crate) fn set_integer(&mut self, k: u8, r: &[u32], x: &[c_int]) {
        let m = self.machine(k);
        let st = self.call(k, "fmi2SetInteger", SET, |c| unsafe {
            (M::API.fmi2SetInteger)(c, r.as_ptr(), r.len(), x.as_ptr())
        });
        self.refusal_names_a_target(k, "fmi2SetInteger", m, st, r);
        if let Some(fmi2OK) = st {
            if let Some(st) = self.slot(k).expect("called").stored.as_mut() {
                accept(&mut st.int, r, x);
            }
        }
    }

    /// fmi2GetReal with the value checks; the values after fmi2OK.
    pub fn get_real(&mut self, k: u8, r: &[u32]) -> Option<Vec<f64>> {
        let mut out = vec![f64::from_bits(SENTINEL); r.len()];
        let st = self.call(k, "fmi2GetReal", GET, |c| unsafe {
            (M::API.fmi2GetReal)(c, r.as_ptr(), r.len(), out.as_mut_ptr())
        })?;
        if st != fmi2OK && st != fmi2Warning {
            return None;
        }
        let params = || {
            let s = self.slots[k as usize % M::SLOTS].as_ref();
            format!(
                "{:?}",
                s.and_then(|s| s.stored.as_ref()).and_then(M::params)
            )
        };
        for (&r, &x) in r.iter().zip(&out) {
            assert_ne!(x.to_bits(), SENTINEL, "fmi2GetReal: vr {r} not written");
            let v = M::VARIABLES.iter().find(|v| v.vr == r).expect("a Real vr");
            // no computed value crosses the boundary non-finite (a model
            // stands for +inf with a large finite value); parameters and
            // inputs are the host's own values, echoed
            let finite = match v.causality {
                Causality::Output | Causality::CalculatedParameter | Causality::Local => {
                    x.is_finite()
                }
                _ => true,
            };
            assert!(finite, "{} = {x} with parameters {}", v.name, params());
            if let Some(p) = M::real_problem(r, x) {
                panic!("{p} with parameters {}", params());
            }
        }
        M::check_reals(r, &out);
        Some(out)
    }

    pub(crate) fn get_integer(&mut self, k: u8, r: &[u32]) {
        let mut out: Vec<c_int> = vec![0x5eed_f00d; r.len()];
        if let Some(fmi2OK) = self.call(k, "fmi2GetInteger", GET, |c| unsafe {
            (M::API.fmi2GetInteger)(c, r.as_ptr(), r.len(), out.as_mut_ptr())
        }) {
            for (&r, &x) in r.iter().zip(&out) {
                match M::integer_in_range(r, x) {
                    Some(ok) => {
                        let name = M::VARIABLES
                            .iter()
                            .find(|v| v.vr == r)
                            .map_or("?", |v| v.name);
                        assert!(ok, "{name} = {x}");
                    }
                    None => assert_ne!(x, 0x5eed_f00d, "fmi2GetInteger: vr {r} not written"),
                }
            }
            M::check_integers(r, &out);
        }
    }

    pub(crate) fn get_boolean(&mut self, k: u8, r: &[u32]) {
        let mut out: Vec<c_int> = vec![-7; r.len()];
        if let Some(fmi2OK) = self.call(k, "fmi2GetBoolean", GET, |c| unsafe {
            (M::API.fmi2GetBoolean)(c, r.as_ptr(), r.len(), out.as_mut_ptr())
        }) {
            for (&r, &x) in r.iter().zip(&out) {
                assert!(x == fmi2True || x == fmi2False, "Boolean vr {r} = {x}");
            }
        }
    }

    pub(crate) fn get_all(&mut self, k: u8) {
        let of = |base: BaseType| -> Vec<u32> {
            M::VARIABLES
                .iter()
                .filter(|v| {
                    v.ty.base() == base
                        && matches!(
                            v.causality,
                            Causality::Output | Causality::CalculatedParameter
                        )
                })
                .map(|v| v.vr)
                .collect()
        };
        self.get_real(k, &of(BaseType::Real));
        self.get_integer(k, &of(BaseType::Integer));
        self.get_boolean(k, &of(BaseType::Boolean));
    }

    pub(crate) fn do_step(&mut self, k: u8, point: Point, h: f64, no_prior: c_int) {
        let Some(s) = self.slot(k) else { return };
        let machine = s.machine;
        let forged = s.forged;
        // The FMU's time: asked where it answers, else the driver's own.
        let mut now = s.time;
        if matches!(
            machine,
            Some(Machine::StepComplete | Machine::StepFailed | Machine::Terminated)
        ) {
            let mut t = f64::NAN;
            if let Some(fmi2OK) = self.call(k, "fmi2GetRealStatus", STATUS, |c| unsafe {
                (M::API.fmi2GetRealStatus)(c, fmi2LastSuccessfulTime, &mut t)
            }) {
                assert!(t.is_finite(), "fmi2LastSuccessfulTime = {t}");
                if let Some(d) = now {
                    assert_eq!(t.to_bits(), d.to_bits(), "fmi2LastSuccessfulTime");
                }
                now = Some(t);
            }
        }
        if M::skip_step(self, k, h, machine, forged) {
            return;
        }
        let base = now.unwrap_or(0.0);
        let t = match point {
            Point::Matching => base,
            Point::Offset(d) => base + d,
            Point::Raw(x) => x,
        };
        // the state before: a refused step must leave it
        let before = if M::STRICT && machine == Some(Machine::StepComplete) {
            self.get_real(k, M::STATE_OUTPUTS)
        } else {
            None
        };
        let known = before.is_some() && M::known_finding(self, k, t, h);
        let machine = self.slot(k).and_then(|s| s.machine);
        let tolerate = self.tolerate_known;
        if std::env::var_os("FUZZ_DRIVER_TRACE").is_some() {
            let s = self.slots[k as usize % M::SLOTS].as_ref();
            let params = s.and_then(|s| s.stored.as_ref()).and_then(M::params);
            eprintln!("fmi2DoStep({t}, {h}) on slot {k}: state {before:?}, parameters {params:?}");
        }
        let Some(st) = self.call(k, "fmi2DoStep", DO_STEP, |c| unsafe {
            (M::API.fmi2DoStep)(c, t, h, no_prior)
        }) else {
            return;
        };
        let s = self.slot(k).expect("called");
        if !(t.is_finite() && h.is_finite() && h > 0.0) {
            assert_eq!(st, fmi2Error, "fmi2DoStep({t}, {h})");
        }
        match st {
            fmi2OK => {
                s.machine = Some(Machine::StepComplete);
                s.time = Some(t + h);
                self.stats.steps_ok += 1;
            }
            fmi2Discard => {
                s.machine = Some(Machine::StepFailed);
                s.time = None;
                self.stats.steps_discard += 1;
                let mut term = fmi2False;
                if let Some(fmi2OK) = self.call(k, "fmi2GetBooleanStatus", STATUS, |c| unsafe {
                    (M::API.fmi2GetBooleanStatus)(c, fmi2Terminated, &mut term)
                }) {
                    let mut last = f64::NAN;
                    if (M::STRICT || term == fmi2False)
                        && self.call(k, "fmi2GetRealStatus", STATUS, |c| unsafe {
                            (M::API.fmi2GetRealStatus)(c, fmi2LastSuccessfulTime, &mut last)
                        }) == Some(fmi2OK)
                    {
                        // the work limit stops inside the step; overturning
                        // and liftOff end the run in it or at its start
                        // (a body that has already overturned)
                        let inside = if term == fmi2False {
                            last >= t && last < t + h
                        } else {
                            last >= t.min(base) && last <= t + h
                        };
                        assert!(
                            inside,
                            "fmi2Discard (fmi2Terminated {term}): fmi2LastSuccessfulTime = {last} outside the step [{t}, {t} + {h}]"
                        );
                    }
                    if M::STRICT && term != fmi2False {
                        self.stats.steps_terminated += 1;
                    }
                }
            }
            fmi2Error
                if M::STRICT
                    && machine == Some(Machine::StepComplete)
                    && tolerate
                    && known
                    && M::known_refusal(&s.recent) =>
            {
                self.stats.known_overflow += 1;
            }
            fmi2Error if M::STRICT && machine == Some(Machine::StepComplete) => {
                if s.inspect && s.logger {
                    assert!(
                        names_one_of(&s.recent, M::STEP_REFUSAL_NAMES),
                        "fmi2DoStep refused naming neither an input nor the communication point: {:?}",
                        s.recent
                    );
                }
                self.stats.steps_refused += 1;
                if let Some(before) = before {
                    let after = self
                        .get_real(k, M::STATE_OUTPUTS)
                        .expect("the state after a refused step");
                    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                    assert_eq!(
                        bits(&after),
                        bits(&before),
                        "a refused fmi2DoStep changed the state (theta .. yG)"
                    );
                }
            }
            _ => {}
        }
    }

    pub(crate) fn status(&mut self, k: u8, which: u8, kind: c_int) {
        let name = [
            "fmi2GetStatus",
            "fmi2GetRealStatus",
            "fmi2GetIntegerStatus",
            "fmi2GetBooleanStatus",
            "fmi2GetStringStatus",
        ][which as usize % 5];
        let mut st_out: fmi2Status = -1;
        let mut r = f64::NAN;
        let mut i: c_int = -1;
        let mut b: c_int = -1;
        let mut s: fmi2String = ptr::null();
        let Some(st) = self.call(k, name, STATUS, |c| unsafe {
            match which % 5 {
                0 => (M::API.fmi2GetStatus)(c, kind, &mut st_out),
                1 => (M::API.fmi2GetRealStatus)(c, kind, &mut r),
                2 => (M::API.fmi2GetIntegerStatus)(c, kind, &mut i),
                3 => (M::API.fmi2GetBooleanStatus)(c, kind, &mut b),
                _ => (M::API.fmi2GetStringStatus)(c, kind, &mut s),
            }
        }) else {
            return;
        };
        if st == fmi2OK {
            match which % 5 {
                0 => check_status(st_out, "fmi2GetStatus value"),
                1 => assert!(r.is_finite(), "{name}({kind}) = {r}"),
                3 => assert!(b == fmi2True || b == fmi2False, "{name}({kind}) = {b}"),
                // SAFETY: a string of the FMU's.
                4 if !s.is_null() => {
                    let _ = unsafe { CStr::from_ptr(s) }.to_bytes().len();
                }
                _ => {}
            }
        }
        if !(0..=3).contains(&kind) {
            assert!(st == fmi2Error, "{name}({kind}) = {st}: unknown kind");
        }
    }
}

/// The values `x` of the value references `r` the FMU accepted, into the
/// driver's copy of its store (`to`, by value reference).
fn accept<T: Copy>(to: &mut [T], r: &[u32], x: &[T]) {
    for (&r, &x) in r.iter().zip(x) {
        if let Some(v) = to.get_mut(r as usize) {
            *v = x;
        }
    }
}

/// The names of the parameters and calculated parameters (what a refused
/// initialization must name: the physics names a derived one, `IO = inf`,
/// where a huge `hG` overflows it).
pub(crate) fn parameter_names<M: Model>() -> Vec<&'static str> {
    M::VARIABLES
        .iter()
        .filter(|v| {
            matches!(
                v.causality,
                Causality::Parameter | Causality::CalculatedParameter
            )
        })
        .map(|v| v.name)
        .collect()
}
