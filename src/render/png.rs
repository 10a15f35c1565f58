//! 8-bit greyscale PNG encoding through the `image` crate.

use image::codecs::png::PngEncoder;
use image::{ExtendedColorType, ImageEncoder};

/// Encodes a `size`×`size` row-major (top row first) 8-bit grey image as PNG bytes.
pub fn encode_grey(pixels: &[u8], size: u32) -> Vec<u8> {
    assert_eq!(
        pixels.len(),
        (size as usize).pow(2),
        "pixel count must be size²"
    );
    let mut out = Vec::new();
    PngEncoder::new(&mut out)
        .write_image(pixels, size, size, ExtendedColorType::L8)
        .expect("encoding a well-sized grey image into memory cannot fail");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_through_the_decoder() {
        let px: Vec<u8> = (0..16 * 16).map(|i| (i % 251) as u8).collect();
        let png = encode_grey(&px, 16);
        let img = image::load_from_memory(&png).unwrap().into_luma8();
        assert_eq!(img.dimensions(), (16, 16));
        assert_eq!(img.into_raw(), px);
    }
}
