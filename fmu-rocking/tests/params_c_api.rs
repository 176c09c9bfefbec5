//! Invalid parameters through the C API (MODEL.md §5): every condition is
//! refused at fmi2ExitInitializationMode with fmi2Error and a logged message
//! naming the variable, its value and the condition; the refused instance
//! can be freed, or reset and run to the same result as a fresh instance.

mod host;

use host::*;

#[test]
fn host_smoke() {
    let h = Host::new();
    h.init();
    assert_eq!(h.do_step(0.0, 0.01), fmi2OK);
    assert_eq!(h.set_real("ag", f64::NAN), fmi2Error);
    assert!(
        h.errors().iter().any(|m| m.contains("ag")),
        "{:?}",
        h.messages()
    );
}
