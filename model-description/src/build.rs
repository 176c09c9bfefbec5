//! What an FMU crate's `build.rs` does with its table (feature `xml`):
//! `modelDescription.xml`, its GUID and `documentation/index.html` written
//! into `OUT_DIR`. The library embeds the GUID (`fmi2Instantiate` checks it,
//! `fmi2_export::generated_files!` includes the three files) and
//! `cargo xtask fmu` packages these very files, so the binary and the
//! archive agree.

use std::{env, fs, path::PathBuf};

use crate::{html, xml, ModelDescription};

/// Writes `modelDescription.xml`, `guid.txt` and `index.html` of `md` into
/// `OUT_DIR`, and asks cargo to run the build script again when it, the
/// table (`src/description.rs`) or its page (`src/description.html`) change.
pub fn generate(md: &ModelDescription) {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("OUT_DIR"));
    let (xml, guid) = xml::model_description_xml(md);
    fs::write(out.join("modelDescription.xml"), &xml).expect("write modelDescription.xml");
    fs::write(out.join("guid.txt"), &guid).expect("write guid.txt");
    fs::write(out.join("index.html"), html::index_html(md, &guid)).expect("write index.html");
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=src/description.rs");
    println!("cargo:rerun-if-changed=src/description.html");
}
