//! Shared helpers for the statistical tests: quantiles, the chi-square distribution, the
//! Šidák correction, and paths to the bundled scenes.
#![allow(dead_code)]

pub mod chi2;

use std::path::PathBuf;

/// Folder of the bundled scenes.
pub fn scenes_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

pub fn scene_path(name: &str) -> PathBuf {
    scenes_dir().join(name).join(format!("{name}.toml"))
}

/// Per-test significance that keeps the family-wise significance at `alpha` over `n`
/// independent tests (Šidák).
pub fn sidak(alpha: f64, n: usize) -> f64 {
    1.0 - (1.0 - alpha).powf(1.0 / n as f64)
}

/// Standard normal quantile (Acklam's rational approximation, relative error < 1.2e-9).
pub fn normal_quantile(p: f64) -> f64 {
    assert!(p > 0.0 && p < 1.0);
    const A: [f64; 6] = [
        -3.969683028665376e1,
        2.209460984245205e2,
        -2.759285104469687e2,
        1.383577518672690e2,
        -3.066479806614716e1,
        2.506628277459239,
    ];
    const B: [f64; 5] = [
        -5.447609879822406e1,
        1.615858368580409e2,
        -1.556989798598866e2,
        6.680131188771972e1,
        -1.328068155288572e1,
    ];
    const C: [f64; 6] = [
        -7.784894002430293e-3,
        -3.223964580411365e-1,
        -2.400758277161838,
        -2.549732539343734,
        4.374664141464968,
        2.938163982698783,
    ];
    const D: [f64; 4] = [
        7.784695709041462e-3,
        3.224671290700398e-1,
        2.445134137142996,
        3.754408661907416,
    ];
    let pl = 0.02425;
    if p < pl {
        let q = (-2.0 * p.ln()).sqrt();
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    } else if p <= 1.0 - pl {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    } else {
        -normal_quantile(1.0 - p)
    }
}

/// Two-sided critical value of Student's t with `dof` degrees of freedom at significance
/// `alpha` (Cornish–Fisher expansion around the normal quantile; accurate to well under 1%
/// for dof >= 20).
pub fn t_critical(alpha: f64, dof: f64) -> f64 {
    let z = normal_quantile(1.0 - alpha / 2.0);
    let z3 = z * z * z;
    let z5 = z3 * z * z;
    let z7 = z5 * z * z;
    z + (z3 + z) / (4.0 * dof)
        + (5.0 * z5 + 16.0 * z3 + 3.0 * z) / (96.0 * dof * dof)
        + (3.0 * z7 + 19.0 * z5 + 17.0 * z3 - 15.0 * z) / (384.0 * dof * dof * dof)
}

/// ln Γ(x) (Lanczos).
fn ln_gamma(x: f64) -> f64 {
    const G: [f64; 9] = [
        0.99999999999980993,
        676.5203681218851,
        -1259.1392167224028,
        771.32342877765313,
        -176.61502916214059,
        12.507343278686905,
        -0.13857109526572012,
        9.9843695780195716e-6,
        1.5056327351493116e-7,
    ];
    if x < 0.5 {
        return (std::f64::consts::PI / (std::f64::consts::PI * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = G[0];
    let t = x + 7.5;
    for (i, g) in G.iter().enumerate().skip(1) {
        a += g / (x + i as f64);
    }
    0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// Upper regularized incomplete gamma Q(a, x) (Numerical Recipes: series / continued fraction).
fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    if x < a + 1.0 {
        let mut sum = 1.0 / a;
        let mut del = sum;
        let mut ap = a;
        for _ in 0..10000 {
            ap += 1.0;
            del *= x / ap;
            sum += del;
            if del.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        1.0 - sum * (-x + a * x.ln() - ln_gamma(a)).exp()
    } else {
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-15 {
                break;
            }
        }
        (-x + a * x.ln() - ln_gamma(a)).exp() * h
    }
}

/// P(X >= chi2) for a chi-square variable with `dof` degrees of freedom.
pub fn chi2_sf(chi2: f64, dof: f64) -> f64 {
    gamma_q(dof / 2.0, chi2 / 2.0)
}

/// Means over a `side x side` grid of image regions, per channel.
pub fn region_means(img: &footprint::film::Image, side: u32) -> Vec<[f64; 3]> {
    let (bw, bh) = (img.width / side, img.height / side);
    let mut out = vec![[0.0f64; 3]; (side * side) as usize];
    for y in 0..bh * side {
        for x in 0..bw * side {
            let p = img.get(x, y);
            let r = &mut out[((y / bh) * side + x / bw) as usize];
            for c in 0..3 {
                r[c] += p[c] as f64 / (bw * bh) as f64;
            }
        }
    }
    out
}

/// OBJ text of an axis-aligned box with outward faces (vertices numbered from `first`).
pub fn box_obj(lo: [f32; 3], hi: [f32; 3], first: usize, material: &str) -> String {
    let mut s = String::new();
    for i in 0..8 {
        let v = [
            if i & 1 == 0 { lo[0] } else { hi[0] },
            if i & 2 == 0 { lo[1] } else { hi[1] },
            if i & 4 == 0 { lo[2] } else { hi[2] },
        ];
        s += &format!("v {} {} {}\n", v[0], v[1], v[2]);
    }
    s += &format!("usemtl {material}\n");
    // Faces as quads counter-clockwise seen from outside, split in two triangles.
    for q in [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ] {
        let v = |i: usize| q[i] + first;
        s += &format!(
            "f {} {} {}\nf {} {} {}\n",
            v(0),
            v(1),
            v(2),
            v(0),
            v(2),
            v(3)
        );
    }
    s
}

/// Mean and standard error of the mean of `xs`.
pub fn mean_stderr(xs: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    let m = xs.iter().sum::<f64>() / n;
    let var = xs.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0);
    (m, (var / n).sqrt())
}
