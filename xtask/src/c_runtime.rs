//! The licences of the C runtime in the win64 binaries. mingw-w64's gcc
//! links its startup code (`dllcrt2.o`, `crt2.o`), its support libraries
//! (`libmingw32`, `libmingwex`) and GCC's `libgcc` statically into every
//! `.dll` and `.exe` it links (the binaries import only Windows' own DLLs:
//! `x86_64-w64-mingw32-objdump -p`), so a shipped win64 binary carries their
//! code and, for mingw-w64's ZPL-2.1 files, must reproduce their notice.
//! Cargo's metadata knows nothing of them ([`crate::licences`] lists the
//! crates only); the texts here are those of the packages that installed
//! the very files the linker takes, asked of the linker and of dpkg, so the
//! notice follows the toolchain that built the binary.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

use crate::{Res, MINGW_GCC};

/// The runtime files the linker takes, as `gcc -print-file-name` names them.
const LINKED: [&str; 4] = ["dllcrt2.o", "crt2.o", "libmingwex.a", "libgcc.a"];

/// The section to append to the licence file of an artefact that ships win64
/// binaries: each Debian package that installed a runtime file the linker
/// links, with its version and its `copyright` file whole.
pub fn section() -> Res<String> {
    let mut packages: Vec<(String, Vec<String>)> = Vec::new();
    for name in LINKED {
        let path = linked_file(name)?;
        let package = owner(&path)?;
        match packages.iter_mut().find(|(p, _)| *p == package) {
            Some((_, files)) => files.push(name.to_string()),
            None => packages.push((package, vec![name.to_string()])),
        }
    }
    let mut out = String::from(
        "\nThe C runtime of the win64 binaries\n\n\
         The win64 binaries are linked by mingw-w64's gcc, which links its C runtime \
         statically into each of them: mingw-w64's startup code and libraries (ZPL-2.1 and \
         public domain files; the ZPL asks binary redistributions to reproduce its notice) \
         and GCC's libgcc (GPL-3.0 with the GCC Runtime Library Exception, which lets the \
         compiled code be distributed under any terms). The packages that installed the \
         files the linker took, and their copyright files whole:\n",
    );
    for (package, files) in &packages {
        let version = version(package)?;
        let copyright = PathBuf::from("/usr/share/doc")
            .join(package)
            .join("copyright");
        let text = fs::read_to_string(&copyright)
            .map_err(|e| format!("{} (the licence of {package}): {e}", copyright.display()))?;
        out.push_str(&format!(
            "\n== {package} {version} ({}): {}\n\n{}\n",
            files.join(", "),
            copyright.display(),
            text.trim_end()
        ));
    }
    Ok(out)
}

/// The file the linker takes for `name`, symbolic links resolved (dpkg
/// knows installed paths, not `..` or links).
fn linked_file(name: &str) -> Res<PathBuf> {
    let arg = format!("-print-file-name={name}");
    let printed = output(
        Command::new(MINGW_GCC).arg(&arg),
        &format!("{MINGW_GCC} {arg}"),
    )?;
    let path = PathBuf::from(printed.trim());
    if !path.is_absolute() {
        // gcc prints the bare name back when it finds no such file
        return Err(format!(
            "{MINGW_GCC} {arg}: no {name} (the win64 binaries' C runtime)"
        ));
    }
    path.canonicalize()
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// The Debian package that installed `path`.
fn owner(path: &Path) -> Res<String> {
    let shown = path.display().to_string();
    let line = output(
        Command::new("dpkg-query").args(["--search", &shown]),
        &format!("dpkg-query --search {shown}"),
    )?;
    // "package[:arch]: path", one line per package that diverts or owns it
    let first = line.lines().next().unwrap_or("");
    let package = first.split(':').next().unwrap_or("").trim();
    if package.is_empty() {
        return Err(format!("dpkg-query --search {shown}: no package named"));
    }
    Ok(package.to_string())
}

fn version(package: &str) -> Res<String> {
    output(
        Command::new("dpkg-query").args(["--show", "--showformat=${Version}", package]),
        &format!("dpkg-query --show {package}"),
    )
}

/// A command's standard output, or an error naming `what` with its stderr.
fn output(cmd: &mut Command, what: &str) -> Res<String> {
    let out = cmd.output().map_err(|e| format!("{what}: {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "{what}: {}: {}",
            out.status,
            String::from_utf8_lossy(&out.stderr).trim()
        ));
    }
    Ok(String::from_utf8_lossy(&out.stdout).trim().to_string())
}
