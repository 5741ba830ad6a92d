//! The configurations every generic BSDF test runs: diffuse, Blinn-Phong and the Mitsuba
//! kinds, from several incident directions, flat and under tilted shading normals.

use crate::principled::mitsuba_principled;
use crate::{MI_ETA, MI_K, MI_KD, MI_KS, blend_of, dir, flat_bsdf, glossy, material};
use footprint::Rgb;
use footprint::bsdf::material::{Material, MaterialKind};
use footprint::bsdf::microfacet::Microfacet;
use footprint::bsdf::{Bsdf, Lobes, TransportMode};
use glam::Vec3;

pub struct Config {
    pub name: String,
    pub bsdf: Bsdf,
    pub wo: Vec3,
    pub mode: TransportMode,
    /// Cap around the mirror direction for narrow lobes, or the whole sphere.
    pub cap: Option<f64>,
    /// The cap's axis when it is not the mirror direction.
    pub axis: Option<Vec3>,
}

pub fn configs() -> Vec<Config> {
    let flat = |l: Lobes| Bsdf::new(l, Vec3::Z, Vec3::Z);
    // A shading normal tilted 20 degrees from the geometric one.
    let tilted = |l: Lobes| Bsdf::new(l, dir(20.0, 90.0), Vec3::Z);
    let mut v = Vec::new();
    for (i, wo) in [dir(0.0, 0.0), dir(45.0, 30.0), dir(85.0, 200.0)]
        .into_iter()
        .enumerate()
    {
        v.push(Config {
            name: format!("diffuse wo#{i}"),
            bsdf: flat(Lobes::Diffuse {
                kd: Rgb::splat(0.7),
            }),
            wo,
            mode: TransportMode::Radiance,
            cap: None,
            axis: None,
        });
    }
    v.push(Config {
        name: "diffuse below".into(),
        bsdf: flat(Lobes::Diffuse {
            kd: Rgb::splat(0.7),
        }),
        wo: -dir(30.0, 10.0),
        mode: TransportMode::Radiance,
        cap: None,
        axis: None,
    });
    for n in [1.0, 10.0, 100.0] {
        for (i, wo) in [dir(10.0, 0.0), dir(60.0, 45.0), dir(88.0, 100.0)]
            .into_iter()
            .enumerate()
        {
            v.push(Config {
                name: format!("glossy n={n} wo#{i}"),
                bsdf: flat(glossy(0.3, 0.6, n)),
                wo,
                mode: TransportMode::Radiance,
                cap: None,
                axis: None,
            });
        }
    }
    for n in [1000.0f32, 10000.0] {
        let cap = 6.0 / n.sqrt() as f64;
        for (i, wo) in [dir(5.0, 0.0), dir(50.0, 45.0)].into_iter().enumerate() {
            v.push(Config {
                name: format!("pure glossy n={n} wo#{i}"),
                bsdf: flat(glossy(0.0, 0.9, n)),
                wo,
                mode: TransportMode::Radiance,
                cap: Some(cap),
                axis: None,
            });
        }
    }
    v.push(Config {
        name: "glossy n=20 tilted normal, importance".into(),
        bsdf: tilted(glossy(0.4, 0.5, 20.0)),
        wo: dir(40.0, 250.0),
        mode: TransportMode::Importance,
        cap: None,
        axis: None,
    });
    v.push(Config {
        name: "diffuse tilted normal, radiance".into(),
        bsdf: tilted(Lobes::Diffuse {
            kd: Rgb::splat(0.5),
        }),
        wo: dir(70.0, 90.0),
        mode: TransportMode::Radiance,
        cap: None,
        axis: None,
    });
    v.extend(mitsuba_configs());
    v.extend(blend_configs());
    v
}

/// The incident directions of the Mitsuba kinds' configurations: near normal, oblique and
/// grazing (cos θ = 0.05).
fn incident_dirs() -> [Vec3; 3] {
    [
        dir(10.0, 30.0),
        dir(60.0, 45.0),
        dir(0.05f32.acos().to_degrees(), 200.0),
    ]
}

/// Rough conductors (GGX and Beckmann, α 0.1, 0.3, 0.7, and anisotropic ones), rough and
/// smooth plastics, each from
/// three incident directions, alternately two-sided seen from below and one-sided seen from
/// above; one-sided ones seen from below (they scatter nothing) and a tilted shading normal.
fn mitsuba_configs() -> Vec<Config> {
    let mut v = Vec::new();
    let mut push = |name: String, m: Material, wo: Vec3, cap: Option<f64>, i: usize| {
        let two_sided = i.is_multiple_of(2);
        let m = Material { two_sided, ..m };
        // Two-sided ones are seen from below, where only the flip makes them reflect.
        let wo = if two_sided {
            Vec3::new(wo.x, wo.y, -wo.z)
        } else {
            wo
        };
        v.push(Config {
            name: format!("{name} two_sided={two_sided}"),
            bsdf: flat_bsdf(&m),
            wo,
            mode: TransportMode::Radiance,
            cap,
            axis: None,
        });
    };
    let mut i = 0;
    for kind in [Microfacet::Ggx, Microfacet::Beckmann] {
        for alpha in [0.1f32, 0.3, 0.7] {
            for (j, wo) in incident_dirs().into_iter().enumerate() {
                let m = mi_rough_conductor(kind, alpha);
                // A finer grid about the mirror direction for the narrow lobe.
                let cap = (alpha < 0.2).then_some(1.0);
                push(
                    format!("roughconductor {kind:?} α={alpha} wo#{j}"),
                    m,
                    wo,
                    cap,
                    i,
                );
                i += 1;
            }
        }
    }
    // Anisotropic rough conductors: α_u along the local x axis, α_v along y, the narrow
    // direction along either axis, from incident azimuths off the axes.
    for (kind, alpha_u, alpha_v) in [
        (Microfacet::Ggx, 0.08f32, 0.4f32),
        (Microfacet::Ggx, 0.6, 0.2),
        (Microfacet::Beckmann, 0.3, 0.08),
        (Microfacet::Beckmann, 0.15, 0.6),
    ] {
        for (j, wo) in incident_dirs().into_iter().enumerate() {
            let m = Material {
                microfacet: kind,
                alpha: alpha_u,
                alpha_v: Some(alpha_v),
                eta: MI_ETA,
                k: MI_K,
                ks: MI_KS,
                ..material(MaterialKind::RoughConductor)
            };
            // A finer grid about the mirror direction where a roughness is narrow.
            let cap = (alpha_u.min(alpha_v) < 0.1).then_some(1.2);
            push(
                format!("roughconductor {kind:?} α_u={alpha_u} α_v={alpha_v} wo#{j}"),
                m,
                wo,
                cap,
                i,
            );
            i += 1;
        }
    }
    for (kind, alpha, ni, kd, ks) in [
        (Microfacet::Ggx, 0.2f32, 1.5f32, 0.5f32, 1.0f32),
        (Microfacet::Beckmann, 0.5, 1.8, 0.3, 0.6),
    ] {
        for (j, wo) in incident_dirs().into_iter().enumerate() {
            let m = Material {
                microfacet: kind,
                alpha,
                ni,
                kd: Rgb::splat(kd),
                ks: Rgb::splat(ks),
                ..material(MaterialKind::RoughPlastic)
            }
            .prepared();
            push(
                format!("roughplastic {kind:?} α={alpha} wo#{j}"),
                m,
                wo,
                None,
                i,
            );
            i += 1;
        }
    }
    for (j, wo) in incident_dirs().into_iter().enumerate() {
        let m = Material {
            ni: 1.5,
            kd: MI_KD,
            ks: Rgb::ONE,
            ..material(MaterialKind::Plastic)
        };
        push(format!("plastic wo#{j}"), m, wo, None, i);
        i += 1;
    }
    for kind in [MaterialKind::RoughConductor, MaterialKind::RoughPlastic] {
        v.push(Config {
            name: format!("{kind:?} one-sided seen from below"),
            bsdf: flat_bsdf(&Material {
                alpha: 0.3,
                kd: Rgb::splat(0.5),
                ks: Rgb::ONE,
                ..material(kind)
            }),
            wo: -dir(30.0, 10.0),
            mode: TransportMode::Radiance,
            cap: None,
            axis: None,
        });
    }
    v.push(tilted_importance(
        "roughconductor Beckmann α_u=0.4 α_v=0.12",
        &Material {
            microfacet: Microfacet::Beckmann,
            alpha: 0.4,
            alpha_v: Some(0.12),
            ks: Rgb::ONE,
            eta: MI_ETA,
            k: MI_K,
            ..material(MaterialKind::RoughConductor)
        },
    ));
    v.push(tilted_importance(
        "roughconductor GGX α=0.3",
        &Material {
            alpha: 0.3,
            ks: Rgb::ONE,
            eta: MI_ETA,
            k: MI_K,
            ..material(MaterialKind::RoughConductor)
        },
    ));
    v
}

/// `m` under a shading normal tilted 20° from the geometric one, in importance mode (where
/// the adjoint correction applies).
fn tilted_importance(name: &str, m: &Material) -> Config {
    Config {
        name: format!("{name} tilted normal, importance"),
        bsdf: Bsdf::new(Lobes::new(m, m.kd, m.ks), dir(20.0, 90.0), Vec3::Z),
        wo: dir(40.0, 250.0),
        mode: TransportMode::Importance,
        cap: None,
        axis: None,
    }
}

/// The principled parameter sets (`scripts/mitsuba_bsdf_values.py principled`): those that
/// reflect only from near-normal, oblique and grazing incidence, alternately one-sided seen
/// from above and two-sided seen from below; the smooth one (roughness 0.05, α 0.0025) on a
/// fine grid about the mirror direction; those that transmit entered from outside, left from
/// inside and from beyond the critical angle, alternately in radiance and importance mode
/// (the narrow glass, α 0.01, on fine grids about the reflection and the refraction); and
/// a tilted shading normal in importance mode.
pub fn principled_configs() -> Vec<Config> {
    let mut v = Vec::new();
    let mut i = 0;
    for name in [
        "default",
        "dielectric_sheen",
        "metallic_anisotropic",
        "clearcoat",
        "rough_sheen_flat",
        "rates",
    ] {
        for (j, wo) in incident_dirs().into_iter().enumerate() {
            let two_sided = i % 2 == 1;
            i += 1;
            let m = Material {
                two_sided,
                ..mitsuba_principled(name)
            };
            let bsdf = flat_bsdf(&m);
            // A finer grid about the mirror direction where the main lobe is narrower than the
            // sphere grid's cells (0.08 rad) can resolve: its masses would be off by percents.
            let narrow =
                matches!(bsdf.lobes, Lobes::Principled(p) if p.alpha_u.max(p.alpha_v) < 0.08);
            v.push(Config {
                name: format!("principled {name} wo#{j} two_sided={two_sided}"),
                bsdf,
                wo: if two_sided {
                    Vec3::new(wo.x, wo.y, -wo.z)
                } else {
                    wo
                },
                mode: TransportMode::Radiance,
                cap: narrow.then_some(0.5),
                axis: None,
            });
        }
    }
    let smooth = mitsuba_principled("smooth");
    let alpha = smooth.principled.roughness.value.powi(2) as f64;
    for (j, wo) in [dir(20.0, 30.0), dir(70.0, 160.0)].into_iter().enumerate() {
        v.push(Config {
            name: format!("principled smooth wo#{j} (mirror cap)"),
            bsdf: flat_bsdf(&smooth),
            wo,
            mode: TransportMode::Radiance,
            cap: Some(12.0 * alpha),
            axis: None,
        });
    }
    for name in [
        "spec_trans",
        "glass",
        "glass_rough_specular",
        "spec_trans_anisotropic",
    ] {
        let m = mitsuba_principled(name);
        let alpha = m.principled.roughness.value.powi(2) as f64;
        let cap = (alpha <= 0.05).then_some(12.0 * alpha);
        let name = format!("principled {name}");
        v.extend(both_sides(
            &name,
            flat_bsdf(&m),
            m.principled.eta,
            cap,
            &mut i,
        ));
    }
    v.push(tilted_importance(
        "principled spec_trans",
        &mitsuba_principled("spec_trans"),
    ));
    v.push(tilted_importance(
        "principled clearcoat",
        &mitsuba_principled("clearcoat"),
    ));
    v
}

/// Relative index of the rough dielectric configurations (interior over exterior).
pub const ROUGH_GLASS_ETA: f32 = 1.5;

/// A rough dielectric of distribution `kind` and roughness `alpha` with constant reflection
/// and transmission factors `ks` and `kt` (per crossing).
pub fn rough_glass(kind: Microfacet, alpha: f32, ks: Rgb, kt: Rgb) -> Material {
    Material {
        microfacet: kind,
        alpha,
        ni: ROUGH_GLASS_ETA,
        ks,
        tf: kt * kt,
        ..material(MaterialKind::RoughGlass)
    }
}

/// The local mirror and refraction directions of `wo` through a smooth interface of relative
/// index `eta` (interior over exterior); `None` for the refraction beyond the critical angle.
pub fn smooth_directions(wo: Vec3, eta: f32) -> (Vec3, Option<Vec3>) {
    let mirror = Vec3::new(-wo.x, -wo.y, wo.z);
    let eta = if wo.z > 0.0 { eta } else { 1.0 / eta };
    let sin2_t = (1.0 - wo.z * wo.z) / (eta * eta);
    let refracted = (sin2_t < 1.0).then(|| {
        let cos_t = (1.0 - sin2_t).sqrt() * -wo.z.signum();
        Vec3::new(-wo.x / eta, -wo.y / eta, cos_t).normalize()
    });
    (mirror, refracted)
}

/// The configurations of `bsdf`, which scatters to both sides: entered from outside at 30°,
/// left from inside at 20° and from beyond the smooth interface's critical angle (55°
/// inside), alternately in radiance and importance mode (`i` counts the configurations
/// made). Narrow lobes (`cap`, about their angular size in radians) get two configurations,
/// a fine grid about the mirror direction and one about the refraction through the interface
/// of index `eta` (the other lobe falls in the harness's extra bin, with its probability as
/// expectation); the others the whole sphere.
fn both_sides(name: &str, bsdf: Bsdf, eta: f32, cap: Option<f64>, i: &mut usize) -> Vec<Config> {
    let mut v = Vec::new();
    for (side, wo) in [
        ("entering", dir(30.0, 20.0)),
        ("leaving", dir(160.0, 70.0)),
        ("leaving beyond the critical angle", dir(125.0, 300.0)),
    ] {
        let mode = if i.is_multiple_of(2) {
            TransportMode::Radiance
        } else {
            TransportMode::Importance
        };
        *i += 1;
        let name = format!("{name} {side} {mode:?}");
        let Some(cap) = cap else {
            v.push(Config {
                name,
                bsdf,
                wo,
                mode,
                cap: None,
                axis: None,
            });
            continue;
        };
        let (mirror, refracted) = smooth_directions(wo, eta);
        // Beyond the critical angle the refracted light leaves about the horizon.
        let refracted = refracted.unwrap_or(Vec3::new(-wo.x, -wo.y, -wo.z).normalize());
        for (lobe, axis) in [("reflection", mirror), ("refraction", refracted)] {
            v.push(Config {
                name: format!("{name} ({lobe} cap)"),
                bsdf,
                wo,
                mode,
                cap: Some(cap),
                axis: Some(axis),
            });
        }
    }
    v
}

/// Rough dielectrics (GGX and Beckmann, α 0.01, 0.1, 0.5) from both sides
/// ([`both_sides`]), and a tilted shading normal.
pub fn rough_glass_configs() -> Vec<Config> {
    let mut v = Vec::new();
    let (ks, kt) = (Rgb::new(0.9, 0.8, 1.0), Rgb::new(0.7, 0.9, 0.8));
    let mut i = 0;
    for kind in [Microfacet::Ggx, Microfacet::Beckmann] {
        for alpha in [0.01f32, 0.1, 0.5] {
            let bsdf = flat_bsdf(&rough_glass(kind, alpha, ks, kt));
            // About the lobes' width: Beckmann's have no tails.
            let widths = if kind == Microfacet::Ggx { 12.0 } else { 6.0 };
            let cap = (alpha < 0.5).then(|| (widths * alpha as f64).min(1.2));
            let name = format!("roughdielectric {kind:?} α={alpha}");
            v.extend(both_sides(&name, bsdf, ROUGH_GLASS_ETA, cap, &mut i));
        }
    }
    // Anisotropic rough dielectrics, entering and leaving, from azimuths off the axes.
    for (kind, alpha_u, alpha_v) in [
        (Microfacet::Ggx, 0.2f32, 0.6f32),
        (Microfacet::Beckmann, 0.5, 0.2),
    ] {
        for (side, wo) in [
            ("entering", dir(40.0, 60.0)),
            ("leaving", dir(150.0, 230.0)),
        ] {
            let m = Material {
                alpha_v: Some(alpha_v),
                ..rough_glass(kind, alpha_u, ks, kt)
            };
            let mode = if i % 2 == 0 {
                TransportMode::Radiance
            } else {
                TransportMode::Importance
            };
            i += 1;
            v.push(Config {
                name: format!(
                    "roughdielectric {kind:?} α_u={alpha_u} α_v={alpha_v} {side} {mode:?}"
                ),
                bsdf: flat_bsdf(&m),
                wo,
                mode,
                cap: None,
                axis: None,
            });
        }
    }
    v.push(tilted_importance(
        "roughdielectric GGX α=0.3",
        &rough_glass(Microfacet::Ggx, 0.3, ks, kt),
    ));
    v.push(tilted_importance(
        "roughdielectric GGX α_u=0.15 α_v=0.45",
        &Material {
            alpha_v: Some(0.45),
            ..rough_glass(Microfacet::Ggx, 0.15, ks, kt)
        },
    ));
    v
}

/// Blends (`blendbsdf`): a Lambertian and a GGX rough conductor; a one-sided Blinn lobe and a
/// two-sided Lambertian seen from below (only the second reflects there); a smooth plastic
/// (a delta coat) and a Beckmann rough conductor in importance mode; each from three
/// incident directions.
fn blend_configs() -> Vec<Config> {
    let conductor = mi_rough_conductor;
    let diffuse = |kd: f32, two_sided| Material {
        kd: Rgb::splat(kd),
        two_sided,
        ..material(MaterialKind::Diffuse)
    };
    let plastic = Material {
        ni: 1.5,
        kd: MI_KD,
        ks: MI_KS,
        ..material(MaterialKind::Plastic)
    };
    let glossy = Material {
        kd: Rgb::splat(0.2),
        ks: Rgb::splat(0.6),
        ns: 20.0,
        ..material(MaterialKind::Glossy)
    };
    let cases = [
        (
            "diffuse + roughconductor GGX α=0.4, w=0.3",
            blend_of(diffuse(0.7, false), conductor(Microfacet::Ggx, 0.4), 0.3),
            false,
            TransportMode::Radiance,
        ),
        (
            "one-sided glossy + two-sided diffuse, w=0.6, from below",
            blend_of(glossy, diffuse(0.8, true), 0.6),
            true,
            TransportMode::Radiance,
        ),
        (
            "plastic + roughconductor Beckmann α=0.3, w=0.5, importance",
            blend_of(plastic, conductor(Microfacet::Beckmann, 0.3), 0.5),
            false,
            TransportMode::Importance,
        ),
    ];
    let mut v = Vec::new();
    for (name, m, below, mode) in cases {
        for (j, wo) in incident_dirs().into_iter().enumerate() {
            v.push(Config {
                name: format!("blend {name} wo#{j}"),
                bsdf: flat_bsdf(&m),
                wo: if below { -wo } else { wo },
                mode,
                cap: None,
                axis: None,
            });
        }
    }
    v
}

/// A rough conductor of the Mitsuba test parameters (`MI_ETA`, `MI_K`, `MI_KS`).
fn mi_rough_conductor(microfacet: Microfacet, alpha: f32) -> Material {
    Material {
        microfacet,
        alpha,
        eta: MI_ETA,
        k: MI_K,
        ks: MI_KS,
        ..material(MaterialKind::RoughConductor)
    }
}
