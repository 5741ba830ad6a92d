//! A piecewise-constant density on the unit square: a grid of `nu x nv` cells, each of
//! constant density proportional to its weight, sampled as a marginal distribution over the
//! rows and a conditional distribution over the columns of the chosen row (pbrt-v3 §13.6.7,
//! "Piecewise-Constant 2D Distributions"; pbrt-v4's `PiecewiseConstant2D`). Sampling and the
//! density read the same per-row and per-column probabilities, so that [`Distribution2D::pdf`]
//! is exactly the density [`Distribution2D::sample`] returns for the point it returns.

use crate::sampling::Distribution1D;
use glam::Vec2;

#[derive(Clone, Debug)]
pub struct Distribution2D {
    nu: usize,
    nv: usize,
    /// The rows, in proportion to the sums of their weights.
    rows: Distribution1D,
    /// Per row, its columns in proportion to their weights (`None` for a row of weight zero,
    /// which the marginal never chooses).
    columns: Vec<Option<Distribution1D>>,
}

impl Distribution2D {
    /// The distribution over `nu x nv` cells of row-major `weights` (row `j` covers
    /// `v ∈ [j/nv, (j+1)/nv)`, column `i` covers `u ∈ [i/nu, (i+1)/nu)`). Negative or
    /// non-finite weights count as zero. `None` when every weight is zero.
    pub fn new(weights: &[f32], nu: usize, nv: usize) -> Option<Self> {
        assert_eq!(weights.len(), nu * nv, "weights of a {nu} x {nv} grid");
        if nu == 0 || nv == 0 {
            return None;
        }
        let columns: Vec<Option<Distribution1D>> =
            weights.chunks_exact(nu).map(Distribution1D::new).collect();
        let row_sums: Vec<f32> = columns
            .iter()
            .map(|c| c.as_ref().map_or(0.0, |c| c.total() as f32))
            .collect();
        let rows = Distribution1D::new(&row_sums)?;
        Some(Distribution2D {
            nu,
            nv,
            rows,
            columns,
        })
    }

    /// A point of the unit square and its density per unit area. The two numbers of `u`
    /// choose the row (`u.y`) and the column (`u.x`); what is left of each places the point
    /// uniformly within its cell.
    #[inline]
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        let (j, pmf_row, rest_v) = self.rows.sample_remapped(u.y);
        let columns = self.columns[j]
            .as_ref()
            .expect("the marginal chooses rows of positive weight only");
        let (i, pmf_column, rest_u) = columns.sample_remapped(u.x);
        let p = Vec2::new(
            (i as f32 + rest_u) / self.nu as f32,
            (j as f32 + rest_v) / self.nv as f32,
        );
        (p, self.density(pmf_row, pmf_column))
    }

    /// Density per unit area of the point `p` of the unit square (0 outside it).
    #[inline]
    pub fn pdf(&self, p: Vec2) -> f32 {
        if !(p.x >= 0.0 && p.x <= 1.0 && p.y >= 0.0 && p.y <= 1.0) {
            return 0.0;
        }
        let i = ((p.x * self.nu as f32) as usize).min(self.nu - 1);
        let j = ((p.y * self.nv as f32) as usize).min(self.nv - 1);
        match &self.columns[j] {
            Some(c) => self.density(self.rows.pmf(j), c.pmf(i)),
            None => 0.0,
        }
    }

    /// The cell's probability spread over its area `1 / (nu nv)`.
    #[inline]
    fn density(&self, pmf_row: f32, pmf_column: f32) -> f32 {
        pmf_row * pmf_column * (self.nu * self.nv) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::Distribution2D;
    use glam::Vec2;

    /// Every sampled point's density is what `pdf` gives there, zero-weight cells are never
    /// chosen, and the density integrates to one.
    #[test]
    fn sample_and_pdf_agree() {
        let w = [1.0, 0.0, 3.0, 0.0, 0.0, 0.0, 2.0, 5.0, 1.0];
        let d = Distribution2D::new(&w, 3, 3).unwrap();
        let n = 64;
        for a in 0..n {
            for b in 0..n {
                let u = Vec2::new((a as f32 + 0.5) / n as f32, (b as f32 + 0.5) / n as f32);
                let (p, pdf) = d.sample(u);
                assert!(pdf > 0.0);
                assert_eq!(pdf, d.pdf(p), "at {p}");
            }
        }
        let total: f32 = (0..9)
            .map(|c| d.pdf(Vec2::new((c % 3) as f32 + 0.5, (c / 3) as f32 + 0.5) / 3.0) / 9.0)
            .sum();
        assert!((total - 1.0).abs() < 1e-5, "{total}");
        assert!(Distribution2D::new(&[0.0; 4], 2, 2).is_none());
    }
}
