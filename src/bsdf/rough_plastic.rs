//! The precomputed tables of the rough plastic BSDF (Mitsuba 3's `roughplastic`): how much
//! light the rough dielectric coating lets through to the diffuse base from each direction,
//! and how much of the base's diffuse light it reflects back down.
//!
//! As Mitsuba: the external transmittance `t(μ)` at 64 cosines `μ = max(1e-6, i/63)` by
//! 32 x 32 Gauss-Legendre points over the visible-normal sample space, interpolated linearly;
//! the internal reflectance `2 · mean_i(R_int(μ_i) μ_i)` with `R_int` the reflectance of the
//! interface seen from inside (relative index `1/η`), 128 x 128 points. Computing them takes
//! a fraction of a second, so they are made once per `(distribution, α, η)` and shared:
//! [`RoughPlasticTables::get`] caches them for the life of the process.

use crate::bsdf::microfacet::{Microfacet, MicrofacetDistribution, gauss_legendre_01};
use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

/// Number of cosines tabled (Mitsuba's `MI_ROUGH_TRANSMITTANCE_RES`).
pub const RES: usize = 64;

/// Tables of one rough plastic coating.
#[derive(Debug)]
pub struct RoughPlasticTables {
    pub kind: Microfacet,
    /// Roughness, already clamped as [`MicrofacetDistribution::new`] clamps it.
    pub alpha: f32,
    pub eta: f32,
    /// `t(μ_i)`: fraction of light from cosine `μ_i` transmitted into the coating.
    pub external_transmittance: [f32; RES],
    /// Fraction of the diffuse base's light the coating reflects back down.
    pub internal_reflectance: f32,
}

type Key = (Microfacet, u32, u32);

impl RoughPlasticTables {
    /// The tables of a coating, computed on first use and cached.
    pub fn get(kind: Microfacet, alpha: f32, eta: f32) -> &'static RoughPlasticTables {
        static CACHE: OnceLock<Mutex<HashMap<Key, &'static RoughPlasticTables>>> = OnceLock::new();
        let alpha = MicrofacetDistribution::new(kind, alpha).alpha_u;
        let key = (kind, alpha.to_bits(), eta.to_bits());
        let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
        if let Some(t) = cache.lock().unwrap().get(&key) {
            return t;
        }
        // Computed without the lock (another thread may do the same; the first insert wins).
        let tables: &'static RoughPlasticTables =
            Box::leak(Box::new(Self::compute(kind, alpha, eta)));
        cache.lock().unwrap().entry(key).or_insert(tables)
    }

    /// True when these are the tables of `(kind, alpha, eta)` (`alpha` as given, unclamped).
    pub fn matches(&self, kind: Microfacet, alpha: f32, eta: f32) -> bool {
        self.kind == kind
            && self.alpha == alpha.max(crate::bsdf::microfacet::ALPHA_MIN)
            && self.eta == eta
    }

    fn compute(kind: Microfacet, alpha: f32, eta: f32) -> Self {
        let distr = MicrofacetDistribution::new(kind, alpha);
        let mu = |i: usize| (i as f32 / (RES - 1) as f32).max(1e-6);
        let res = |e: f32| if e > 1.0 { 32 } else { 128 };
        let q_ext = gauss_legendre_01(res(eta));
        let q_int = gauss_legendre_01(res(1.0 / eta));
        let rows: Vec<(f32, f64)> = (0..RES)
            .into_par_iter()
            .map(|i| {
                let t = distr.dielectric_transmittance(mu(i), eta, &q_ext) as f32;
                let r = distr.dielectric_reflectance(mu(i), 1.0 / eta, &q_int);
                (t, r * mu(i) as f64)
            })
            .collect();
        let mut external_transmittance = [0.0; RES];
        for (e, (t, _)) in external_transmittance.iter_mut().zip(&rows) {
            *e = *t;
        }
        let internal_reflectance =
            (2.0 * rows.iter().map(|(_, r)| r).sum::<f64>() / RES as f64) as f32;
        RoughPlasticTables {
            kind,
            alpha: distr.alpha_u,
            eta,
            external_transmittance,
            internal_reflectance,
        }
    }

    /// `t(cos)`, linearly interpolated (as Mitsuba's `lerp_gather`).
    pub fn transmittance(&self, cos: f32) -> f32 {
        let x = cos.clamp(0.0, 1.0) * (RES - 1) as f32;
        let i = (x as usize).min(RES - 2);
        let w = x - i as f32;
        (1.0 - w) * self.external_transmittance[i] + w * self.external_transmittance[i + 1]
    }
}
