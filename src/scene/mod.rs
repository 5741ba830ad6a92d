//! The scene: triangles with their shading data, materials, textures, lights, the camera,
//! the BVH, the settings from the scene file, and the effect analysis. Its parts and
//! loaders are the submodules: geometry and the BVH, the camera, lights, textures, the
//! effect analysis, and the TOML/OBJ and Mitsuba 3 XML loaders behind [`load`].

pub mod accel;
pub mod bvh;
pub mod camera;
pub mod cwbvh_walk;
pub mod effects;
pub mod embree;
pub mod envmap;
pub mod features;
pub mod geometry;
pub mod light;
pub mod load;
pub mod mitsuba;
pub mod obj;
pub mod shadow_order;
pub mod texture;
pub mod toml_file;
pub mod triangle_block;

use crate::bsdf::blend::Blend;
use crate::bsdf::bump::{Bump, BumpMap, NormalSource, bumped_normal, mapped_normal, uv_partials};
use crate::bsdf::material::{Material, MaterialKind};
use crate::bsdf::{Bsdf, Lobes, SurfaceLobes};
use crate::features::{Features, General};
use crate::math::{Frame, Rgb};
use crate::sampling::Distribution1D;
use crate::scene::accel::Accel;
pub use crate::scene::accel::Toward;
use crate::scene::camera::Camera;
use crate::scene::effects::Effects;
use crate::scene::geometry::{
    SurfaceHit, TriangleGeom, TriangleShading, offset_ray_origin, spawn_origin,
};
use crate::scene::light::Light;
use crate::scene::texture::Texture;
use crate::settings::{GuideParams, MapSettings, RenderSettings};
use glam::{Vec2, Vec3};
use std::sync::Arc;

/// The least probability of choosing a light for which the choice reuses the light point's
/// number ([`Scene::choose_light`]): stretched back from an interval of width `2^-8`, a
/// number keeps 16 of its 24 bits.
pub const LIGHT_CHOICE_OWN_NUMBER: f32 = 1.0 / 256.0;

/// How far from its file's origin anything of a scene may lie, in metres on every axis: far
/// beyond any scene (f32 steps there are 10⁸ m), short of where products of coordinates
/// overflow. The readers name the field or line past it; [`Scene::new`] checks the whole.
pub const MAX_COORDINATE: f32 = 1e15;

/// Most cut-out surfaces ([`Scene::opacity`] under 1) a ray passes before it counts as
/// blocked: a bound on the work of one ray through foliage, far above what a scene's leaves
/// stack up to (a ray through 1024 layers each letting half through carries 2⁻¹⁰²⁴).
pub const MAX_CUTOUT_CROSSINGS: u32 = 1024;

/// Paths (camera paths for shadow rays toward a light, light paths for those toward the
/// camera) whose shadow rays [`Scene::probe_shadow_segments`] draws.
pub const SHADOW_PROBES: usize = 2048;

/// Counts reported after loading.
#[derive(Clone, Debug, Default)]
pub struct LoadStats {
    pub triangles: usize,
    pub degenerate_skipped: usize,
    pub meshes: usize,
}

/// Cloning shares the large, immutable parts (triangles, shading data, textures, the BVH)
/// and copies the rest: [`Scene::with_resolution`] makes a view through another camera.
#[derive(Clone)]
pub struct Scene {
    pub camera: Camera,
    pub triangles: Arc<[TriangleGeom]>,
    pub shading: Arc<[TriangleShading]>,
    pub materials: Vec<Material>,
    pub textures: Arc<[Texture]>,
    pub lights: Vec<Light>,
    /// Chooses lights in proportion to power.
    pub light_distribution: Distribution1D,
    /// The light choice draws its own number (see [`Scene::choose_light`]).
    pub light_choice_own_number: bool,
    pub bvh: Arc<Accel>,
    pub settings: RenderSettings,
    pub maps: MapSettings,
    pub guide: GuideParams,
    pub effects: Effects,
    pub stats: LoadStats,
    /// Scene bounding box, in the scene's own coordinates (see [`Scene::origin`]).
    pub bounds: (Vec3, Vec3),
    /// Where the scene's own origin lies in the coordinates of its file: zero, or the centre
    /// of its geometry's bounds when the scene lies far from the origin ([`rebase_origin`]).
    /// Positions in a `Scene` (vertices, lights, the camera, particles, caches) are relative
    /// to it; `position + origin` is where the scene file put them.
    pub origin: Vec3,
    /// The scale of the robust ray offset's fixed steps near the origin
    /// ([`offset_ray_origin`]): the bounds' diagonal, at most 1.
    pub offset_scale: f32,
    /// What a lenient import replaced, one line each (empty otherwise).
    pub import_notes: Vec<String>,
    /// Index of the environment light, if any (at most one).
    pub environment_light: Option<u32>,
    /// Parameters the scene was loaded with (`-D name=value ...`), part of a reference's key.
    pub source_params: String,
}

/// The point a scene whose geometry spans `lo`..`hi` (in its file's coordinates) is moved
/// to the origin from: the centre of the bounds (rounded to f32), when it lies farther from
/// the origin than the bounds' diagonal is long; zero otherwise.
///
/// Rays, hits and offsets are f32, whose spacing grows with a coordinate's magnitude: at 10⁵
/// it is 2⁻⁷, and the robust ray offset ([`offset_ray_origin`], 256 steps of it) moves a ray
/// two units off its surface; particle positions, cache regions and their radii lose as much.
/// Centred, every coordinate is at most about the scene's size and keeps the precision a
/// scene near the origin has. A scene whose centre lies within its diagonal of the origin
/// would gain at most a bit or two and keeps its coordinates (and its images, bit for bit).
/// The vertices keep the precision their file gave them: subtracting the centre from a
/// nearby f32 coordinate is exact.
pub fn rebase_origin(lo: Vec3, hi: Vec3) -> Vec3 {
    let (lo, hi) = (lo.as_dvec3(), hi.as_dvec3());
    let centre = 0.5 * (lo + hi);
    if !centre.is_finite() || centre.abs().max_element() <= (hi - lo).length() {
        Vec3::ZERO
    } else {
        centre.as_vec3()
    }
}

/// [`Scene::offset_scale`] of a scene whose geometry spans `lo`..`hi`: its diagonal where
/// that is under a unit, else 1. Scenes of a unit or more keep Wächter and Binder's constants
/// (and their images, bit for bit); a smaller scene's offsets near the origin shrink with it.
pub fn offset_scale(lo: Vec3, hi: Vec3) -> f32 {
    let d = (hi - lo).length();
    if d > 0.0 && d < 1.0 { d } else { 1.0 }
}

impl Scene {
    /// A light chosen in proportion to its power, the probability of that choice, and the
    /// pair of numbers for the point on it. The choice reuses the pair's first number,
    /// stretched back to `[0, 1)` within the chosen light's interval
    /// ([`Distribution1D::sample_remapped`]), so that next-event estimation and light paths
    /// spend no dimension of the sequence on it: at a vertex the light point's pair and the
    /// direction's pair share one group of four (`footprint::rng`), one scrambled group
    /// instead of two. Where a light is chosen with probability under
    /// [`LIGHT_CHOICE_OWN_NUMBER`] (thousands of emitting triangles: the stretched number
    /// would keep too few bits), the choice draws a number of its own.
    #[inline]
    pub fn choose_light(&self, rng: &mut crate::rng::Rng) -> (usize, f32, Vec2) {
        if self.light_choice_own_number {
            let (i, pmf) = self.light_distribution.sample(rng.uniform());
            return (i, pmf, rng.uniform2());
        }
        let u = rng.uniform2();
        let (i, pmf, x) = self.light_distribution.sample_remapped(u.x);
        (i, pmf, Vec2::new(x, u.y))
    }

    /// Assembles a scene from its parts, builds the BVH and the light distribution and runs
    /// the effect analysis. Errors when there is no geometry or no light with power.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        camera: Camera,
        triangles: Vec<TriangleGeom>,
        shading: Vec<TriangleShading>,
        materials: Vec<Material>,
        textures: Vec<Texture>,
        mut lights: Vec<Light>,
        settings: RenderSettings,
        stats: LoadStats,
    ) -> Result<Self, String> {
        if triangles.is_empty() {
            return Err("the scene has no geometry (no valid triangles)".into());
        }
        assert_eq!(triangles.len(), shading.len());
        // Derived per-material data (rough plastic tables) is made here, once, for every loader.
        let materials: Vec<Material> = materials.into_iter().map(Material::prepared).collect();
        let (wlo, whi) = crate::math::bounds(
            triangles
                .iter()
                .flat_map(|t| [t.p0, t.p0 + t.e1, t.p0 + t.e2]),
        );
        let far = |p: Vec3| !(p.abs().max_element() <= MAX_COORDINATE);
        if far(wlo) || far(whi) || far(camera.position) {
            return Err(format!(
                "the scene reaches farther than {MAX_COORDINATE:e} m from the origin (geometry from {wlo} to {whi}, camera at {})",
                camera.position
            ));
        }
        for l in &lights {
            if let Light::Point { position, .. } | Light::Spot { position, .. } = l {
                if far(*position) {
                    return Err(format!(
                        "a light at {position} is farther than {MAX_COORDINATE:e} m from the origin"
                    ));
                }
            }
        }
        let origin = rebase_origin(wlo, whi);
        let (mut triangles, mut camera) = (triangles, camera);
        if origin != Vec3::ZERO {
            for t in &mut triangles {
                t.p0 -= origin;
            }
            camera.position -= origin;
            for l in &mut lights {
                match l {
                    Light::Point { position, .. } | Light::Spot { position, .. } => {
                        *position -= origin
                    }
                    Light::Area { geom, .. } => geom.p0 -= origin,
                    Light::Directional { .. } | Light::Environment { .. } => {}
                }
            }
        }
        let mut shading = shading;
        // Area lights from emissive materials, one per triangle.
        for (i, (t, s)) in triangles.iter().zip(shading.iter_mut()).enumerate() {
            let m = &materials[s.material as usize];
            if m.emits() {
                let c = t.cross();
                let area = 0.5 * c.length();
                if area > 0.0 {
                    s.light = Some(lights.len() as u32);
                    lights.push(Light::Area {
                        triangle: i as u32,
                        geom: *t,
                        n: c.normalize(),
                        area,
                        le: m.ke,
                    });
                }
            }
        }
        let (lo, hi) = crate::math::bounds(
            triangles
                .iter()
                .flat_map(|t| [t.p0, t.p0 + t.e1, t.p0 + t.e2]),
        );
        // The lights at infinity surround the scene's bounding sphere (the camera's lens
        // included).
        let lens = Vec3::splat(camera.lens_radius());
        let (blo, bhi) = (
            lo.min(camera.position - lens),
            hi.max(camera.position + lens),
        );
        let (center, radius) = (
            0.5 * (blo + bhi),
            (0.5 * (bhi - blo).length()).max(1e-3) * 1.01,
        );
        for l in &mut lights {
            if let Light::Environment {
                center: c,
                radius: r,
                ..
            }
            | Light::Directional {
                center: c,
                radius: r,
                ..
            } = l
            {
                *c = center;
                *r = radius;
            }
        }
        let powers: Vec<f32> = lights.iter().map(|l| l.power()).collect();
        if powers.iter().any(|p| !p.is_finite()) {
            return Err(
                "a light's power is not a finite number: an intensity or Ke too large (times its area) for 32-bit floats".into(),
            );
        }
        let light_distribution = Distribution1D::new(&powers)
            .ok_or("the scene has no lights (no emissive material with Ke > 0 and no [[light]] with intensity > 0)")?;
        let envs: Vec<u32> = (0..lights.len() as u32)
            .filter(|&i| lights[i as usize].is_environment())
            .collect();
        if envs.len() > 1 {
            return Err("the scene has more than one environment light".into());
        }
        let environment_light = envs.first().copied();
        let light_choice_own_number = light_distribution.min_pmf() < LIGHT_CHOICE_OWN_NUMBER;
        let bvh = Accel::build(&triangles)?;
        let effects = Effects::analyse(&materials, &shading, &lights);
        let mut scene = Scene {
            camera,
            triangles: Arc::from(triangles),
            shading: Arc::from(shading),
            materials,
            light_choice_own_number,
            textures: Arc::from(textures),
            lights,
            light_distribution,
            bvh: Arc::new(bvh),
            settings,
            maps: MapSettings::default(),
            guide: GuideParams::default(),
            effects,
            stats,
            bounds: (lo, hi),
            origin,
            offset_scale: offset_scale(lo, hi),
            import_notes: Vec::new(),
            source_params: String::new(),
            environment_light,
        };
        // The order of the CWBVH's shadow rays (Embree keeps its own; in a scene with thin
        // sheets or cut-outs every shadow segment is walked with closest hits instead).
        if matches!(*scene.bvh, Accel::Cwbvh(_)) && !scene.effects.passes_light() {
            for toward in [Toward::Light, Toward::Camera] {
                let segments = scene.probe_shadow_segments(toward);
                if let Some(bvh) = Arc::get_mut(&mut scene.bvh) {
                    bvh.choose_shadow_order(toward, &segments);
                }
            }
        }
        Ok(scene)
    }

    /// Shadow rays of the kind `toward` that the scene's renders trace, from the first and
    /// second surfaces of [`SHADOW_PROBES`] paths: toward a light, from the surfaces camera
    /// paths meet (through random pixels, then a cosine-weighted bounce) to points drawn on
    /// the lights as next-event estimation draws them; toward the camera, from the surfaces
    /// light paths meet (emitted as light tracing emits them, then a cosine-weighted bounce)
    /// to the lens centre. The CWBVH chooses each kind's traversal order on these
    /// ([`Accel::choose_shadow_order`]). Fixed seeds: the same scene gives the same segments.
    pub fn probe_shadow_segments(&self, toward: Toward) -> Vec<(Vec3, Vec3, f32)> {
        let cam = &self.camera;
        let size = Vec2::new(cam.width as f32, cam.height as f32);
        let mut segments = Vec::with_capacity(2 * SHADOW_PROBES);
        for i in 0..SHADOW_PROBES as u64 {
            let mut rng = crate::rng::Rng::new(0x5AD0, toward as u64, i);
            let (mut o, mut d) = match toward {
                Toward::Light => (cam.position, cam.ray_dir(rng.uniform2() * size)),
                Toward::Camera => {
                    let (light, _, _) = self.choose_light(&mut rng);
                    let Some(e) = self.lights[light].sample_le(rng.uniform2(), rng.uniform2())
                    else {
                        continue;
                    };
                    // Leaving the light as light tracing's paths do (off its surface).
                    (e.n.map_or(e.p, |n| self.offset_origin(e.p, n)), e.dir)
                }
            };
            for _ in 0..2 {
                let Some(h) = self.intersect(o, d, f32::INFINITY) else {
                    break;
                };
                let n = if h.ng.dot(d) < 0.0 { h.ng } else { -h.ng };
                let segment = match toward {
                    Toward::Light => {
                        let (light, _, u) = self.choose_light(&mut rng);
                        self.lights[light]
                            .sample_li(h.p, u)
                            .and_then(|s| self.shadow_segment(h.p, n, s.p, s.n))
                    }
                    Toward::Camera => self.shadow_segment(h.p, n, cam.position, None),
                };
                segments.extend(segment);
                d = crate::math::Frame::from_z(n)
                    .to_world(crate::sampling::sample_cosine_hemisphere(rng.uniform2()));
                o = self.spawn_origin(h.p, n, d);
            }
        }
        segments
    }

    /// The same scene seen by a camera of `width` x `height` pixels (its position, view and
    /// filter kept); the geometry, textures and BVH are shared, not copied. `auto`'s pilot
    /// renders a large image at a lower resolution this way.
    pub fn with_resolution(&self, width: u32, height: u32) -> Result<Scene, String> {
        Ok(Scene {
            camera: self.camera.with_resolution(width, height)?,
            ..self.clone()
        })
    }

    /// Closest surface hit along a ray.
    #[inline]
    pub fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<SurfaceHit> {
        self.intersect_with::<General>(origin, dir, t_max)
    }

    /// [`Scene::intersect`] compiled for the effects `F` (see [`features`]).
    #[inline]
    pub fn intersect_with<F: Features>(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
    ) -> Option<SurfaceHit> {
        let h = self.bvh.intersect(origin, dir, t_max)?;
        Some(self.surface_hit_with::<F>(h.triangle, h.t, h.b1, h.b2))
    }

    /// The full surface description of a hit on triangle `tri` at barycentrics `(b1, b2)`.
    #[inline]
    pub fn surface_hit(&self, tri: u32, t: f32, b1: f32, b2: f32) -> SurfaceHit {
        self.surface_hit_with::<General>(tri, t, b1, b2)
    }

    /// [`Scene::surface_hit`] compiled for the effects `F`: without shading normals the
    /// shading normal is the geometric one, without textures the texture coordinates are not
    /// interpolated (nothing reads them).
    #[inline]
    pub fn surface_hit_with<F: Features>(&self, tri: u32, t: f32, b1: f32, b2: f32) -> SurfaceHit {
        let g = &self.triangles[tri as usize];
        let s = &self.shading[tri as usize];
        let ng = g.cross().normalize();
        let b0 = 1.0 - b1 - b2;
        let normals = if F::SHADING_NORMALS { s.normals } else { None };
        let ns = match normals {
            Some(n) => {
                let n = (b0 * n[0] + b1 * n[1] + b2 * n[2]).normalize_or_zero();
                if n == Vec3::ZERO || !n.is_finite() {
                    ng
                } else {
                    n
                }
            }
            None => ng,
        };
        let uv = match s.uvs {
            Some(uv) if F::TEXTURES => b0 * uv[0] + b1 * uv[1] + b2 * uv[2],
            _ => Vec2::new(b1, b2),
        };
        SurfaceHit {
            t,
            p: g.point(b1, b2),
            ng,
            ns,
            uv,
            triangle: tri,
            material: s.material,
            light: s.light,
        }
    }

    /// The BSDF at a hit (textures looked up only when the material has one).
    #[inline]
    pub fn bsdf(&self, hit: &SurfaceHit) -> Bsdf {
        self.bsdf_with::<General>(hit)
    }

    /// [`Scene::bsdf`] compiled for the effects `F`: no texture lookups without textures,
    /// and a Lambertian material's lobes made directly when every surface is Lambertian.
    /// The BSDF's front is the side the shading normal faces ([`SurfaceHit::facing_ng`]), as
    /// in Mitsuba 3.
    #[inline]
    pub fn bsdf_with<F: Features>(&self, hit: &SurfaceHit) -> Bsdf {
        let m = &self.materials[hit.material as usize];
        if F::LAMBERTIAN && !F::TEXTURES && m.kind == MaterialKind::Diffuse && m.blend.is_none() {
            let lobes = SurfaceLobes {
                lobes: Lobes::Diffuse { kd: m.kd },
                two_sided: m.two_sided,
            };
            return Bsdf::new(lobes, hit.ns, hit.facing_ng());
        }
        let mut bsdf = Bsdf::new(self.lobes_with::<F>(m, hit), hit.ns, hit.facing_ng());
        if let Some(b) = &m.blend {
            let weight = match b.weight_texture {
                Some(t) if F::TEXTURES => b.weight * self.textures[t as usize].lookup_1(hit.uv),
                _ => b.weight,
            };
            let other = self.lobes_with::<F>(&b.other, hit);
            bsdf.blend = Some(Blend {
                weight: weight.clamp(0.0, 1.0),
                lobes: other.lobes,
                two_sided: other.two_sided,
            });
        }
        // An anisotropic roughness is oriented by ∂p/∂u, as in Mitsuba (the isotropic lobes
        // do not depend on the frame's tangent): Mitsuba's shading frame, whose tangent is
        // ∂p/∂u made orthogonal to the normal.
        if bsdf.lobes.is_anisotropic() || bsdf.blend.is_some_and(|b| b.lobes.is_anisotropic()) {
            let (dp_du, _) = self.uv_partials_at(hit);
            if let Some(frame) = Frame::from_z_and_tangent(bsdf.frame.z, dp_du) {
                bsdf.frame = frame;
            }
        }
        if F::TEXTURES
            && let Some(map) = &m.bump
        {
            bsdf.bump = self.bump_at(map, hit, &bsdf);
        }
        bsdf
    }

    /// The lobes of material `m` at `hit`, its textures looked up (compiled for the effects
    /// `F`: none without textures).
    #[inline]
    fn lobes_with<F: Features>(&self, m: &Material, hit: &SurfaceHit) -> SurfaceLobes {
        let (kd_texture, ks_texture) = if F::TEXTURES {
            (m.kd_texture, m.ks_texture)
        } else {
            (None, None)
        };
        let kd = match kd_texture {
            Some(t) => m.kd * self.textures[t as usize].lookup(hit.uv),
            None => m.kd,
        };
        let ks = match ks_texture {
            Some(t) => m.ks * self.textures[t as usize].lookup(hit.uv),
            None => m.ks,
        };
        // Scalar parameters may be textures (the principled BSDF's), read as Mitsuba's
        // `eval_1` reads them.
        Lobes::new_at(m, kd, ks, |t| {
            F::TEXTURES.then(|| self.textures[t as usize].lookup_1(hit.uv))
        })
    }

    /// The opacity of the surface at `hit` (Mitsuba's `mask`: the material's constant times
    /// its opacity texture read as Mitsuba's `eval_1` reads it, [`Texture::lookup_1`],
    /// clamped to [0, 1]): the
    /// probability that light arriving there scatters, `1 - opacity` that it passes straight
    /// through. 1 on every unmasked surface, and without masks in the scene.
    #[inline]
    pub fn opacity(&self, hit: &SurfaceHit) -> f32 {
        if !self.effects.masks {
            return 1.0;
        }
        let m = &self.materials[hit.material as usize];
        match m.opacity_texture {
            Some(t) => (m.opacity * self.textures[t as usize].lookup_1(hit.uv)).clamp(0.0, 1.0),
            None => m.opacity,
        }
    }

    /// The bump of `map` at `hit` for the BSDF `bsdf` there ([`crate::bsdf::bump`]), from
    /// the triangle's partials ([`Scene::uv_partials_at`]) and the texture at the hit's
    /// coordinates: a height field's gradient, or a normal map's colour. `None` where the gradient is zero (the shading
    /// frame stays exactly the surface's) or the parametrisation is degenerate (no normal to
    /// tilt to).
    fn bump_at(&self, map: &BumpMap, hit: &SurfaceHit, bsdf: &Bsdf) -> Option<Bump> {
        let texture = &self.textures[map.texture as usize];
        let grad = match map.source {
            NormalSource::Height { scale } => {
                let grad = texture.luminance_gradient(hit.uv)? * scale;
                if grad == Vec2::ZERO {
                    return None;
                }
                Some(grad)
            }
            NormalSource::Normals => None,
        };
        let (dp_du, dp_dv) = self.uv_partials_at(hit);
        let n = match grad {
            Some(grad) => bumped_normal(hit.ns, bsdf.ng, dp_du, dp_dv, grad)?,
            None => mapped_normal(hit.ns, dp_du, texture.lookup(hit.uv))?,
        };
        Some(Bump::new(map, &bsdf.frame, n))
    }

    /// The partials `∂p/∂u`, `∂p/∂v` of the hit's triangle in Mitsuba's texture coordinates
    /// (`(u, 1 - v)` of the stored ones; the importer stores barycentric ones on a mesh
    /// without any, as Mitsuba parametrises it).
    fn uv_partials_at(&self, hit: &SurfaceHit) -> (Vec3, Vec3) {
        let g = &self.triangles[hit.triangle as usize];
        let uv = self.shading[hit.triangle as usize]
            .uvs
            .map(|uv| uv.map(|t| Vec2::new(t.x, 1.0 - t.y)))
            .unwrap_or([Vec2::ZERO, Vec2::X, Vec2::Y]);
        uv_partials(g.e1, g.e2, uv)
    }

    /// The shadow ray from surface point `p` (normal `ng`) to `target` (`target_n` the normal
    /// at the target when it lies on a surface, `None` for a point): origin, unit direction and
    /// length, both ends offset off their surfaces; `None` for a degenerate segment.
    #[inline]
    pub fn shadow_segment(
        &self,
        p: Vec3,
        ng: Vec3,
        target: Vec3,
        target_n: Option<Vec3>,
    ) -> Option<(Vec3, Vec3, f32)> {
        let d = target - p;
        let o = self.spawn_origin(p, ng, d);
        let end = match target_n {
            Some(n) => self.offset_origin(target, if n.dot(-d) >= 0.0 { n } else { -n }),
            None => target,
        };
        let v = end - o;
        let dist = v.length();
        if dist <= 0.0 || !dist.is_finite() {
            return None;
        }
        Some((o, v / dist, dist * (1.0 - 1e-5)))
    }

    /// A ray origin off the surface at `p` on the side of normal `n` ([`offset_ray_origin`]
    /// at this scene's [`Scene::offset_scale`]).
    #[inline]
    pub fn offset_origin(&self, p: Vec3, n: Vec3) -> Vec3 {
        offset_ray_origin(p, n, self.offset_scale)
    }

    /// The origin of a ray leaving surface point `p` (geometric normal `ng`) in direction
    /// `dir` ([`spawn_origin`] at this scene's [`Scene::offset_scale`]).
    #[inline]
    pub fn spawn_origin(&self, p: Vec3, ng: Vec3, dir: Vec3) -> Vec3 {
        spawn_origin(p, ng, dir, self.offset_scale)
    }

    /// Shadow ray from surface point `p` (normal `ng`) to `target`; `target_n` is the normal
    /// at the target when it lies on a surface (area light), `None` for a point.
    #[inline]
    pub fn visible(&self, p: Vec3, ng: Vec3, target: Vec3, target_n: Option<Vec3>) -> bool {
        self.visible_toward(Toward::Light, p, ng, target, target_n)
    }

    /// [`Scene::visible`] for a shadow ray `toward` a light or the camera (the CWBVH's
    /// traversal order for that kind, [`Accel::choose_shadow_order`]).
    #[inline]
    fn visible_toward(
        &self,
        toward: Toward,
        p: Vec3,
        ng: Vec3,
        target: Vec3,
        target_n: Option<Vec3>,
    ) -> bool {
        self.shadow_segment(p, ng, target, target_n)
            .is_some_and(|(o, dir, t_max)| self.bvh.unoccluded(toward, o, dir, t_max))
    }

    /// The fraction of light that goes from `p` (normal `ng`) to `target` (normal `target_n`
    /// on a surface, `None` for a point) in a straight line: zero when an opaque surface is
    /// in the way or more than `max_sheets` thin dielectric sheets are, else the product of
    /// the sheets' [`Bsdf::pass_through`] and of `1 - opacity` of the cut-out surfaces
    /// crossed ([`Scene::opacity`]), and the number of sheets crossed (each a segment of the
    /// path, as sampling through it makes; a cut-out is no segment, as a walk passes it
    /// without a vertex). Without thin sheets and masks in the scene, the shadow ray of
    /// [`Scene::visible`]. `toward`: whether the segment ends at a light (next-event
    /// estimation) or at the camera's lens (either way round: light tracing's and the
    /// importance map's connections), for the CWBVH's traversal order
    /// ([`Accel::choose_shadow_order`]).
    pub fn transmittance(
        &self,
        toward: Toward,
        p: Vec3,
        ng: Vec3,
        target: Vec3,
        target_n: Option<Vec3>,
        max_sheets: u32,
    ) -> (Rgb, u32) {
        if !self.effects.passes_light() {
            let v = self.visible_toward(toward, p, ng, target, target_n);
            return (if v { Rgb::ONE } else { Rgb::ZERO }, 0);
        }
        let mut t = Rgb::ONE;
        let (mut sheets, mut cutouts) = (0, 0);
        let (mut from, mut from_n) = (p, ng);
        loop {
            let Some((o, dir, t_max)) = self.shadow_segment(from, from_n, target, target_n) else {
                return (Rgb::ZERO, 0);
            };
            let Some(hit) = self.intersect(o, dir, t_max) else {
                return (t, sheets);
            };
            let opacity = self.opacity(&hit);
            if opacity < 1.0 {
                cutouts += 1;
                if cutouts > MAX_CUTOUT_CROSSINGS {
                    break;
                }
                t *= 1.0 - opacity;
            } else {
                if sheets == max_sheets {
                    break;
                }
                sheets += 1;
                t *= self.bsdf(&hit).pass_through(-dir);
            }
            if t.max_element() <= 0.0 {
                break;
            }
            (from, from_n) = (hit.p, hit.ng);
        }
        (Rgb::ZERO, 0)
    }

    /// Shadow ray from surface point `p` (normal `ng`) to the camera position (the lens
    /// centre).
    #[inline]
    pub fn visible_from_camera(&self, p: Vec3, ng: Vec3) -> bool {
        self.visible_toward(Toward::Camera, p, ng, self.camera.position, None)
    }

    /// The maximum particle query distance: the setting, or 5% of the bounding-box diagonal.
    pub fn map_max_dist(&self) -> f32 {
        self.maps
            .max_dist
            .unwrap_or(0.05 * (self.bounds.1 - self.bounds.0).length())
    }

    /// The environment light, if the scene has one, with its index.
    #[inline]
    pub fn environment(&self) -> Option<(u32, &Light)> {
        self.environment_light
            .map(|i| (i, &self.lights[i as usize]))
    }

    /// Probability of choosing light `i`.
    #[inline]
    pub fn light_pmf(&self, i: u32) -> f32 {
        self.light_distribution.pmf(i as usize)
    }
}
