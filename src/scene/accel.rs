//! The acceleration structure a scene's rays are traced with: Embree 3 where the system has
//! it ([`crate::scene::embree`], loaded at run time), else footprint's own CWBVH
//! ([`crate::scene::bvh`]). Both answer the same two queries (closest hit, occlusion) for
//! the same triangles; their arithmetic differs in the last bits, so images agree
//! statistically, not bit for bit, across backends (the EXR header names the one used).
//!
//! The backend is chosen per process: `--accel` on the command line
//! ([`set_backend`]), else the `FOOTPRINT_ACCEL` environment variable (`auto`, `embree`,
//! `cwbvh`), else `auto` (Embree when it loads).

use crate::keyword::Keyword;
use crate::scene::bvh::{Bvh, BvhHit};
use crate::scene::embree::{self, EmbreeBvh};
use crate::scene::geometry::TriangleGeom;
pub use crate::scene::shadow_order::{ShadowOrder, Toward};
use glam::Vec3;
use std::sync::atomic::{AtomicU8, Ordering};

/// Which acceleration structure scenes are built with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// Embree when the system has it (`libembree3`), else the CWBVH
    Auto,
    /// Embree 3, loaded at run time; an error when it cannot be loaded
    Embree,
    /// footprint's own compressed wide BVH (obvhs)
    Cwbvh,
}

impl Keyword for Backend {
    const ALL: &'static [Self] = &[Backend::Auto, Backend::Embree, Backend::Cwbvh];

    /// The name `--accel` and `FOOTPRINT_ACCEL` take.
    fn name(self) -> &'static str {
        match self {
            Backend::Auto => "auto",
            Backend::Embree => "embree",
            Backend::Cwbvh => "cwbvh",
        }
    }

    fn about(self) -> &'static str {
        match self {
            Backend::Auto => "Embree when the system has it (`libembree3`), else the CWBVH",
            Backend::Embree => "Embree 3, loaded at run time; an error when it cannot be loaded",
            Backend::Cwbvh => "footprint's own compressed wide BVH (obvhs)",
        }
    }
}

/// 0: not set (read `FOOTPRINT_ACCEL`), else 1 + the backend's index.
static BACKEND: AtomicU8 = AtomicU8::new(0);

/// Sets the backend every scene built after this call uses.
pub fn set_backend(backend: Backend) {
    BACKEND.store(1 + backend as u8, Ordering::Relaxed);
}

/// The backend asked for: [`set_backend`]'s, else `FOOTPRINT_ACCEL`'s, else `auto`. An
/// unknown `FOOTPRINT_ACCEL` is an error naming it.
pub fn backend() -> Result<Backend, String> {
    match BACKEND.load(Ordering::Relaxed) {
        0 => match std::env::var("FOOTPRINT_ACCEL") {
            Ok(s) => Backend::from_name(&s).ok_or_else(|| {
                format!("FOOTPRINT_ACCEL={s}: expected one of {}", Backend::names())
            }),
            Err(_) => Ok(Backend::Auto),
        },
        b => Ok(Backend::ALL[(b - 1) as usize]),
    }
}

/// A scene's acceleration structure.
pub enum Accel {
    Embree(EmbreeBvh),
    Cwbvh(Bvh),
}

impl Accel {
    /// Builds the backend [`backend`] asks for over `triangles` (at least one).
    pub fn build(triangles: &[TriangleGeom]) -> Result<Self, String> {
        Self::build_with(triangles, backend()?)
    }

    /// Builds `backend` over `triangles`: `auto` falls back to the CWBVH when Embree cannot
    /// be loaded; `embree` is then an error saying why.
    pub fn build_with(triangles: &[TriangleGeom], backend: Backend) -> Result<Self, String> {
        match backend {
            Backend::Cwbvh => Ok(Accel::Cwbvh(Bvh::build(triangles))),
            Backend::Embree => EmbreeBvh::build(triangles)
                .map(Accel::Embree)
                .map_err(|e| format!("Embree asked for: {e} (Debian: apt install libembree3-3)")),
            // Embree absent, or present but failing (an unsupported CPU): the CWBVH.
            Backend::Auto => match embree::available().and_then(|()| EmbreeBvh::build(triangles)) {
                Ok(b) => Ok(Accel::Embree(b)),
                Err(_) => Ok(Accel::Cwbvh(Bvh::build(triangles))),
            },
        }
    }

    /// `embree` or `cwbvh`.
    pub fn name(&self) -> &'static str {
        match self {
            Accel::Embree(_) => Backend::Embree.name(),
            Accel::Cwbvh(_) => Backend::Cwbvh.name(),
        }
    }

    /// Closest hit along `origin + t dir`, `0 < t < t_max`.
    #[inline]
    pub fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<BvhHit> {
        match self {
            Accel::Embree(b) => b.intersect(origin, dir, t_max),
            Accel::Cwbvh(b) => b.intersect(origin, dir, t_max),
        }
    }

    /// True when nothing blocks `origin + t dir` for `0 < t < t_max` (shadow rays
    /// `toward` a light or the camera: the CWBVH may visit nodes in another order for
    /// each, [`Accel::choose_shadow_order`]).
    #[inline]
    pub fn unoccluded(&self, toward: Toward, origin: Vec3, dir: Vec3, t_max: f32) -> bool {
        match self {
            Accel::Embree(b) => b.unoccluded(origin, dir, t_max),
            Accel::Cwbvh(b) => b.unoccluded(toward, origin, dir, t_max),
        }
    }

    /// Lets the CWBVH choose the order in which its shadow rays `toward` a light or the
    /// camera visit nodes, from `segments`, a sample of such rays
    /// ([`Bvh::choose_shadow_order`]); Embree keeps its own. The choice and the nodes and
    /// triangles tested per segment each way, or `None`.
    pub fn choose_shadow_order(
        &mut self,
        toward: Toward,
        segments: &[(Vec3, Vec3, f32)],
    ) -> Option<(ShadowOrder, [f64; 2])> {
        match self {
            Accel::Embree(_) => None,
            Accel::Cwbvh(b) => Some(b.choose_shadow_order(toward, segments)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every backend's name reads back as it, and `set_backend` stores the index
    /// `backend` reads (`ALL` is in declaration order).
    #[test]
    fn names_and_indices_agree() {
        for &b in Backend::ALL {
            assert_eq!(Backend::from_name(b.name()), Some(b));
            assert_eq!(Backend::ALL[b as usize], b);
        }
        assert_eq!(Backend::from_name("optix"), None);
    }
}
