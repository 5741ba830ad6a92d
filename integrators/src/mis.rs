//! Multiple importance sampling weights of the combined image (Veach 1997, ch. 9 and 10),
//! kept as running quantities along each subpath, as SmallVCM keeps its `dVCM`/`dVC`: a
//! [`CameraMis`] rides along every camera path and a [`LightMis`] along every light path,
//! each updated once per vertex, so that every weight costs O(1) where it is needed.
//!
//! The combined image weighs three strategies for a path `x0 (camera) ... xk (light)` of `k`
//! segments: `p0` a camera path that hits the light, `p1` a camera path whose last vertex is
//! connected to a light sample (next-event estimation), `pk` a light path whose last vertex is
//! connected to the camera (light tracing). Each is the density of the whole path in the
//! area-product measure under that strategy, and the weight is the power heuristic
//! `w_s = p_s² / (p0² + p1² + pk²)`.
//!
//! The direction densities come from [`Densities`]: either the **unguided** ones (the BSDF's,
//! the light's emission, the camera's), or the **guided** ones, the mixture pdfs the guided
//! samplers really draw with (a region lookup and a pdf with the guide cache), evaluated with
//! a white path colour so that both subpaths compute the same value for the same path.
//! (A camera path's last scattering vertex samples its BSDF alone, `walk::Start::max_segments`,
//! where these densities still read the mixture: there the weights' density is not the one
//! drawn with, which the partition below allows.)
//! Either way the weights are a partition of unity for every path, so the combined estimate
//! stays unbiased (Veach 1997, §9.2.2: any weights that sum to one over the strategies able to
//! make a path will do); the guided densities weigh each path by how likely the guided
//! strategies really make it.
//!
//! Both directions are counted equally: one camera path per pixel per pass and one light path
//! per pixel per pass, with the camera pdf taken over the whole image, give equal sample
//! counts. The camera vertex `x0` is the pinhole, or a point of a thin lens: a camera path
//! samples it uniformly on the lens and a light path's camera connection does too
//! (`footprint::scene::camera`), so its area density `1 / A_lens` is a factor of all three
//! strategies and is left out; the direction from it has the density per unit solid angle
//! `Camera::pdf_dir` at that lens point, turned into an area density at `x1`. Delta (specular) steps have area density 1 in both directions, as in pbrt-v3's
//! `MISWeight`; connections at delta vertices are impossible and get density 0.

use footprint::Rgb;
use footprint::bsdf::{Bsdf, Lobes, TransportMode};
use footprint::guide::sampler::{GuidedSampler, ScatterPoint};
use footprint::scene::Scene;
use footprint::scene::light::{Light, LightSample};
use glam::Vec3;

/// Converts a solid-angle density at `from` into an area density at `to` (normal `n_to`, or
/// none for a point such as a delta light).
#[inline]
pub fn to_area(pdf_w: f64, from: Vec3, to: Vec3, n_to: Option<Vec3>) -> f64 {
    let d = to - from;
    let d2 = d.length_squared() as f64;
    if d2 <= 0.0 {
        return 0.0;
    }
    let cos = match n_to {
        Some(n) => (n.dot(d) as f64).abs() / d2.sqrt(),
        None => 1.0,
    };
    pdf_w * cos / d2
}

/// The direction densities of the weights: unguided, or those of the guided samplers.
pub struct Densities<'s, 'a> {
    /// Draws camera-path directions (over the photon map).
    pub camera: &'s GuidedSampler<'a>,
    /// Draws light-path directions and emission at area lights (over the importance map).
    pub light: &'s GuidedSampler<'a>,
    pub guided: bool,
}

impl Densities<'_, '_> {
    /// Solid-angle density of `wi` at a vertex with `bsdf` at `p` for a path that arrived
    /// from direction `wo`: a camera path's (`Radiance`) or a light path's (`Importance`).
    #[inline]
    pub fn direction(&self, mode: TransportMode, bsdf: &Bsdf, p: Vec3, wo: Vec3, wi: Vec3) -> f32 {
        if !self.guided {
            return bsdf.pdf(wo, wi);
        }
        let sampler = match mode {
            TransportMode::Radiance => self.camera,
            TransportMode::Importance => self.light,
        };
        let at = ScatterPoint {
            p,
            bsdf,
            wo,
            mode,
            throughput: Rgb::ONE,
        };
        sampler.mis_pdf(&at, wi)
    }

    /// Solid-angle density of emitting in `dir` from the point `p` (normal `n`) of `light`;
    /// guided at area lights as the light tracer guides them (the cosine lobe as a white
    /// Lambertian).
    #[inline]
    pub fn emission(&self, light: &Light, p: Vec3, n: Option<Vec3>, dir: Vec3) -> f32 {
        match n {
            Some(n) if self.guided => {
                let lobe = Bsdf::new(Lobes::Diffuse { kd: Rgb::ONE }, n, n);
                self.direction(TransportMode::Importance, &lobe, p, n, dir)
            }
            _ => light.pdf_le_dir(dir),
        }
    }

    /// The area density at `next` (normal `n_next`) of a light path's first segment from the
    /// point `p` (normal `n`) of `light` along `dir`, without the choice of the light and the
    /// point: the emission's direction density turned into an area density at `next`. The
    /// directional light emits along one direction from a point of the bounding disk of
    /// density `pdf_pos` per unit area, so the first vertex's area density is
    /// `pdf_pos |cos θ_next|` (SmallVCM's `DirectionalLight`: no distance², the direction's
    /// delta shared with next-event estimation). Its positional density is the disk's: the
    /// caller's factor for the light ([`light_pos_pdf`]) is the choice alone, as a point
    /// light's, which next-event estimation's weight shares.
    #[inline]
    pub fn emission_area(
        &self,
        light: &Light,
        p: Vec3,
        n: Option<Vec3>,
        dir: Vec3,
        next: Vec3,
        n_next: Option<Vec3>,
    ) -> f64 {
        match light {
            Light::Directional { .. } => {
                let pdf_pos = light.disk_pdf().unwrap_or(0.0) as f64;
                let cos = n_next.map_or(1.0, |m| (m.dot(dir) as f64).abs());
                pdf_pos * cos
            }
            _ => to_area(self.emission(light, p, n, dir) as f64, p, next, n_next),
        }
    }

    /// The area density of sampling `next` from a vertex with `bsdf` at `p`, given the
    /// path's other neighbour in direction `toward_other` (unit), for a path of `mode`.
    /// `delta`: the path's direction at this vertex came from a delta lobe (per sample, not
    /// per BSDF: smooth plastic mixes a delta coat with a diffuse base); such steps give 1
    /// (in both directions).
    #[allow(clippy::too_many_arguments)]
    #[inline]
    pub fn step(
        &self,
        mode: TransportMode,
        bsdf: &Bsdf,
        delta: bool,
        p: Vec3,
        toward_other: Vec3,
        next: Vec3,
        n_next: Option<Vec3>,
    ) -> f64 {
        if delta || bsdf.is_delta() {
            return 1.0;
        }
        let wi = (next - p).normalize_or_zero();
        to_area(
            self.direction(mode, bsdf, p, toward_other, wi) as f64,
            p,
            next,
            n_next,
        )
    }
}

/// Power-heuristic weight of the strategy with density `own` among `all` (scaled by the
/// largest, so that neither overflow nor underflow spoils it).
#[inline]
pub fn weight(own: f64, all: [f64; 3]) -> f32 {
    let m = all.iter().copied().fold(0.0f64, f64::max);
    if !(own > 0.0) || !(m > 0.0) || !m.is_finite() {
        return 0.0;
    }
    let o = own / m;
    let sum: f64 = all.iter().map(|p| (p / m) * (p / m)).sum();
    (o * o / sum) as f32
}

/// One path's densities under the three strategies (`p0` a camera path that hits the light,
/// `p1` next-event estimation, `pk` light tracing), the strategy that made it, and the same
/// path's densities under the unguided samplers (where a pilot tracks both,
/// [`PilotMis`]; else `p`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Strategies {
    pub p: [f64; 3],
    pub own: usize,
    pub unguided: [f64; 3],
}

impl Strategies {
    /// No strategy: weight 0 (what a walk without a second estimate reports).
    pub const NONE: Strategies = Strategies {
        p: [0.0; 3],
        own: 0,
        unguided: [0.0; 3],
    };

    /// `p` made by strategy `own`, with no separate unguided densities.
    pub fn new(p: [f64; 3], own: usize) -> Self {
        Strategies {
            p,
            own,
            unguided: p,
        }
    }

    /// The power-heuristic weight of the strategy that made the path.
    #[inline]
    pub fn weight(&self) -> f32 {
        weight(self.p[self.own], self.p)
    }
}

/// Two trackers along one subpath: the samplers' densities (the weights) and the unguided
/// ones (for `auto`'s pilot, which estimates unguided methods' second moments from guided
/// paths, `crate::moments`).
#[derive(Clone, Copy)]
pub struct PilotMis<T> {
    pub main: T,
    pub unguided: T,
    /// The horizon of the second-moment layers the pilot writes.
    pub horizon: crate::moments::Horizon,
}

/// The unguided positional density of light `li` at one of its points: choice x area pdf
/// (the choice alone for point, spot and directional lights: see
/// [`Densities::emission_area`] for the directional light's disk).
#[inline]
pub fn light_pos_pdf(scene: &Scene, li: u32) -> f64 {
    let pmf = scene.light_pmf(li) as f64;
    match &scene.lights[li as usize] {
        Light::Area { area, .. } => pmf / *area as f64,
        _ => pmf,
    }
}

/// A subpath vertex as the trackers remember it.
#[derive(Clone, Copy)]
struct MisVertex {
    p: Vec3,
    n: Option<Vec3>,
    /// `None` for the subpath's source (the camera, or the light point).
    bsdf: Option<Bsdf>,
    /// The path left this vertex by a delta lobe.
    delta: bool,
}

/// The last two vertices of a subpath and whether its first surface vertex was left by a
/// delta lobe (then the other direction cannot connect to it).
#[derive(Clone, Copy)]
struct Recent {
    before: [MisVertex; 2],
    first_delta: bool,
}

impl Recent {
    fn new(source: MisVertex) -> Self {
        Recent {
            before: [source; 2],
            first_delta: false,
        }
    }

    /// The path left the vertex of depth `depth` at `p` by a direction sampled with `delta`.
    fn scattered(&mut self, depth: u32, p: Vec3, ng: Vec3, bsdf: &Bsdf, delta: bool) {
        if depth == 1 {
            self.first_delta = delta;
        }
        self.before[1] = self.before[0];
        self.before[0] = MisVertex {
            p,
            n: Some(ng),
            bsdf: Some(*bsdf),
            delta,
        };
    }
}

/// The running densities of a camera subpath `x0 (camera), x1, ..., xj`.
#[derive(Clone, Copy)]
pub struct CameraMis<'d> {
    d: &'d Densities<'d, 'd>,
    /// Product of the camera-direction area densities up to `xj`.
    d_fwd: f64,
    /// Product of the light-direction area densities of `x1 .. x_{j-2}`.
    b_back: f64,
    /// The last factor of `d_fwd`: the density of `xj` from `x_{j-1}`.
    last_fwd: f64,
    /// `x_{j-1}`, `x_{j-2}`, and whether `x1` was left by a delta lobe (light tracing
    /// cannot connect to it then).
    recent: Recent,
}

impl<'d> CameraMis<'d> {
    /// A camera subpath from the camera vertex `camera`: the lens point its ray starts at
    /// (the camera's position for a pinhole).
    pub fn new(camera: Vec3, d: &'d Densities<'d, 'd>) -> Self {
        let cam = MisVertex {
            p: camera,
            n: None,
            bsdf: None,
            delta: false,
        };
        CameraMis {
            d,
            d_fwd: 1.0,
            b_back: 1.0,
            last_fwd: 0.0,
            recent: Recent::new(cam),
        }
    }

    /// The path arrived at `xj = p` (normal `ng`, `depth = j`) along `dir`.
    #[allow(clippy::too_many_arguments)]
    pub fn arrive(&mut self, scene: &Scene, depth: u32, dir: Vec3, p: Vec3, ng: Vec3) {
        let cam = &scene.camera;
        let [b0, b1] = self.recent.before;
        self.last_fwd = match b0.bsdf {
            // From the camera vertex (the lens point the path started at).
            None => to_area(cam.pdf_dir(dir.dot(cam.frame.z)) as f64, b0.p, p, Some(ng)),
            Some(b) => self.d.step(
                TransportMode::Radiance,
                &b,
                b0.delta,
                b0.p,
                (b1.p - b0.p).normalize_or_zero(),
                p,
                Some(ng),
            ),
        };
        self.d_fwd *= self.last_fwd;
        // Light-direction density of x_{j-2} from x_{j-1}, now that xj is known.
        if depth >= 3 {
            if let Some(b) = b0.bsdf {
                self.b_back *= self.d.step(
                    TransportMode::Importance,
                    &b,
                    b0.delta,
                    b0.p,
                    dir,
                    b1.p,
                    b1.n,
                );
            }
        }
    }

    /// The strategies of the path that found light `li`'s emission at `xj = p` (`wo` back
    /// along the path).
    pub fn light_hit(&self, scene: &Scene, li: u32, depth: u32, wo: Vec3, p: Vec3) -> Strategies {
        let light = &scene.lights[li as usize];
        let b0 = &self.recent.before[0];
        let p_l = light_pos_pdf(scene, li);
        let p0 = self.d_fwd;
        let p1 = match b0.bsdf {
            Some(_) if !b0.delta && self.last_fwd > 0.0 => self.d_fwd / self.last_fwd * p_l,
            _ => 0.0,
        };
        let pk = if depth == 1 {
            p_l
        } else if self.recent.first_delta {
            0.0
        } else {
            let n = match light {
                Light::Area { n, .. } => Some(*n),
                _ => None,
            };
            let emit = self.d.emission_area(light, p, n, wo, b0.p, b0.n);
            p_l * self.b_back * emit
        };
        Strategies::new([p0, p1, pk], 0)
    }

    /// The strategies of a next-event connection from `xj` (BSDF `bsdf`, `wo` back along
    /// the path) to the light sample `ls` of light `li`.
    #[allow(clippy::too_many_arguments)]
    pub fn nee(
        &self,
        scene: &Scene,
        li: u32,
        depth: u32,
        bsdf: &Bsdf,
        p: Vec3,
        ng: Vec3,
        wo: Vec3,
        ls: &LightSample,
    ) -> Strategies {
        let light = &scene.lights[li as usize];
        let b0 = &self.recent.before[0];
        let p_l = light_pos_pdf(scene, li);
        let fwd_l = if ls.delta {
            0.0
        } else {
            self.d
                .step(TransportMode::Radiance, bsdf, false, p, wo, ls.p, ls.n)
        };
        let p0 = self.d_fwd * fwd_l;
        let p1 = self.d_fwd * p_l;
        let pk = if depth >= 2 && self.recent.first_delta {
            0.0
        } else {
            let emit = self.d.emission_area(light, ls.p, ls.n, -ls.wi, p, Some(ng));
            let back = if depth >= 2 {
                self.d
                    .step(TransportMode::Importance, bsdf, false, p, ls.wi, b0.p, b0.n)
            } else {
                1.0
            };
            p_l * self.b_back * back * emit
        };
        Strategies::new([p0, p1, pk], 1)
    }

    /// The path left `xj` by a direction sampled with `delta`.
    pub fn scattered(&mut self, depth: u32, p: Vec3, ng: Vec3, bsdf: &Bsdf, delta: bool) {
        self.recent.scattered(depth, p, ng, bsdf, delta);
    }
}

/// The running densities of a light subpath `y0 (light point), y1, ..., yj`.
#[derive(Clone, Copy)]
pub struct LightMis<'d> {
    d: &'d Densities<'d, 'd>,
    /// Light-direction area densities, the light position's included.
    l_fwd: f64,
    /// Camera-direction densities of `y1 .. y_{j-2}` (each from its successor).
    r_prod: f64,
    /// Camera-direction density of the light point from `y1` (0 for delta lights).
    pf_light: f64,
    p_l: f64,
    /// The light is a delta (a point, or the directional light): a camera path cannot hit it.
    delta_light: bool,
    /// `y_{j-1}`, `y_{j-2}`, and whether `y1` was left by a delta lobe (next-event
    /// estimation cannot reach it then).
    recent: Recent,
}

impl<'d> LightMis<'d> {
    /// A light subpath starting at the point `p` (normal `n`, `None` for a point light) of
    /// light `li`.
    pub fn new(scene: &Scene, d: &'d Densities<'d, 'd>, li: u32, p: Vec3, n: Option<Vec3>) -> Self {
        let p_l = light_pos_pdf(scene, li);
        let start = MisVertex {
            p,
            n,
            bsdf: None,
            delta: false,
        };
        LightMis {
            d,
            l_fwd: p_l,
            r_prod: 1.0,
            pf_light: 0.0,
            p_l,
            delta_light: n.is_none(),
            recent: Recent::new(start),
        }
    }

    /// The strategies of the light point `y0` itself seen by the camera vertex `lens` (a
    /// lens point, or the pinhole) in direction `-to_camera`.
    pub fn light_seen(&self, scene: &Scene, lens: Vec3, to_camera: Vec3) -> Strategies {
        let cam = &scene.camera;
        let y0 = &self.recent.before[0];
        // k = 1: the camera path could hit an area light here, nothing else.
        let p0 = if y0.n.is_some() {
            to_area(
                cam.pdf_dir((-to_camera).dot(cam.frame.z)) as f64,
                lens,
                y0.p,
                y0.n,
            )
        } else {
            0.0
        };
        Strategies::new([p0, 0.0, self.p_l], 2)
    }

    /// The path arrived at `yj = p` (normal `ng`, `depth = j`) along `dir`.
    #[allow(clippy::too_many_arguments)]
    pub fn arrive(&mut self, light: &Light, depth: u32, dir: Vec3, p: Vec3, ng: Vec3) {
        let [b0, b1] = self.recent.before;
        self.l_fwd *= match b0.bsdf {
            None => self.d.emission_area(light, b0.p, b0.n, dir, p, Some(ng)),
            Some(b) => self.d.step(
                TransportMode::Importance,
                &b,
                b0.delta,
                b0.p,
                (b1.p - b0.p).normalize_or_zero(),
                p,
                Some(ng),
            ),
        };
        if depth >= 2 {
            if let Some(b) = b0.bsdf {
                let back = if depth == 2 && self.delta_light {
                    0.0 // a camera path cannot hit a delta light
                } else {
                    self.d
                        .step(TransportMode::Radiance, &b, b0.delta, b0.p, dir, b1.p, b1.n)
                };
                if depth == 2 {
                    self.pf_light = back
                } else {
                    self.r_prod *= back
                }
            }
        }
    }

    /// The strategies of the camera connection from `yj = p` (BSDF `bsdf`, normal `ng`) to
    /// the camera vertex `lens` (a lens point, or the pinhole) in direction `wi`.
    #[allow(clippy::too_many_arguments)]
    pub fn camera_connection(
        &self,
        scene: &Scene,
        depth: u32,
        bsdf: &Bsdf,
        p: Vec3,
        ng: Vec3,
        lens: Vec3,
        wi: Vec3,
    ) -> Strategies {
        let cam = &scene.camera;
        let b0 = &self.recent.before[0];
        let cam_area = to_area(
            cam.pdf_dir((-wi).dot(cam.frame.z)) as f64,
            lens,
            p,
            Some(ng),
        );
        let now = if depth == 1 && self.delta_light {
            0.0
        } else {
            self.d
                .step(TransportMode::Radiance, bsdf, false, p, wi, b0.p, b0.n)
        };
        let (p0, p1) = if depth == 1 {
            (cam_area * now, cam_area * self.p_l)
        } else {
            let base = cam_area * now * self.r_prod;
            (
                base * self.pf_light,
                if self.recent.first_delta {
                    0.0
                } else {
                    base * self.p_l
                },
            )
        };
        Strategies::new([p0, p1, self.l_fwd], 2)
    }

    /// The path left `yj` by a direction sampled with `delta`.
    pub fn scattered(&mut self, depth: u32, p: Vec3, ng: Vec3, bsdf: &Bsdf, delta: bool) {
        self.recent.scattered(depth, p, ng, bsdf, delta);
    }
}
