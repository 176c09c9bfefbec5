//! Generates `modelDescription.xml`, its GUID and `documentation/index.html`
//! from the one variable table (`src/description.rs`) into `OUT_DIR`.
//! The library embeds the GUID (`fmi2Instantiate` checks it) and `cargo xtask
//! fmu` packages these very files, so the binary and the archive agree.

use std::{env, fs, path::PathBuf};

use model_description::{html, xml};

// The same file the library compiles as `description`: one table for both.
#[allow(dead_code)] // the value references and enums are for the library
#[path = "src/description.rs"]
mod description;
use description::ROCKING_BLOCK;

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("OUT_DIR"));
    let (xml, guid) = xml::model_description_xml(&ROCKING_BLOCK);
    fs::write(out.join("modelDescription.xml"), &xml).expect("write modelDescription.xml");
    fs::write(out.join("guid.txt"), &guid).expect("write guid.txt");
    fs::write(
        out.join("index.html"),
        html::index_html(&ROCKING_BLOCK, &guid),
    )
    .expect("write index.html");
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=src/description.rs");
    println!("cargo:rerun-if-changed=src/description.html");
}
