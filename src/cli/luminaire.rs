//! `morgana luminaire FILE [--png polar.png]`: reads a luminaire photometry file and prints what
//! it says (flux, symmetry, peak, beam and field angles); optionally draws its polar curves.

use crate::error::Result;
use std::path::PathBuf;

/// The command line of `morgana luminaire`.
#[derive(clap::Args, Clone, Debug)]
pub struct LuminaireArgs {
    /// Photometric file (.ies, .ldt).
    pub file: PathBuf,
    /// Write the C0–C180 and C90–C270 polar intensity curves to this PNG.
    #[arg(long)]
    pub png: Option<PathBuf>,
}

/// The text `morgana luminaire` prints.
pub fn run(args: &LuminaireArgs) -> Result<String> {
    crate::luminaire::inspect(&args.file, args.png.as_deref())
}
