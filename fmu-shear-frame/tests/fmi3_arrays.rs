//! ShearFrame's FMI 3.0 arrays through the exported C functions: `n` is a
//! `UInt64` structural parameter set in configuration mode only, within 1
//! to 20; an array's value reference stands for its `n` elements, so
//! `nValues` must count them, and a wrong count (or an element's own value
//! reference) is refused with `fmi3Error` and one logged line naming the
//! array and its size, never a crash. The sizes are checked against the
//! standard's rule (nValues = the sum of the variables' element counts),
//! counted here by hand.

use std::ffi::{c_char, c_void, CStr, CString};
use std::ptr;

use fmu_shear_frame::description::vr;
use fmu_shear_frame::*;
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

const OK: i32 = 0;
const ERROR: i32 = 3;
/// `ag`, `time`, `der(ag)`: one value each.
const SCALARS: [u32; 3] = [vr::AG, vr::PERIOD + 21, vr::PERIOD + 22];
/// The nine arrays and `der(Fx)`, `der(Fz)`: n values each.
const ARRAYS: [u32; 11] = [
    vr::M + 1,
    vr::K + 1,
    vr::FX + 1,
    vr::FZ + 1,
    vr::U + 1,
    vr::V + 1,
    vr::A + 1,
    vr::DRIFT + 1,
    vr::PERIOD + 1,
    DER_FX,
    DER_FX + 20,
];

/// `time` is one past the table's largest value reference (`period[20]`);
/// `der(ag)` follows, then `der(Fx)` (its 20 elements), then `der(Fz)`.
const DER_FX: u32 = vr::PERIOD + 20 + 3;

unsafe extern "C" fn collect(env: *mut c_void, _s: i32, _c: *const c_char, m: *const c_char) {
    // SAFETY: env is the Vec this test passed; m a C string from the FMU.
    unsafe {
        let log = &mut *(env as *mut Vec<String>);
        log.push(CStr::from_ptr(m).to_string_lossy().into_owned());
    }
}

/// One co-simulation instance and its log.
struct Frame {
    c: *mut c_void,
    // boxed: the FMU holds its address, which must survive moves of `Frame`
    #[allow(clippy::box_collection)]
    log: Box<Vec<String>>,
}

impl Frame {
    fn new() -> Frame {
        let mut log = Box::new(Vec::new());
        let env = &mut *log as *mut Vec<String> as *mut c_void;
        let token = CString::new(GUID).unwrap();
        // SAFETY: valid strings and callback; freed in Drop.
        let c = unsafe {
            fmi3InstantiateCoSimulation(
                c"frame".as_ptr(),
                token.as_ptr(),
                ptr::null(),
                false,
                false,
                false,
                false,
                ptr::null(),
                0,
                env,
                Some(collect),
                ptr::null(),
            )
        };
        assert!(!c.is_null());
        Frame { c, log }
    }

    /// Configured with `n` storeys and initialized.
    fn with(n: u64) -> Frame {
        let f = Frame::new();
        unsafe {
            assert_eq!(fmi3EnterConfigurationMode(f.c), OK);
            assert_eq!(fmi3SetUInt64(f.c, &vr::N, 1, &n, 1), OK, "{:?}", f.log);
            assert_eq!(fmi3ExitConfigurationMode(f.c), OK);
            assert_eq!(
                fmi3EnterInitializationMode(f.c, false, 0.0, 0.0, false, 0.0),
                OK
            );
            assert_eq!(fmi3ExitInitializationMode(f.c), OK, "{:?}", f.log);
        }
        f
    }

    fn get(&self, vrs: &[u32], n_values: usize) -> (i32, Vec<f64>) {
        let mut out = vec![0.0; n_values];
        let s =
            unsafe { fmi3GetFloat64(self.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr(), n_values) };
        (s, out)
    }

    fn set(&self, vrs: &[u32], values: &[f64]) -> i32 {
        unsafe {
            fmi3SetFloat64(
                self.c,
                vrs.as_ptr(),
                vrs.len(),
                values.as_ptr(),
                values.len(),
            )
        }
    }

    /// The one line the last refused call logged.
    fn refused(&self, before: usize) -> &str {
        assert_eq!(self.log.len(), before + 1, "{:?}", self.log);
        self.log.last().unwrap()
    }
}

impl Drop for Frame {
    fn drop(&mut self) {
        unsafe { fmi3FreeInstance(self.c) }
    }
}

#[test]
fn arrays_have_n_elements_and_wrong_counts_are_refused_by_name() {
    let first = |base: u32| vr::at(base, 1);
    // right counts: 1 (ag) + 4 (Fx) + 4 (der(Fx)), and a whole array of outputs
    let f = Frame::with(4);
    let forces = [1.0e3, 2.0e3, 3.0e3, 4.0e3];
    let mut values = vec![0.5];
    values.extend(forces);
    values.extend([0.0; 4]);
    assert_eq!(
        f.set(&[vr::AG, first(vr::FX), DER_FX], &values),
        OK,
        "{:?}",
        f.log
    );
    let (s, got) = f.get(&[first(vr::FX), vr::AG], 5);
    assert_eq!(s, OK);
    assert_eq!(got, [forces.as_slice(), &[0.5]].concat());
    let (s, a) = f.get(&[first(vr::A)], 4);
    assert_eq!(s, OK);
    assert!(a.iter().all(|x| x.is_finite() && *x != 0.0), "{a:?}");
    // each wrong count on a fresh instance (a refused call leaves the error state)
    for (vrs, n_values, names) in [
        (vec![first(vr::A)], 3, "a has 4 elements"),
        (vec![first(vr::A)], 5, "a has 4 elements"),
        (vec![vr::AG, first(vr::U)], 4, "u has 4 elements"),
        (
            vec![first(vr::U), first(vr::V)],
            4,
            "u has 4, v has 4 elements",
        ),
        (vec![DER_FX], 1, "der(Fx) has 4 elements"),
    ] {
        let f = Frame::with(4);
        let (s, _) = f.get(&vrs, n_values);
        assert_eq!(s, ERROR, "{vrs:?} {n_values}");
        let line = f.refused(0);
        assert!(line.contains(&format!("nValues = {n_values}")), "{line}");
        assert!(line.contains(names) && line.contains("n = 4"), "{line}");
    }
    let f = Frame::with(4);
    assert_eq!(f.set(&[first(vr::FX)], &forces[..3]), ERROR);
    assert!(f.refused(0).contains("Fx has 4 elements"), "{:?}", f.log);
    // an element's own value reference is no 3.0 variable
    let f = Frame::with(4);
    assert_eq!(f.get(&[vr::at(vr::FX, 2)], 1).0, ERROR);
    let line = f.refused(0);
    assert!(
        line.contains("element 2 of Fx") && line.contains("301"),
        "{line}"
    );
}

#[test]
fn n_is_set_in_configuration_mode_only_within_1_to_20() {
    let f = Frame::new();
    let set = |n: u64| unsafe { fmi3SetUInt64(f.c, &vr::N, 1, &n, 1) };
    assert_eq!(set(5), ERROR);
    assert!(f.refused(0).contains("configuration mode"), "{:?}", f.log);
    unsafe { assert_eq!(fmi3Reset(f.c), OK) };
    unsafe { assert_eq!(fmi3EnterConfigurationMode(f.c), OK) };
    for bad in [0, 21] {
        let before = f.log.len();
        assert_eq!(set(bad), ERROR);
        assert!(f
            .refused(before)
            .contains(&format!("n = {bad}: must be 1 to 20")));
        unsafe { assert_eq!(fmi3Reset(f.c), OK) };
        unsafe { assert_eq!(fmi3EnterConfigurationMode(f.c), OK) };
    }
    assert_eq!(set(7), OK);
    // n is no Int32 in 3.0; a 2.0 function is no configuration-mode call
    let (mut i, before) = (0i32, f.log.len());
    assert_eq!(unsafe { fmi3GetInt32(f.c, &vr::N, 1, &mut i, 1) }, ERROR);
    assert!(f.refused(before).contains("no Int32"), "{:?}", f.log);
    let f = Frame::with(7);
    let mut n = 0u64;
    assert_eq!(unsafe { fmi3GetUInt64(f.c, &vr::N, 1, &mut n, 1) }, OK);
    assert_eq!(n, 7);
    assert_eq!(f.get(&[vr::at(vr::PERIOD, 1)], 7).0, OK);
    assert_eq!(unsafe { fmi3EnterConfigurationMode(f.c) }, ERROR);
    assert!(f.refused(0).contains("only in instantiated"), "{:?}", f.log);
}

#[test]
fn a_null_values_pointer_is_refused_not_dereferenced() {
    let f = Frame::with(3);
    let s = unsafe { fmi3GetFloat64(f.c, &vr::at(vr::A, 1), 1, ptr::null_mut(), 3) };
    assert_eq!(s, ERROR);
    assert!(f.refused(0).contains("values"), "{:?}", f.log);
}

/// A value reference the host may pass: a scalar, an array, or an array's
/// element past the first (no 3.0 variable), by index into the lists above.
#[derive(Clone, Copy, Debug)]
enum Ref {
    Scalar(usize),
    Array(usize),
    Element(usize, u32),
}

fn any_ref() -> impl Strategy<Value = Ref> {
    prop_oneof![
        1 => (0..SCALARS.len()).prop_map(Ref::Scalar),
        4 => (0..ARRAYS.len()).prop_map(Ref::Array),
        1 => ((0..ARRAYS.len()), 1..20u32).prop_map(|(a, k)| Ref::Element(a, k)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 256,
        rng_seed: RngSeed::Fixed(0x5348_4652),
        ..ProptestConfig::default()
    })]

    /// fmi3GetFloat64 on random lists: `fmi3OK` exactly when no element is
    /// among them and nValues is the count the standard gives (n per array,
    /// 1 per scalar), else `fmi3Error` with one logged line; never a crash.
    /// With the right count, `Fx` reads back what was set, element by element.
    #[test]
    fn get_float64_counts_n_per_array(
        n in 1..=20u64,
        refs in proptest::collection::vec(any_ref(), 0..6),
        off in prop_oneof![3 => Just(0i64), 1 => -3..=3i64],
    ) {
        let f = Frame::with(n);
        let forces: Vec<f64> = (1..=n).map(|i| 100.0 * i as f64).collect();
        prop_assert_eq!(f.set(&[vr::FX + 1], &forces), OK);
        let (mut vrs, mut count, mut element) = (vec![], 0usize, false);
        for r in &refs {
            match *r {
                Ref::Scalar(i) => { vrs.push(SCALARS[i]); count += 1 }
                Ref::Array(i) => { vrs.push(ARRAYS[i]); count += n as usize }
                Ref::Element(i, k) => { vrs.push(ARRAYS[i] + k); element = true }
            }
        }
        let n_values = (count as i64 + off).max(0) as usize;
        let (s, got) = f.get(&vrs, n_values);
        if element || n_values != count {
            prop_assert_eq!(s, ERROR);
            prop_assert_eq!(f.log.len(), 1, "{:?}", f.log);
        } else {
            prop_assert_eq!(s, OK, "{:?}", f.log);
            let mut at = 0;
            for &r in &vrs {
                let len = if ARRAYS.contains(&r) { n as usize } else { 1 };
                if r == vr::FX + 1 {
                    prop_assert_eq!(&got[at..at + len], forces.as_slice());
                }
                at += len;
            }
        }
    }
}
