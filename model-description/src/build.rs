//! What an FMU crate's `build.rs` does with its table (feature `xml`):
//! `modelDescription.xml`, its GUID and `documentation/index.html` written
//! into `OUT_DIR`. The library embeds the GUID (`fmi2Instantiate` checks it,
//! `fmi2_export::generated_files!` includes the three files) and
//! `cargo xtask fmu` packages these very files, so the binary and the
//! archive agree.

use std::{env, fs, path::PathBuf, process::Command};

use crate::{html, xml, xml3, ModelDescription};

/// Writes `modelDescription.xml` (FMI 2.0), `modelDescription3.xml` (FMI
/// 3.0), `guid.txt` and `index.html` of `md` into
/// `OUT_DIR`, and asks cargo to run the build script again when it, the
/// table (`src/description.rs`) or its page (`src/description.html`) change.
pub fn generate(md: &ModelDescription) {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("OUT_DIR"));
    let generated = generation_epoch().map(utc_date_time);
    let (xml, guid) = xml::model_description_xml(md, generated.as_deref());
    fs::write(out.join("modelDescription.xml"), &xml).expect("write modelDescription.xml");
    fs::write(out.join("guid.txt"), &guid).expect("write guid.txt");
    fs::write(out.join("index.html"), html::index_html(md, &guid)).expect("write index.html");
    let xml3 = xml3::model_description_xml(md, generated.as_deref());
    fs::write(out.join("modelDescription3.xml"), xml3).expect("write modelDescription3.xml");
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=src/description.rs");
    println!("cargo:rerun-if-changed=src/description.html");
    println!("cargo:rerun-if-env-changed=SOURCE_DATE_EPOCH");
}

/// The generation time, in seconds since 1970 UTC: `$SOURCE_DATE_EPOCH` if
/// set (the reproducible-builds convention), else the time of the commit
/// the build starts from, so that two builds of one commit write the same
/// XML byte for byte; `None` outside a git checkout (the attribute is
/// optional).
fn generation_epoch() -> Option<i64> {
    if let Ok(s) = env::var("SOURCE_DATE_EPOCH") {
        return s.trim().parse().ok();
    }
    let dir = env::var_os("CARGO_MANIFEST_DIR")?;
    let out = Command::new("git")
        .arg("-C")
        .arg(dir)
        .args(["log", "-1", "--format=%ct"])
        .output()
        .ok()?;
    String::from_utf8(out.stdout).ok()?.trim().parse().ok()
}

/// `secs` since 1970-01-01T00:00:00Z as `YYYY-MM-DDThh:mm:ssZ`
/// (`xs:dateTime`). The civil date from the day count is the proleptic
/// Gregorian algorithm of H. Hinnant ("chrono-Compatible Low-Level Date
/// Algorithms"); written out rather than taken from a date crate because a
/// build script needs these dozen lines and nothing else of one.
pub fn utc_date_time(secs: i64) -> String {
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}

#[cfg(test)]
mod tests {
    use super::utc_date_time;

    /// Against dates whose epoch seconds are known independently (`date -u
    /// -d @N` of GNU coreutils), across leap days and centuries.
    #[test]
    fn epoch_seconds_to_utc() {
        for (secs, s) in [
            (0, "1970-01-01T00:00:00Z"),
            (951_782_400, "2000-02-29T00:00:00Z"),
            (1_709_251_199, "2024-02-29T23:59:59Z"),
            (4_107_542_400, "2100-03-01T00:00:00Z"),
            (-86_400, "1969-12-31T00:00:00Z"),
            (1_795_744_196, "2026-11-27T01:49:56Z"),
        ] {
            assert_eq!(utc_date_time(secs), s, "{secs}");
        }
    }
}
