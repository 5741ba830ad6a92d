//! The `<bsdf>` element: Mitsuba's BSDFs as footprint materials (`docs/mitsuba.md` tables
//! the mapping).

use super::builder::Builder;
use super::conductors::NAMED_CONDUCTORS;
use super::xml::Props;
use crate::Rgb;
use crate::bsdf::material::{Material, MaterialBlend, MaterialKind};
use crate::bsdf::microfacet::Microfacet;
use crate::error::Result;
use roxmltree::{Node, NodeId};

/// Named indices of refraction Mitsuba 3 accepts for `int_ior`/`ext_ior`.
const NAMED_IOR: &[(&str, f32)] = &[
    ("vacuum", 1.0),
    ("helium", 1.000036),
    ("hydrogen", 1.000132),
    ("air", 1.000277),
    ("carbon dioxide", 1.00045),
    ("water", 1.333),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.470),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.575),
    ("diamond", 2.419),
];

const BSDFS: &str = "diffuse, twosided, mask, blendbsdf, bumpmap, normalmap, dielectric, thindielectric, roughdielectric, conductor, roughconductor, plastic, roughplastic, principled";

impl<'a, 'd> Builder<'a, 'd> {
    fn ior(&self, p: &Props<'a, 'd>, name: &str, default: f32) -> Result<f32> {
        let Some(n) = p.get(name) else {
            return Ok(default);
        };
        let v = self.doc.req_attr(n, "value")?;
        if let Ok(x) = v.trim().parse::<f32>() {
            if x.is_finite() && x > 0.0 {
                return Ok(x);
            }
        }
        NAMED_IOR
            .iter()
            .find(|(k, _)| *k == v.trim().to_lowercase())
            .map(|(_, x)| *x)
            .ok_or_else(|| {
                self.doc.err(
                    n,
                    format!(
                        "'{name}': '{v}' is neither a positive number nor a known material ({})",
                        NAMED_IOR
                            .iter()
                            .map(|(k, _)| *k)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                )
            })
    }

    /// The microfacet distribution, roughness `α` (of an anisotropic one `α_u`) and, where
    /// `anisotropic` and `alpha_u` differs from `alpha_v`, `α_v` (else the isotropic
    /// `sqrt(α_u α_v)` stands in, lenient).
    fn microfacet(
        &self,
        p: &Props<'a, 'd>,
        node: Node,
        anisotropic: bool,
    ) -> Result<(Microfacet, f32, Option<f32>)> {
        let dist = match p.string("distribution")?.as_deref().unwrap_or("beckmann") {
            "beckmann" => Microfacet::Beckmann,
            "ggx" => Microfacet::Ggx,
            other => {
                return Err(self.doc.err(
                    node,
                    format!("distribution '{other}' (expected beckmann or ggx)"),
                ));
            }
        };
        let (alpha, alpha_v) = match (p.float("alpha")?, p.float("alpha_u")?, p.float("alpha_v")?) {
            (Some(a), None, None) => (a, None),
            (None, Some(u), Some(v)) if u == v => (u, None),
            (None, Some(u), Some(v)) if anisotropic => (u, Some(v)),
            (None, Some(u), Some(v)) => {
                if (u - v).abs() > 1e-6 * u.max(v) {
                    self.doc.unsupported(
                        node,
                        "anisotropic roughness (alpha_u != alpha_v) here",
                        "isotropic alpha (anisotropy in roughconductor and roughdielectric)",
                        &format!(
                            "isotropic alpha = sqrt(alpha_u alpha_v) = {}",
                            (u * v).sqrt()
                        ),
                    )?;
                }
                ((u * v).sqrt(), None)
            }
            (None, None, None) => (0.1, None),
            _ => {
                return Err(self
                    .doc
                    .err(node, "give either 'alpha' or both 'alpha_u' and 'alpha_v'"));
            }
        };
        for a in std::iter::once(alpha).chain(alpha_v) {
            if !(a > 0.0 && a <= 4.0) {
                return Err(self
                    .doc
                    .err(node, format!("alpha must be in (0, 4], got {a}")));
            }
        }
        if ["alpha", "alpha_u", "alpha_v"]
            .iter()
            .any(|n| p.is_texture(n))
        {
            return Err(self.doc.err(node, "a textured alpha is not supported"));
        }
        p.ignore(&["sample_visible"]);
        Ok((dist, alpha.max(1e-4), alpha_v.map(|v| v.max(1e-4))))
    }

    fn conductor_ior(&self, p: &Props<'a, 'd>, node: Node) -> Result<(Rgb, Rgb)> {
        let eta = p.rgb("eta")?;
        let k = p.rgb("k")?;
        let material = p.string("material")?;
        // Mitsuba's eta and k are relative to the exterior's index.
        let ext = self.ior(p, "ext_eta", 1.0)?;
        match (eta, k, material.as_deref()) {
            (Some(e), Some(k), None) => Ok((e / ext, k / ext)),
            // Mitsuba: `k` defaults to 1 when `eta` is given.
            (Some(e), None, None) => Ok((e / ext, Rgb::ONE / ext)),
            // Mitsuba's default `none`: η = 0, k = 1, whose Fresnel factor is 1 at every angle
            // (a perfect mirror).
            (None, None, None | Some("none")) => Ok((Rgb::ZERO, Rgb::ONE)),
            // Mitsuba's presets, as its RGB variant renders them (`conductors.rs`).
            (None, None, Some(m)) => match NAMED_CONDUCTORS.iter().find(|(n, ..)| *n == m) {
                Some((_, e, k)) => Ok((Rgb::from_array(*e) / ext, Rgb::from_array(*k) / ext)),
                None => {
                    self.doc.unsupported(
                        node,
                        &format!("conductor material '{m}'"),
                        &format!(
                            "'none', {}, or explicit 'eta' and 'k' colours",
                            NAMED_CONDUCTORS
                                .iter()
                                .map(|(n, ..)| *n)
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                        "a perfect mirror (material 'none')",
                    )?;
                    Ok((Rgb::ZERO, Rgb::ONE))
                }
            },
            _ => Err(self.doc.err(
                node,
                "give 'eta' (and 'k', default 1) or a 'material', not both",
            )),
        }
    }

    /// Builds a `<bsdf>` (once per element); the material is not yet in the scene.
    pub(super) fn bsdf(&mut self, node: Node<'a, 'a>) -> Result<Material> {
        if let Some(m) = self.material_of.get(&node.id()) {
            return Ok(m.clone());
        }
        if self.building.contains(&node.id()) {
            return Err(self
                .doc
                .err(node, "this BSDF contains itself (a cycle of references)"));
        }
        self.building.push(node.id());
        let m = self.build_bsdf(node);
        self.building.pop();
        m
    }

    fn build_bsdf(&mut self, node: Node<'a, 'a>) -> Result<Material> {
        let kind = self.kind(node)?;
        let p = Props::new(self.doc, node)?;
        let name = node
            .attribute("id")
            .map(str::to_string)
            .unwrap_or_else(|| format!("{kind}@{}", self.doc.pos(node).0));
        let mut m = Material {
            name,
            two_sided: false,
            ..Material::default()
        };
        match kind.as_str() {
            "twosided" => {
                let inner: Vec<Node> = p
                    .unnamed
                    .iter()
                    .map(|n| self.deref(*n))
                    .collect::<Result<_>>()?;
                let inner: Vec<Node> = inner
                    .into_iter()
                    .filter(|n| n.has_tag_name("bsdf"))
                    .collect();
                let transmits = |m: &Material| {
                    m.kind == MaterialKind::Principled && m.principled.may_transmit()
                };
                match inner.as_slice() {
                    [b] => {
                        let mut im = self.bsdf(*b)?;
                        if transmits(&im) {
                            // Mitsuba: "Only materials without a transmission component can
                            // be nested!"
                            return Err(self.doc.err(
                                node,
                                "twosided cannot hold a principled BSDF with 'spec_trans' (it transmits), as in Mitsuba",
                            ));
                        }
                        im.two_sided = true;
                        if let Some(blend) = im.blend.as_mut() {
                            blend.other.two_sided = true;
                        }
                        im.name = m.name;
                        m = im;
                    }
                    [b, ..] => {
                        self.doc.unsupported(
                            node,
                            "twosided with different front and back BSDFs",
                            "twosided with one BSDF",
                            "the front BSDF on both sides",
                        )?;
                        let mut im = self.bsdf(*b)?;
                        im.two_sided = true;
                        m = im;
                    }
                    [] => return Err(self.doc.err(node, "twosided needs a nested <bsdf>")),
                }
            }
            "blendbsdf" => {
                let mut blended = self.blend(node, &p)?;
                blended.name = m.name;
                m = blended;
            }
            "mask" => {
                let mut masked = self.mask(node, &p)?;
                masked.name = m.name;
                m = masked;
            }
            "bumpmap" | "normalmap" => {
                let mut bumped = self.bumpmap(node, &p, kind == "normalmap")?;
                bumped.name = m.name;
                m = bumped;
            }
            "diffuse" => {
                m.kind = MaterialKind::Diffuse;
                (m.kd, m.kd_texture) = self.color_or_texture(&p, "reflectance", Rgb::splat(0.5))?;
            }
            "dielectric" | "thindielectric" => {
                let int = self.ior(&p, "int_ior", 1.5046)?;
                let ext = self.ior(&p, "ext_ior", 1.000277)?;
                m.ni = int / ext;
                let (sr, srt) = self.color_or_texture(&p, "specular_reflectance", Rgb::ONE)?;
                let (st, stt) = self.color_or_texture(&p, "specular_transmittance", Rgb::ONE)?;
                if srt.is_some() || stt.is_some() || sr != Rgb::ONE {
                    self.doc.unsupported(
                        node,
                        "a textured or non-white specular_reflectance, or a textured specular_transmittance, of a dielectric",
                        "a constant specular_transmittance",
                        "white reflectance and the constant factor",
                    )?;
                }
                m.ks = sr;
                if kind == "dielectric" {
                    m.kind = MaterialKind::Glass;
                    // `tf` is the transmittance of a passage in and out: two interfaces.
                    m.tf = st * st;
                } else {
                    m.kind = MaterialKind::ThinGlass;
                    m.tf = st;
                }
            }
            "roughdielectric" => {
                let int = self.ior(&p, "int_ior", 1.5046)?;
                let ext = self.ior(&p, "ext_ior", 1.000277)?;
                if int == ext {
                    return Err(self.doc.err(
                        node,
                        format!("int_ior and ext_ior must differ (both {int})"),
                    ));
                }
                m.kind = MaterialKind::RoughGlass;
                m.ni = int / ext;
                (m.ks, m.ks_texture) =
                    self.color_or_texture(&p, "specular_reflectance", Rgb::ONE)?;
                let (st, stt) = self.color_or_texture(&p, "specular_transmittance", Rgb::ONE)?;
                if stt.is_some() {
                    self.doc.unsupported(
                        node,
                        "a textured specular_transmittance of a roughdielectric",
                        "a constant specular_transmittance",
                        "its constant factor",
                    )?;
                }
                // `tf` is the transmittance of a passage in and out: two interfaces.
                m.tf = st * st;
                (m.microfacet, m.alpha, m.alpha_v) = self.microfacet(&p, node, true)?;
            }
            "conductor" | "roughconductor" => {
                (m.eta, m.k) = self.conductor_ior(&p, node)?;
                (m.ks, m.ks_texture) =
                    self.color_or_texture(&p, "specular_reflectance", Rgb::ONE)?;
                if kind == "conductor" {
                    m.kind = MaterialKind::Conductor;
                } else {
                    m.kind = MaterialKind::RoughConductor;
                    (m.microfacet, m.alpha, m.alpha_v) = self.microfacet(&p, node, true)?;
                }
            }
            "principled" => self.principled(&p, node, &mut m)?,
            "plastic" | "roughplastic" => {
                let int = self.ior(&p, "int_ior", 1.49)?;
                let ext = self.ior(&p, "ext_ior", 1.000277)?;
                m.ni = int / ext;
                (m.kd, m.kd_texture) =
                    self.color_or_texture(&p, "diffuse_reflectance", Rgb::splat(0.5))?;
                (m.ks, m.ks_texture) =
                    self.color_or_texture(&p, "specular_reflectance", Rgb::ONE)?;
                m.nonlinear = p.boolean("nonlinear")?.unwrap_or(false);
                if kind == "plastic" {
                    m.kind = MaterialKind::Plastic;
                } else {
                    m.kind = MaterialKind::RoughPlastic;
                    (m.microfacet, m.alpha, _) = self.microfacet(&p, node, false)?;
                }
            }
            other => {
                self.doc.unsupported(
                    node,
                    &format!("bsdf '{other}'"),
                    BSDFS,
                    "a grey diffuse BSDF (reflectance 0.5)",
                )?;
                self.material_of.insert(node.id(), m.clone());
                return Ok(m);
            }
        }
        p.finish(&format!("bsdf '{kind}'"))?;
        let m = m.sanitized();
        self.material_of.insert(node.id(), m.clone());
        Ok(m)
    }

    /// Mitsuba's `blendbsdf`: two nested BSDFs (in document order, `bsdf_0` then `bsdf_1`)
    /// and `weight`, the share of the second (a number or a texture's luminance; required, as
    /// in Mitsuba, and clamped to [0, 1] where it is read, as Mitsuba's `eval_weight`). The
    /// components must be reflecting kinds without a bump map, a mask or a blend of their own
    /// (a bump map or mask around the blend applies to both).
    fn blend(&mut self, node: Node<'a, 'a>, p: &Props<'a, 'd>) -> Result<Material> {
        let nested = self.nested_bsdfs(p)?;
        let [first, second] = nested.as_slice() else {
            return Err(self.doc.err(
                node,
                format!("blendbsdf needs two nested <bsdf>, found {}", nested.len()),
            ));
        };
        if p.get("weight").is_none() {
            return Err(self.doc.err(node, "blendbsdf needs a 'weight'"));
        }
        let (colour, weight_texture) = self.color_or_texture(p, "weight", Rgb::ONE)?;
        let weight = crate::math::luminance(colour).clamp(0.0, 1.0);
        let (mut a, mut b) = (self.bsdf(*first)?, self.bsdf(*second)?);
        for (c, n) in [(&mut a, *first), (&mut b, *second)] {
            if c.transmits() {
                return Err(self.doc.err(
                    n,
                    "a dielectric in a blendbsdf is not supported (blends of reflecting BSDFs are)",
                ));
            }
            if c.bump.is_some() || c.is_masked() || c.blend.is_some() {
                self.doc.unsupported(
                    n,
                    "a bump map, mask or blend inside a blendbsdf",
                    "a bump map or mask around the blend",
                    "the component without it",
                )?;
                c.bump = None;
                (c.opacity, c.opacity_texture, c.blend) = (1.0, None, None);
            }
        }
        a.blend = Some(Box::new(MaterialBlend {
            weight,
            weight_texture,
            other: b,
        }));
        Ok(a)
    }

    /// The nested `<bsdf>` elements of a BSDF, references resolved, in document order.
    fn nested_bsdfs(&self, p: &Props<'a, 'd>) -> Result<Vec<Node<'a, 'a>>> {
        Ok(p.unnamed
            .iter()
            .map(|n| self.deref(*n))
            .collect::<Result<Vec<_>>>()?
            .into_iter()
            .filter(|n| n.has_tag_name("bsdf"))
            .collect())
    }

    /// Mitsuba's `mask`: the one nested BSDF, cut out where `opacity` (a number, the
    /// luminance of a colour, or a texture's luminance; default 0.5) is under 1. A mask in a mask multiplies the
    /// opacities where at most one is a texture. Light passes a cut-out in a straight line,
    /// so a mask around a dielectric (which bends or splits it) is unsupported.
    fn mask(&mut self, node: Node<'a, 'a>, p: &Props<'a, 'd>) -> Result<Material> {
        let nested = self.nested_bsdfs(p)?;
        let [inner] = nested.as_slice() else {
            return Err(self.doc.err(
                node,
                format!(
                    "mask needs exactly one nested <bsdf>, found {}",
                    nested.len()
                ),
            ));
        };
        let mut m = self.bsdf(*inner)?;
        // A number, a colour or a spectrum (its luminance, as Mitsuba's `eval_1`), or a
        // texture.
        let (colour, texture) = self.color_or_texture(p, "opacity", Rgb::splat(0.5))?;
        let opacity = crate::math::luminance(colour);
        if !(0.0..=1.0).contains(&opacity) {
            let n = p.get("opacity").unwrap_or(node);
            return Err(self
                .doc
                .err(n, format!("opacity must be in [0, 1], got {opacity}")));
        }
        if m.transmits() {
            self.doc.unsupported(
                node,
                "a mask around a dielectric",
                "masks around reflecting BSDFs",
                "the dielectric without its mask",
            )?;
            return Ok(m);
        }
        if texture.is_some() && m.opacity_texture.is_some() {
            return Err(self.doc.err(
                node,
                "a textured mask inside a textured mask is not supported",
            ));
        }
        m.opacity *= opacity;
        m.opacity_texture = m.opacity_texture.or(texture);
        Ok(m)
    }

    /// Index of the scene material made from BSDF element `bsdf` (`None`: the default BSDF)
    /// with emission `m.ke`, adding `m` when new.
    pub(super) fn material_id(&mut self, bsdf: Option<NodeId>, m: Material) -> u32 {
        let key = (bsdf, m.ke.to_array().map(f32::to_bits));
        if let Some(&i) = self.material_index.get(&key) {
            return i;
        }
        self.materials.push(m);
        let i = self.materials.len() as u32 - 1;
        self.material_index.insert(key, i);
        i
    }
}
