//! The packaged RockingBlock.fmu, for the tests that load it as a host
//! would: `fmu-rocking/tests/fmu_import.rs` and `fmi-import/tests/`, which
//! includes this file with `#[path]` (both crates lie one folder below the
//! repository root).

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Packages the FMUs (`cargo xtask fmu` at the repository root, once per
/// test process) and returns the path of `RockingBlock.fmu`.
pub fn rocking_block_fmu() -> &'static Path {
    static PATH: OnceLock<PathBuf> = OnceLock::new();
    PATH.get_or_init(|| {
        // the repository root, where `cargo xtask` is defined and `target/` lives
        let root = Path::new(env!("CARGO_MANIFEST_DIR"))
            .parent()
            .expect("the crate is a folder of the repository");
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        let status = std::process::Command::new(cargo)
            .current_dir(root)
            .args(["xtask", "fmu"])
            .status()
            .expect("run cargo xtask fmu");
        assert!(status.success(), "cargo xtask fmu failed");
        let target = std::env::var_os("CARGO_TARGET_DIR")
            .map(PathBuf::from)
            .map(|p| if p.is_absolute() { p } else { root.join(p) })
            .unwrap_or_else(|| root.join("target"));
        let p = target.join("fmu").join("RockingBlock.fmu");
        assert!(
            p.is_file(),
            "{} not found after cargo xtask fmu",
            p.display()
        );
        p
    })
}
