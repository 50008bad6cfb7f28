//! Little-endian byte forms of saved states: a writer and a reader whose errors name the
//! field and the offset (`truncated: the scene needs 812 bytes at offset 64, only 3 left`).

/// Appends little-endian numbers and length-prefixed texts.
#[derive(Default)]
pub struct ByteWriter {
    pub bytes: Vec<u8>,
}

impl ByteWriter {
    pub fn u8(&mut self, x: u8) {
        self.bytes.push(x);
    }

    pub fn flag(&mut self, x: bool) {
        self.bytes.push(u8::from(x));
    }

    pub fn u32(&mut self, x: u32) {
        self.bytes.extend_from_slice(&x.to_le_bytes());
    }

    pub fn u64(&mut self, x: u64) {
        self.bytes.extend_from_slice(&x.to_le_bytes());
    }

    pub fn f64(&mut self, x: f64) {
        self.bytes.extend_from_slice(&x.to_le_bytes());
    }

    pub fn raw(&mut self, bytes: &[u8]) {
        self.bytes.extend_from_slice(bytes);
    }

    /// A u32 length, then the bytes.
    pub fn bytes_u32(&mut self, bytes: &[u8]) {
        self.u32(bytes.len() as u32);
        self.raw(bytes);
    }

    /// A u64 length, then the bytes.
    pub fn bytes_u64(&mut self, bytes: &[u8]) {
        self.u64(bytes.len() as u64);
        self.raw(bytes);
    }
}

/// Reads what a [`ByteWriter`] wrote; every read names the field it reads.
pub struct ByteReader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> ByteReader<'a> {
    pub fn new(bytes: &'a [u8]) -> ByteReader<'a> {
        ByteReader { bytes, at: 0 }
    }

    /// The offset of the next read.
    pub fn offset(&self) -> usize {
        self.at
    }

    /// The bytes not read yet.
    pub fn left(&self) -> usize {
        self.bytes.len() - self.at
    }

    pub fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], String> {
        let left = self.left();
        if n > left {
            return Err(format!(
                "truncated: {what} needs {n} bytes at offset {}, only {left} left",
                self.at
            ));
        }
        let b = &self.bytes[self.at..self.at + n];
        self.at += n;
        Ok(b)
    }

    pub fn u8(&mut self, what: &str) -> Result<u8, String> {
        Ok(self.take(1, what)?[0])
    }

    /// 0 or 1.
    pub fn flag(&mut self, what: &str) -> Result<bool, String> {
        match self.u8(what)? {
            0 => Ok(false),
            1 => Ok(true),
            b => Err(format!("{what} is {b}, allowed 0 or 1")),
        }
    }

    pub fn u32(&mut self, what: &str) -> Result<u32, String> {
        let mut a = [0u8; 4];
        a.copy_from_slice(self.take(4, what)?);
        Ok(u32::from_le_bytes(a))
    }

    pub fn u64(&mut self, what: &str) -> Result<u64, String> {
        let mut a = [0u8; 8];
        a.copy_from_slice(self.take(8, what)?);
        Ok(u64::from_le_bytes(a))
    }

    pub fn f64(&mut self, what: &str) -> Result<f64, String> {
        Ok(f64::from_bits(self.u64(what)?))
    }

    /// A u32 length, then that many bytes.
    pub fn bytes_u32(&mut self, what: &str) -> Result<&'a [u8], String> {
        let n = self.u32(what)? as usize;
        self.take(n, what)
    }

    /// A u64 length, then that many bytes.
    pub fn bytes_u64(&mut self, what: &str) -> Result<&'a [u8], String> {
        let n = self.u64(what)?;
        let n = usize::try_from(n).map_err(|_| format!("{what}: length {n} is too large"))?;
        self.take(n, what)
    }

    /// A u32 length, then UTF-8 text.
    pub fn str_u32(&mut self, what: &str) -> Result<&'a str, String> {
        let b = self.bytes_u32(what)?;
        std::str::from_utf8(b).map_err(|_| format!("{what} is not UTF-8"))
    }

    /// Every byte was read.
    pub fn finish(&self, what: &str) -> Result<(), String> {
        match self.left() {
            0 => Ok(()),
            n => Err(format!(
                "{n} unexpected bytes after the end of {what} at offset {}",
                self.at
            )),
        }
    }
}
