//! The thin-lens camera (`footprint::scene::camera`): its lens points, its rays, and the
//! importance `W_e` and densities its light-tracing connections use.
//!
//! Statistical checks use fixed seeds; each bound is stated where it is made, from the
//! standard error of the estimate (or a chi-square p-value), so a wrong density or a wrong
//! normalisation fails while the checked quantities hold.

mod common;

use common::{chi2_sf, mean_stderr};
use footprint::rng::Rng;
use footprint::scene::camera::Camera;
use glam::{Vec2, Vec3};

/// A camera looking obliquely at no axis, wider than tall, with a lens of radius 0.2 focused
/// at 6 along its view axis (or `radius` 0: the pinhole).
fn camera(radius: f32) -> Camera {
    Camera::new(
        Vec3::new(1.0, 2.0, 3.0),
        Vec3::new(1.5, 2.2, 10.0),
        Vec3::Y,
        40.0,
        64,
        48,
    )
    .unwrap()
    .with_lens(radius, 6.0)
    .unwrap()
}

fn film(cam: &Camera) -> Vec2 {
    Vec2::new(cam.width as f32, cam.height as f32)
}

/// Half extents of the image at distance 1 along the view axis.
fn tan_halves(cam: &Camera) -> Vec2 {
    let ty = (cam.fov_y_deg.to_radians() * 0.5).tan();
    Vec2::new(ty * cam.width as f32 / cam.height as f32, ty)
}

/// Radius 0 is the pinhole exactly: rays start at the position, connections do not depend on
/// the lens sample, and no numbers are drawn for the lens.
#[test]
fn a_zero_radius_lens_is_the_pinhole() {
    let cam = camera(0.0);
    assert!(!cam.has_lens());
    let mut rng = Rng::new(1, 2, 3);
    for _ in 0..1000 {
        let raster = rng.uniform2() * film(&cam);
        let u = rng.uniform2();
        assert_eq!(cam.ray(raster, u), (cam.position, cam.ray_dir(raster)));
        let p = cam.position + 5.0 * cam.ray_dir(raster);
        let (a, b) = (
            cam.connect(p, u).unwrap(),
            cam.connect(p, Vec2::ZERO).unwrap(),
        );
        assert_eq!((a.raster, a.lens, a.we_geom), (b.raster, b.lens, b.we_geom));
        assert_eq!(a.lens, cam.position);
    }
    let (mut a, mut b) = (Rng::new(9, 9, 9), Rng::new(9, 9, 9));
    cam.draw_lens_sample(&mut a);
    assert_eq!(a.uniform(), b.uniform(), "the pinhole drew numbers");
    // A negative radius or a focus distance of 0 is refused.
    assert!(camera(0.0).with_lens(-0.1, 1.0).is_err());
    assert!(camera(0.0).with_lens(0.1, 0.0).is_err());
}

/// Lens points lie on the aperture disk (perpendicular to the view axis, within the radius)
/// and are uniform over it: 64 cells of equal area (8 rings of equal area by 8 sectors),
/// 64,000 points, Pearson's chi-square with 63 degrees of freedom; fails below p = 1e-4
/// (fixed seed).
#[test]
fn lens_points_are_uniform_on_the_aperture() {
    let cam = camera(0.2);
    let mut rng = Rng::new(5, 0, 0);
    let n = 64_000;
    let mut counts = [0u32; 64];
    for _ in 0..n {
        let p = cam.lens_point(rng.uniform2()) - cam.position;
        assert!(p.dot(cam.frame.z).abs() < 1e-6, "off the lens plane");
        let (x, y) = (p.dot(cam.frame.x), p.dot(cam.frame.y));
        let r2 = (x * x + y * y) / (0.2 * 0.2);
        assert!(r2 <= 1.0 + 1e-5, "outside the aperture: {r2}");
        let ring = ((r2 * 8.0) as usize).min(7);
        let phi = y.atan2(x) + std::f32::consts::PI;
        let sector = ((phi / std::f32::consts::TAU * 8.0) as usize).min(7);
        counts[ring * 8 + sector] += 1;
    }
    let expect = n as f64 / 64.0;
    let chi2: f64 = counts
        .iter()
        .map(|&c| (c as f64 - expect).powi(2) / expect)
        .sum();
    let p = chi2_sf(chi2, 63.0);
    eprintln!("lens cells: chi2 {chi2:.1}, p {p:.3}");
    assert!(
        p > 1e-4,
        "lens points are not uniform: chi2 {chi2:.1}, p {p:.2e}"
    );
}

/// A connection from a point of a camera ray to the ray's lens point lands on the ray's
/// raster position, from the ray's origin, against its direction (the focused ray through a
/// lens point is the one the connection splats to), in front of, at and behind the focal
/// plane.
#[test]
fn connections_land_where_the_camera_ray_from_their_lens_point_starts() {
    let cam = camera(0.2);
    let mut rng = Rng::new(7, 0, 0);
    let mut worst = 0.0f32;
    for i in 0..20_000 {
        let raster = rng.uniform2() * film(&cam);
        let u = rng.uniform2();
        let (o, d) = cam.ray(raster, u);
        assert!((d.length() - 1.0).abs() < 1e-5);
        assert!((o - cam.lens_point(u)).length() < 1e-6);
        let t = [0.7f32, 6.0, 23.0][i % 3] / d.dot(cam.frame.z);
        let c = cam
            .connect(o + t * d, u)
            .expect("a point on a camera ray is seen");
        assert!((c.lens - o).length() < 1e-5);
        assert!((c.dir_to_camera + d).length() < 1e-4);
        assert!((c.distance - t).abs() < 1e-4 * t);
        worst = worst.max((c.raster - raster).abs().max_element());
    }
    eprintln!("largest raster difference {worst:.2e} pixels");
    assert!(worst < 2e-3, "raster positions differ by {worst} pixels");
}

/// The importance a connection carries integrates to 1 over the lens and the film, as a
/// pinhole's over the film (`W_e` is normalised over the whole image), and to a quarter over
/// each quarter of the film. Estimator: points uniform on a plane perpendicular to the view
/// axis, large enough that every lens point sees the whole film on it, each connected to a
/// uniform lens point: `we_geom · cos θ_plane · area` has mean
/// `∫ W_e cos θ_cam cos θ_plane / d² dA_plane dA_lens = ∫ W_e cos θ dω dA_lens = 1`.
/// 400,000 samples per plane (in front of, at and behind the focal plane; a lens and the
/// pinhole); each mean must lie within 4.5 standard errors of 1 (a quarter's: of 1/4; 30
/// tests, a chance failure below 2e-4 in all), with a standard error under 1%.
#[test]
fn connection_importance_integrates_to_one_over_lens_and_film() {
    for radius in [0.2f32, 0.0] {
        let cam = camera(radius);
        let th = tan_halves(&cam);
        for depth in [2.5f32, 6.0, 15.0] {
            // A ray from lens point l through focal point q crosses the plane at
            // l (1 - depth/f) + q depth/f: within this of the axis.
            let half = th * depth + Vec2::splat(radius * (1.0 + depth / cam.focus_distance()));
            let area = 4.0 * half.x * half.y;
            let mut rng = Rng::new(11, depth.to_bits() as u64, radius.to_bits() as u64);
            let n = 400_000;
            let mut total = Vec::with_capacity(n);
            let mut quarters: Vec<Vec<f64>> = (0..4).map(|_| Vec::with_capacity(n)).collect();
            for _ in 0..n {
                let s = (2.0 * rng.uniform2() - Vec2::ONE) * half;
                let p = cam.position + cam.frame.x * s.x + cam.frame.y * s.y + cam.frame.z * depth;
                let c = cam.connect(p, rng.uniform2());
                let x = c.map_or(0.0, |c| {
                    (c.we_geom * -c.dir_to_camera.dot(cam.frame.z) * area) as f64
                });
                let quarter = c.map(|c| {
                    let q = 2.0 * c.raster / film(&cam);
                    (q.x as usize).min(1) + 2 * (q.y as usize).min(1)
                });
                total.push(x);
                for (k, v) in quarters.iter_mut().enumerate() {
                    v.push(if quarter == Some(k) { x } else { 0.0 });
                }
            }
            let (m, se) = mean_stderr(&total);
            eprintln!("radius {radius}, plane at {depth}: ∫ W_e = {m:.4} ± {se:.4}");
            assert!(se < 0.01, "the estimate is too noisy to test: ± {se}");
            // (The pinhole's estimator is the constant 1 on the plane of its frustum: f32
            // rounding alone.)
            assert!(
                (m - 1.0).abs() < 4.5 * se + 1e-5,
                "radius {radius}, plane at {depth}: ∫ W_e = {m} ± {se}"
            );
            for (k, v) in quarters.iter().enumerate() {
                let (m, se) = mean_stderr(v);
                assert!(
                    (m - 0.25).abs() < 4.5 * se + 1e-5,
                    "radius {radius}, plane at {depth}, quarter {k}: {m} ± {se}"
                );
            }
        }
    }
}

/// Camera rays from one lens point have the direction density `Camera::pdf_dir`: the mean of
/// `1 / pdf_dir` over rays through uniform raster positions is the solid angle the film
/// subtends there (the focal plane's image rectangle seen from that lens point), which a
/// 2000 x 2000 midpoint rule integrates. 100,000 rays per lens point; within 4.5 standard
/// errors (fixed seed).
#[test]
fn camera_rays_have_the_pinhole_direction_density_at_each_lens_point() {
    let cam = camera(0.2);
    let th = tan_halves(&cam);
    let f = 6.0f32;
    let mut rng = Rng::new(13, 0, 0);
    for u in [
        Vec2::new(0.5, 0.5),
        Vec2::new(0.95, 0.2),
        Vec2::new(0.1, 0.7),
    ] {
        let lens = cam.lens_point(u) - cam.position;
        let lens_local = Vec3::new(lens.dot(cam.frame.x), lens.dot(cam.frame.y), 0.0);
        // The film's solid angle from the lens point: ∫ cos / d² over the focal rectangle.
        let m = 2000;
        let (w, h) = (2.0 * th.x * f, 2.0 * th.y * f);
        let mut omega = 0.0f64;
        for j in 0..m {
            for i in 0..m {
                let q = Vec3::new(
                    -w / 2.0 + (i as f32 + 0.5) * w / m as f32,
                    -h / 2.0 + (j as f32 + 0.5) * h / m as f32,
                    f,
                ) - lens_local;
                let d2 = q.length_squared() as f64;
                omega += (q.z as f64 / d2.sqrt()) / d2;
            }
        }
        omega *= (w as f64 / m as f64) * (h as f64 / m as f64);
        let xs: Vec<f64> = (0..100_000)
            .map(|_| {
                let (o, d) = cam.ray(rng.uniform2() * film(&cam), u);
                assert!((o - cam.lens_point(u)).length() < 1e-6);
                1.0 / cam.pdf_dir(d.dot(cam.frame.z)) as f64
            })
            .collect();
        let (mean, se) = mean_stderr(&xs);
        eprintln!("lens point {u}: E[1/pdf] = {mean:.5} ± {se:.5}, film solid angle {omega:.5}");
        assert!(
            (mean - omega).abs() < 4.5 * se,
            "lens point {u}: E[1/pdf] {mean} vs {omega}"
        );
    }
}
