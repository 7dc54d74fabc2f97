//! A square root in f64 for the arc centre, bit for bit `libm::sqrt` (correctly
//! rounded), without its last step: `libm::sqrt` adds a tiny value to the result
//! only to raise the floating-point environment's inexact flag, which Rust never
//! reads — in soft float on the Cortex-M4 that addition is a call of ~80
//! instructions, as much as the root itself.
//!
//! The root is libm's: a 7-bit table estimate of `1/√m`, two Goldschmidt
//! iterations in 32 bits and two in 64, and an exact rounding test — ported from
//! the `libm` crate 0.2.16, `src/math/generic/sqrt.rs` (SPDX-License-Identifier:
//! MIT; the Rust libm authors, from musl's `src/math/sqrt.c`, Copyright © 2005-2020
//! Rich Felker, et al., MIT), specialised to f64 and positive normal arguments.

/// `√x`, the same bits as `libm::sqrt(x)`: for positive normal `x` by the
/// integer iterations below, for anything else (zero, subnormal, infinite, NaN,
/// negative) by `libm::sqrt` itself.
pub fn sqrt(x: f64) -> f64 {
    let ix = x.to_bits();
    let top = (ix >> 52) as u32;
    // Sign clear and exponent 1..=2046: positive, normal, finite.
    if top.wrapping_sub(1) >= 2046 {
        return libm::sqrt(x);
    }
    // x = 4^e · m with m_u2 ∈ [1, 4) in U2.62 fixed point.
    let mut m_u2 = (ix | 1 << 52) << 11;
    if top & 1 != 0 {
        m_u2 >>= 1;
    }
    let e = (top + 1023) >> 1;
    let i = ((ix >> 46) & 0x7f) as usize;
    let r1 = RSQRT_TAB.get(i).map_or(0, |&r| u32::from(r) << 16);
    let (r2, _) = gold32(r1, (m_u2 >> 32) as u32);
    let s = gold64(u64::from(r2) << 32, m_u2);
    let mut m = s >> 9;
    // s < √m < s + 0x1.09p-52: the nearest is s or s + 2^-52 (see libm).
    let d0 = (m_u2 << 42).wrapping_sub(m.wrapping_mul(m));
    let d1 = m.wrapping_sub(d0);
    m += d1 >> 63;
    m &= (1 << 52) - 1;
    f64::from_bits(m | u64::from(e) << 52)
}

/// High half of the 64-bit product.
fn mulh32(a: u32, b: u32) -> u32 {
    ((u64::from(a) * u64::from(b)) >> 32) as u32
}

/// High half of the 128-bit product.
fn mulh64(a: u64, b: u64) -> u64 {
    ((u128::from(a) * u128::from(b)) >> 64) as u64
}

/// Two Goldschmidt iterations in 32 bits: `r → 1/√m` (U0.32), `s → √m` (U2.30).
fn gold32(mut r: u32, mut s: u32) -> (u32, u32) {
    const THREE: u32 = 3 << 30;
    let mut u = r;
    for i in 0..2 {
        s = mulh32(s, u);
        if i > 0 {
            s <<= 1;
        }
        u = THREE.wrapping_sub(mulh32(s, r));
        r = mulh32(r, u) << 1;
    }
    (r, s)
}

/// The final two Goldschmidt iterations in 64 bits; returns `s ≈ √m` (U3.61).
fn gold64(mut r: u64, mut s: u64) -> u64 {
    const THREE: u64 = 3 << 62;
    let mut u = r;
    for _ in 0..2 {
        s = mulh64(s, u);
        u = THREE.wrapping_sub(mulh64(s, r));
        r = mulh64(r, u) << 1;
    }
    s
}

/// `1/√x` in U0.16, indexed by one exponent bit and six bits of the significand
/// (libm's table).
#[rustfmt::skip]
static RSQRT_TAB: [u16; 128] = [
    0xb451, 0xb2f0, 0xb196, 0xb044, 0xaef9, 0xadb6, 0xac79, 0xab43,
    0xaa14, 0xa8eb, 0xa7c8, 0xa6aa, 0xa592, 0xa480, 0xa373, 0xa26b,
    0xa168, 0xa06a, 0x9f70, 0x9e7b, 0x9d8a, 0x9c9d, 0x9bb5, 0x9ad1,
    0x99f0, 0x9913, 0x983a, 0x9765, 0x9693, 0x95c4, 0x94f8, 0x9430,
    0x936b, 0x92a9, 0x91ea, 0x912e, 0x9075, 0x8fbe, 0x8f0a, 0x8e59,
    0x8daa, 0x8cfe, 0x8c54, 0x8bac, 0x8b07, 0x8a64, 0x89c4, 0x8925,
    0x8889, 0x87ee, 0x8756, 0x86c0, 0x862b, 0x8599, 0x8508, 0x8479,
    0x83ec, 0x8361, 0x82d8, 0x8250, 0x81c9, 0x8145, 0x80c2, 0x8040,
    0xff02, 0xfd0e, 0xfb25, 0xf947, 0xf773, 0xf5aa, 0xf3ea, 0xf234,
    0xf087, 0xeee3, 0xed47, 0xebb3, 0xea27, 0xe8a3, 0xe727, 0xe5b2,
    0xe443, 0xe2dc, 0xe17a, 0xe020, 0xdecb, 0xdd7d, 0xdc34, 0xdaf1,
    0xd9b3, 0xd87b, 0xd748, 0xd61a, 0xd4f1, 0xd3cd, 0xd2ad, 0xd192,
    0xd07b, 0xcf69, 0xce5b, 0xcd51, 0xcc4a, 0xcb48, 0xca4a, 0xc94f,
    0xc858, 0xc764, 0xc674, 0xc587, 0xc49d, 0xc3b7, 0xc2d4, 0xc1f4,
    0xc116, 0xc03c, 0xbf65, 0xbe90, 0xbdbe, 0xbcef, 0xbc23, 0xbb59,
    0xba91, 0xb9cc, 0xb90a, 0xb84a, 0xb78c, 0xb6d0, 0xb617, 0xb560,
];

#[cfg(test)]
mod tests {
    use super::*;
    use canon::xorshift::XorShift;

    #[test]
    fn same_bits_as_libm() {
        let mut rng = XorShift::new(0x9e37_79b9_7f4a_7c15);
        let mut next = || rng.next_u64();
        let check = |x: f64| assert_eq!(sqrt(x).to_bits(), libm::sqrt(x).to_bits(), "{x:e}");
        for x in [0.0, -0.0, 1.0, 2.0, 4.0, 0.25, f64::MIN_POSITIVE, 5e-324, f64::MAX, f64::INFINITY, -1.0, f64::NAN] {
            check(x);
        }
        for _ in 0..1_000_000 {
            let r = next();
            // Any bit pattern, and values of the sizes the arc centre takes.
            check(f64::from_bits(r));
            check(f64::from_bits(r >> 1));
            check((r >> 11) as f64 / (1u64 << (r % 60)) as f64);
        }
        // Perfect squares and their neighbours (the exact rounding test).
        for k in 1..100_000u64 {
            let sq = (k * k) as f64;
            for x in [sq, f64::from_bits(sq.to_bits() + 1), f64::from_bits(sq.to_bits() - 1)] {
                check(x);
            }
        }
    }
}
