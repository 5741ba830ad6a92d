//! Counters of a render's paths: guided scattering events and fallbacks to BSDF sampling,
//! surface hits and escaping rays (what the skip counters of [`crate::skips`] are made of).

use footprint::guide::sampler::SamplerState;

/// Counts of guided scattering events and of fallbacks to BSDF sampling, and of the surface
/// hits and escaping rays of the paths (what the skip counters are made of).
#[derive(Clone, Copy, Debug, Default)]
pub struct GuideCounts {
    pub prepared: u64,
    pub fallbacks: u64,
    pub vertices: u64,
    pub escapes: u64,
}

impl GuideCounts {
    pub fn of(s: &SamplerState) -> Self {
        GuideCounts {
            prepared: s.prepared_events,
            fallbacks: s.fallbacks,
            vertices: s.vertices,
            escapes: s.escapes,
        }
    }

    pub fn add(&mut self, o: &GuideCounts) {
        self.prepared += o.prepared;
        self.fallbacks += o.fallbacks;
        self.vertices += o.vertices;
        self.escapes += o.escapes;
    }

    pub fn minus(&self, o: &GuideCounts) -> Self {
        GuideCounts {
            prepared: self.prepared - o.prepared,
            fallbacks: self.fallbacks - o.fallbacks,
            vertices: self.vertices - o.vertices,
            escapes: self.escapes - o.escapes,
        }
    }
}
