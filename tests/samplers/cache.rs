//! The guide cache: its regions' samplers through the chi-square harness with a coloured
//! throughput, and their particle density estimates.

use crate::common::chi2::ChiSquareTest;
use crate::common::sidak;
use crate::masses::{footprint_masses, grid_masses};
use crate::{dir, mix_at};
use footprint::Rgb;
use footprint::bsdf::{Bsdf, Lobes, TransportMode};
use footprint::guide::footprint::{FootprintDistribution, FootprintGuide};
use footprint::guide::grid::GridDistribution;
use footprint::guide::particle_map::{MapKind, ParticleMap};
use footprint::guide::sampler::{GuideSource, GuidedSampler, SamplerState, ScatterPoint};
use footprint::math::Frame;
use footprint::rng::Rng;
use footprint::sampling::sample_uniform_sphere;
use footprint::settings::GuideParams;
use glam::Vec3;

/// The guide cache end to end: particles on a wall (a photon map), the other pass's
/// scattering points on the same wall as seeds, the region found by a lookup, and the
/// sampler over it run through the chi-square harness against its exact masses (caps
/// integrated in their own coordinates, grid cells as exact overlaps). The particles are
/// strongly coloured per direction (red light from one side at grazing angles, blue light
/// from above), the path's throughput is almost pure red, the BSDF is a glossy lobe over a
/// tilted shading normal: the channel mixture must follow the throughput, and sample and
/// pdf must agree. Significance 0.01, Šidák over the guides tested.
#[test]
fn cached_regions_pass_chi_square_with_coloured_throughput() {
    use footprint::guide::Guide;
    use footprint::guide::cache::{GuideCache, Seed};
    use footprint::guide::grid::GridGuide;
    use footprint::guide::particle_map::ParticleInput;
    use footprint::guide::selection::{MIN_RECORDS, SelectionLearner, SelectionRecord};
    let mut rng = Rng::new(5, 5, 5);
    let mut particles = Vec::new();
    for i in 0..4000 {
        let pos = Vec3::new(rng.uniform() * 0.2, rng.uniform() * 0.2, 0.0);
        let (d, w) = if i % 2 == 0 {
            // Red, grazing: 3 to 10 degrees above the wall, from -x.
            let elev = (3.0 + 7.0 * rng.uniform()).to_radians();
            let az = std::f32::consts::PI + 0.4 * (rng.uniform() - 0.5);
            (
                Vec3::new(elev.cos() * az.cos(), elev.cos() * az.sin(), elev.sin()),
                Rgb::new(1.0, 0.02, 0.0),
            )
        } else {
            // Blue, from near the normal.
            (
                (Vec3::Z + 0.3 * sample_uniform_sphere(rng.uniform2())).normalize(),
                Rgb::new(0.0, 0.05, 1.0),
            )
        };
        particles.push(ParticleInput {
            position: pos,
            dir: d,
            normal: Vec3::Z,
            weight: w,
            depth: 1,
            specular_chain: true,
        });
    }
    let map = ParticleMap::build(MapKind::Photons, &particles);
    let seeds: Vec<Seed> = (0..200)
        .map(|_| Seed {
            position: Vec3::new(0.05 + 0.1 * rng.uniform(), 0.05 + 0.1 * rng.uniform(), 0.0),
            normal: Vec3::Z,
        })
        .collect();
    let bsdf = Bsdf::new(
        Lobes::Glossy {
            kd: Rgb::new(0.5, 0.4, 0.3),
            ks: Rgb::splat(0.3),
            exponent: 20.0,
            p_glossy: 0.4,
        },
        (Vec3::Z + Vec3::new(0.2, 0.1, 0.0)).normalize(),
        Vec3::Z,
    );
    // Footprints rasterised for sampling (the default), footprints sampled from their caps,
    // and the grid; the default once more with the region's BSDF probability learned
    // (src/guide/selection.rs) down to 0.1, which sample and pdf must both use.
    let guides: [(&dyn Guide, usize, bool); 4] = [
        (&FootprintGuide, 16, false),
        (&FootprintGuide, 0, false),
        (&GridGuide, 0, false),
        (&FootprintGuide, 16, true),
    ];
    let alpha = sidak(0.01, guides.len());
    for (guide, raster, learned) in guides {
        let params = GuideParams {
            region_particles: 1000,
            raster,
            ..GuideParams::default()
        };
        let cache = GuideCache::build(&map, guide, &seeds, &params, 0.2);
        let x = Vec3::new(0.1, 0.1, 0.0);
        let region = cache.lookup(x, Vec3::Z).expect("a region holds the point");
        let dist = region
            .distribution
            .as_ref()
            .expect("the region guides")
            .get();
        let learner = SelectionLearner::new(cache.regions().len(), params.p_bsdf);
        let i = cache.lookup_index(x, Vec3::Z).unwrap();
        // Returns only where the guide is dense and the BSDF is not: the least BSDF share.
        let records: Vec<SelectionRecord> = (0..MIN_RECORDS)
            .map(|_| SelectionRecord {
                region: i,
                returned2: 1.0,
                pdf_bsdf_w: 0.01,
                pdf_guide_w: 1.0,
                pdf_w: 0.505,
            })
            .collect();
        learner.absorb(&records);
        assert_eq!(learner.p_bsdf(i), 0.1);
        let sampler = GuidedSampler {
            source: GuideSource::Cached(&cache),
            params: params.clone(),
            soft_glossy_max: 100.0,
            selection: learned.then_some(&learner),
        };
        // The masses of the mixture with the probability the sampler uses.
        let params = GuideParams {
            p_bsdf: if learned { 0.1 } else { params.p_bsdf },
            ..params.clone()
        };
        let at = ScatterPoint {
            p: x,
            bsdf: &bsdf,
            wo: dir(40.0, 60.0),
            mode: TransportMode::Radiance,
            throughput: Rgb::new(1.0, 0.01, 0.001),
        };
        let mut state = SamplerState::default();
        sampler.prepare(&at, &mut state);
        assert!(state.guided(), "{}: not guided", guide.name());
        let mix = mix_at(&at, dist);
        assert!(
            mix.0[0] > 0.9,
            "{}: the red throughput should pick the red channel: {:?}",
            guide.name(),
            mix
        );
        let frame = Frame::from_z(region.normal);
        let test = ChiSquareTest {
            axis: region.normal,
            theta_max: std::f64::consts::PI,
            res_theta: 60,
            res_phi: 80,
            samples: 1_000_000,
            integration_res: 4,
            seed: 23,
        };
        let masses = if let Some(fp) = dist.as_any().downcast_ref::<FootprintDistribution>() {
            footprint_masses(&test, &at, fp, &mix, params.p_bsdf)
        } else {
            let grid = dist
                .as_any()
                .downcast_ref::<GridDistribution>()
                .expect("a grid");
            grid_masses(&test, &at, &frame, grid, &mix, &params)
        };
        let r = test.run_with_masses(
            |rng| sampler.sample(&at, &state, rng).map(|s| s.wi),
            &masses,
        );
        eprintln!(
            "cached {} (raster {raster}, p_bsdf {}, {} particles): chi2 {:.0} dof {} p {:.3e}, channel mixture {:?}",
            guide.name(),
            params.p_bsdf,
            region.particles,
            r.chi2,
            r.dof,
            r.p_value,
            mix.0
        );
        assert!(
            r.p_value > alpha,
            "cached {}: p = {:.3e}",
            guide.name(),
            r.p_value
        );
        // The density a draw reports is what `pdf` and (for a white path) the combined
        // image's `mis_pdf` give the same direction, with the same (learned) probability:
        // a sampler that kept the default 0.5 in either would be off by far more than 1e-4.
        let white = ScatterPoint {
            throughput: Rgb::ONE,
            ..at
        };
        let mut white_state = SamplerState::default();
        sampler.prepare(&white, &mut white_state);
        let mut rng = Rng::new(31, 0, 0);
        for _ in 0..200 {
            let Some(s) = sampler.sample(&white, &white_state, &mut rng) else {
                continue;
            };
            let pdf = sampler.pdf(&white, &white_state, s.wi);
            let mis = sampler.mis_pdf(&white, s.wi);
            let close = |a: f32, b: f32| (a - b).abs() <= 1e-4 * b.abs().max(1e-6);
            assert!(close(s.pdf_w, pdf), "sample {} vs pdf {pdf}", s.pdf_w);
            // (Footprints sampled from their caps give the weights a tabulated density.)
            if region.table.is_none() {
                assert!(close(s.pdf_w, mis), "sample {} vs mis_pdf {mis}", s.pdf_w);
            }
        }
    }
}

/// A cached region's particle density (`Region::density`, what guided Russian roulette
/// reads) estimates the weight per unit area: particles spread uniformly over a unit square
/// with a known total give `Σ w / (π r²)` over the disc holding a region's particles. Its
/// relative standard deviation is about `1/sqrt(k)` for `k` particles (a k-nearest density
/// estimate); every interior region must lie within 5 of those and their median (the regions
/// share particles, so the median is no better than one region) within 3.
#[test]
fn cached_regions_estimate_the_particle_density() {
    let n = 40_000;
    let w = Rgb::new(2.0, 1.0, 0.5) / n as f32;
    // Seeds in the middle, so that every region's disc lies inside the square.
    let (cache, _) = square_cache(&mut Rng::new(8, 8, 8), n, w, 0.3, 0.4);
    let expected = w * n as f32; // per unit area: the square's area is 1
    let mut ratios = Vec::new();
    for r in cache.regions().iter().filter(|r| r.distribution.is_some()) {
        let sd = 1.0 / (r.particles as f32).sqrt();
        let density = r.density.expect("a finite density");
        let ratio = density / expected;
        // One colour: every channel is the same ratio.
        assert!((ratio.x - ratio.z).abs() < 1e-4 && (ratio.x - ratio.y).abs() < 1e-4);
        assert!(
            (ratio.x - 1.0).abs() < 5.0 * sd,
            "region at {:?}: density {:?} against {expected:?} ({} particles)",
            r.centre,
            density,
            r.particles
        );
        ratios.push((ratio.x, sd));
    }
    assert!(
        ratios.len() >= 5,
        "{} regions: too few to test",
        ratios.len()
    );
    ratios.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (median, sd) = ratios[ratios.len() / 2];
    eprintln!(
        "{} regions, median density ratio {median:.4} (sd {sd:.4})",
        ratios.len()
    );
    assert!((median - 1.0).abs() < 3.0 * sd, "median ratio {median}");
}

/// A region that learned BSDF sampling alone (`p_BSDF = 1`, where the guide does not pay for
/// its time: `src/guide/selection.rs`) is not guided: `prepare` leaves the vertex to the
/// BSDF, whose density `sample`, `pdf` and the combined image's `mis_pdf` all report, while
/// its particle density still reaches Russian roulette; a neighbouring region that learned
/// 0.9 keeps guiding with the mixture. Learned from records whose guide density equals the
/// BSDF's (a guide no better than the BSDF) and from ones where it is ten times it.
#[test]
fn a_region_that_learned_bsdf_sampling_alone_is_not_guided() {
    use footprint::guide::selection::{MIN_RECORDS, SelectionLearner, SelectionRecord};
    let (cache, params) = square_cache(&mut Rng::new(9, 9, 9), 20_000, Rgb::splat(1e-4), 0.2, 0.6);
    let points = [Vec3::new(0.3, 0.3, 0.0), Vec3::new(0.7, 0.7, 0.0)];
    let [alone, guided] = points.map(|x| cache.lookup_index(x, Vec3::Z).expect("a region"));
    assert_ne!(alone, guided, "the two points must lie in two regions");
    let learner = SelectionLearner::new(cache.regions().len(), params.p_bsdf);
    let records = |region: u32, pdf_guide_w: f32| SelectionRecord {
        region,
        returned2: 1.0,
        pdf_bsdf_w: 1.0,
        pdf_guide_w,
        pdf_w: 0.5 + 0.5 * pdf_guide_w,
    };
    let mut r: Vec<SelectionRecord> = (0..MIN_RECORDS).map(|_| records(alone, 1.0)).collect();
    r.extend((0..MIN_RECORDS).map(|_| records(guided, 10.0)));
    learner.absorb(&r);
    assert_eq!(learner.p_bsdf(alone), 1.0);
    assert!(learner.p_bsdf(guided) < 1.0);
    let sampler = GuidedSampler {
        source: GuideSource::Cached(&cache),
        params: params.clone(),
        soft_glossy_max: 100.0,
        selection: Some(&learner),
    };
    let bsdf = Bsdf::new(
        Lobes::Diffuse {
            kd: Rgb::splat(0.5),
        },
        Vec3::Z,
        Vec3::Z,
    );
    for (x, region) in points.into_iter().zip([alone, guided]) {
        let at = ScatterPoint {
            p: x,
            bsdf: &bsdf,
            wo: dir(40.0, 60.0),
            mode: TransportMode::Radiance,
            throughput: Rgb::ONE,
        };
        let mut state = SamplerState::default();
        sampler.prepare(&at, &mut state);
        assert_eq!(state.guided(), region == guided, "region {region}");
        assert!(
            state.region_density().is_some(),
            "region {region}: roulette loses its estimate"
        );
        assert_eq!(state.fallbacks, 0, "a learned choice is not a fallback");
        let mut rng = Rng::new(3, 0, 0);
        let mut differs = false;
        for _ in 0..200 {
            let s = sampler.sample(&at, &state, &mut rng).expect("a direction");
            let bsdf_pdf = bsdf.pdf(at.wo, s.wi);
            let close = |a: f32, b: f32| (a - b).abs() <= 1e-4 * b.abs().max(1e-6);
            let pdf = sampler.pdf(&at, &state, s.wi);
            let mis = sampler.mis_pdf(&at, s.wi);
            assert!(close(s.pdf_w, pdf), "sample {} vs pdf {pdf}", s.pdf_w);
            assert!(close(s.pdf_w, mis), "sample {} vs mis_pdf {mis}", s.pdf_w);
            if region == alone {
                assert!(close(s.pdf_w, bsdf_pdf), "{} vs {bsdf_pdf}", s.pdf_w);
                assert!(s.guided.is_none(), "no record from an unguided vertex");
            } else {
                differs |= !close(s.pdf_w, bsdf_pdf);
            }
        }
        assert!(
            region == alone || differs,
            "the guided region must draw from the mixture"
        );
    }
}

/// A photon map of `n` particles of weight `w` spread uniformly over the unit square of the
/// plane `z = 0` (directions about its normal), and its guide cache (footprints, 40 seeds per
/// region) over 400 seeds uniform in the square `[lo, lo + span]²`.
fn square_cache(
    rng: &mut Rng,
    n: usize,
    w: Rgb,
    lo: f32,
    span: f32,
) -> (footprint::guide::cache::GuideCache, GuideParams) {
    use footprint::guide::cache::{GuideCache, Seed};
    use footprint::guide::particle_map::ParticleInput;
    let particles: Vec<ParticleInput> = (0..n)
        .map(|_| ParticleInput {
            position: Vec3::new(rng.uniform(), rng.uniform(), 0.0),
            dir: (Vec3::Z + 0.5 * sample_uniform_sphere(rng.uniform2())).normalize(),
            normal: Vec3::Z,
            weight: w,
            depth: 2,
            specular_chain: false,
        })
        .collect();
    let map = ParticleMap::build(MapKind::Photons, &particles);
    let seeds: Vec<Seed> = (0..400)
        .map(|_| Seed {
            position: Vec3::new(lo + span * rng.uniform(), lo + span * rng.uniform(), 0.0),
            normal: Vec3::Z,
        })
        .collect();
    let params = GuideParams {
        region_seeds: 40,
        ..GuideParams::default()
    };
    (
        GuideCache::build(&map, &FootprintGuide, &seeds, &params, 0.2),
        params,
    )
}
