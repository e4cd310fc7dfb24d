//! The photometric formats morgana knows, as one closed set: how each is recognised (file
//! extension, else content) and read. Adding a format is one variant here, one file beside
//! this one, and a test.

use super::text::SourceText;
use super::{ParseError, Photometry, eulumdat, gldf, ies, tm14, tm33};
use std::path::Path;

/// A photometric file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// IES LM-63 (1986–2019), `.ies`.
    Lm63,
    /// EULUMDAT, `.ldt`, `.eul`.
    Eulumdat,
    /// IES TM-33-18 and TM-33-23 (XML), `.xml`.
    Tm33,
    /// GLDF container (zip), `.gldf`.
    Gldf,
    /// CIBSE TM14: recognised by extension, not read (`tm14.rs` says why).
    Tm14,
}

impl Format {
    /// Every format, in the order messages list them.
    pub const ALL: [Format; 5] = [Format::Lm63, Format::Eulumdat, Format::Tm33, Format::Gldf, Format::Tm14];

    /// The format's name for messages.
    pub fn name(self) -> &'static str {
        match self {
            Format::Lm63 => ies::READER.name,
            Format::Eulumdat => eulumdat::READER.name,
            Format::Tm33 => tm33::NAME,
            Format::Gldf => gldf::NAME,
            Format::Tm14 => tm14::READER.name,
        }
    }

    /// Lower-case extensions, without the dot.
    pub fn extensions(self) -> &'static [&'static str] {
        match self {
            Format::Lm63 => ies::READER.extensions,
            Format::Eulumdat => eulumdat::READER.extensions,
            Format::Tm33 => tm33::EXTENSIONS,
            Format::Gldf => gldf::EXTENSIONS,
            Format::Tm14 => tm14::READER.extensions,
        }
    }

    /// False for a format morgana recognises but cannot read.
    pub fn implemented(self) -> bool {
        !matches!(self, Format::Tm14)
    }

    /// The format a file's extension names.
    pub fn by_extension(path: &Path) -> Option<Format> {
        let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase)?;
        Format::ALL.into_iter().find(|f| f.extensions().contains(&ext.as_str()))
    }

    /// The format the content looks like: a zip is GLDF, an XML document rooted at
    /// `<IESTM33…>` is TM-33, then the LM-63 and EULUMDAT sniffers on the decoded text (binary
    /// and XML first: the text sniffers would accept too much).
    pub fn sniff(bytes: &[u8]) -> Option<Format> {
        if gldf::sniff(bytes) {
            return Some(Format::Gldf);
        }
        if tm33::sniff(bytes) {
            return Some(Format::Tm33);
        }
        let src = SourceText::decode(bytes);
        [Format::Lm63, Format::Eulumdat].into_iter().find(|f| match f {
            Format::Lm63 => (ies::READER.sniff)(&src),
            _ => (eulumdat::READER.sniff)(&src),
        })
    }

    /// Reads `bytes`, the file at `path` (whose folder resolves files an LM-63 file names);
    /// `variant` chooses a GLDF variant.
    pub fn read(self, bytes: &[u8], path: &Path, variant: Option<&str>) -> Result<Photometry, ParseError> {
        match self {
            Format::Lm63 => (ies::READER.read)(&SourceText::decode(bytes), path),
            Format::Eulumdat => (eulumdat::READER.read)(&SourceText::decode(bytes), path),
            Format::Tm14 => (tm14::READER.read)(&SourceText::decode(bytes), path),
            Format::Tm33 => tm33::read(bytes, path),
            Format::Gldf => gldf::read(bytes, path, variant),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extensions_then_content() {
        assert_eq!(Format::by_extension(Path::new("a/B.GLDF")), Some(Format::Gldf));
        assert_eq!(Format::by_extension(Path::new("a.tm33.xml")), Some(Format::Tm33));
        assert_eq!(Format::by_extension(Path::new("a.cibse")), Some(Format::Tm14));
        assert_eq!(Format::by_extension(Path::new("noext")), None);
        assert_eq!(Format::sniff(b"PK\x03\x04...."), Some(Format::Gldf));
        assert_eq!(Format::sniff(b"<?xml version=\"1.0\"?><IESTM33-22>"), Some(Format::Tm33));
        assert_eq!(Format::sniff(b"IESNA:LM-63-2002\nTILT=NONE\n"), Some(Format::Lm63));
        assert_eq!(Format::sniff(b"hello"), None);
        for f in Format::ALL {
            assert!(!f.extensions().is_empty() && !f.name().is_empty());
        }
    }
}
