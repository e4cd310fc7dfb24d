//! The checkpoint's byte layout: little-endian numbers, floats as their IEEE 754 bits (so a
//! value read back is the value written, bit for bit), strings and vectors as a u64 length and
//! their elements. [`Reader`] fails, never panics, on truncated or malformed bytes.

/// Appends values to a byte buffer.
#[derive(Default)]
pub struct Writer {
    /// The bytes so far.
    pub bytes: Vec<u8>,
}

impl Writer {
    /// Appends `x`.
    pub fn u64(&mut self, x: u64) {
        self.bytes.extend_from_slice(&x.to_le_bytes());
    }

    /// Appends `x` (as a u64).
    pub fn u32(&mut self, x: u32) {
        self.u64(u64::from(x));
    }

    /// Appends `x` (as a u64).
    pub fn usize(&mut self, x: usize) {
        self.u64(x as u64);
    }

    /// Appends the bits of `x`.
    pub fn f64(&mut self, x: f64) {
        self.u64(x.to_bits());
    }

    /// Appends `x`: a 0/1 flag, then the value when there is one.
    pub fn opt_f64(&mut self, x: Option<f64>) {
        self.u64(u64::from(x.is_some()));
        if let Some(v) = x {
            self.f64(v);
        }
    }

    /// Appends `s`: its length in bytes, then its UTF-8 bytes.
    pub fn str(&mut self, s: &str) {
        self.usize(s.len());
        self.bytes.extend_from_slice(s.as_bytes());
    }

    /// Appends `v`: its length, then the bits of each value.
    pub fn f64s(&mut self, v: &[f64]) {
        self.usize(v.len());
        self.bytes.reserve(v.len() * 8);
        v.iter().for_each(|x| self.f64(*x));
    }
}

/// Reads values back in the order a [`Writer`] appended them.
pub struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

/// What went wrong reading: in words.
pub type Result<T> = std::result::Result<T, String>;

impl<'a> Reader<'a> {
    /// A reader at the start of `bytes`.
    pub fn new(bytes: &'a [u8]) -> Reader<'a> {
        Reader { bytes, at: 0 }
    }

    /// The next `n` bytes.
    pub fn take(&mut self, n: usize) -> Result<&'a [u8]> {
        let end = self.at.checked_add(n).filter(|e| *e <= self.bytes.len());
        let end = end.ok_or_else(|| format!("it ends early (byte {} of {})", self.at, self.bytes.len()))?;
        let s = &self.bytes[self.at..end];
        self.at = end;
        Ok(s)
    }

    /// The next u64.
    pub fn u64(&mut self) -> Result<u64> {
        let b = self.take(8)?;
        let mut a = [0u8; 8];
        a.copy_from_slice(b);
        Ok(u64::from_le_bytes(a))
    }

    /// The next u32 (stored as a u64).
    pub fn u32(&mut self) -> Result<u32> {
        let x = self.u64()?;
        u32::try_from(x).map_err(|_| format!("a count {x} is out of range"))
    }

    /// The next count: a u64 that must be at most `max` (the values it counts must fit in
    /// what is left).
    pub fn len(&mut self, element_bytes: usize) -> Result<usize> {
        let n = self.u64()?;
        let left = (self.bytes.len() - self.at) as u64;
        if n.saturating_mul(element_bytes.max(1) as u64) > left {
            return Err(format!("a length {n} runs past its end"));
        }
        Ok(n as usize)
    }

    /// The next f64.
    pub fn f64(&mut self) -> Result<f64> {
        self.u64().map(f64::from_bits)
    }

    /// The next optional f64.
    pub fn opt_f64(&mut self) -> Result<Option<f64>> {
        match self.u64()? {
            0 => Ok(None),
            1 => self.f64().map(Some),
            x => Err(format!("a flag is {x}, not 0 or 1")),
        }
    }

    /// The next string.
    pub fn str(&mut self) -> Result<String> {
        let n = self.len(1)?;
        String::from_utf8(self.take(n)?.to_vec()).map_err(|_| "a string is not UTF-8".to_string())
    }

    /// The next vector of f64.
    pub fn f64s(&mut self) -> Result<Vec<f64>> {
        let n = self.len(8)?;
        (0..n).map(|_| self.f64()).collect()
    }

    /// Whether every byte has been read.
    pub fn at_end(&self) -> bool {
        self.at == self.bytes.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_come_back_bit_for_bit() {
        let mut w = Writer::default();
        let odd = [f64::MIN_POSITIVE / 3.0, -0.0, 1.0 / 3.0, f64::NAN];
        w.f64s(&odd);
        w.str("Ed_se, µm");
        w.opt_f64(None);
        w.opt_f64(Some(0.1));
        w.u32(7);
        let mut r = Reader::new(&w.bytes);
        let back = r.f64s().unwrap();
        assert_eq!(back.iter().map(|x| x.to_bits()).collect::<Vec<_>>(), odd.map(f64::to_bits).to_vec());
        assert_eq!(r.str().unwrap(), "Ed_se, µm");
        assert_eq!(r.opt_f64().unwrap(), None);
        assert_eq!(r.opt_f64().unwrap(), Some(0.1));
        assert_eq!(r.u32().unwrap(), 7);
        assert!(r.at_end());
    }

    #[test]
    fn truncated_bytes_are_an_error() {
        let mut w = Writer::default();
        w.f64s(&[1.0, 2.0]);
        for n in 0..w.bytes.len() {
            assert!(Reader::new(&w.bytes[..n]).f64s().is_err(), "{n} bytes");
        }
        let mut huge = Writer::default();
        huge.u64(u64::MAX);
        assert!(Reader::new(&huge.bytes).f64s().is_err());
    }
}
