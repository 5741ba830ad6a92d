//! What a user asks to render: a fixed method (`pt-footprint`), or `auto`'s choice among
//! candidates, with the integrator, the guide or both chosen by the pilot (`auto-bsdf`,
//! `pt-auto`, `auto`). The one place where `auto` in a name is understood; a fixed name is
//! resolved by [`Method`].

use crate::integrator::{Integrator, find_integrator};
use crate::method::Method;
use footprint::guide::{GUIDES, Guide};
use footprint::scene::Scene;
use footprint::settings::Named;
use std::fmt;

/// The integrators `auto` chooses among when the integrator is not fixed.
const AUTO_INTEGRATORS: [&str; 3] = ["pt", "lt", "combined"];

/// What `auto` chooses among: every registered guide with every integrator of
/// [`AUTO_INTEGRATORS`], less the part that is fixed.
#[derive(Clone)]
pub struct AutoSpec {
    /// The integrator when it is fixed (`pt-auto`), `None` when it is chosen.
    pub integrator: Option<&'static dyn Integrator>,
    /// The guide when it is fixed (`auto-bsdf`), `None` when it is chosen.
    pub guide: Option<&'static dyn Guide>,
    pub candidates: Vec<Method>,
    /// `auto`, `auto-bsdf` (integrator chosen), `pt-auto` (guide chosen).
    pub label: String,
}

impl fmt::Debug for AutoSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.label)
    }
}

impl PartialEq for AutoSpec {
    fn eq(&self, o: &Self) -> bool {
        self.label == o.label
    }
}

impl AutoSpec {
    /// `integrator` and `guide` fixed when given, chosen when `None`.
    pub fn new(
        integrator: Option<&'static dyn Integrator>,
        guide: Option<&'static dyn Guide>,
    ) -> Self {
        let integrators: Vec<&'static dyn Integrator> = match integrator {
            Some(i) => vec![i],
            None => AUTO_INTEGRATORS
                .iter()
                .filter_map(|n| find_integrator(n))
                .collect(),
        };
        let guides: Vec<&'static dyn Guide> = match guide {
            Some(g) => vec![g],
            None => GUIDES.to_vec(),
        };
        let mut candidates = Vec::new();
        for g in &guides {
            for i in &integrators {
                candidates.push(Method {
                    integrator: *i,
                    guide: *g,
                });
            }
        }
        let label = match (integrator, guide) {
            (None, None) => "auto".to_string(),
            (i, g) => format!(
                "{}-{}",
                i.map_or("auto", |i| i.name()),
                g.map_or("auto", |g| g.name())
            ),
        };
        AutoSpec {
            integrator,
            guide,
            candidates,
            label,
        }
    }

    /// Every registered method.
    pub fn all() -> Self {
        Self::new(None, None)
    }
}

/// A fixed method or `auto`'s choice.
#[derive(Clone, Debug, PartialEq)]
pub enum Request {
    Fixed(Method),
    Auto(AutoSpec),
}

impl Default for Request {
    /// Unguided path tracing.
    fn default() -> Self {
        Request::Fixed(Method::default())
    }
}

impl From<Method> for Request {
    fn from(m: Method) -> Self {
        Request::Fixed(m)
    }
}

impl Request {
    /// From the two parts, `None` for a part `auto` chooses.
    fn from_parts(
        integrator: Option<&'static dyn Integrator>,
        guide: Option<&'static dyn Guide>,
    ) -> Self {
        match (integrator, guide) {
            (Some(integrator), Some(guide)) => Request::Fixed(Method { integrator, guide }),
            (i, g) => Request::Auto(AutoSpec::new(i, g)),
        }
    }

    /// The two parts, `None` for a part `auto` chooses.
    fn parts(&self) -> (Option<&'static dyn Integrator>, Option<&'static dyn Guide>) {
        match self {
            Request::Fixed(m) => (Some(m.integrator), Some(m.guide)),
            Request::Auto(s) => (s.integrator, s.guide),
        }
    }

    /// `pt-footprint`, or `auto`'s label (`auto`, `pt-auto`, `auto-bsdf`).
    pub fn label(&self) -> String {
        match self {
            Request::Fixed(m) => m.name(),
            Request::Auto(s) => s.label.clone(),
        }
    }

    /// The method when it is fixed.
    pub fn fixed(&self) -> Option<Method> {
        match self {
            Request::Fixed(m) => Some(*m),
            Request::Auto(_) => None,
        }
    }

    /// Parses `INTEGRATOR-GUIDE`, with `auto` for either part, or `auto` alone
    /// (`compare --methods`).
    pub fn parse(s: &str) -> Result<Self, String> {
        if s == "auto" {
            return Ok(Request::Auto(AutoSpec::all()));
        }
        let (i, g) = s.split_once('-').ok_or_else(|| {
            format!("'{s}' is not a method (expected INTEGRATOR-GUIDE, e.g. pt-footprint, or auto)")
        })?;
        Request::default().with_names(Some(i), Some(g))
    }

    /// The request of a scene file's `[render] integrator` and `guide` (`auto` allowed for
    /// either; unguided path tracing's part where one is not given); an unknown name is an
    /// error at its place in the file.
    pub fn from_scene(scene: &Scene) -> Result<Self, String> {
        let s = &scene.settings;
        let name = |n: &Option<Named>, key: &str| -> Result<Option<String>, String> {
            let Some(n) = n else { return Ok(None) };
            let known = match (n.name.as_str(), key) {
                ("auto", _) => Ok(()),
                (name, "integrator") => Method::integrator(name).map(|_| ()),
                (name, _) => Method::guide(name).map(|_| ()),
            };
            known
                .map(|_| Some(n.name.clone()))
                .map_err(|e| format!("{}: render.{key}: {e}", n.at))
        };
        let i = name(&s.integrator, "integrator")?;
        let g = name(&s.guide, "guide")?;
        Request::default().with_names(i.as_deref(), g.as_deref())
    }

    /// This request with names given on the command line applied over it: a named part is
    /// fixed (or chosen, for `auto`), a part not named keeps what it was.
    pub fn with_names(
        &self,
        integrator: Option<&str>,
        guide: Option<&str>,
    ) -> Result<Self, String> {
        let (i, g) = self.parts();
        let i = match integrator {
            Some("auto") => None,
            Some(n) => Some(Method::integrator(n)?),
            None => i,
        };
        let g = match guide {
            Some("auto") => None,
            Some(n) => Some(Method::guide(n)?),
            None => g,
        };
        Ok(Self::from_parts(i, g))
    }
}
