//! Embree 3 (Intel's ray-tracing kernels, the traversal Mitsuba 3 uses) as the acceleration
//! structure, loaded at run time from the system's `libembree3` (Debian: `libembree3-3`).
//! Where it is not installed, [`crate::scene::accel`] falls back to the CWBVH of
//! [`crate::scene::bvh`]; nothing is linked at build time, so footprint builds and runs on a
//! machine without it.
//!
//! Only the dozen entry points footprint calls are declared here, with the layouts of
//! Embree 3.13's `rtcore_ray.h` and `rtcore_common.h` (`RTC_MAX_INSTANCE_LEVEL_COUNT` 1,
//! `RTC_MIN_WIDTH` 0: the released builds' configuration; a library of another major version
//! has another file name and is not loaded). The scene is built with high quality and the
//! robust (watertight) test, from quads: pairs of triangles that share an edge ([`quads`]),
//! half the primitives, as Embree recommends for quad meshes; queries are single incoherent
//! rays. Without the robust flag Embree runs fewer instructions but takes longer
//! (`docs/measurements/speed.md`, "The acceleration structure").

use crate::scene::bvh::BvhHit;
use crate::scene::geometry::TriangleGeom;
use glam::Vec3;
use libloading::Library;
use std::ffi::{c_char, c_void};
use std::sync::OnceLock;

type Device = *mut c_void;
type RtcScene = *mut c_void;
type Geometry = *mut c_void;

/// `struct RTCRay`.
#[repr(C, align(16))]
#[derive(Clone, Copy)]
struct Ray {
    org: [f32; 3],
    tnear: f32,
    dir: [f32; 3],
    time: f32,
    tfar: f32,
    mask: u32,
    id: u32,
    flags: u32,
}

/// `struct RTCHit`.
#[repr(C, align(16))]
#[derive(Clone, Copy)]
struct Hit {
    ng: [f32; 3],
    u: f32,
    v: f32,
    prim_id: u32,
    geom_id: u32,
    inst_id: [u32; 1],
}

/// `struct RTCRayHit`.
#[repr(C)]
struct RayHit {
    ray: Ray,
    hit: Hit,
}

/// `struct RTCIntersectContext`.
#[repr(C)]
struct IntersectContext {
    flags: u32,
    filter: *const c_void,
    inst_id: [u32; 1],
}

// The sizes of Embree 3.13's released configuration (`rtcore_config.h`:
// `RTC_MAX_INSTANCE_LEVEL_COUNT` 1, `RTC_MIN_WIDTH` 0); a library built otherwise has a larger
// context, and is not supported.
const _: () = assert!(std::mem::size_of::<Ray>() == 48 && std::mem::align_of::<Ray>() == 16);
const _: () = assert!(std::mem::size_of::<Hit>() == 32 && std::mem::align_of::<Hit>() == 16);
const _: () = assert!(std::mem::size_of::<RayHit>() == 80);
const _: () = assert!(std::mem::size_of::<IntersectContext>() == 24);

const INVALID_ID: u32 = u32::MAX;
const BUFFER_TYPE_INDEX: u32 = 0;
const BUFFER_TYPE_VERTEX: u32 = 1;
const FORMAT_UINT4: u32 = 0x5004;
const FORMAT_FLOAT3: u32 = 0x9003;
const GEOMETRY_TYPE_QUAD: u32 = 1;
const BUILD_QUALITY_HIGH: u32 = 2;
const SCENE_FLAG_ROBUST: u32 = 1 << 2;
const CONTEXT_FLAG_INCOHERENT: u32 = 0;

/// The entry points, resolved once from the library (kept loaded for the process).
struct Api {
    new_device: unsafe extern "C" fn(*const c_char) -> Device,
    release_device: unsafe extern "C" fn(Device),
    get_device_error: unsafe extern "C" fn(Device) -> u32,
    new_scene: unsafe extern "C" fn(Device) -> RtcScene,
    release_scene: unsafe extern "C" fn(RtcScene),
    set_scene_build_quality: unsafe extern "C" fn(RtcScene, u32),
    set_scene_flags: unsafe extern "C" fn(RtcScene, u32),
    new_geometry: unsafe extern "C" fn(Device, u32) -> Geometry,
    set_new_geometry_buffer:
        unsafe extern "C" fn(Geometry, u32, u32, u32, usize, usize) -> *mut c_void,
    commit_geometry: unsafe extern "C" fn(Geometry),
    attach_geometry: unsafe extern "C" fn(RtcScene, Geometry) -> u32,
    release_geometry: unsafe extern "C" fn(Geometry),
    commit_scene: unsafe extern "C" fn(RtcScene),
    intersect1: unsafe extern "C" fn(RtcScene, *mut IntersectContext, *mut RayHit),
    occluded1: unsafe extern "C" fn(RtcScene, *mut IntersectContext, *mut Ray),
    _library: Library,
}

/// The library's file name on this platform.
const LIBRARY: &str = if cfg!(target_os = "macos") {
    "libembree3.dylib"
} else if cfg!(target_os = "windows") {
    "embree3.dll"
} else {
    "libembree3.so.3"
};

impl Api {
    fn load() -> Result<Api, String> {
        // SAFETY: loading Embree runs its initialisers, which have no preconditions; every
        // symbol is declared with the signature of Embree 3's headers.
        unsafe {
            let library = Library::new(LIBRARY).map_err(|e| format!("{LIBRARY}: {e}"))?;
            macro_rules! symbol {
                ($name:literal) => {
                    *library
                        .get(concat!($name, "\0").as_bytes())
                        .map_err(|e| format!("{LIBRARY}: {}: {e}", $name))?
                };
            }
            Ok(Api {
                new_device: symbol!("rtcNewDevice"),
                release_device: symbol!("rtcReleaseDevice"),
                get_device_error: symbol!("rtcGetDeviceError"),
                new_scene: symbol!("rtcNewScene"),
                release_scene: symbol!("rtcReleaseScene"),
                set_scene_build_quality: symbol!("rtcSetSceneBuildQuality"),
                set_scene_flags: symbol!("rtcSetSceneFlags"),
                new_geometry: symbol!("rtcNewGeometry"),
                set_new_geometry_buffer: symbol!("rtcSetNewGeometryBuffer"),
                commit_geometry: symbol!("rtcCommitGeometry"),
                attach_geometry: symbol!("rtcAttachGeometry"),
                release_geometry: symbol!("rtcReleaseGeometry"),
                commit_scene: symbol!("rtcCommitScene"),
                intersect1: symbol!("rtcIntersect1"),
                occluded1: symbol!("rtcOccluded1"),
                _library: library,
            })
        }
    }
}

/// The library, loaded on first use; the error says why it could not be.
fn api() -> Result<&'static Api, &'static str> {
    static API: OnceLock<Result<Api, String>> = OnceLock::new();
    API.get_or_init(Api::load).as_ref().map_err(|e| e.as_str())
}

/// Whether Embree can be loaded here, and why not.
pub fn available() -> Result<(), String> {
    api().map(|_| ()).map_err(str::to_string)
}

/// An Embree scene over the triangles, triangle `i` being Embree's primitive `i`.
pub struct EmbreeBvh {
    api: &'static Api,
    device: Device,
    scene: RtcScene,
    /// Embree's primitive `i` is the quad `quads[i]`.
    quads: Vec<Quad>,
}

/// An Embree quad as footprint's triangles: its first half is triangle `first`, its second
/// (when `j[2]` is not [`UNPAIRED`]) triangle `first + 1`; `j` says where each half's
/// triangle has its corners 1 and 2 among the half's corners in Embree's order (`(v0, v1,
/// v3)` for the first half, `(v2, v3, v1)` for the second), so that the hit's barycentrics
/// on the triangle are the weights Embree gives those corners. Eight bytes a quad, read at
/// every hit (1.5 MB on Veach Ajar).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Quad {
    first: u32,
    j: [u8; 4],
}

/// `Quad::j[2]` of a triangle without a partner.
const UNPAIRED: u8 = u8::MAX;

/// Embree's quads from the triangles: two consecutive triangles that share an edge
/// ([`shared_edge`]) become one quad with the shared edge as its diagonal `v1 v3`, as the
/// triangulations of quads (OBJ faces, Mitsuba's rectangles and cubes, footprint's own
/// spheres) produce them; any other triangle is a quad whose second half is degenerate
/// (`v3 = v2`, never hit). The second half takes the shared corners from the first triangle
/// (a few ulps from its own, and watertight along the diagonal). Returns each quad's four
/// vertex indices into the vertex buffer (three vertices per triangle, triangle `i`'s at
/// `3i`) and the quads as footprint's triangles. Embree intersects a quad as its two
/// triangles at once, so a mesh of quads has half the primitives.
fn quads(triangles: &[TriangleGeom]) -> (Vec<[u32; 4]>, Vec<Quad>) {
    let corners = |t: &TriangleGeom| [t.p0, t.p0 + t.e1, t.p0 + t.e2];
    let (mut index, mut quads) = (Vec::new(), Vec::new());
    let mut i = 0;
    while i < triangles.len() {
        let a = corners(&triangles[i]);
        let ia = 3 * i as u32;
        match triangles
            .get(i + 1)
            .and_then(|t| shared_edge(&a, &corners(t)))
        {
            Some((k, m, second)) => {
                // v0 = a[k], v1 = a[k + 1], v3 = a[k + 2], v2 = b[m]: the first half is
                // triangle i, its corner c at Embree's position (c - k) mod 3.
                let (p, q) = ((k + 1) % 3, (k + 2) % 3);
                let ib = 3 * (i as u32 + 1);
                index.push([ia + k as u32, ia + p as u32, ib + m as u32, ia + q as u32]);
                quads.push(Quad {
                    first: i as u32,
                    j: [
                        ((4 - k) % 3) as u8,
                        ((5 - k) % 3) as u8,
                        second[0],
                        second[1],
                    ],
                });
                i += 2;
            }
            None => {
                index.push([ia, ia + 1, ia + 2, ia + 2]);
                quads.push(Quad {
                    first: i as u32,
                    j: [1, 2, UNPAIRED, UNPAIRED],
                });
                i += 1;
            }
        }
    }
    (index, quads)
}

/// Two corners equal to a few ulps: a triangle keeps a corner and two edges, so a corner it
/// shares comes back from `p0 + e1` within a few ulps of its neighbour's, not always bit
/// for bit.
#[inline]
fn same(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() <= 1e-6 * a.abs().max_element()
}

/// When triangles `a` and `b` share an edge (exactly one corner of each lies off the
/// other): the corner `k` of `a` and the corner `m` of `b` off it, and where `b`'s corners 1
/// and 2 stand in the quad's second half `(v2, v3, v1) = (b[m], a[k + 2], a[k + 1])`. A
/// sliver whose two shared corners fall on one corner of `a` is not paired.
fn shared_edge(a: &[Vec3; 3], b: &[Vec3; 3]) -> Option<(usize, usize, [u8; 2])> {
    let off = |x: &[Vec3; 3], y: &[Vec3; 3]| {
        let mut alone = (0..3).filter(|&c| !y.iter().any(|&q| same(x[c], q)));
        let c = alone.next()?;
        alone.next().is_none().then_some(c)
    };
    let (k, m) = (off(a, b)?, off(b, a)?);
    let v3 = a[(k + 2) % 3];
    let pos = |c: usize| match c {
        _ if c == m => 0,
        _ if same(b[c], v3) => 1,
        _ => 2,
    };
    let second = [pos(1), pos(2)];
    (second[0] != second[1]).then_some((k, m, second))
}

/// The triangle and its barycentrics of a hit at Embree's quad coordinates `(u, v)`: the
/// first half `(v0, v1, v3)` where `u + v <= 1`, with weights `(1 - u - v, u, v)`; else the
/// second `(v2, v3, v1)`, whose own coordinates Embree reports as `1 - u`, `1 - v`.
#[inline]
fn on_triangle(q: &Quad, u: f32, v: f32) -> (u32, f32, f32) {
    // An unpaired triangle has one half: a hit on it a rounding past its diagonal edge
    // (`u + v` just above 1) stays on it. `!(.. > 1)` sends NaN there too.
    let (triangle, w, j1, j2) = if !(u + v > 1.0) || q.j[2] == UNPAIRED {
        (q.first, [(1.0 - u - v).max(0.0), u, v], q.j[0], q.j[1])
    } else {
        (
            q.first + 1,
            [(u + v - 1.0).max(0.0), 1.0 - u, 1.0 - v],
            q.j[2],
            q.j[3],
        )
    };
    (triangle, w[j1 as usize], w[j2 as usize])
}

// SAFETY: a committed Embree scene is read-only; Embree documents `rtcIntersect1` and
// `rtcOccluded1` as safe to call from any number of threads at once.
unsafe impl Send for EmbreeBvh {}
unsafe impl Sync for EmbreeBvh {}

impl Drop for EmbreeBvh {
    fn drop(&mut self) {
        // SAFETY: both handles were made by `build` and are released once.
        unsafe {
            (self.api.release_scene)(self.scene);
            (self.api.release_device)(self.device);
        }
    }
}

impl EmbreeBvh {
    /// Builds the scene over `triangles` (at least one); an error when Embree cannot be
    /// loaded or fails (its error code).
    pub fn build(triangles: &[TriangleGeom]) -> Result<Self, String> {
        assert!(!triangles.is_empty(), "a BVH needs at least one triangle");
        let api = api()?;
        let config = c"verbose=0";
        // SAFETY: the calls follow Embree's API: buffers are written within the sizes asked
        // for before the geometry is committed, and handles are released once (the geometry
        // after the scene holds it; the scene and device by `Drop`).
        unsafe {
            let device = (api.new_device)(config.as_ptr());
            if device.is_null() {
                // The reason of a device that was not made is the null device's error.
                let code = (api.get_device_error)(std::ptr::null_mut());
                return Err(format!("Embree: rtcNewDevice failed (RTCError {code})"));
            }
            let scene = (api.new_scene)(device);
            if scene.is_null() {
                let code = (api.get_device_error)(device);
                (api.release_device)(device);
                return Err(format!("Embree: rtcNewScene failed (RTCError {code})"));
            }
            let (quad_index, quads) = quads(triangles);
            let bvh = EmbreeBvh {
                api,
                device,
                scene,
                quads,
            };
            (api.set_scene_build_quality)(bvh.scene, BUILD_QUALITY_HIGH);
            (api.set_scene_flags)(bvh.scene, SCENE_FLAG_ROBUST);
            let geometry = (api.new_geometry)(device, GEOMETRY_TYPE_QUAD);
            if geometry.is_null() {
                return Err(bvh.error("rtcNewGeometry"));
            }
            let n = triangles.len();
            // (Embree pads a buffer it allocates for its 16-byte loads itself.)
            let vertices = (api.set_new_geometry_buffer)(
                geometry,
                BUFFER_TYPE_VERTEX,
                0,
                FORMAT_FLOAT3,
                12,
                3 * n,
            ) as *mut [f32; 3];
            let indices = (api.set_new_geometry_buffer)(
                geometry,
                BUFFER_TYPE_INDEX,
                0,
                FORMAT_UINT4,
                16,
                quad_index.len(),
            ) as *mut [u32; 4];
            if vertices.is_null() || indices.is_null() {
                (api.release_geometry)(geometry);
                return Err(bvh.error("rtcSetNewGeometryBuffer"));
            }
            for (i, t) in triangles.iter().enumerate() {
                vertices.add(3 * i).write(t.p0.to_array());
                vertices.add(3 * i + 1).write((t.p0 + t.e1).to_array());
                vertices.add(3 * i + 2).write((t.p0 + t.e2).to_array());
            }
            for (i, q) in quad_index.iter().enumerate() {
                indices.add(i).write(*q);
            }
            (api.commit_geometry)(geometry);
            (api.attach_geometry)(bvh.scene, geometry);
            (api.release_geometry)(geometry);
            (api.commit_scene)(bvh.scene);
            // Reading the error clears it: the code read is the one reported.
            match (api.get_device_error)(device) {
                0 => Ok(bvh),
                code => Err(format!("Embree: rtcCommitScene failed (RTCError {code})")),
            }
        }
    }

    fn error(&self, call: &str) -> String {
        // SAFETY: the device is live.
        let code = unsafe { (self.api.get_device_error)(self.device) };
        format!("Embree: {call} failed (RTCError {code})")
    }

    fn context() -> IntersectContext {
        IntersectContext {
            flags: CONTEXT_FLAG_INCOHERENT,
            filter: std::ptr::null(),
            inst_id: [INVALID_ID],
        }
    }

    /// The segment `0 < t < t_max` as Embree's closed `[tnear, tfar]`: the smallest positive
    /// float and the float below `t_max`.
    fn ray(origin: Vec3, dir: Vec3, t_max: f32) -> Ray {
        Ray {
            org: origin.to_array(),
            tnear: f32::MIN_POSITIVE,
            dir: dir.to_array(),
            time: 0.0,
            tfar: t_max.next_down(),
            mask: u32::MAX,
            id: 0,
            flags: 0,
        }
    }

    /// Closest hit along `origin + t dir`, `0 < t < t_max`.
    #[inline]
    pub fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<BvhHit> {
        let mut context = Self::context();
        let mut rayhit = RayHit {
            ray: Self::ray(origin, dir, t_max),
            hit: Hit {
                ng: [0.0; 3],
                u: 0.0,
                v: 0.0,
                prim_id: INVALID_ID,
                geom_id: INVALID_ID,
                inst_id: [INVALID_ID],
            },
        };
        // SAFETY: a committed scene, a context and a ray-hit of Embree's layouts.
        unsafe { (self.api.intersect1)(self.scene, &mut context, &mut rayhit) };
        let (ray, hit) = (rayhit.ray, rayhit.hit);
        (hit.geom_id != INVALID_ID).then(|| {
            let (triangle, b1, b2) = on_triangle(&self.quads[hit.prim_id as usize], hit.u, hit.v);
            BvhHit {
                triangle,
                t: ray.tfar,
                b1,
                b2,
            }
        })
    }

    /// True when nothing blocks `origin + t dir` for `0 < t < t_max` (shadow rays).
    #[inline]
    pub fn unoccluded(&self, origin: Vec3, dir: Vec3, t_max: f32) -> bool {
        let mut context = Self::context();
        let mut ray = Self::ray(origin, dir, t_max);
        // SAFETY: as in `intersect`.
        unsafe { (self.api.occluded1)(self.scene, &mut context, &mut ray) };
        // Embree sets `tfar` to -inf when the ray is blocked.
        ray.tfar != f32::NEG_INFINITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Barycentrics `(s, t)` of `p` in the triangle `(x0, x1, x2)`: `p = x0 + s (x1 - x0) +
    /// t (x2 - x0)`, solved by Cramer's rule on the triangle's plane.
    fn barycentric(p: Vec3, x0: Vec3, x1: Vec3, x2: Vec3) -> (f32, f32) {
        let (e1, e2, d) = (x1 - x0, x2 - x0, p - x0);
        let n = e1.cross(e2);
        let s = d.cross(e2).dot(n) / n.length_squared();
        let t = e1.cross(d).dot(n) / n.length_squared();
        (s, t)
    }

    /// Every split of a quad into two triangles (each corner order and orientation of the
    /// second) becomes one Embree quad; a point on either triangle, given as Embree's
    /// documented quad coordinates (first half `(v0, v1, v3)`: `(u, v)`; second half
    /// `(v2, v3, v1)`: its own coordinates `(1 - u, 1 - v)`), comes back as that triangle
    /// and the point's barycentrics on it.
    #[test]
    fn quad_hits_map_back_to_their_triangle() {
        let [a, b, c, d] = [
            Vec3::new(0.1, 0.2, 0.0),
            Vec3::new(1.3, 0.1, 0.2),
            Vec3::new(1.1, 1.4, 0.1),
            Vec3::new(-0.2, 0.9, 0.3),
        ];
        let rotate = |t: [Vec3; 3], r: usize| [t[r % 3], t[(r + 1) % 3], t[(r + 2) % 3]];
        let mut checked = 0;
        for r1 in 0..3 {
            for r2 in 0..3 {
                for flip in [false, true] {
                    let t2 = if flip { [a, d, c] } else { [a, c, d] };
                    let tris = [rotate([a, b, c], r1), rotate(t2, r2)]
                        .map(|[p, q, s]| TriangleGeom::new(p, q, s));
                    let (index, made) = quads(&tris);
                    assert_eq!(index.len(), 1, "a shared edge makes one quad");
                    let corners: Vec<Vec3> = tris
                        .iter()
                        .flat_map(|t| [t.p0, t.p0 + t.e1, t.p0 + t.e2])
                        .collect();
                    let [v0, v1, v2, v3] = index[0].map(|i| corners[i as usize]);
                    for (i, tri) in tris.iter().enumerate() {
                        for (b1, b2) in [(0.2, 0.3), (0.6, 0.1), (0.05, 0.9), (0.33, 0.33)] {
                            let p = tri.point(b1, b2);
                            // Embree's coordinates of `p` on the half that holds it.
                            let (s, t) = barycentric(p, v0, v1, v3);
                            let (u, v) = if s >= 0.0 && t >= 0.0 && s + t <= 1.0 {
                                (s, t)
                            } else {
                                let (s, t) = barycentric(p, v2, v3, v1);
                                (1.0 - s, 1.0 - t)
                            };
                            let (got, g1, g2) = on_triangle(&made[0], u, v);
                            assert_eq!(got as usize, i, "r1 {r1} r2 {r2} flip {flip}");
                            let q = tris[got as usize].point(g1, g2);
                            assert!(
                                (q - p).length() < 1e-5,
                                "r1 {r1} r2 {r2} flip {flip}: {p} vs {q}"
                            );
                            checked += 1;
                        }
                    }
                }
            }
        }
        assert_eq!(checked, 3 * 3 * 2 * 2 * 4);
    }

    /// Triangles that share no edge with their neighbour stay alone: a quad whose second
    /// half is degenerate, hits on it mapped with the identity.
    #[test]
    fn triangles_without_a_shared_edge_stay_alone() {
        let t = |x: f32| {
            TriangleGeom::new(
                Vec3::new(x, 0.0, 0.0),
                Vec3::new(x + 1.0, 0.0, 0.0),
                Vec3::new(x, 1.0, 0.0),
            )
        };
        // Two corners shared but not the same edge would need a third: here only one
        // corner is shared (`t(0)`'s second is `t(1)`'s first).
        let (index, made) = quads(&[t(0.0), t(1.0), t(5.0)]);
        assert_eq!(index, vec![[0, 1, 2, 2], [3, 4, 5, 5], [6, 7, 8, 8]]);
        for (i, h) in made.iter().enumerate() {
            assert_eq!(on_triangle(h, 0.25, 0.5), (i as u32, 0.25, 0.5));
            // A hit a rounding past the diagonal edge stays where it is (no mirrored half).
            assert_eq!(on_triangle(h, 0.6, 0.40001), (i as u32, 0.6, 0.40001));
        }
    }
}
