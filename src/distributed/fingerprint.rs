//! A 64-bit fingerprint of bytes, to tell whether two ranks loaded the same inputs.
//!
//! FNV-1a: `h ← (h ⊕ byte) · 1099511628211`, from `h = 14695981039346656037` (mod 2⁶⁴). It is
//! fixed by its definition (unlike `std`'s hasher), fast enough for scene files, and catches
//! accidental differences (a stale copy of a file on one node); it is not meant to resist
//! deliberate collisions.
//!
//! # References
//! - Fowler, Noll & Vo, "The FNV Non-Cryptographic Hash Algorithm", IETF
//!   draft-eastlake-fnv (offset basis and prime for 64 bits).

/// A running FNV-1a 64 hash.
#[derive(Clone, Copy, Debug)]
pub struct Fnv64(u64);

impl Default for Fnv64 {
    fn default() -> Self {
        Self::new()
    }
}

impl Fnv64 {
    const OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;

    /// The hash of no bytes (the FNV offset basis).
    pub fn new() -> Fnv64 {
        Fnv64(Self::OFFSET_BASIS)
    }

    /// Adds `bytes`, then their length (so that the boundaries between writes count).
    pub fn write(&mut self, bytes: &[u8]) {
        for b in bytes.iter().chain(&(bytes.len() as u64).to_le_bytes()) {
            self.0 = (self.0 ^ u64::from(*b)).wrapping_mul(Self::PRIME);
        }
    }

    /// The fingerprint of the bytes written so far.
    pub fn finish(&self) -> u64 {
        self.0
    }

    /// The fingerprint of one byte string.
    pub fn of(bytes: &[u8]) -> u64 {
        let mut h = Fnv64::new();
        h.write(bytes);
        h.finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Plain FNV-1a 64 (no length suffix), to check the constants against published values.
    fn fnv1a(bytes: &[u8]) -> u64 {
        bytes.iter().fold(Fnv64::OFFSET_BASIS, |h, b| (h ^ u64::from(*b)).wrapping_mul(Fnv64::PRIME))
    }

    #[test]
    fn constants_give_the_published_test_vectors() {
        // Test vectors of the FNV reference (isthe.com/chongo/tech/comp/fnv, "FNV-1a 64").
        assert_eq!(fnv1a(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a(b"foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn write_boundaries_count() {
        let mut a = Fnv64::new();
        a.write(b"ab");
        a.write(b"c");
        let mut b = Fnv64::new();
        b.write(b"a");
        b.write(b"bc");
        assert_ne!(a.finish(), b.finish());
        assert_ne!(Fnv64::of(b"scene"), Fnv64::of(b"scenf"));
    }
}
