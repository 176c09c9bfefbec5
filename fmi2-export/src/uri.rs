//! `fmuResourceLocation`: the `file:` URI of the unpacked `resources` folder
//! as a path.

use std::path::PathBuf;

/// Decodes a `file:` URI (`file:///p`, `file:/p`, `file://localhost/p`,
/// percent-encoded) to a path.
pub fn decode_file_uri(uri: &str) -> Option<PathBuf> {
    let rest = uri
        .strip_prefix("file://localhost/")
        .map(|r| format!("/{r}"))
        .or_else(|| uri.strip_prefix("file:///").map(|r| format!("/{r}")))
        .or_else(|| {
            uri.strip_prefix("file:/")
                .filter(|r| !r.starts_with('/'))
                .map(|r| format!("/{r}"))
        })?;
    let b = rest.as_bytes();
    let mut bytes = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            let hex = std::str::from_utf8(b.get(i + 1..i + 3)?).ok()?;
            bytes.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            bytes.push(b[i]);
            i += 1;
        }
    }
    #[cfg(unix)]
    {
        use std::os::unix::ffi::OsStringExt;
        Some(PathBuf::from(std::ffi::OsString::from_vec(bytes)))
    }
    #[cfg(not(unix))]
    {
        // Windows: the URI's path is UTF-8, and `/C:/dir` is the drive path `C:/dir`
        let path = String::from_utf8(bytes).ok()?;
        let drive = matches!(path.as_bytes(), [b'/', d, b':', ..] if d.is_ascii_alphabetic());
        Some(PathBuf::from(if drive { &path[1..] } else { &path[..] }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn file_uris() {
        assert_eq!(
            decode_file_uri("file:///tmp/a%20b/resources").unwrap(),
            PathBuf::from("/tmp/a b/resources")
        );
        assert_eq!(
            decode_file_uri("file:/tmp/x").unwrap(),
            PathBuf::from("/tmp/x")
        );
        assert_eq!(
            decode_file_uri("file://localhost/tmp/x").unwrap(),
            PathBuf::from("/tmp/x")
        );
        assert!(decode_file_uri("http://example.org/x").is_none());
        assert!(decode_file_uri("file:///bad%2").is_none());
        assert!(decode_file_uri("file:///bad%zz").is_none());
    }
}
