//! CIBSE TM14 (.cib, .cibse, .tm14): recognised, not read.
//!
//! TM14 is the CIBSE's 1988 standard file format for luminaire photometry. What is known of it:
//! intensities in candela per 1000 lamp lumens, on C-γ planes, with the luminaire lying along the
//! C90–C270 axis. Its line-by-line layout is not published in any source available to this
//! project (CIBSE has archived the document, and no public parser or sample file exists), so
//! morgana does not guess one: a TM14 file gets an error that says so and how to convert it.
//!
//! To add the reader once the layout can be cited: implement `read` here (returning a
//! [`Photometry`] whose web is in the luminaire frame of [`super`] — note TM14's luminaire axis
//! along C90–C270, i.e. rotate its planes by 90° so the length lies along C0), set `implemented`
//! and give `sniff` a test; nothing else changes.

use super::text::SourceText;
use super::{ParseError, Photometry, Reader, supported_formats};
use std::path::Path;

pub const READER: Reader =
    Reader { name: "CIBSE TM14", extensions: &["cib", "cibse", "tm14"], sniff, read, implemented: false };

/// Never claims a file by content: only the extension says TM14.
fn sniff(_: &SourceText) -> bool {
    false
}

fn read(_: &SourceText, _: &Path) -> Result<Photometry, ParseError> {
    Err(ParseError::whole_file(
        "CIBSE TM14 file",
        "a TM14 file, which morgana cannot read: the 1988 TM14 layout is not published in any source morgana can \
         cite, and a guessed layout could silently misread intensities",
        format!(
            "one of the supported formats, {}. Ask the manufacturer for the IES or EULUMDAT file of this \
             luminaire (most publish all three), or open the TM14 file in a lighting-design program that imports \
             CIBSE TM14 and export it as IES LM-63 or EULUMDAT",
            supported_formats()
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tm14_file_gets_an_error_naming_the_supported_formats_and_the_conversion_route() {
        let e = crate::luminaire::read_bytes(b"anything", Path::new("lamp.cib")).unwrap_err().to_string();
        assert!(e.starts_with("lamp.cib: CIBSE TM14 file"), "{e}");
        assert!(e.contains("IES LM-63 (.ies)") && e.contains("EULUMDAT (.ldt, .eul)"), "{e}");
        assert!(e.contains("export it as IES LM-63 or EULUMDAT"), "{e}");
        for ext in ["cibse", "tm14", "CIB"] {
            let p = format!("x.{ext}");
            assert!(crate::luminaire::read_bytes(b"", Path::new(&p)).unwrap_err().to_string().contains("TM14"));
        }
    }
}
