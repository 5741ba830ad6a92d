//! Pictures of the particle maps for `footprint maps`: what a map holds, seen from the
//! camera, as a density estimate per pixel on a log scale with a legend.
//!
//! For every pixel the camera ray's first hit asks the map for the `k` nearest particles
//! (the guiding query: facing the camera's side of the surface, near its tangent plane,
//! within the maximum distance); the estimate is the classic one of photon mapping,
//! `Σ w_p / (π r²)` with `r` the distance of the `k`-th particle (the maximum distance when
//! fewer are found): irradiance (W/m²) for the photon map, importance per square metre for
//! the importance map. Values are shown through a viridis-like ramp over the decades from the
//! 1st to the 99.5th percentile (at most five); surfaces without a particle are grey,
//! shaded by their angle to the camera, so the scene stays recognisable. A legend strip
//! below the image gives the caption, the ramp with its decades, and the grey of "none".

use footprint::Rgb;
use footprint::film::Image;
use footprint::guide::particle_map::{MapKind, Neighbor, ParticleMap};
use footprint::math::luminance;
use footprint::scene::Scene;
use glam::Vec2;
use rayon::prelude::*;

/// Particles per density estimate.
pub const PICTURE_K: usize = 32;

/// A map's picture and its scale.
pub struct MapPicture {
    /// The image with the legend strip below it (sRGB values stored linearly, so that
    /// `write_png` at exposure 0 reproduces them).
    pub image: Image,
    /// The ramp's ends, in the estimate's unit (`None`: no particle seen at all).
    pub range: Option<(f32, f32)>,
    /// Share of the pixels that see a surface and find particles there.
    pub covered: f64,
    /// What the values are, e.g. `irradiance (W/m²)`.
    pub quantity: &'static str,
}

/// What a map's estimate measures.
pub fn quantity(kind: MapKind) -> &'static str {
    match kind {
        MapKind::Photons => "irradiance W/m²",
        MapKind::Importons => "importance per m²",
    }
}

/// The picture of `map` seen from `scene`'s camera (see the module doc).
pub fn density_picture(scene: &Scene, map: &ParticleMap, k: usize) -> MapPicture {
    let cam = &scene.camera;
    let (w, h) = (cam.width as usize, cam.height as usize);
    let max_dist = scene.map_max_dist();
    // Per pixel: the estimate (luminance; 0: none found), and the shade of the surface (a
    // negative shade: no surface).
    let px: Vec<(f32, f32)> = (0..h)
        .into_par_iter()
        .flat_map_iter(|y| {
            let mut found: Vec<Neighbor> = Vec::with_capacity(k);
            (0..w)
                .map(|x| {
                    let dir = cam.ray_dir(Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
                    let Some(hit) = scene.intersect(cam.position, dir, f32::INFINITY) else {
                        return (0.0, -1.0);
                    };
                    let n = if hit.ng.dot(dir) > 0.0 {
                        -hit.ng
                    } else {
                        hit.ng
                    };
                    let shade = n.dot(-dir).abs();
                    let got = map.query(
                        hit.p,
                        n,
                        k,
                        max_dist,
                        |nb| luminance(nb.weight).max(0.0),
                        &mut found,
                    );
                    if got == 0 {
                        return (0.0, shade);
                    }
                    let r2 = if got == k {
                        found[k - 1].dist2.max(1e-12)
                    } else {
                        max_dist * max_dist
                    };
                    let sum: f32 = found.iter().map(|nb| luminance(nb.weight)).sum();
                    (sum / (std::f32::consts::PI * r2), shade)
                })
                .collect::<Vec<_>>()
        })
        .collect();
    let mut values: Vec<f32> = px.iter().map(|p| p.0).filter(|v| *v > 0.0).collect();
    let surface = px.iter().filter(|p| p.1 >= 0.0).count();
    let covered = values.len() as f64 / surface.max(1) as f64;
    let range = (!values.is_empty()).then(|| {
        values.sort_by(|a, b| a.total_cmp(b));
        let q = |f: f64| values[((values.len() - 1) as f64 * f).round() as usize];
        // Ends on half decades (1, 3.2, 10, ...), so that both can be labelled.
        let hi = (2.0 * q(0.995).log10()).ceil() / 2.0;
        let lo = ((2.0 * q(0.01).log10()).floor() / 2.0).clamp(hi - 5.0, hi - 1.0);
        (lo, hi)
    });
    let scale = (cam.width / 256).max(1) as usize;
    let legend_h = 34 * scale;
    let mut img = Image::new(cam.width, cam.height + legend_h as u32);
    for (i, &(v, shade)) in px.iter().enumerate() {
        img.pixels[i] = match (v > 0.0, range) {
            (true, Some((lo, hi))) => ramp(((v.log10() - lo) / (hi - lo)).clamp(0.0, 1.0)),
            _ if shade >= 0.0 => grey(shade),
            _ => Rgb::ZERO,
        };
    }
    legend(&mut img, h, scale, quantity(map.kind), range);
    MapPicture {
        image: img,
        range: range.map(|(lo, hi)| (10f32.powf(lo), 10f32.powf(hi))),
        covered,
        quantity: quantity(map.kind),
    }
}

/// The grey of a surface without particles (by its cosine to the camera).
fn grey(shade: f32) -> Rgb {
    srgb(Rgb::splat(0.22 + 0.28 * shade))
}

/// Viridis-like ramp (sRGB control points), `t` in 0..=1.
fn ramp(t: f32) -> Rgb {
    const STOPS: [[f32; 3]; 5] = [
        [68.0, 1.0, 84.0],
        [59.0, 82.0, 139.0],
        [33.0, 145.0, 140.0],
        [94.0, 201.0, 98.0],
        [253.0, 231.0, 37.0],
    ];
    let x = t.clamp(0.0, 1.0) * (STOPS.len() - 1) as f32;
    let i = (x as usize).min(STOPS.len() - 2);
    let f = x - i as f32;
    let c = |j: usize| (1.0 - f) * STOPS[i][j] + f * STOPS[i + 1][j];
    srgb(Rgb::new(c(0), c(1), c(2)) / 255.0)
}

/// An sRGB colour stored as the linear value that `write_png` encodes back to it.
fn srgb(c: Rgb) -> Rgb {
    let f = |v: f32| {
        if v <= 0.04045 {
            v / 12.92
        } else {
            ((v + 0.055) / 1.055).powf(2.4)
        }
    };
    Rgb::new(f(c.x), f(c.y), f(c.z))
}

/// The legend strip below row `top`: the caption and the "none" swatch, the ramp, and
/// its decades.
fn legend(img: &mut Image, top: usize, s: usize, quantity: &str, range: Option<(f32, f32)>) {
    let w = img.width as usize;
    let white = Rgb::ONE;
    let fill = |img: &mut Image, x0: usize, y0: usize, x1: usize, y1: usize, c: Rgb| {
        for y in y0..y1.min(img.height as usize) {
            for x in x0..x1.min(w) {
                img.pixels[y * w + x] = c;
            }
        }
    };
    let caption = format!("{quantity}, log scale");
    text(img, 3 * s, top + 3 * s, s, &caption, white);
    // "none": the grey of surfaces without particles, at the right.
    let none_w = text_width("none", s);
    let sw = 8 * s;
    let nx = w.saturating_sub(none_w + sw + 5 * s);
    fill(img, nx, top + 3 * s, nx + sw, top + 10 * s, grey(0.5));
    text(img, nx + sw + 2 * s, top + 3 * s, s, "none", white);
    let (x0, x1) = (3 * s, w.saturating_sub(3 * s).max(3 * s + 1));
    let (by0, by1) = (top + 13 * s, top + 21 * s);
    let Some((lo, hi)) = range else {
        text(img, x0, by0, s, "no particle seen", white);
        return;
    };
    for x in x0..x1 {
        let c = ramp((x - x0) as f32 / (x1 - x0 - 1).max(1) as f32);
        fill(img, x, by0, x + 1, by1, c);
    }
    // A tick at every half decade; labels at both ends, then at the whole decades, then at
    // the half decades, each where it keeps a gap to the labels already placed.
    let n = ((hi - lo) * 2.0).round() as usize;
    let ticks: Vec<f32> = (0..=n).map(|i| lo + 0.5 * i as f32).collect();
    let xof = |d: f32| (x0 as f32 + (d - lo) / (hi - lo) * (x1 - x0 - 1) as f32).round() as usize;
    let mut placed: Vec<(usize, usize)> = Vec::new();
    let whole = |i: &usize| (ticks[*i] - ticks[*i].floor()) < 0.25;
    let order = [0, n]
        .into_iter()
        .chain((1..n).filter(whole))
        .chain((1..n).filter(|i| !whole(i)));
    for i in order {
        let d = ticks[i];
        let x = xof(d);
        fill(img, x, by1, x + s, by1 + 2 * s, white);
        let label = decade_label(d);
        let lw = text_width(&label, s);
        let lx = x.saturating_sub(lw / 2).min(w.saturating_sub(lw));
        let span = (lx.saturating_sub(4 * s), lx + lw + 4 * s);
        if placed.iter().all(|p| span.1 <= p.0 || span.0 >= p.1) {
            placed.push(span);
            text(img, lx, by1 + 3 * s, s, &label, white);
        }
    }
}

/// `1e-3` for a whole decade, `3.2e-3` for a half one.
fn decade_label(d: f32) -> String {
    let e = d.floor();
    if d - e < 0.25 {
        format!("1e{}", e as i32)
    } else {
        format!("3.2e{}", e as i32)
    }
}

fn text_width(t: &str, s: usize) -> usize {
    t.chars().count() * 6 * s
}

/// Draws `t` with its top-left corner at `(x, y)` in a 5x7 font, `s` pixels per dot.
fn text(img: &mut Image, x: usize, y: usize, s: usize, t: &str, c: Rgb) {
    let (w, h) = (img.width as usize, img.height as usize);
    for (i, ch) in t.chars().enumerate() {
        let Some(rows) = glyph(ch) else { continue };
        for (r, bits) in rows.iter().enumerate() {
            for col in 0..5 {
                if bits & (0b10000 >> col) == 0 {
                    continue;
                }
                for dy in 0..s {
                    for dx in 0..s {
                        let (px, py) = (x + (i * 6 + col) * s + dx, y + r * s + dy);
                        if px < w && py < h {
                            img.pixels[py * w + px] = c;
                        }
                    }
                }
            }
        }
    }
}

/// A 5x7 glyph (rows top to bottom, bit 4 the leftmost dot); `None` draws a space.
fn glyph(c: char) -> Option<[u8; 7]> {
    FONT.iter().find(|(g, _)| *g == c).map(|(_, rows)| *rows)
}

const FONT: &[(char, [u8; 7])] = &[
    (
        '0',
        [
            0b01110, 0b10001, 0b10011, 0b10101, 0b11001, 0b10001, 0b01110,
        ],
    ),
    (
        '1',
        [
            0b00100, 0b01100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110,
        ],
    ),
    (
        '2',
        [
            0b01110, 0b10001, 0b00001, 0b00010, 0b00100, 0b01000, 0b11111,
        ],
    ),
    (
        '3',
        [
            0b11111, 0b00010, 0b00100, 0b00010, 0b00001, 0b10001, 0b01110,
        ],
    ),
    (
        '4',
        [
            0b00010, 0b00110, 0b01010, 0b10010, 0b11111, 0b00010, 0b00010,
        ],
    ),
    (
        '5',
        [
            0b11111, 0b10000, 0b11110, 0b00001, 0b00001, 0b10001, 0b01110,
        ],
    ),
    (
        '6',
        [
            0b00110, 0b01000, 0b10000, 0b11110, 0b10001, 0b10001, 0b01110,
        ],
    ),
    (
        '7',
        [
            0b11111, 0b00001, 0b00010, 0b00100, 0b01000, 0b01000, 0b01000,
        ],
    ),
    (
        '8',
        [
            0b01110, 0b10001, 0b10001, 0b01110, 0b10001, 0b10001, 0b01110,
        ],
    ),
    (
        '9',
        [
            0b01110, 0b10001, 0b10001, 0b01111, 0b00001, 0b00010, 0b01100,
        ],
    ),
    (
        'a',
        [
            0b00000, 0b00000, 0b01110, 0b00001, 0b01111, 0b10001, 0b01111,
        ],
    ),
    (
        'b',
        [
            0b10000, 0b10000, 0b10110, 0b11001, 0b10001, 0b10001, 0b11110,
        ],
    ),
    (
        'c',
        [
            0b00000, 0b00000, 0b01110, 0b10000, 0b10000, 0b10001, 0b01110,
        ],
    ),
    (
        'd',
        [
            0b00001, 0b00001, 0b01101, 0b10011, 0b10001, 0b10001, 0b01111,
        ],
    ),
    (
        'e',
        [
            0b00000, 0b00000, 0b01110, 0b10001, 0b11111, 0b10000, 0b01110,
        ],
    ),
    (
        'f',
        [
            0b00110, 0b01001, 0b01000, 0b11100, 0b01000, 0b01000, 0b01000,
        ],
    ),
    (
        'g',
        [
            0b00000, 0b01111, 0b10001, 0b10001, 0b01111, 0b00001, 0b01110,
        ],
    ),
    (
        'h',
        [
            0b10000, 0b10000, 0b10110, 0b11001, 0b10001, 0b10001, 0b10001,
        ],
    ),
    (
        'i',
        [
            0b00100, 0b00000, 0b01100, 0b00100, 0b00100, 0b00100, 0b01110,
        ],
    ),
    (
        'j',
        [
            0b00010, 0b00000, 0b00110, 0b00010, 0b00010, 0b10010, 0b01100,
        ],
    ),
    (
        'k',
        [
            0b10000, 0b10000, 0b10010, 0b10100, 0b11000, 0b10100, 0b10010,
        ],
    ),
    (
        'l',
        [
            0b01100, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110,
        ],
    ),
    (
        'm',
        [
            0b00000, 0b00000, 0b11010, 0b10101, 0b10101, 0b10001, 0b10001,
        ],
    ),
    (
        'n',
        [
            0b00000, 0b00000, 0b10110, 0b11001, 0b10001, 0b10001, 0b10001,
        ],
    ),
    (
        'o',
        [
            0b00000, 0b00000, 0b01110, 0b10001, 0b10001, 0b10001, 0b01110,
        ],
    ),
    (
        'p',
        [
            0b00000, 0b00000, 0b11110, 0b10001, 0b11110, 0b10000, 0b10000,
        ],
    ),
    (
        'q',
        [
            0b00000, 0b00000, 0b01101, 0b10011, 0b01111, 0b00001, 0b00001,
        ],
    ),
    (
        'r',
        [
            0b00000, 0b00000, 0b10110, 0b11001, 0b10000, 0b10000, 0b10000,
        ],
    ),
    (
        's',
        [
            0b00000, 0b00000, 0b01110, 0b10000, 0b01110, 0b00001, 0b11110,
        ],
    ),
    (
        't',
        [
            0b01000, 0b01000, 0b11100, 0b01000, 0b01000, 0b01001, 0b00110,
        ],
    ),
    (
        'u',
        [
            0b00000, 0b00000, 0b10001, 0b10001, 0b10001, 0b10011, 0b01101,
        ],
    ),
    (
        'v',
        [
            0b00000, 0b00000, 0b10001, 0b10001, 0b10001, 0b01010, 0b00100,
        ],
    ),
    (
        'w',
        [
            0b00000, 0b00000, 0b10001, 0b10001, 0b10101, 0b10101, 0b01010,
        ],
    ),
    (
        'x',
        [
            0b00000, 0b00000, 0b10001, 0b01010, 0b00100, 0b01010, 0b10001,
        ],
    ),
    (
        'y',
        [
            0b00000, 0b00000, 0b10001, 0b10001, 0b01111, 0b00001, 0b01110,
        ],
    ),
    (
        'z',
        [
            0b00000, 0b00000, 0b11111, 0b00010, 0b00100, 0b01000, 0b11111,
        ],
    ),
    (
        'W',
        [
            0b10001, 0b10001, 0b10001, 0b10101, 0b10101, 0b10101, 0b01010,
        ],
    ),
    (
        '-',
        [
            0b00000, 0b00000, 0b00000, 0b01110, 0b00000, 0b00000, 0b00000,
        ],
    ),
    (
        '+',
        [
            0b00000, 0b00100, 0b00100, 0b11111, 0b00100, 0b00100, 0b00000,
        ],
    ),
    (
        '.',
        [
            0b00000, 0b00000, 0b00000, 0b00000, 0b00000, 0b01100, 0b01100,
        ],
    ),
    (
        ',',
        [
            0b00000, 0b00000, 0b00000, 0b00000, 0b01100, 0b00100, 0b01000,
        ],
    ),
    (
        ':',
        [
            0b00000, 0b01100, 0b01100, 0b00000, 0b01100, 0b01100, 0b00000,
        ],
    ),
    (
        '/',
        [
            0b00000, 0b00001, 0b00010, 0b00100, 0b01000, 0b10000, 0b00000,
        ],
    ),
    (
        '(',
        [
            0b00100, 0b01000, 0b10000, 0b10000, 0b10000, 0b01000, 0b00100,
        ],
    ),
    (
        ')',
        [
            0b00100, 0b00010, 0b00001, 0b00001, 0b00001, 0b00010, 0b00100,
        ],
    ),
    (
        '²',
        [
            0b01100, 0b00010, 0b00100, 0b01110, 0b00000, 0b00000, 0b00000,
        ],
    ),
];
