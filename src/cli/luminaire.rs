//! `morgana luminaire FILE [--png polar.png] [--variant ID]`: reads a luminaire photometry file
//! (IES LM-63, EULUMDAT, IES TM-33, GLDF) and prints what it says (format, flux, symmetry,
//! spectrum, peak, beam and field angles); optionally draws its polar curves.

use crate::error::Result;
use std::path::PathBuf;

/// The command line of `morgana luminaire`.
#[derive(clap::Args, Clone, Debug)]
pub struct LuminaireArgs {
    /// Photometric file (.ies, .ldt, .xml TM-33, .gldf).
    pub file: PathBuf,
    /// Write the C0–C180 and C90–C270 polar intensity curves to this PNG.
    #[arg(long)]
    pub png: Option<PathBuf>,
    /// GLDF only: the id of the variant to read (default: the first).
    #[arg(long)]
    pub variant: Option<String>,
}

/// The text `morgana luminaire` prints.
pub fn run(args: &LuminaireArgs) -> Result<String> {
    if let Some(png) = &args.png {
        super::check_output_file("--png", png)?;
    }
    crate::luminaire::inspect_variant(&args.file, args.png.as_deref(), args.variant.as_deref())
}
