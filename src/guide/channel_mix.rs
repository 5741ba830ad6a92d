//! The channel mixture: how per-channel guide distributions, prepared once, reproduce a
//! path's colour steering.

use crate::Rgb;

/// Probabilities of the three colour channels in a per-channel mixture (they sum to 1).
///
/// A particle's selection weight at a Lambertian vertex is `c_p = Σ_c a_c W_p,c` with
/// `a_c = (luminance coefficient · throughput · albedo)_c` (paper eq. 1-2 with the
/// throughput colour). So choosing channel `c` with probability `a_c S_c / Σ a S` (`S_c` the
/// channel's total weight) and then a particle with probability `W_p,c / S_c` picks `p`
/// with exactly `c_p / Σ c`: per-channel distributions prepared once reproduce per-event
/// colour steering.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChannelMix(pub [f32; 3]);

impl ChannelMix {
    /// The mixture for a path colour `a` (luminance coefficients, throughput and albedo
    /// multiplied) over channel totals `totals`; `None` when nothing would be chosen.
    pub fn new(a: Rgb, totals: Rgb) -> Option<Self> {
        let w = a.max(Rgb::ZERO) * totals.max(Rgb::ZERO);
        let sum = w.x + w.y + w.z;
        if !(sum > 0.0 && sum.is_finite()) {
            return None;
        }
        Some(ChannelMix([w.x / sum, w.y / sum, w.z / sum]))
    }

    /// A channel drawn with these probabilities from `u` in [0, 1).
    #[inline]
    pub fn pick(&self, u: f32) -> usize {
        let [a, b, _] = self.0;
        if u < a && a > 0.0 {
            0
        } else if u < a + b && b > 0.0 {
            1
        } else if self.0[2] > 0.0 {
            2
        } else if b > 0.0 {
            1
        } else {
            0
        }
    }
}
