//! FMU states: `fmi2GetFMUstate` and friends, and their serialized form
//! (the envelope is in `bytes`).

use std::ffi::CString;

use model_description::Type;

use crate::bytes::{self, ByteReader, ByteWriter, ReadError};
use crate::fail::{error, guarded, Res};
use crate::instance::Inner;
use crate::machine::{mask, Machine};
use crate::slave::{Scalar, Setup, Slave};
use crate::types::Status;
use crate::values::start_value;

use Machine as M;

/// A saved FMU state (`fmi2FMUstate` points to one).
pub struct Snapshot<S: Slave> {
    machine: Machine,
    setup: Setup,
    time: f64,
    last_successful_time: f64,
    terminated: bool,
    values: Vec<Option<Scalar>>,
    derivatives: Vec<f64>,
    slave: Option<S::State>,
}

impl<S: Slave> Inner<S> {
    fn snapshot(&self) -> Snapshot<S> {
        Snapshot {
            machine: self.machine,
            setup: self.setup,
            time: self.time,
            last_successful_time: self.last_successful_time,
            terminated: self.terminated,
            values: self.values.clone(),
            derivatives: self.derivatives.clone(),
            // before initialization the model is only a cache of the values
            // (built to evaluate a calculated variable): not saved, as
            // deserialize refuses a model state in state instantiated
            slave: match (&self.slave, self.stale, self.machine) {
                (Some(s), false, m) if m != M::Instantiated => Some(s.state()),
                _ => None,
            },
        }
    }

    /// `fmi2GetFMUstate`: a new state, or `existing` (one of ours) overwritten.
    pub fn get_fmu_state(&mut self, existing: usize) -> Res<usize> {
        self.check_state(mask::fmi2GetFMUstate)?;
        let snap = self.snapshot();
        if existing != 0 {
            if !self.states.contains(&existing) {
                return error(format!(
                    "*FMUstate = {existing:#x} is not a live FMU state of this instance"
                ));
            }
            // SAFETY: the pointer is in our registry: we created it with
            // Box::into_raw and it has not been freed.
            unsafe { *(existing as *mut Snapshot<S>) = snap };
            return Ok(existing);
        }
        let p = Box::into_raw(Box::new(snap)) as usize;
        self.states.insert(p);
        Ok(p)
    }

    fn state_ref(&self, p: usize) -> Res<&Snapshot<S>> {
        if p == 0 || !self.states.contains(&p) {
            return error(format!(
                "FMUstate {p:#x} is not a live FMU state of this instance"
            ));
        }
        // SAFETY: registered pointers come from Box::into_raw and are live.
        Ok(unsafe { &*(p as *const Snapshot<S>) })
    }

    pub fn set_fmu_state(&mut self, p: usize) -> Res<Status> {
        self.check_state(mask::fmi2SetFMUstate)?;
        let snap = self.state_ref(p)?;
        let (machine, setup, time, lst, terminated, slave_state) = (
            snap.machine,
            snap.setup,
            snap.time,
            snap.last_successful_time,
            snap.terminated,
            snap.slave,
        );
        let (values, derivatives) = (snap.values.clone(), snap.derivatives.clone());
        let same_values = self.slave.is_some()
            && !self.stale
            && self.setup == setup
            && self.values.len() == values.len()
            && self.values.iter().zip(&values).all(|(a, b)| match (a, b) {
                (Some(a), Some(b)) => a.same(b),
                (None, None) => true,
                _ => false,
            });
        self.values = values;
        self.derivatives = derivatives;
        self.setup = setup;
        self.time = time;
        self.last_successful_time = lst;
        self.terminated = terminated;
        match slave_state {
            Some(st) => {
                if !same_values {
                    self.stale = true;
                    self.ensure_slave()?;
                }
                let slave = self.slave.as_mut().expect("built above");
                guarded("fmi2SetFMUstate", || {
                    slave.set_state(st);
                    Ok(())
                })?;
            }
            None => {
                self.slave = None;
                self.stale = true;
            }
        }
        self.machine = machine;
        Ok(Status::Ok)
    }

    pub fn free_fmu_state(&mut self, p: usize) -> Res<Status> {
        self.check_state(mask::fmi2FreeFMUstate)?;
        if p == 0 {
            return Ok(Status::Ok);
        }
        self.state_ref(p)?;
        self.states.remove(&p);
        // SAFETY: registered, created by Box::into_raw, now unregistered.
        drop(unsafe { Box::from_raw(p as *mut Snapshot<S>) });
        Ok(Status::Ok)
    }

    fn serialize(&self, snap: &Snapshot<S>) -> Vec<u8> {
        let mut w = ByteWriter::new();
        w.u8(snap.machine.code());
        w.opt_f64(snap.setup.tolerance);
        w.f64(snap.setup.start_time);
        w.opt_f64(snap.setup.stop_time);
        w.f64(snap.time);
        w.f64(snap.last_successful_time);
        w.bool(snap.terminated);
        w.u32(snap.values.len() as u32);
        for v in &snap.values {
            match v {
                None => w.u8(0),
                Some(Scalar::Real(x)) => {
                    w.u8(1);
                    w.f64(*x);
                }
                Some(Scalar::Integer(x)) => {
                    w.u8(2);
                    w.i32(*x);
                }
                Some(Scalar::Boolean(x)) => {
                    w.u8(3);
                    w.bool(*x);
                }
                Some(Scalar::String(s)) => {
                    w.u8(4);
                    w.bytes(s.as_bytes());
                }
            }
        }
        w.u32(snap.derivatives.len() as u32);
        for d in &snap.derivatives {
            w.f64(*d);
        }
        match &snap.slave {
            None => w.u8(0),
            Some(s) => {
                w.u8(1);
                S::write_state(s, &mut w);
            }
        }
        bytes::seal(S::guid(), &w.buf)
    }

    fn deserialize(&self, buf: &[u8]) -> Result<Snapshot<S>, ReadError> {
        let payload = bytes::unseal(S::guid(), buf)?;
        let mut r = ByteReader::new(payload);
        let code = r.u8("machine state")?;
        let machine =
            Machine::from_code(code).ok_or_else(|| format!("invalid machine state {code}"))?;
        if machine == M::Fatal {
            return Err("a state cannot be in state fatal".into());
        }
        // event mode is also FMI 3.0 co-simulation's, with eventModeUsed
        let me_only =
            machine == M::ContinuousTimeMode || (machine == M::EventMode && !self.event_mode_used);
        let cs_only = matches!(machine, M::StepComplete | M::StepFailed);
        if (me_only && !self.model_exchange) || (cs_only && self.model_exchange) {
            return Err(format!(
                "a state in state {} belongs to an instance of the other fmuType",
                machine.name()
            ));
        }
        let tolerance = r.opt_f64("tolerance")?;
        let start_time = r.f64("start time")?;
        let stop_time = r.opt_f64("stop time")?;
        let time = r.f64("time")?;
        let last_successful_time = r.f64("last successful time")?;
        let terminated = r.bool("terminated")?;
        let n = r.u32("number of values")? as usize;
        if n != self.md.variables.len() {
            return Err(format!(
                "{n} values, the model has {} variables",
                self.md.variables.len()
            ));
        }
        let mut values = Vec::with_capacity(n);
        for v in self.md.variables {
            let tag = r.u8("value tag")?;
            let s = match tag {
                0 => None,
                1 => Some(Scalar::Real(r.f64(v.name)?)),
                2 => Some(Scalar::Integer(r.i32(v.name)?)),
                3 => Some(Scalar::Boolean(r.bool(v.name)?)),
                4 => Some(Scalar::String(
                    CString::new(r.bytes(v.name)?.to_vec())
                        .map_err(|_| format!("{}: NUL in string", v.name))?,
                )),
                t => return Err(format!("{}: invalid value tag {t}", v.name)),
            };
            let expected = start_value(v);
            let ok = match (&s, &expected) {
                (None, None) => true,
                (Some(a), Some(b)) => a.base() == b.base(),
                _ => false,
            };
            if !ok {
                return Err(format!("{}: value of the wrong kind", v.name));
            }
            if let (Some(Scalar::Integer(x)), Type::Enumeration { declared_type, .. }) = (&s, v.ty)
            {
                if self
                    .md
                    .enum_type(declared_type)
                    .is_some_and(|t| t.item(*x).is_none())
                {
                    return Err(format!("{} = {x}: not an item of {declared_type}", v.name));
                }
            }
            values.push(s);
        }
        let nd = r.u32("number of derivatives")? as usize;
        if nd != n {
            return Err(format!("{nd} input derivatives, expected {n}"));
        }
        let mut derivatives = Vec::with_capacity(nd);
        for _ in 0..nd {
            derivatives.push(r.f64("input derivative")?);
        }
        let slave = match r.u8("model state tag")? {
            0 => None,
            1 => Some(S::read_state(&mut r)?),
            t => return Err(format!("invalid model state tag {t}")),
        };
        r.finish("serialized FMU state")?;
        if slave.is_some() && machine == M::Instantiated {
            return Err("a model state in state instantiated".into());
        }
        Ok(Snapshot {
            machine,
            setup: Setup {
                tolerance,
                start_time,
                stop_time,
                model_exchange: self.model_exchange,
            },
            time,
            last_successful_time,
            terminated,
            values,
            derivatives,
            slave,
        })
    }

    pub fn serialized_size(&mut self, p: usize) -> Res<usize> {
        self.check_state(mask::fmi2SerializedFMUstateSize)?;
        let snap = self.state_ref(p)?;
        Ok(self.serialize(snap).len())
    }

    pub fn serialize_fmu_state(&mut self, p: usize, out: &mut [u8]) -> Res<Status> {
        self.check_state(mask::fmi2SerializeFMUstate)?;
        let snap = self.state_ref(p)?;
        let bytes = self.serialize(snap);
        if out.len() < bytes.len() {
            return error(format!(
                "size = {} is too small: the serialized state has {} bytes (fmi2SerializedFMUstateSize)",
                out.len(),
                bytes.len()
            ));
        }
        out[..bytes.len()].copy_from_slice(&bytes);
        out[bytes.len()..].fill(0);
        Ok(Status::Ok)
    }

    /// `fmi2DeSerializeFMUstate`: checks the buffer, returns a new state.
    pub fn deserialize_fmu_state(&mut self, buf: &[u8]) -> Res<usize> {
        self.check_state(mask::fmi2DeSerializeFMUstate)?;
        // A buffer may carry trailing zero padding from fmi2SerializeFMUstate
        // with a larger size: the envelope's length field tells the real end.
        let snap = match self.deserialize(buf) {
            Ok(s) => s,
            Err(first) => match trim_padding(buf) {
                Some(t) if t.len() < buf.len() => self.deserialize(t).map_err(|_| first),
                _ => Err(first),
            }
            .or_else(|e| error(format!("refused: {e}")))?,
        };
        let p = Box::into_raw(Box::new(snap)) as usize;
        self.states.insert(p);
        Ok(p)
    }

    /// Frees every FMU state still alive (at fmi2FreeInstance).
    pub(crate) fn free_all_states(&mut self) {
        for p in std::mem::take(&mut self.states) {
            // SAFETY: registered pointers are live boxes created by us.
            drop(unsafe { Box::from_raw(p as *mut Snapshot<S>) });
        }
    }
}

/// The envelope's own length, if the buffer is longer and the rest is zero
/// padding (anything else after the envelope is refused).
fn trim_padding(buf: &[u8]) -> Option<&[u8]> {
    let mut r = ByteReader::new(buf);
    r.u64("magic").ok()?;
    r.u32("version").ok()?;
    let g = r.bytes("guid").ok()?.len();
    let n = r.u64("length").ok()? as usize;
    let total = 8usize
        .checked_add(4)?
        .checked_add(4)?
        .checked_add(g)?
        .checked_add(8)?
        .checked_add(n)?
        .checked_add(4)?;
    let (envelope, rest) = buf.split_at_checked(total)?;
    rest.iter().all(|&b| b == 0).then_some(envelope)
}
