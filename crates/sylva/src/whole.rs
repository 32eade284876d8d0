//! Whole numbers from floats, as `x.floor() as i64` and `x.ceil() as i64` give them, without a
//! call into libm. On the baseline x86-64 target (no SSE4.1 `roundss`) `f32::floor` and
//! `f32::ceil` are calls to `floorf` and `ceilf`; in the light grid's walk and the growth
//! model's grids they took 6% of a growth step. These are a truncating conversion and a
//! compare, and give the same integer for every input, NaN and infinities included.

/// `x.floor() as i64`, bit for bit (NaN gives 0, values past the range saturate).
#[inline]
pub fn floor_i64(x: f32) -> i64 {
    // Truncation rounds toward zero; below zero that is one above the floor unless x is
    // whole. Where |x| >= 2^23 every f32 is whole and `t as f32 == x`.
    let t = x as i64;
    if t as f32 > x { t.saturating_sub(1) } else { t }
}

/// `x.ceil() as i64`, bit for bit (NaN gives 0, values past the range saturate).
#[inline]
pub fn ceil_i64(x: f32) -> i64 {
    let t = x as i64;
    if (t as f32) < x {
        t.saturating_add(1)
    } else {
        t
    }
}

/// `x.ceil().max(1.0) as usize`, bit for bit: a count of pieces, at least one.
#[inline]
pub fn pieces(x: f32) -> usize {
    // Past i64's range (2^63) every float is whole and `as usize` takes it as it is.
    if x >= 9.223_372e18 {
        return x as usize;
    }
    ceil_i64(x).max(1) as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every kind of input: whole and fractional, either sign, zeros, the edges of the range
    /// where every float is whole, huge values, infinities and NaN.
    fn samples() -> Vec<f32> {
        let mut xs = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            0.999_999_94,
            -0.999_999_94,
            1.5,
            -1.5,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
            8_388_607.5,
            -8_388_607.5,
            8_388_608.0,
            -8_388_608.0,
            16_777_217.0,
            9.223_372e18,
            -9.223_372e18,
            1e19,
            -1e19,
            f32::MAX,
            f32::MIN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        let mut bits = 0x1234_5678u32;
        for _ in 0..200_000 {
            // A spread of magnitudes from 2^-30 to 2^40 and both signs.
            bits ^= bits << 13;
            bits ^= bits >> 17;
            bits ^= bits << 5;
            let x = f32::from_bits(bits);
            if x.is_finite() && x.abs() < 1e12 && x.abs() > 1e-9 {
                xs.push(x);
            }
        }
        xs
    }

    #[test]
    fn floors_and_ceilings_are_libms_to_the_last_integer() {
        for x in samples() {
            assert_eq!(floor_i64(x), x.floor() as i64, "floor of {x:e}");
            assert_eq!(ceil_i64(x), x.ceil() as i64, "ceiling of {x:e}");
            assert_eq!(pieces(x), x.ceil().max(1.0) as usize, "pieces of {x:e}");
        }
    }
}
