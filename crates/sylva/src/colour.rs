//! The sRGB transfer curve. Species files and pictures speak sRGB; materials and lighting are
//! linear.

/// sRGB 0..1 to linear (the exact piecewise curve).
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear 0..1 to sRGB: the inverse of [`srgb_to_linear`].
pub fn linear_to_srgb(c: f32) -> f32 {
    if c <= 0.0031308 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_curves_invert_each_other() {
        for i in 0..=100 {
            let c = i as f32 / 100.0;
            assert!((linear_to_srgb(srgb_to_linear(c)) - c).abs() < 1e-5, "{c}");
        }
        // Mid-grey: sRGB 0.5 is 21.4% linear.
        assert!((srgb_to_linear(0.5) - 0.2140).abs() < 1e-4);
    }
}
