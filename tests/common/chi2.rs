//! A reusable chi-square goodness-of-fit harness for direction samplers (as Mitsuba 3's
//! `ChiSquareTest` and pbrt-v4's BSDF tests): a histogram of sampled directions against the
//! sampler's pdf integrated over each cell.
//!
//! Cells are a `(θ, φ)` grid over a spherical cap of half-angle `theta_max` around `axis`
//! (`theta_max = π` is the whole sphere), so narrow lobes get a fine grid where they live.
//! Directions outside the cap and failed samples share one extra bin whose expected count is
//! `N (1 - ∫_cap pdf)`. Cells expected to hold fewer than 5 samples are pooled.

use footprint::math::Frame;
use footprint::rng::Rng;
use glam::Vec3;

pub struct ChiSquareTest {
    pub axis: Vec3,
    pub theta_max: f64,
    pub res_theta: usize,
    pub res_phi: usize,
    pub samples: usize,
    /// Midpoint-rule points per cell side for integrating the pdf.
    pub integration_res: usize,
    pub seed: u64,
}

#[derive(Debug)]
pub struct ChiSquareResult {
    pub chi2: f64,
    pub dof: usize,
    pub p_value: f64,
    /// ∫ pdf over the cap, by the midpoint rule.
    pub integral: f64,
}

impl ChiSquareTest {
    pub fn sphere(samples: usize) -> Self {
        ChiSquareTest {
            axis: Vec3::Z,
            theta_max: std::f64::consts::PI,
            res_theta: 40,
            res_phi: 80,
            samples,
            integration_res: 16,
            seed: 1,
        }
    }

    fn dir(frame: &Frame, theta: f64, phi: f64) -> Vec3 {
        let (st, ct) = theta.sin_cos();
        let (sp, cp) = phi.sin_cos();
        frame
            .to_world(Vec3::new((st * cp) as f32, (st * sp) as f32, ct as f32))
            .normalize()
    }

    /// The cell of a unit direction, or `None` outside the cap.
    pub fn cell_of(&self, d: Vec3) -> Option<usize> {
        let frame = Frame::from_z(self.axis.normalize());
        let (nt, np) = (self.res_theta, self.res_phi);
        let dt = self.theta_max / nt as f64;
        let dp = 2.0 * std::f64::consts::PI / np as f64;
        // In f64, and the polar angle by atan2: acos of an f32 cosine resolves angles near
        // the axis only to 6e-8 / sin θ (1.5% of a cell 0.002 rad wide, at its edge), which
        // shifts a narrow lobe's samples between the innermost rings.
        let d = d.as_dvec3().normalize();
        let (lx, ly, lz) = (
            d.dot(frame.x.as_dvec3()),
            d.dot(frame.y.as_dvec3()),
            d.dot(frame.z.as_dvec3()),
        );
        let th = (lx * lx + ly * ly).sqrt().atan2(lz);
        if th >= self.theta_max {
            return None;
        }
        let mut ph = ly.atan2(lx);
        if ph < 0.0 {
            ph += 2.0 * std::f64::consts::PI;
        }
        let it = ((th / dt) as usize).min(nt - 1);
        let ip = ((ph / dp) as usize).min(np - 1);
        Some(it * np + ip)
    }

    /// Probability mass of every cell under `pdf` (midpoint rule, `integration_res`² points
    /// per cell).
    pub fn masses_from_pdf(&self, pdf: impl Fn(Vec3) -> f64) -> Vec<f64> {
        let frame = Frame::from_z(self.axis.normalize());
        let (nt, np) = (self.res_theta, self.res_phi);
        let dt = self.theta_max / nt as f64;
        let dp = 2.0 * std::f64::consts::PI / np as f64;
        let k = self.integration_res;
        let mut expected = vec![0.0f64; nt * np];
        for it in 0..nt {
            for ip in 0..np {
                let mut m = 0.0;
                for a in 0..k {
                    let th = (it as f64 + (a as f64 + 0.5) / k as f64) * dt;
                    for b in 0..k {
                        let ph = (ip as f64 + (b as f64 + 0.5) / k as f64) * dp;
                        let p = pdf(Self::dir(&frame, th, ph));
                        assert!(p.is_finite() && p >= 0.0, "pdf returned {p}");
                        m += p * th.sin();
                    }
                }
                expected[it * np + ip] = m * dt * dp / (k * k) as f64;
            }
        }
        expected
    }

    /// Runs the test: `sample(rng)` draws one direction (or fails), `pdf(dir)` is its density
    /// per steradian.
    pub fn run(
        &self,
        sample: impl FnMut(&mut Rng) -> Option<Vec3>,
        pdf: impl Fn(Vec3) -> f64,
    ) -> ChiSquareResult {
        let masses = self.masses_from_pdf(pdf);
        self.run_with_masses(sample, &masses)
    }

    /// Runs the test against given cell masses (for densities with features finer than the
    /// cells, whose masses the caller integrates exactly).
    pub fn run_with_masses(
        &self,
        mut sample: impl FnMut(&mut Rng) -> Option<Vec3>,
        expected: &[f64],
    ) -> ChiSquareResult {
        let integral: f64 = expected.iter().sum();
        let mut observed = vec![0.0f64; expected.len()];
        let mut outside = 0.0f64;
        let mut rng = Rng::new(self.seed, 0xC41, 0);
        for _ in 0..self.samples {
            match sample(&mut rng) {
                Some(d) => {
                    assert!(d.is_finite(), "sampled a non-finite direction");
                    match self.cell_of(d) {
                        Some(c) => observed[c] += 1.0,
                        None => outside += 1.0,
                    }
                }
                None => outside += 1.0,
            }
        }
        let n = self.samples as f64;
        // Pool low-expectation cells; the outside bin is one more cell.
        let mut cells: Vec<(f64, f64)> = observed
            .iter()
            .zip(expected)
            .map(|(o, e)| (*o, e * n))
            .collect();
        cells.push((outside, (1.0 - integral).max(0.0) * n));
        let (chi2, bins) = pearson_pooled(cells);
        let dof = bins.saturating_sub(1).max(1);
        let p_value = if chi2.is_finite() {
            super::chi2_sf(chi2, dof as f64)
        } else {
            0.0
        };
        ChiSquareResult {
            chi2,
            dof,
            p_value,
            integral,
        }
    }
}

/// Pearson's statistic over `(observed, expected)` cells, cells expecting fewer than 5
/// pooled into one; returns the statistic and the number of bins. Observations where nothing
/// is expected give an infinite statistic.
pub fn pearson_pooled(cells: impl IntoIterator<Item = (f64, f64)>) -> (f64, usize) {
    let mut chi2 = 0.0;
    let mut bins = 0usize;
    let (mut pool_o, mut pool_e) = (0.0, 0.0);
    for (o, e) in cells {
        if e < 5.0 {
            pool_o += o;
            pool_e += e;
        } else {
            chi2 += (o - e) * (o - e) / e;
            bins += 1;
        }
    }
    if pool_e > 0.0 {
        chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
        bins += 1;
    } else if pool_o > 0.0 {
        // Samples where the pdf says there can be none.
        chi2 = f64::INFINITY;
    }
    (chi2, bins)
}
