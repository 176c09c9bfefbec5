//! Generates `modelDescription.xml`, its GUID and `documentation/index.html`
//! from the one variable table (`model_description::shear_frame`) into
//! `OUT_DIR`. The library embeds the GUID (`fmi2Instantiate` checks it) and
//! `cargo xtask fmu` packages these very files.

use std::{env, fs, path::PathBuf};

use model_description::shear_frame::SHEAR_FRAME;
use model_description::{html, xml};

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("OUT_DIR"));
    let (xml, guid) = xml::model_description_xml(&SHEAR_FRAME);
    fs::write(out.join("modelDescription.xml"), &xml).expect("write modelDescription.xml");
    fs::write(out.join("guid.txt"), &guid).expect("write guid.txt");
    fs::write(
        out.join("index.html"),
        html::index_html(&SHEAR_FRAME, &guid),
    )
    .expect("write index.html");
    println!("cargo:rerun-if-changed=build.rs");
}
