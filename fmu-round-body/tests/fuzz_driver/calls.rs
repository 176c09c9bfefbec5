//! The driver's FMI calls on one instance: life cycle, get/set, stepping,
//! status.

use super::*;
use Machine as M;

impl Driver {
    /// One Model Exchange call; after `fmi2OK` every value written is finite
    /// (the nominals positive), and the driver follows the ME state machine.
    pub(crate) fn model_exchange(&mut self, k: u8, which: u8, x: [f64; 8], n: usize) {
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
        let (what, allowed): (&str, &[M]) = match op {
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
                0 => fmu::fmi2SetTime(c, x[0]),
                1 => fmu::fmi2SetContinuousStates(c, x.as_ptr(), n.min(x.len())),
                2 => fmu::fmi2GetContinuousStates(c, p, n),
                3 => fmu::fmi2GetDerivatives(c, p, n),
                4 => fmu::fmi2GetEventIndicators(c, p, n),
                5 => fmu::fmi2GetNominalsOfContinuousStates(c, p, n),
                6 => fmu::fmi2EnterEventMode(c),
                7 => fmu::fmi2NewDiscreteStates(c, &mut info),
                8 => fmu::fmi2EnterContinuousTimeMode(c),
                _ => fmu::fmi2CompletedIntegratorStep(c, fmi2True, &mut enter, &mut terminate),
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
            6 => self.set_machine(k, Some(M::EventMode)),
            7 => {
                for b in [
                    info.newDiscreteStatesNeeded,
                    info.terminateSimulation,
                    info.valuesOfContinuousStatesChanged,
                ] {
                    assert!(b == fmi2True || b == fmi2False, "{what}: fmi2Boolean {b}");
                }
            }
            8 => self.set_machine(k, Some(M::ContinuousTime)),
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
        let k = k as usize % SLOTS;
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
            Guid::Right => Some(CString::new(fmu::GUID).expect("GUID")),
            Guid::Wrong => Some(c"{00000000-0000-0000-0000-000000000000}".to_owned()),
            Guid::Null => None,
            Guid::Truncated => Some(CString::new(&fmu::GUID[..fmu::GUID.len() - 1]).expect("GUID")),
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
            fmu::fmi2Instantiate(
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
        if let Some(p) = problem(&log, [0; 5], &recent, &name_back, debug) {
            panic!("fmi2Instantiate: logger: {p}");
        }
        let valid = name.as_ref().is_some_and(|n| !n.is_empty())
            && (spec.fmu_type == fmi2CoSimulation
                || (spec.fmu_type == fmi2ModelExchange && model_exchange()))
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
            machine: Some(M::Instantiated),
            stored: Some(Stored::start()),
            time: Some(0.0),
            forged: false,
            states: Vec::new(),
            me: spec.fmu_type == fmi2ModelExchange,
            inspect: spec.inspect,
            recent: Vec::new(),
            derivatives: Some([0.0; 3]),
        });
    }

    pub(crate) fn free(&mut self, k: u8) {
        let k = k as usize % SLOTS;
        if let Some(s) = self.slots[k].take() {
            let before = s.log.counts();
            let p0 = panics();
            // SAFETY: a live instance of ours; its FMU states go with it.
            unsafe { fmu::fmi2FreeInstance(s.c) };
            self.stats.calls += 1;
            assert_eq!(panics(), p0, "fmi2FreeInstance: the FMU panicked");
            let recent = s.log.take();
            if let Some(p) = problem(&s.log, before, &recent, &s.name, s.debug) {
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
            fmu::fmi2SetupExperiment(c, tol_def, tol, start, stop_def, stop)
        }) {
            let tol_ok = tol_def == fmi2False || (tol.is_finite() && tol > 0.0);
            let stop_ok = stop_def == fmi2False || (stop.is_finite() && stop >= start);
            let s = self.slot(k).expect("called");
            if before == Some(M::Instantiated) || st == fmi2OK {
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
                fmu::fmi2EnterInitializationMode(c)
            })
        {
            self.set_machine(k, Some(M::Init));
        }
    }

    pub(crate) fn exit(&mut self, k: u8) {
        let Some(s) = self.slot(k) else { return };
        let expect = (s.machine == Some(M::Init))
            .then(|| s.stored.as_ref().map(Stored::valid))
            .flatten();
        let stored = s.stored.clone();
        let Some(st) = self.call(k, "fmi2ExitInitializationMode", INIT, |c| unsafe {
            fmu::fmi2ExitInitializationMode(c)
        }) else {
            return;
        };
        if let Some(valid) = expect {
            assert_eq!(
                st,
                if valid { fmi2OK } else { fmi2Error },
                "fmi2ExitInitializationMode with parameters {:?}",
                stored.and_then(|s| s.params())
            );
            if valid {
                self.stats.exit_init_ok += 1;
            } else {
                self.stats.exit_init_error += 1;
                let s = self.slot(k).expect("called");
                if s.inspect && s.logger {
                    assert!(
                        names_one_of(&s.recent, &parameter_names()),
                        "fmi2ExitInitializationMode refused without naming a parameter: {:?}",
                        s.recent
                    );
                }
            }
        }
        if st == fmi2OK {
            let me = self.slot(k).is_some_and(|s| s.me);
            self.set_machine(k, Some(if me { M::EventMode } else { M::StepComplete }));
        }
    }

    pub(crate) fn set_real(&mut self, k: u8, r: &[u32], x: &[f64]) {
        let m = self.machine(k);
        let st = self.call(k, "fmi2SetReal", SET, |c| unsafe {
            fmu::fmi2SetReal(c, r.as_ptr(), r.len(), x.as_ptr())
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
                    if let Some(i) = INPUTS.iter().position(|p| p == q) {
                        d[i] = 0.0;
                    }
                }
            }
        }
    }

    pub(crate) fn set_integer(&mut self, k: u8, r: &[u32], x: &[c_int]) {
        let m = self.machine(k);
        let st = self.call(k, "fmi2SetInteger", SET, |c| unsafe {
            fmu::fmi2SetInteger(c, r.as_ptr(), r.len(), x.as_ptr())
        });
        self.refusal_names_a_target(k, "fmi2SetInteger", m, st, r);
        if let Some(fmi2OK) = st {
            if let Some(st) = self.slot(k).expect("called").stored.as_mut() {
                accept(&mut st.int, r, x);
            }
        }
    }

    /// fmi2GetReal with the value checks; the values after fmi2OK.
    pub(crate) fn get_real(&mut self, k: u8, r: &[u32]) -> Option<Vec<f64>> {
        let mut out = vec![f64::from_bits(SENTINEL); r.len()];
        let st = self.call(k, "fmi2GetReal", GET, |c| unsafe {
            fmu::fmi2GetReal(c, r.as_ptr(), r.len(), out.as_mut_ptr())
        })?;
        if st != fmi2OK && st != fmi2Warning {
            return None;
        }
        let params = || {
            let s = self.slots[k as usize % SLOTS].as_ref();
            format!(
                "{:?}",
                s.and_then(|s| s.stored.as_ref()).and_then(Stored::params)
            )
        };
        for (&r, &x) in r.iter().zip(&out) {
            assert_ne!(x.to_bits(), SENTINEL, "fmi2GetReal: vr {r} not written");
            let v = VARIABLES.iter().find(|v| v.vr == r).expect("a Real vr");
            // no computed value crosses the boundary non-finite:
            // frictionDemand while Fz <= 0 stands at 1e60
            // (docs/round-body.md); parameters and inputs are the host's
            // own values, echoed
            let finite = match v.causality {
                Causality::Output | Causality::CalculatedParameter | Causality::Local => {
                    x.is_finite()
                }
                _ => true,
            };
            assert!(finite, "{} = {x} with parameters {}", v.name, params());
            if let Some(p) = value_problem(r, x) {
                panic!("{p} with parameters {}", params());
            }
        }
        let of = |v: u32| r.iter().position(|&q| q == v).map(|i| out[i]);
        if let (Some(theta), Some(ex), Some(ey)) = (of(vr::THETA), of(vr::EX), of(vr::EY)) {
            // theta = asin(sqrt(ex^2 + ey^2)) (docs/round-body.md), to
            // rounding: asin's slope is 1/cos(theta)
            let want = ex.hypot(ey).min(1.0).asin();
            let tol = 1e-12 / theta.cos().max(1e-6);
            assert!(
                (theta - want).abs() <= tol,
                "theta = {theta}, asin(|(ex, ey)|) = {want} (ex = {ex}, ey = {ey})"
            );
        }
        if let (Some(alpha), Some(theta_ov)) = (of(vr::ALPHA), of(vr::THETA_OV)) {
            // on the rigid bed the body overturns at alpha
            assert_eq!(alpha, theta_ov, "alpha and thetaOv differ");
        }
        Some(out)
    }

    pub(crate) fn get_integer(&mut self, k: u8, r: &[u32]) {
        let mut out: Vec<c_int> = vec![0x5eed_f00d; r.len()];
        if let Some(fmi2OK) = self.call(k, "fmi2GetInteger", GET, |c| unsafe {
            fmu::fmi2GetInteger(c, r.as_ptr(), r.len(), out.as_mut_ptr())
        }) {
            for (&r, &x) in r.iter().zip(&out) {
                match r {
                    vr::REGIME => assert!(x == enums::REST || x == enums::ROCKING, "regime = {x}"),
                    vr::IMPACTS => assert!(x >= 0, "impacts = {x}"),
                    _ => assert_ne!(x, 0x5eed_f00d, "fmi2GetInteger: vr {r} not written"),
                }
            }
        }
    }

    pub(crate) fn get_boolean(&mut self, k: u8, r: &[u32]) {
        let mut out: Vec<c_int> = vec![-7; r.len()];
        if let Some(fmi2OK) = self.call(k, "fmi2GetBoolean", GET, |c| unsafe {
            fmu::fmi2GetBoolean(c, r.as_ptr(), r.len(), out.as_mut_ptr())
        }) {
            for (&r, &x) in r.iter().zip(&out) {
                assert!(x == fmi2True || x == fmi2False, "Boolean vr {r} = {x}");
            }
        }
    }

    pub(crate) fn get_all(&mut self, k: u8) {
        let of = |base: BaseType| -> Vec<u32> {
            VARIABLES
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
        // The FMU's time: asked where it answers, else the driver's own.
        let mut now = s.time;
        if matches!(
            machine,
            Some(M::StepComplete | M::StepFailed | M::Terminated)
        ) {
            let mut t = f64::NAN;
            if let Some(fmi2OK) = self.call(k, "fmi2GetRealStatus", STATUS, |c| unsafe {
                fmu::fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &mut t)
            }) {
                assert!(t.is_finite(), "fmi2LastSuccessfulTime = {t}");
                if let Some(d) = now {
                    assert_eq!(t.to_bits(), d.to_bits(), "fmi2LastSuccessfulTime");
                }
                now = Some(t);
            }
        }
        let base = now.unwrap_or(0.0);
        let t = match point {
            Point::Matching => base,
            Point::Offset(d) => base + d,
            Point::Raw(x) => x,
        };
        // the state before: a refused step must leave it
        let before = if machine == Some(M::StepComplete) {
            self.get_real(k, &STATE_OUTPUTS)
        } else {
            None
        };
        // the inputs over the step, where the driver knows their slopes
        let inputs = if before.is_some() {
            self.get_real(k, &INPUTS)
        } else {
            None
        };
        let derivatives = self.slot(k).and_then(|s| s.derivatives);
        let huge_input = match (inputs, derivatives) {
            (Some(x), Some(d)) => (0..3).any(|i| {
                x[i].abs().max((x[i] + d[i] * h).abs()) >= KNOWN_OVERFLOW || !h.is_finite()
            }),
            _ => true,
        };
        let extreme = before.is_some() && self.extreme_body(k);
        let machine = self.slot(k).and_then(|s| s.machine);
        let tolerate = self.tolerate_known_overflow;
        if std::env::var_os("FUZZ_DRIVER_TRACE").is_some() {
            let s = self.slots[k as usize % SLOTS].as_ref();
            let params = s.and_then(|s| s.stored.as_ref()).and_then(Stored::params);
            eprintln!("fmi2DoStep({t}, {h}) on slot {k}: state {before:?}, parameters {params:?}");
        }
        let Some(st) = self.call(k, "fmi2DoStep", DO_STEP, |c| unsafe {
            fmu::fmi2DoStep(c, t, h, no_prior)
        }) else {
            return;
        };
        let s = self.slot(k).expect("called");
        if !(t.is_finite() && h.is_finite() && h > 0.0) {
            assert_eq!(st, fmi2Error, "fmi2DoStep({t}, {h})");
        }
        match st {
            fmi2OK => {
                s.machine = Some(M::StepComplete);
                s.time = Some(t + h);
                self.stats.steps_ok += 1;
            }
            fmi2Discard => {
                s.machine = Some(M::StepFailed);
                s.time = None;
                self.stats.steps_discard += 1;
                let mut term = fmi2False;
                if let Some(fmi2OK) = self.call(k, "fmi2GetBooleanStatus", STATUS, |c| unsafe {
                    fmu::fmi2GetBooleanStatus(c, fmi2Terminated, &mut term)
                }) {
                    let mut last = f64::NAN;
                    if let Some(fmi2OK) = self.call(k, "fmi2GetRealStatus", STATUS, |c| unsafe {
                        fmu::fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &mut last)
                    }) {
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
                    if term != fmi2False {
                        self.stats.steps_terminated += 1;
                    }
                }
            }
            fmi2Error
                if machine == Some(M::StepComplete)
                    && tolerate
                    && (huge_input || extreme || t.abs().max(h) >= 1e15)
                    && s.recent.iter().any(|m| m.text.contains(NON_FINITE_STATE)) =>
            {
                // the known findings (tests/fmi2_fuzz.rs, finding_*)
                self.stats.known_overflow += 1;
            }
            fmi2Error if machine == Some(M::StepComplete) => {
                if s.inspect && s.logger {
                    assert!(
                        names_one_of(
                            &s.recent,
                            &["agx", "agy", "av", "currentCommunicationPoint", "stopTime"]
                        ),
                        "fmi2DoStep refused naming neither an input nor the communication point: {:?}",
                        s.recent
                    );
                }
                self.stats.steps_refused += 1;
                if let Some(before) = before {
                    let after = self
                        .get_real(k, &STATE_OUTPUTS)
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

    /// Whether the body is one of the known finding's absurd ones
    /// ([`Driver::tolerate_known_overflow`]): mass, R0, IO or g outside
    /// 1e-30..1e30, an initial angular velocity of 1e15 rad/s or more
    /// (g = 5e-324 m/s2 with omegaZ0 = 1e300 rad/s and av = 2 m/s2 gives
    /// the non-finite state), or an inertia about the centre of mass (Ic,
    /// or the axial one) beyond 1e-12..1e12 times m R0^2.
    pub(crate) fn extreme_body(&mut self, k: u8) -> bool {
        let Some(x) = self.get_real(k, &[vr::MASS, vr::R0, vr::IO]) else {
            return true;
        };
        let Some(stored) = self.slot(k).and_then(|s| s.stored.clone()) else {
            return true;
        };
        let [m, r0, io] = [x[0], x[1], x[2]];
        let r = |q: u32| stored.real[q as usize];
        let m_r0 = m * r0 * r0;
        let axial = if stored.int[vr::MASS_MODEL as usize] == enums::LUMPED {
            r(vr::IC_AXIAL)
        } else {
            let ri = if stored.int[vr::SHAPE as usize] == enums::HOLLOW_CIRCLE {
                r(vr::RI)
            } else {
                0.0
            };
            m * (r(vr::RO).powi(2) + ri * ri) / 2.0
        };
        let out = |x: f64, lo: f64, hi: f64| !(lo..=hi).contains(&x);
        let spin = [vr::OMEGA_X0, vr::OMEGA_Y0, vr::OMEGA_Z0]
            .iter()
            .any(|&q| r(q).abs() >= 1e15);
        spin || [m, r0, io, r(vr::G)].iter().any(|&x| out(x, 1e-30, 1e30))
            || out((io - m_r0) / m_r0, 1e-12, 1e12)
            || out(axial / m_r0, 1e-12, 1e12)
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
                0 => fmu::fmi2GetStatus(c, kind, &mut st_out),
                1 => fmu::fmi2GetRealStatus(c, kind, &mut r),
                2 => fmu::fmi2GetIntegerStatus(c, kind, &mut i),
                3 => fmu::fmi2GetBooleanStatus(c, kind, &mut b),
                _ => fmu::fmi2GetStringStatus(c, kind, &mut s),
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

/// The outputs of the state alone (theta .. yG): they do not depend on the
/// inputs, so they read back whatever the inputs are.
pub(crate) const STATE_OUTPUTS: [u32; 10] = [
    vr::THETA,
    vr::PSI,
    vr::THETA_OVER_ALPHA,
    vr::EX,
    vr::EY,
    vr::OMEGA_X,
    vr::OMEGA_Y,
    vr::OMEGA_Z,
    vr::XG,
    vr::YG,
];

/// What is wrong with the value `x` of the computed Real `r` read with
/// fmi2OK (docs/round-body.md's ranges), if anything.
pub(crate) fn value_problem(r: u32, x: f64) -> Option<String> {
    use std::f64::consts::{FRAC_PI_2, PI};
    let ok = match r {
        vr::THETA => (0.0..=FRAC_PI_2).contains(&x),
        vr::PSI => x > -PI && x <= PI,
        vr::EX | vr::EY => x.abs() <= 1.0,
        vr::THETA_OVER_ALPHA => x >= 0.0,
        vr::FRICTION_DEMAND => (0.0..=UNBOUNDED).contains(&x),
        vr::MASS | vr::WEIGHT | vr::R0 | vr::IO => x > 0.0,
        // atan(Ro/hG): pi/2 where hG underflows to 0 (H = 5e-324)
        vr::ALPHA | vr::THETA_OV => x > 0.0 && x <= FRAC_PI_2,
        vr::ETA_HOUSNER => x <= 1.0,
        _ => true,
    };
    let name = VARIABLES.iter().find(|v| v.vr == r).map_or("?", |v| v.name);
    (!ok).then(|| format!("{name} = {x} is outside its range"))
}

/// The names of the parameters and calculated parameters (what a refused
/// initialization must name: the physics names a derived one, `IO = inf`,
/// where a huge `hG` overflows it).
pub(crate) fn parameter_names() -> Vec<&'static str> {
    VARIABLES
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
