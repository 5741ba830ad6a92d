//! A method: an integrator with a guide (`pt-footprint`). The one place where the names
//! given on the command line, in scene files and in `compare --methods` are resolved
//! against the two registries ([`crate::integrator::INTEGRATORS`],
//! [`footprint::guide::GUIDES`]). `auto` in a name is understood one layer up
//! (`crate::auto::Request`).

use crate::integrator::{Integrator, find_integrator, integrator_names};
use footprint::guide::{Guide, find_guide, guide_names};
use footprint::scene::Scene;
use footprint::settings::Named;
use std::fmt;

/// An integrator with a direction sampler.
#[derive(Clone, Copy)]
pub struct Method {
    pub integrator: &'static dyn Integrator,
    pub guide: &'static dyn Guide,
}

impl fmt::Debug for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name())
    }
}

impl PartialEq for Method {
    fn eq(&self, o: &Self) -> bool {
        self.integrator.name() == o.integrator.name() && self.guide.name() == o.guide.name()
    }
}

impl Eq for Method {}

impl Default for Method {
    /// Unguided path tracing.
    fn default() -> Self {
        Method::from_names("pt", "bsdf").expect("pt and bsdf are registered")
    }
}

impl Method {
    /// `INTEGRATOR-GUIDE`, e.g. `pt-footprint`.
    pub fn name(&self) -> String {
        format!("{}-{}", self.integrator.name(), self.guide.name())
    }

    /// True when the method guides with particles (and so needs maps).
    pub fn guided(&self) -> bool {
        self.guide.uses_particles()
    }

    pub fn integrator(name: &str) -> Result<&'static dyn Integrator, String> {
        find_integrator(name).ok_or_else(|| {
            format!(
                "unknown integrator '{name}' (expected one of {})",
                integrator_names()
            )
        })
    }

    pub fn guide(name: &str) -> Result<&'static dyn Guide, String> {
        find_guide(name)
            .ok_or_else(|| format!("unknown guide '{name}' (expected one of {})", guide_names()))
    }

    pub fn from_names(integrator: &str, guide: &str) -> Result<Self, String> {
        Ok(Method {
            integrator: Self::integrator(integrator)?,
            guide: Self::guide(guide)?,
        })
    }

    /// Parses `INTEGRATOR-GUIDE`.
    pub fn parse(s: &str) -> Result<Self, String> {
        let (i, g) = s.split_once('-').ok_or_else(|| {
            format!("'{s}' is not a method (expected INTEGRATOR-GUIDE, e.g. pt-footprint)")
        })?;
        Self::from_names(i, g)
    }

    /// The method a scene file asks for (`[render] integrator`, `guide`), defaulting to
    /// unguided path tracing; an unknown name is an error at its place in the file.
    pub fn from_scene(scene: &Scene) -> Result<Self, String> {
        Self::from_settings(&scene.settings)
    }

    fn from_settings(s: &footprint::settings::RenderSettings) -> Result<Self, String> {
        let resolve = |n: &Option<Named>, key: &str, default: &str| -> Result<String, String> {
            match n {
                Some(n) => {
                    let ok = match key {
                        "integrator" => Self::integrator(&n.name).map(|_| ()),
                        _ => Self::guide(&n.name).map(|_| ()),
                    };
                    ok.map(|_| n.name.clone())
                        .map_err(|e| format!("{}: render.{key}: {e}", n.at))
                }
                None => Ok(default.to_string()),
            }
        };
        let i = resolve(&s.integrator, "integrator", "pt")?;
        let g = resolve(&s.guide, "guide", "bsdf")?;
        Self::from_names(&i, &g)
    }

    /// `compare`'s default set: path and light tracing with each guide, and the combined
    /// image with footprints.
    pub fn all() -> Vec<Method> {
        let mut v = Vec::new();
        for i in ["pt", "lt"] {
            for g in footprint::guide::GUIDES {
                v.push(Method {
                    integrator: find_integrator(i).expect("registered"),
                    guide: *g,
                });
            }
        }
        v.push(Method::from_names("combined", "footprint").expect("registered"));
        v
    }
}
