//! LM-63 lamp tilt data (`TILT=INCLUDE` or `TILT=<file>`).
//!
//! Some lamps (metal halide, high-pressure sodium) give less light when burned tilted. The tilt
//! block lists the lamp-to-luminaire geometry (1: lamp vertical base up or down; 2: lamp
//! horizontal, tilting in the plane of its axis; 3: lamp horizontal, tilting across it), then N
//! angle–factor pairs: the candela values are multiplied by the factor at the angle by which the
//! luminaire is tilted in use from its orientation in the photometric test (LM-63-2002 §5.4).
//! Factors are interpolated linearly in angle and held constant beyond the first and last angle.

use super::ParseError;
use super::text::Tokens;

/// A tilt table.
#[derive(Clone, Debug, PartialEq)]
pub struct Tilt {
    /// "INCLUDE" or the tilt file's name as the IES file writes it.
    pub source: String,
    /// Lamp-to-luminaire geometry: 1 vertical lamp, 2 horizontal tilting along its axis, 3
    /// horizontal tilting across it.
    pub geometry: i64,
    /// Tilt angles, degrees, increasing.
    pub angles_deg: Vec<f64>,
    /// Candela multipliers at those angles.
    pub factors: Vec<f64>,
}

impl Tilt {
    /// Reads the four items of a tilt block from `tok`.
    pub fn read(tok: &mut Tokens, source: &str) -> Result<Tilt, ParseError> {
        let (geometry, _) = tok.integer_in("TILT lamp-to-luminaire geometry", 1, 3)?;
        let (n, _) = tok.integer_in("TILT number of angle and multiplying-factor pairs", 1, 3600)?;
        let n = n as usize;
        let mut angles_deg = Vec::with_capacity(n);
        for i in 0..n {
            let field = format!("TILT angle {} of {n}", i + 1);
            let (a, line) = tok.number_in(&field, 0.0, 180.0)?;
            if let Some(prev) = angles_deg.last()
                && a <= *prev
            {
                return Err(ParseError::new(line, field, a.to_string(), format!("an angle above {prev}° (ascending)")));
            }
            angles_deg.push(a);
        }
        let mut factors = Vec::with_capacity(n);
        for i in 0..n {
            let (f, _) = tok.number_in(&format!("TILT multiplying factor {} of {n}", i + 1), 0.0, f64::INFINITY)?;
            factors.push(f);
        }
        Ok(Tilt { source: source.to_string(), geometry, angles_deg, factors })
    }

    /// The multiplying factor at a tilt of `angle_deg`.
    pub fn factor(&self, angle_deg: f64) -> f64 {
        let (a, f) = (&self.angles_deg, &self.factors);
        let n = a.len();
        if angle_deg <= a[0] {
            return f[0];
        }
        if angle_deg >= a[n - 1] {
            return f[n - 1];
        }
        let i = a.partition_point(|x| *x <= angle_deg) - 1;
        let t = (angle_deg - a[i]) / (a[i + 1] - a[i]);
        f[i] + t * (f[i + 1] - f[i])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::luminaire::text::SourceText;

    #[test]
    fn reads_the_lm63_2002_example_block_and_interpolates() {
        let text =
            "1\n13\n0 15 30 45 60 75 90 105 120 135 150 165 180\n1.0 .95 .94 .90 .88 .87 .98 .87 .88 .90 .94 .95 1.0\n";
        let src = SourceText::decode(text.as_bytes());
        let mut tok = Tokens::new(&src, 1, true);
        let t = Tilt::read(&mut tok, "INCLUDE").unwrap();
        assert_eq!(t.geometry, 1);
        assert_eq!(t.angles_deg.len(), 13);
        assert_eq!(t.factor(0.0), 1.0);
        assert_eq!(t.factor(15.0), 0.95);
        assert!((t.factor(7.5) - 0.975).abs() < 1e-12);
        assert_eq!(t.factor(200.0), 1.0);
    }

    #[test]
    fn bad_blocks_name_the_tilt_field() {
        let err = |text: &str| {
            let src = SourceText::decode(text.as_bytes());
            Tilt::read(&mut Tokens::new(&src, 1, true), "INCLUDE").unwrap_err()
        };
        assert!(err("4\n").field.contains("geometry"));
        assert!(err("1\n2\n0 0\n1 1\n").expected.contains("ascending"));
        assert!(err("1\n2\n0 10\n1 -1\n").field.contains("multiplying factor 2"));
        assert_eq!(err("1\n2\n0 10\n1\n").found, "the end of the file");
    }
}
