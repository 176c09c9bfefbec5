//! A checked little-endian byte format for serialized FMU states.
//!
//! Layout: magic `FMI2STAT` (8 bytes), format version (u32), the model's
//! GUID (u32 length + UTF-8), payload length (u64), payload, CRC-32 (IEEE)
//! of everything before it. Reading checks every field and never reads past
//! the buffer: a corrupted or foreign buffer is an error.

/// Magic number at the start of every serialized state.
pub const MAGIC: &[u8; 8] = b"FMI2STAT";
/// Version of the layout and of the generic payload.
pub const FORMAT_VERSION: u32 = 1;

/// Appends values to a byte buffer.
#[derive(Default)]
pub struct ByteWriter {
    pub buf: Vec<u8>,
}

impl ByteWriter {
    pub fn new() -> ByteWriter {
        ByteWriter::default()
    }
    pub fn u8(&mut self, x: u8) {
        self.buf.push(x);
    }
    pub fn bool(&mut self, x: bool) {
        self.buf.push(x as u8);
    }
    pub fn u32(&mut self, x: u32) {
        self.buf.extend_from_slice(&x.to_le_bytes());
    }
    pub fn i32(&mut self, x: i32) {
        self.buf.extend_from_slice(&x.to_le_bytes());
    }
    pub fn u64(&mut self, x: u64) {
        self.buf.extend_from_slice(&x.to_le_bytes());
    }
    /// Bit-exact (NaN payloads and signed zeros included).
    pub fn f64(&mut self, x: f64) {
        self.u64(x.to_bits());
    }
    pub fn opt_f64(&mut self, x: Option<f64>) {
        match x {
            Some(v) => {
                self.u8(1);
                self.f64(v);
            }
            None => self.u8(0),
        }
    }
    pub fn bytes(&mut self, b: &[u8]) {
        self.u32(b.len() as u32);
        self.buf.extend_from_slice(b);
    }
}

/// Reads values back; every read is bounds-checked.
pub struct ByteReader<'a> {
    buf: &'a [u8],
    pos: usize,
}

/// Why a buffer was refused.
pub type ReadError = String;

impl<'a> ByteReader<'a> {
    pub fn new(buf: &'a [u8]) -> ByteReader<'a> {
        ByteReader { buf, pos: 0 }
    }
    pub fn remaining(&self) -> usize {
        self.buf.len() - self.pos
    }
    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], ReadError> {
        if self.remaining() < n {
            return Err(format!(
                "truncated: {what} needs {n} bytes at offset {}, {} left",
                self.pos,
                self.remaining()
            ));
        }
        let s = &self.buf[self.pos..self.pos + n];
        self.pos += n;
        Ok(s)
    }
    pub fn u8(&mut self, what: &str) -> Result<u8, ReadError> {
        Ok(self.take(1, what)?[0])
    }
    pub fn bool(&mut self, what: &str) -> Result<bool, ReadError> {
        match self.u8(what)? {
            0 => Ok(false),
            1 => Ok(true),
            x => Err(format!("{what}: invalid boolean byte {x}")),
        }
    }
    pub fn u32(&mut self, what: &str) -> Result<u32, ReadError> {
        let b = self.take(4, what)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }
    pub fn i32(&mut self, what: &str) -> Result<i32, ReadError> {
        Ok(self.u32(what)? as i32)
    }
    pub fn u64(&mut self, what: &str) -> Result<u64, ReadError> {
        let b = self.take(8, what)?;
        let mut a = [0u8; 8];
        a.copy_from_slice(b);
        Ok(u64::from_le_bytes(a))
    }
    pub fn f64(&mut self, what: &str) -> Result<f64, ReadError> {
        Ok(f64::from_bits(self.u64(what)?))
    }
    pub fn opt_f64(&mut self, what: &str) -> Result<Option<f64>, ReadError> {
        match self.u8(what)? {
            0 => Ok(None),
            1 => Ok(Some(self.f64(what)?)),
            x => Err(format!("{what}: invalid option tag {x}")),
        }
    }
    pub fn bytes(&mut self, what: &str) -> Result<&'a [u8], ReadError> {
        let n = self.u32(what)? as usize;
        self.take(n, what)
    }
    /// Requires that everything was read.
    pub fn finish(&self, what: &str) -> Result<(), ReadError> {
        if self.remaining() == 0 {
            Ok(())
        } else {
            Err(format!(
                "{what}: {} unexpected trailing bytes",
                self.remaining()
            ))
        }
    }
}

/// Wraps `payload` in the checked envelope for the model `guid`.
pub fn seal(guid: &str, payload: &[u8]) -> Vec<u8> {
    let mut w = ByteWriter::new();
    w.buf.extend_from_slice(MAGIC);
    w.u32(FORMAT_VERSION);
    w.bytes(guid.as_bytes());
    w.u64(payload.len() as u64);
    w.buf.extend_from_slice(payload);
    let crc = crc32fast::hash(&w.buf);
    w.u32(crc);
    w.buf
}

/// Checks the envelope and returns the payload.
pub fn unseal<'a>(guid: &str, buf: &'a [u8]) -> Result<&'a [u8], ReadError> {
    if buf.len() < MAGIC.len() + 4 || &buf[..MAGIC.len()] != MAGIC {
        return Err("not a serialized FMU state of this FMU (bad magic number)".into());
    }
    if buf.len() < 4 {
        return Err("truncated".into());
    }
    let (body, tail) = buf.split_at(buf.len() - 4);
    let stored = u32::from_le_bytes([tail[0], tail[1], tail[2], tail[3]]);
    let mut r = ByteReader::new(body);
    r.take(MAGIC.len(), "magic")?;
    let version = r.u32("format version")?;
    if version != FORMAT_VERSION {
        return Err(format!(
            "serialized state format version {version}, this FMU reads version {FORMAT_VERSION}"
        ));
    }
    let g = r.bytes("GUID")?;
    if g != guid.as_bytes() {
        return Err(format!(
            "the state was serialized by another model (GUID {}), this one is {guid}",
            String::from_utf8_lossy(g)
        ));
    }
    let n = r.u64("payload length")?;
    if n != r.remaining() as u64 {
        return Err(format!(
            "payload length {n} does not match the buffer ({} bytes)",
            r.remaining()
        ));
    }
    let computed = crc32fast::hash(body);
    if computed != stored {
        return Err(format!(
            "checksum mismatch (stored {stored:08x}, computed {computed:08x}): the buffer is corrupted"
        ));
    }
    r.take(n as usize, "payload")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The envelope's checksum is CRC-32/ISO-HDLC (IEEE 802.3, zlib's), whose
    /// published check value over "123456789" is 0xCBF43926.
    #[test]
    fn crc_is_the_ieee_crc32() {
        assert_eq!(crc32fast::hash(b"123456789"), 0xCBF4_3926);
    }

    #[test]
    fn seal_roundtrip_and_corruption() {
        let b = seal("{g}", b"hello");
        assert_eq!(unseal("{g}", &b).unwrap(), b"hello");
        assert!(unseal("{other}", &b).unwrap_err().contains("another model"));
        for i in 0..b.len() {
            let mut c = b.clone();
            c[i] ^= 0x10;
            assert!(unseal("{g}", &c).is_err(), "flip at {i} accepted");
        }
        for n in 0..b.len() {
            assert!(unseal("{g}", &b[..n]).is_err());
        }
        let mut longer = b.clone();
        longer.push(0);
        assert!(unseal("{g}", &longer).is_err());
    }

    #[test]
    fn reader_is_bounded() {
        let mut r = ByteReader::new(&[1, 2, 3]);
        assert!(r.u64("x").is_err());
        assert_eq!(r.u8("x").unwrap(), 1);
        assert!(r.finish("x").is_err());
        let mut w = ByteWriter::new();
        w.bytes(&[9; 3]);
        w.buf[0] = 200; // length beyond the buffer
        assert!(ByteReader::new(&w.buf).bytes("b").is_err());
    }
}
