//! The morgana side of the colour-science cross-check (`scripts/colour_check.py`).

/// Reads the check's JSON request and answers with morgana's colorimetry as JSON.
pub fn run(request_json: &str) -> Result<String, String> {
    todo!("{request_json}")
}
