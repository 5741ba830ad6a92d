//! The registered guides, by name.

use crate::guide::distribution::{Guide, GuideDistribution, GuideParticle};
use crate::guide::footprint::FootprintGuide;
use crate::guide::grid::GridGuide;
use crate::math::Frame;
use crate::settings::GuideParams;

/// BSDF sampling alone: the guide that guides nowhere.
pub struct BsdfOnly;

impl Guide for BsdfOnly {
    fn name(&self) -> &'static str {
        "bsdf"
    }
    fn about(&self) -> &'static str {
        "The BSDF's own sampling (no particle map)"
    }
    fn uses_particles(&self) -> bool {
        false
    }
    fn build(
        &self,
        _frame: &Frame,
        _particles: &[GuideParticle],
        _params: &GuideParams,
    ) -> Option<Box<dyn GuideDistribution>> {
        None
    }
}

/// Every guide, by name: the one registration list.
pub static GUIDES: &[&dyn Guide] = &[&BsdfOnly, &GridGuide, &FootprintGuide];

/// The guide named `name`.
pub fn find_guide(name: &str) -> Option<&'static dyn Guide> {
    GUIDES.iter().copied().find(|g| g.name() == name)
}

/// The registered guides' names, comma-separated (for error messages).
pub fn guide_names() -> String {
    GUIDES
        .iter()
        .map(|g| g.name())
        .collect::<Vec<_>>()
        .join(", ")
}
