//! The driver's FMU-state calls: get, set, free, serialize, deserialize.

use crate::*;

impl<M: Model> Driver<M> {
    /// The state `r` names, if it exists: (pointer, owner slot, index).
    pub(crate) fn lookup_state(&self, r: StateRef) -> Option<(fmi2FMUstate, usize, usize)> {
        match r {
            StateRef::Null => Some((ptr::null_mut(), usize::MAX, usize::MAX)),
            StateRef::Of { slot, k } => {
                let owner = slot as usize % M::SLOTS;
                let s = self.slots[owner].as_ref()?;
                if s.states.is_empty() {
                    return None;
                }
                let i = k as usize % s.states.len();
                Some((s.states[i].p, owner, i))
            }
        }
    }

    /// For a call on slot `k` with the state `r`: the state's (pointer,
    /// owner slot, index) and whether slot `k` owns it; `None` if the slot is
    /// empty or the state does not exist.
    fn state_for(&self, k: u8, r: StateRef) -> Option<(fmi2FMUstate, usize, usize, bool)> {
        self.slots[k as usize % M::SLOTS].as_ref()?;
        let (p, owner, i) = self.lookup_state(r)?;
        Some((p, owner, i, owner == k as usize % M::SLOTS))
    }

    /// What the driver knows of slot `k` now, with its outputs read if that
    /// cannot fail (the model exists and its parameters are valid).
    pub(crate) fn know(&mut self, k: u8) -> Known {
        let Some(s) = self.slot(k) else {
            return Known::unknown();
        };
        let outputs = if matches!(
            s.machine,
            Some(Machine::StepComplete | Machine::StepFailed | Machine::Terminated)
        ) {
            self.get_real(k, &real_outputs::<M>())
                .map(|v| v.iter().map(|x| x.to_bits()).collect())
        } else {
            None
        };
        let s = self.slot(k).expect("exists");
        Known {
            machine: s.machine,
            stored: s.stored.clone(),
            outputs,
        }
    }

    pub(crate) fn get_state(&mut self, k: u8, reuse: Option<u8>) {
        let Some(s) = self.slot(k) else { return };
        if s.states.len() >= MAX_STATES && reuse.is_none() {
            // Keep the number bounded: free the oldest instead.
            self.free_state(k, StateRef::Of { slot: k, k: 0 });
            return;
        }
        let (mut p, index) = match reuse {
            Some(i) if !s.states.is_empty() => {
                let i = i as usize % s.states.len();
                (s.states[i].p, Some(i))
            }
            _ => (ptr::null_mut(), None),
        };
        let known = self.know(k);
        let Some(st) = self.call(k, "fmi2GetFMUstate", ANY, |c| unsafe {
            (M::API.fmi2GetFMUstate)(c, &mut p)
        }) else {
            return;
        };
        assert_eq!(st, fmi2OK, "fmi2GetFMUstate");
        assert!(!p.is_null(), "fmi2GetFMUstate gave NULL");
        let s = self.slot(k).expect("called");
        let state = FmuState {
            p,
            genuine: true,
            known,
        };
        match index {
            Some(i) => {
                assert_eq!(p, s.states[i].p, "fmi2GetFMUstate moved a reused state");
                s.states[i] = state;
            }
            None => s.states.push(state),
        }
    }

    pub(crate) fn set_state(&mut self, k: u8, r: StateRef) {
        let Some((p, owner, i, own)) = self.state_for(k, r) else {
            return;
        };
        let state = own.then(|| {
            let s = &self.slots[owner].as_ref().expect("owner").states[i];
            (s.genuine, s.known.clone())
        });
        let Some(st) = self.call(k, "fmi2SetFMUstate", ANY, |c| unsafe {
            (M::API.fmi2SetFMUstate)(c, p)
        }) else {
            return;
        };
        let Some((genuine, known)) = state else {
            assert_eq!(
                st, fmi2Error,
                "fmi2SetFMUstate with a state not of this instance"
            );
            return;
        };
        if genuine {
            assert_eq!(st, fmi2OK, "fmi2SetFMUstate of a live own state");
        }
        if st != fmi2OK {
            return;
        }
        let s = self.slot(k).expect("called");
        s.machine = known.machine;
        s.stored = known.stored.clone();
        s.time = None;
        s.forged = !genuine;
        s.derivatives = None;
        if let Some(before) = known.outputs {
            let now = self
                .get_real(k, &real_outputs::<M>())
                .expect("outputs after restoring a state where they were read");
            let now: Vec<u64> = now.iter().map(|x| x.to_bits()).collect();
            assert_eq!(
                now, before,
                "outputs after fmi2SetFMUstate differ from when it was taken"
            );
            self.stats.restores_checked += 1;
        }
    }

    pub(crate) fn free_state(&mut self, k: u8, r: StateRef) {
        let Some((p, _, i, own)) = self.state_for(k, r) else {
            return;
        };
        let mut q = p;
        let Some(st) = self.call(k, "fmi2FreeFMUstate", ANY, |c| unsafe {
            (M::API.fmi2FreeFMUstate)(c, &mut q)
        }) else {
            return;
        };
        if p.is_null() {
            assert_eq!(st, fmi2OK, "fmi2FreeFMUstate(NULL) is ignored");
        } else if own {
            assert_eq!(st, fmi2OK, "fmi2FreeFMUstate of a live own state");
            assert!(q.is_null(), "fmi2FreeFMUstate leaves the pointer set");
            self.slot(k).expect("called").states.remove(i);
        } else {
            assert_eq!(
                st, fmi2Error,
                "fmi2FreeFMUstate of another instance's state"
            );
            assert_eq!(q, p, "a refused fmi2FreeFMUstate changed the pointer");
        }
    }

    pub(crate) fn serialize(&mut self, k: u8, r: StateRef, size_mode: u8) {
        let Some((p, owner, i, own)) = self.state_for(k, r) else {
            return;
        };
        let own = own && !p.is_null();
        let mut size: usize = usize::MAX;
        let Some(st) = self.call(k, "fmi2SerializedFMUstateSize", ANY, |c| unsafe {
            (M::API.fmi2SerializedFMUstateSize)(c, p, &mut size)
        }) else {
            return;
        };
        if !own {
            assert_eq!(
                st, fmi2Error,
                "fmi2SerializedFMUstateSize of a foreign state"
            );
            return;
        }
        assert_eq!(st, fmi2OK, "fmi2SerializedFMUstateSize of a live own state");
        assert!(size > 0 && size < 1 << 20, "serialized size {size}");
        let len = match size_mode % 3 {
            0 => size,
            1 => size - 1,
            _ => size + 17,
        };
        let mut buf = vec![0xa5u8; len];
        let Some(st) = self.call(k, "fmi2SerializeFMUstate", ANY, |c| unsafe {
            (M::API.fmi2SerializeFMUstate)(c, p, buf.as_mut_ptr() as *mut fmi2Byte, len)
        }) else {
            return;
        };
        if len < size {
            assert_eq!(
                st, fmi2Error,
                "fmi2SerializeFMUstate into {len} < {size} bytes"
            );
            return;
        }
        assert_eq!(st, fmi2OK, "fmi2SerializeFMUstate of a live own state");
        assert!(buf[size..].iter().all(|&b| b == 0), "padding is zero");
        let s = &self.slots[owner].as_ref().expect("owner").states[i];
        let known = s.genuine.then(|| s.known.clone());
        if self.pool.len() >= POOL {
            self.pool.remove(0);
        }
        let me = self.slots[owner].as_ref().is_some_and(|o| o.me);
        self.pool.push(Blob {
            bytes: buf,
            known,
            me,
        });
    }

    pub(crate) fn deserialize(&mut self, k: u8, from: u8, m: &Mutation) {
        if self.slot(k).is_none() {
            return;
        }
        let (mut bytes, known, source_me) = match m {
            Mutation::Random(b) => (b.clone(), None, false),
            _ if self.pool.is_empty() => (Vec::new(), None, false),
            _ => {
                let blob = &self.pool[from as usize % self.pool.len()];
                (blob.bytes.clone(), blob.known.clone(), blob.me)
            }
        };
        // a state of one fmuType's own states does not restore into an
        // instance of the other (fmu_state.rs)
        let target_me = self.slot(k).is_some_and(|s| s.me);
        let fits = known.as_ref().is_some_and(|kn| match kn.machine {
            Some(Machine::EventMode | Machine::ContinuousTime) => target_me,
            Some(Machine::StepComplete | Machine::StepFailed) => !target_me,
            Some(_) => true,
            None => source_me == target_me,
        });
        let genuine = fits && matches!(m, Mutation::None);
        match m {
            Mutation::None | Mutation::Random(_) => {}
            Mutation::Flip { pos, bit } => {
                if !bytes.is_empty() {
                    let i = *pos as usize % bytes.len();
                    bytes[i] ^= 1 << (bit % 8);
                }
            }
            Mutation::Truncate(n) => {
                let n = *n as usize % (bytes.len() + 1);
                bytes.truncate(n);
            }
            Mutation::Append(extra) => bytes.extend_from_slice(extra),
            Mutation::Reseal { edits, cut, extend } => {
                let mut payload = match trim(&bytes).and_then(|t| bytes::unseal(M::GUID, t).ok()) {
                    Some(p) => p.to_vec(),
                    None => bytes.clone(),
                };
                if !payload.is_empty() {
                    for &(pos, val) in edits {
                        let i = pos as usize % payload.len();
                        payload[i] = val;
                    }
                }
                let keep = payload.len().saturating_sub(*cut as usize);
                payload.truncate(keep);
                payload.extend_from_slice(extend);
                bytes = bytes::seal(M::GUID, &payload);
            }
        }
        let mut p: fmi2FMUstate = ptr::null_mut();
        let Some(st) = self.call(k, "fmi2DeSerializeFMUstate", ANY, |c| unsafe {
            (M::API.fmi2DeSerializeFMUstate)(
                c,
                bytes.as_ptr() as *const fmi2Byte,
                bytes.len(),
                &mut p,
            )
        }) else {
            return;
        };
        if genuine {
            assert_eq!(
                st, fmi2OK,
                "fmi2DeSerializeFMUstate of an unmodified buffer"
            );
        }
        if st != fmi2OK {
            assert!(p.is_null(), "a refused buffer gave a state");
            return;
        }
        assert!(!p.is_null());
        self.stats.deserialized += 1;
        let known = if genuine {
            known.expect("genuine")
        } else {
            Known::unknown()
        };
        self.slot(k)
            .expect("called")
            .states
            .push(FmuState { p, genuine, known });
        // Serializing it again gives the same bytes (up to zero padding).
        let mut size = 0usize;
        let st = self.call(k, "fmi2SerializedFMUstateSize", ANY, |c| unsafe {
            (M::API.fmi2SerializedFMUstateSize)(c, p, &mut size)
        });
        assert_eq!(
            st,
            Some(fmi2OK),
            "fmi2SerializedFMUstateSize of a deserialized state"
        );
        let mut again = vec![0u8; size];
        let st = self.call(k, "fmi2SerializeFMUstate", ANY, |c| unsafe {
            (M::API.fmi2SerializeFMUstate)(c, p, again.as_mut_ptr() as *mut fmi2Byte, size)
        });
        assert_eq!(
            st,
            Some(fmi2OK),
            "fmi2SerializeFMUstate of a deserialized state"
        );
        let mismatch = (0..size.min(bytes.len())).find(|&i| again[i] != bytes[i]);
        let nonzero_tail = bytes
            .get(size..)
            .map_or(0, |t| t.iter().filter(|&&b| b != 0).count());
        assert!(
            bytes.len() >= size && mismatch.is_none() && nonzero_tail == 0,
            "a deserialized state serializes to other bytes: {} bytes in, {size} out, first difference at {mismatch:?}, {nonzero_tail} non-zero bytes after the envelope",
            bytes.len()
        );
        // Keep the number bounded.
        if self.slot(k).expect("called").states.len() > MAX_STATES {
            self.free_state(k, StateRef::Of { slot: k, k: 0 });
        }
    }
}

/// The envelope without trailing zero padding (by its own length field).
pub(crate) fn trim(buf: &[u8]) -> Option<&[u8]> {
    // magic 8, version 4, GUID length 4 + bytes, payload length 8, payload, CRC 4
    let g = u32::from_le_bytes(buf.get(12..16)?.try_into().ok()?) as usize;
    let at = 16usize.checked_add(g)?;
    let n = u64::from_le_bytes(buf.get(at..at + 8)?.try_into().ok()?) as usize;
    let total = at.checked_add(8)?.checked_add(n)?.checked_add(4)?;
    buf.get(..total)
}
