//! Magnitude against time as an SVG plot.

use crate::scene::Response;

/// Writes an SVG plot of magnitude (inverted axis: brighter up) against time.
pub fn magnitude_svg(response: &Response, title: &str) -> Result<String, String> {
    let _ = (response, title);
    Err("plot not implemented yet".into())
}
