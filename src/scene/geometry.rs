//! Rays, triangles, surface hits and robust ray offsetting.

use glam::{Vec2, Vec3};

/// A ray `origin + t * dir`, `t` in `(0, t_max)`. `dir` is unit length.
#[derive(Clone, Copy, Debug)]
pub struct Ray {
    pub origin: Vec3,
    pub dir: Vec3,
    pub t_max: f32,
}

impl Ray {
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        Ray {
            origin,
            dir,
            t_max: f32::INFINITY,
        }
    }
}

/// A triangle stored for intersection: a vertex and two edges.
#[derive(Clone, Copy, Debug, Default)]
pub struct TriangleGeom {
    pub p0: Vec3,
    pub e1: Vec3,
    pub e2: Vec3,
}

impl TriangleGeom {
    pub fn new(p0: Vec3, p1: Vec3, p2: Vec3) -> Self {
        TriangleGeom {
            p0,
            e1: p1 - p0,
            e2: p2 - p0,
        }
    }

    /// Möller–Trumbore intersection. Returns `(t, b1, b2)` for a hit with `0 < t < t_max`.
    #[inline(always)]
    pub fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<(f32, f32, f32)> {
        self.intersect_range(origin, dir, 0.0, t_max)
    }

    /// Möller–Trumbore intersection for `t_min < t < t_max`. Every test is computed and
    /// the results combined without a branch each (a ray's data decide them, so branches
    /// would mispredict; one branch remains, on the combined result). A parallel ray
    /// (`det` zero) makes `inv_det` infinite and the barycentrics infinite or NaN, and a
    /// non-finite `det` makes `t` zero or NaN: both fail the tests, as they must.
    #[inline(always)]
    pub fn intersect_range(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_min: f32,
        t_max: f32,
    ) -> Option<(f32, f32, f32)> {
        let pvec = dir.cross(self.e2);
        let det = self.e1.dot(pvec);
        let inv_det = 1.0 / det;
        let tvec = origin - self.p0;
        let qvec = tvec.cross(self.e1);
        let b1 = tvec.dot(pvec) * inv_det;
        let b2 = dir.dot(qvec) * inv_det;
        let t = self.e2.dot(qvec) * inv_det;
        let hit = (b1 >= 0.0) & (b2 >= 0.0) & (b1 + b2 <= 1.0) & (t > t_min) & (t < t_max);
        if hit { Some((t, b1, b2)) } else { None }
    }

    /// Unnormalised geometric normal (`e1 x e2`, length twice the area).
    #[inline]
    pub fn cross(&self) -> Vec3 {
        self.e1.cross(self.e2)
    }

    #[inline]
    pub fn area(&self) -> f32 {
        0.5 * self.cross().length()
    }

    #[inline]
    pub fn point(&self, b1: f32, b2: f32) -> Vec3 {
        self.p0 + b1 * self.e1 + b2 * self.e2
    }
}

/// Per-triangle shading data: vertex normals and texture coordinates, material and light.
#[derive(Clone, Copy, Debug)]
pub struct TriangleShading {
    /// Vertex normals, or `None` for a flat (faceted) triangle.
    pub normals: Option<[Vec3; 3]>,
    pub uvs: Option<[Vec2; 3]>,
    pub material: u32,
    /// Index into the scene's lights when the triangle emits.
    pub light: Option<u32>,
}

/// What a closest-hit query returns: the surface point and its local geometry.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceHit {
    pub t: f32,
    pub p: Vec3,
    /// Geometric normal, unit, as the triangle's winding gives it.
    pub ng: Vec3,
    /// Shading normal, unit, as the vertex normals interpolate it: on either side of `ng`
    /// (a mesh may be wound against its normals); `ng` without vertex normals.
    pub ns: Vec3,
    pub uv: Vec2,
    pub triangle: u32,
    pub material: u32,
    pub light: Option<u32>,
}

impl SurfaceHit {
    /// The geometric normal turned to the side the shading normal faces: the surface's front,
    /// as Mitsuba 3 takes it. Mitsuba evaluates every BSDF in the shading frame, so where the
    /// vertex normals point against the winding, the shading normal decides which side of a
    /// `dielectric` is outside (its `cos θ_i > 0`: entering) and which side a one-sided BSDF
    /// reflects on; the winding alone would turn a glass ball into a bubble in glass.
    #[inline]
    pub fn facing_ng(&self) -> Vec3 {
        if self.ns.dot(self.ng) < 0.0 {
            -self.ng
        } else {
            self.ng
        }
    }
}

/// Offsets a ray origin off a surface along the geometric normal `n` (pointing to the side
/// the ray leaves from), by an amount that grows with the magnitude of `p` so that the new
/// ray never re-hits the surface it starts on (Wächter & Binder, "A Fast and Robust Method
/// for Avoiding Self-Intersection", Ray Tracing Gems, ch. 6).
///
/// Coordinates under `scale / 32` move by the fixed `scale / 65536` instead: near zero the
/// ulps of `p` say nothing of the error of a hit computed from vertices of the scene's size.
/// Wächter and Binder's constants (`scale` 1) suit scenes of a unit or more; `scale` is the
/// scene's size where it is smaller ([`crate::scene::Scene::offset_scale`]), so that a scene
/// of 10⁻⁴ m is not offset by a quarter of itself.
#[inline]
pub fn offset_ray_origin(p: Vec3, n: Vec3, scale: f32) -> Vec3 {
    let origin = scale * (1.0 / 32.0);
    let float_scale = scale * (1.0 / 65536.0);
    const INT_SCALE: f32 = 256.0;
    let of_i = (n * INT_SCALE).as_ivec3();
    let step = |x: f32, o: i32| -> f32 {
        let bits = x.to_bits() as i32;
        let moved = if x < 0.0 { bits - o } else { bits + o };
        f32::from_bits(moved as u32)
    };
    let p_i = Vec3::new(step(p.x, of_i.x), step(p.y, of_i.y), step(p.z, of_i.z));
    Vec3::new(
        if p.x.abs() < origin {
            p.x + float_scale * n.x
        } else {
            p_i.x
        },
        if p.y.abs() < origin {
            p.y + float_scale * n.y
        } else {
            p_i.y
        },
        if p.z.abs() < origin {
            p.z + float_scale * n.z
        } else {
            p_i.z
        },
    )
}

/// Origin for a ray leaving surface point `p` (geometric normal `ng`) in direction `dir`
/// (`scale` as [`offset_ray_origin`]'s).
#[inline]
pub fn spawn_origin(p: Vec3, ng: Vec3, dir: Vec3, scale: f32) -> Vec3 {
    let n = if dir.dot(ng) >= 0.0 { ng } else { -ng };
    offset_ray_origin(p, n, scale)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The branch-free test rejects what it must through the arithmetic alone: rays
    /// parallel to the triangle (in its plane too), non-finite origins and directions,
    /// hits outside `(t_min, t_max)` and outside the triangle; and finds the hit inside,
    /// with its barycentrics.
    #[test]
    fn the_triangle_test_rejects_degenerate_rays_and_finds_hits() {
        let tri = TriangleGeom::new(Vec3::ZERO, Vec3::X, Vec3::Y);
        let down = -Vec3::Z;
        let (t, b1, b2) = tri
            .intersect(Vec3::new(0.25, 0.5, 2.0), down, 10.0)
            .expect("a hit inside");
        assert_eq!((t, b1, b2), (2.0, 0.25, 0.5));
        let miss = |o: Vec3, d: Vec3, t_min: f32, t_max: f32| {
            tri.intersect_range(o, d, t_min, t_max).is_none()
        };
        assert!(
            miss(Vec3::new(0.25, 0.5, 2.0), down, 0.0, 2.0),
            "t_max is exclusive"
        );
        assert!(
            miss(Vec3::new(0.25, 0.5, 2.0), down, 2.0, 3.0),
            "t_min is exclusive"
        );
        assert!(
            miss(Vec3::new(0.25, 0.5, 2.0), Vec3::Z, 0.0, 10.0),
            "behind"
        );
        assert!(miss(Vec3::new(0.75, 0.5, 2.0), down, 0.0, 10.0), "outside");
        assert!(
            miss(Vec3::new(0.25, 0.5, 1.0), Vec3::X, 0.0, 10.0),
            "parallel"
        );
        assert!(
            miss(Vec3::new(-1.0, 0.2, 0.0), Vec3::X, 0.0, 10.0),
            "in its plane"
        );
        let nan = Vec3::splat(f32::NAN);
        assert!(miss(nan, down, 0.0, 10.0) && miss(Vec3::Z, nan, 0.0, 10.0));
        let inf = Vec3::new(0.25, 0.5, f32::INFINITY);
        assert!(miss(inf, down, 0.0, f32::INFINITY));
        // On an edge and at a vertex: inside (closed triangle).
        assert!(
            tri.intersect(Vec3::new(0.0, 0.5, 1.0), down, 10.0)
                .is_some()
        );
        assert!(
            tri.intersect(Vec3::new(1.0, 0.0, 1.0), down, 10.0)
                .is_some()
        );
    }
}
