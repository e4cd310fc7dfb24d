//! CIBSE TM14 (.cib, .cibse, .tm14): recognised, not read.
//!
//! TM14 is a published document: CIBSE Technical Memorandum 14 (1988), the UK standard file
//! format for the electronic transfer of luminaire photometric data, which CIBSE has since
//! archived. What is known of it here: intensities in candela per 1000 lamp lumens, on C-γ
//! planes, with the luminaire lying along the C90–C270 axis. morgana does not read it because
//! no copy of the specification is available to the project, so its line-by-line layout cannot
//! be checked, and a guessed layout could silently misread intensities. A TM14 file gets an
//! error that says so and names the formats that work: convert the file to EULUMDAT, IES LM-63
//! or IES TM-33 (or ask the manufacturer for one of those).
//!
//! To add the reader once the specification is at hand: implement `read` here (returning a
//! [`Photometry`] whose web is in the luminaire frame of [`super`] — note TM14's luminaire axis
//! along C90–C270, i.e. rotate its planes by 90° so the length lies along C0), make
//! [`super::Format::implemented`] true for it and give `sniff` a test; nothing else changes.

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
        "a CIBSE TM14 (1988) file, which morgana does not read: TM14 is a published CIBSE document, now archived, \
         but no copy of its specification is available to the project, so morgana cannot check its layout and \
         will not guess one",
        format!(
            "one of the supported formats, {}. Convert the file to EULUMDAT, IES LM-63 or IES TM-33 with the \
             lighting-design or photometry program you use (programs that import CIBSE TM14 can usually export \
             EULUMDAT or IES), or ask the manufacturer for the EULUMDAT, IES or TM-33 file of this luminaire",
            supported_formats()
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tm14_file_gets_an_error_saying_why_and_naming_the_conversions() {
        let e = crate::luminaire::read_bytes(b"anything", Path::new("lamp.cib")).unwrap_err().to_string();
        assert!(e.starts_with("lamp.cib: CIBSE TM14 file"), "{e}");
        assert!(e.contains("published CIBSE document, now archived"), "{e}");
        assert!(e.contains("no copy of its specification is available to the project"), "{e}");
        assert!(!e.contains("not published"), "the old claim that TM14 is unpublished: {e}");
        assert!(e.contains("Convert the file to EULUMDAT, IES LM-63 or IES TM-33"), "{e}");
        assert!(e.contains("IES LM-63 (.ies)") && e.contains("EULUMDAT (.ldt, .eul)"), "{e}");
        assert!(e.contains("IES TM-33 (.xml)") && e.contains("GLDF (.gldf)"), "{e}");
        assert_eq!(crate::luminaire::read_bytes(b"", Path::new("lamp.cib")).unwrap_err().exit_code(), 2);
        for ext in ["cibse", "tm14", "CIB"] {
            let p = format!("x.{ext}");
            assert!(crate::luminaire::read_bytes(b"", Path::new(&p)).unwrap_err().to_string().contains("TM14"));
        }
    }
}
