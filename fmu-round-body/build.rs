//! Generates `modelDescription.xml`, its GUID and `documentation/index.html`
//! from the one variable table (`src/description.rs`) into `OUT_DIR`
//! ([`model_description::build::generate`]).

// The same file the library compiles as `description`: one table for both.
#[allow(dead_code)] // the value references and enums are for the library
#[path = "src/description.rs"]
mod description;

fn main() {
    model_description::build::generate(&description::ROUND_BODY);
}
