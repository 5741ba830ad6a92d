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
//! robust (watertight) triangle test; queries are single incoherent rays.

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
const FORMAT_UINT3: u32 = 0x5003;
const FORMAT_FLOAT3: u32 = 0x9003;
const GEOMETRY_TYPE_TRIANGLE: u32 = 0;
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
            let bvh = EmbreeBvh { api, device, scene };
            (api.set_scene_build_quality)(bvh.scene, BUILD_QUALITY_HIGH);
            (api.set_scene_flags)(bvh.scene, SCENE_FLAG_ROBUST);
            let geometry = (api.new_geometry)(device, GEOMETRY_TYPE_TRIANGLE);
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
            let indices =
                (api.set_new_geometry_buffer)(geometry, BUFFER_TYPE_INDEX, 0, FORMAT_UINT3, 12, n)
                    as *mut [u32; 3];
            if vertices.is_null() || indices.is_null() {
                (api.release_geometry)(geometry);
                return Err(bvh.error("rtcSetNewGeometryBuffer"));
            }
            for (i, t) in triangles.iter().enumerate() {
                vertices.add(3 * i).write(t.p0.to_array());
                vertices.add(3 * i + 1).write((t.p0 + t.e1).to_array());
                vertices.add(3 * i + 2).write((t.p0 + t.e2).to_array());
                let v = 3 * i as u32;
                indices.add(i).write([v, v + 1, v + 2]);
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
        (hit.geom_id != INVALID_ID).then_some(BvhHit {
            triangle: hit.prim_id,
            t: ray.tfar,
            b1: hit.u,
            b2: hit.v,
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
