//! One schema for the settings a user sets by name: the `[guide]` and `[maps]` tables of
//! a scene file ([`GuideParams`], [`MapSettings`], read by serde under these keys), the
//! command-line flags and their help, `compare --sweep`, the run's EXR header, and the keys
//! that saved maps and shards are matched by. A new setting is a field with its serde key
//! and one row of [`SETTINGS`]; the test below fails when the two disagree.
//!
//! Values travel as text through the structs' serde form: [`set`] reads `"on"`, `"0.5"` or
//! `"solid-angle"` into the field named by the key, [`get`] writes it back, and
//! [`describe`] lists `key=value` words.

use crate::settings::{GuideParams, MapSettings, SettingError};
use serde::Serialize;
use serde::de::DeserializeOwned;

/// The scene file's table a setting lives in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Table {
    Guide,
    Maps,
}

impl Table {
    pub fn name(self) -> &'static str {
        match self {
            Table::Guide => "guide",
            Table::Maps => "maps",
        }
    }
}

/// What a setting's value is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A whole number.
    Count,
    /// A real number.
    Number,
    /// On or off (`on`/`off`, `true`/`false`, `1`/`0`).
    Switch,
    /// One of these names.
    Name(&'static [&'static str]),
    /// A size in bytes, with a unit (`512M`, `4G`; [`crate::memory::parse_size`]).
    Size,
}

/// Whether the particle passes depend on a setting (saved maps are refused for a render
/// that differs in it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Passes {
    /// The passes depend on it.
    Always,
    /// With several map rounds only: later rounds are guided by the earlier rounds' maps.
    WithRounds,
    /// They do not.
    Never,
}

/// One setting.
#[derive(Clone, Copy, Debug)]
pub struct Setting {
    pub table: Table,
    /// The key in the scene file's table (also its name in sweeps and headers).
    pub key: &'static str,
    /// The command-line flag, without its dashes.
    pub flag: &'static str,
    pub kind: Kind,
    pub passes: Passes,
    /// One line of help (the default is appended where it is shown).
    pub help: &'static str,
}

const fn s(
    table: Table,
    key: &'static str,
    flag: &'static str,
    kind: Kind,
    passes: Passes,
    help: &'static str,
) -> Setting {
    Setting {
        table,
        key,
        flag,
        kind,
        passes,
        help,
    }
}

use Kind::*;
use Passes::*;
use Table::*;

/// Every setting of the `[guide]` and `[maps]` tables.
pub const SETTINGS: &[Setting] = &[
    s(
        Guide,
        "k_p",
        "k-p",
        Count,
        WithRounds,
        "Particles per query, k_p (paper §3)",
    ),
    s(
        Guide,
        "k_g",
        "k-g",
        Count,
        WithRounds,
        "Side of the footprint density grid (k_g = side²)",
    ),
    s(
        Guide,
        "k_r",
        "k-r",
        Number,
        WithRounds,
        "Footprint radius scale k_r (paper eq. 7)",
    ),
    s(
        Guide,
        "p_bsdf",
        "p-bsdf",
        Number,
        WithRounds,
        "Probability of sampling the BSDF where guiding",
    ),
    s(
        Guide,
        "learn_p_bsdf",
        "learn-p-bsdf",
        Switch,
        Never,
        "Camera paths (pt, combined) and light paths (lt, combined) learn the probability of sampling the BSDF per region of their guide cache from earlier passes, a region short of its own records taking the cache's pooled choice (at most 0.9) (on), or keep --p-bsdf everywhere (off)",
    ),
    s(
        Guide,
        "guided_rr",
        "guided-rr",
        Switch,
        Never,
        "Russian roulette reads the guide cache's estimate of what a path would still gather against that estimate at its first vertex (on), or its throughput alone (off); guided paths only",
    ),
    s(
        Guide,
        "guided_split",
        "guided-split",
        Count,
        Never,
        "Guided splitting (pt, lt; not the combined image): a guided path expected to gather r > 1 times what its first estimated vertex did is split into r branches (in expectation), at most this many; 1 never splits; needs --guided-rr on",
    ),
    s(
        Guide,
        "relative_importance",
        "relative-importance",
        Switch,
        Always,
        "The view pass weighs each importon path by m / (L + 0.1 m), L its pixel's luminance in a short unguided pre-render and m the image's mean: light paths are guided where the relative error is (on), or by the camera's importance alone (off)",
    ),
    s(
        Guide,
        "radius_rule",
        "radius-rule",
        Name(&["solid-angle", "literal"]),
        WithRounds,
        "Footprint radius rule: the cap's solid angle is k_r over the directional density (solid-angle), or eq. 7 as printed (literal)",
    ),
    s(
        Guide,
        "grid",
        "grid",
        Count,
        WithRounds,
        "Side of the classic sampler's grid per hemisphere (Jensen 1995)",
    ),
    s(
        Guide,
        "cache",
        "guide-cache",
        Switch,
        Never,
        "Prepare guide distributions once per region (on) or at every scattering event as the paper does (off)",
    ),
    s(
        Guide,
        "region_particles",
        "region-particles",
        Count,
        WithRounds,
        "Most particles per cached region",
    ),
    s(
        Guide,
        "region_seeds",
        "region-seeds",
        Count,
        WithRounds,
        "Most scattering points of the other pass per cached region",
    ),
    s(
        Guide,
        "min_depth",
        "min-depth",
        Count,
        WithRounds,
        "Leave particles that arrived in fewer segments out of the guiding maps (2: no direct light in the photon map, no camera directions in the importance map; 1: keep all)",
    ),
    s(
        Guide,
        "guided_mis",
        "guided-mis",
        Switch,
        Never,
        "The combined image's MIS weights from the guided samplers' densities (on) or the unguided ones (off)",
    ),
    s(
        Guide,
        "mis_table",
        "mis-table",
        Count,
        Never,
        "Side of the per-hemisphere table of each cached region's density that the guided MIS weights read when footprints are sampled from their caps (--raster 0); 0 reads the exact density",
    ),
    s(
        Guide,
        "raster",
        "raster",
        Count,
        Never,
        "Side of the equal-area grid per hemisphere on which each cached region's footprint mixture is rasterised for sampling; 0 samples the caps, as the paper does",
    ),
    s(
        Maps,
        "photons",
        "photons",
        Count,
        Always,
        "Photon paths shot by the light pass (with --time, more when the map grows: --map-grow)",
    ),
    s(
        Maps,
        "importons",
        "importons",
        Count,
        Always,
        "Importon paths shot by the view pass (the first quarter of them seed the photon map's cache; path tracing shoots only those)",
    ),
    s(
        Maps,
        "max_dist",
        "max-dist",
        Number,
        Never,
        "Maximum distance of a particle from a query point (default: 5% of the scene's bounding-box diagonal)",
    ),
    s(
        Maps,
        "soft_glossy_max",
        "soft-glossy-max",
        Number,
        Always,
        "Largest Blinn exponent counted as soft glossy (particles stored)",
    ),
    s(
        Maps,
        "rounds",
        "map-rounds",
        Count,
        Always,
        "Rounds of passes that refine each other: each round's light pass is guided by the round before's importance map, its view pass by the photon map; each round shoots twice the paths of the one before, the last the full counts",
    ),
    s(
        Maps,
        "grow",
        "map-grow",
        Switch,
        Never,
        "With --time: when the photon map's guide cache is sparse (under 80% of its regions guide, or their particles fill under 60% of region_particles), unless most of its regions guide and most of the light arriving in them is direct, the light pass shoots 2, 4, 8 or 16 times its paths, as many as fit 15% of the budget (on), or keeps its count (off); not with several map rounds or --guide-cache off",
    ),
    s(
        Maps,
        "max_memory",
        "max-memory",
        Size,
        Never,
        "Memory the particle maps and guide caches may take (512M, 4G; default: half the machine's memory): past it each pass keeps an even share of its particles, their weights raised to match, and the run says so",
    ),
];

/// The setting whose key or flag (dashes or underscores) is `name`.
pub fn find(name: &str) -> Option<&'static Setting> {
    let dashed = name.replace('_', "-");
    SETTINGS.iter().find(|s| s.key == name || s.flag == dashed)
}

/// The names [`find`] accepts, for error messages.
pub fn names() -> String {
    SETTINGS
        .iter()
        .map(|s| s.key)
        .collect::<Vec<_>>()
        .join(", ")
}

/// A struct of settings as its serde table.
fn table<T: Serialize>(settings: &T) -> toml::Table {
    toml::Table::try_from(settings).expect("settings serialise to a table")
}

/// The settings as their serde tables.
fn tables(guide: &GuideParams, maps: &MapSettings) -> (toml::Table, toml::Table) {
    (table(guide), table(maps))
}

/// `setting`'s value as text (`on`/`off` for switches; `auto` for an unset distance).
pub fn get(guide: &GuideParams, maps: &MapSettings, setting: &Setting) -> String {
    let (g, m) = tables(guide, maps);
    let table = match setting.table {
        Guide => &g,
        Maps => &m,
    };
    match table.get(setting.key) {
        Some(toml::Value::Boolean(b)) => if *b { "on" } else { "off" }.to_string(),
        Some(toml::Value::String(s)) => s.clone(),
        // Every real-valued setting is an `f32`: shown as one (0.1, not 0.10000000149).
        Some(toml::Value::Float(x)) => (*x as f32).to_string(),
        Some(v) => v.to_string(),
        None => "auto".to_string(),
    }
}

/// `setting`'s value from text, as the kind of value it is.
fn parse(setting: &Setting, value: &str) -> Result<toml::Value, String> {
    let v = value.trim();
    match setting.kind {
        Count => v
            .parse::<i64>()
            .ok()
            .filter(|n| *n >= 0)
            .map(toml::Value::Integer)
            .ok_or_else(|| format!("expects a whole number, got '{v}'")),
        Number => v
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .map(toml::Value::Float)
            .ok_or_else(|| format!("expects a finite number, got '{v}'")),
        Switch => match v {
            "on" | "true" | "1" => Ok(toml::Value::Boolean(true)),
            "off" | "false" | "0" => Ok(toml::Value::Boolean(false)),
            _ => Err(format!("expects on or off, got '{v}'")),
        },
        Name(names) => names
            .iter()
            .find(|n| **n == v)
            .map(|n| toml::Value::String(n.to_string()))
            .ok_or_else(|| format!("expects one of {}, got '{v}'", names.join(", "))),
        Size => {
            crate::memory::parse_size(v).map(|b| toml::Value::String(crate::memory::format_size(b)))
        }
    }
}

/// `settings` with `values` (key, value) set through its serde form.
fn with<T: Serialize + DeserializeOwned>(
    settings: &T,
    values: impl Iterator<Item = (&'static str, toml::Value)>,
) -> Result<T, String> {
    let mut t = table(settings);
    for (key, value) in values {
        t.insert(key.to_string(), value);
    }
    toml::Value::Table(t)
        .try_into()
        .map_err(|e: toml::de::Error| e.message().to_string())
}

/// Sets `setting` from text and checks its table (the error names the setting).
pub fn set(
    guide: &mut GuideParams,
    maps: &mut MapSettings,
    setting: &'static Setting,
    value: &str,
) -> Result<(), SettingError> {
    set_all(guide, maps, &[(setting, value)])
}

/// Sets every `(setting, text)` of `values`, then checks both tables: settings that must
/// agree (`region_particles` at least `k_p`) may be given in any order. On an error (which
/// names its setting) nothing changes.
pub fn set_all(
    guide: &mut GuideParams,
    maps: &mut MapSettings,
    values: &[(&'static Setting, &str)],
) -> Result<(), SettingError> {
    let mut parsed = Vec::new();
    for (setting, value) in values {
        let v = parse(setting, value).map_err(|message| SettingError {
            table: setting.table.name(),
            key: setting.key,
            message,
        })?;
        parsed.push((*setting, v));
    }
    // A value the serde form refuses (none the kinds let through) is reported at the first
    // setting of its table.
    let of = |t: Table| {
        let first = parsed.iter().find(|(s, _)| s.table == t);
        let entries = parsed
            .iter()
            .filter(move |(s, _)| s.table == t)
            .map(|(s, v)| (s.key, v.clone()));
        (first.map(|(s, _)| s.key).unwrap_or(""), entries)
    };
    let refused = |t: Table, key: &'static str| {
        move |message: String| SettingError {
            table: t.name(),
            key,
            message,
        }
    };
    let (key, entries) = of(Guide);
    let mut g: GuideParams = with(guide, entries).map_err(refused(Guide, key))?;
    // Not a user setting (not serialised): kept as it was.
    g.grazing_cos_min = guide.grazing_cos_min;
    let (key, entries) = of(Maps);
    let m: MapSettings = with(maps, entries).map_err(refused(Maps, key))?;
    g.validate()?;
    m.validate()?;
    *guide = g;
    *maps = m;
    Ok(())
}

/// `key=value` words of the settings `which` accepts, in the schema's order.
pub fn describe(
    guide: &GuideParams,
    maps: &MapSettings,
    which: impl Fn(&Setting) -> bool,
) -> String {
    SETTINGS
        .iter()
        .filter(|s| which(s))
        .map(|s| format!("{}={}", s.key, get(guide, maps, s)))
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The schema names every serialised field of both tables once, and nothing else: a
    /// field added without its row (or a row without its field) fails here.
    #[test]
    fn the_schema_names_every_field_of_both_tables() {
        let maps = MapSettings {
            max_dist: Some(1.0),
            max_memory: Some(1 << 30),
            ..MapSettings::default()
        };
        let (g, m) = tables(&GuideParams::default(), &maps);
        for (table, fields) in [(Guide, &g), (Maps, &m)] {
            let mut keys: Vec<&str> = fields.keys().map(|k| k.as_str()).collect();
            let mut schema: Vec<&str> = SETTINGS
                .iter()
                .filter(|s| s.table == table)
                .map(|s| s.key)
                .collect();
            keys.sort();
            schema.sort();
            assert_eq!(keys, schema, "{}", table.name());
        }
        let mut flags: Vec<&str> = SETTINGS.iter().map(|s| s.flag).collect();
        flags.sort();
        flags.dedup();
        assert_eq!(flags.len(), SETTINGS.len(), "two settings share a flag");
    }

    /// Every setting set from text reads back as that text and changes its field alone;
    /// the kinds match the fields' types (a Count given to a float field would fail to
    /// deserialise).
    #[test]
    fn set_then_get_gives_the_value_back_and_changes_nothing_else() {
        let sample = |s: &Setting| match s.kind {
            Count => match s.key {
                "region_particles" => "500",
                "mis_table" | "raster" | "k_g" | "grid" => "8",
                "min_depth" | "guided_split" | "rounds" => "3",
                _ => "60",
            },
            Number => match s.key {
                "p_bsdf" => "0.25",
                _ => "2.5",
            },
            Switch => {
                if get(&GuideParams::default(), &MapSettings::default(), s) == "on" {
                    "off"
                } else {
                    "on"
                }
            }
            Name(names) => names[1],
            Size => "1.5G",
        };
        for setting in SETTINGS {
            let (mut g, mut m) = (GuideParams::default(), MapSettings::default());
            let v = sample(setting);
            set(&mut g, &mut m, setting, v).unwrap_or_else(|e| panic!("{}: {e}", setting.key));
            assert_eq!(get(&g, &m, setting), v, "{}", setting.key);
            let (d, dm) = (GuideParams::default(), MapSettings::default());
            for other in SETTINGS.iter().filter(|o| o.key != setting.key) {
                assert_eq!(get(&g, &m, other), get(&d, &dm, other), "{}", other.key);
            }
        }
    }

    /// Bad text and bad values are errors naming the setting.
    #[test]
    fn bad_values_name_their_setting() {
        let (mut g, mut m) = (GuideParams::default(), MapSettings::default());
        for (name, value) in [
            ("k_p", "many"),
            ("k_p", "-3"),
            ("k_p", "0"),
            ("p_bsdf", "1.5"),
            ("k_r", "nan"),
            ("guide-cache", "maybe"),
            ("radius_rule", "round"),
            ("photons", "0"),
            ("max_memory", "lots"),
            ("max-memory", "0"),
        ] {
            let s = find(name).expect(name);
            let e = set(&mut g, &mut m, s, value).expect_err(name);
            assert_eq!(e.key, s.key, "{name}={value}: {e}");
        }
        assert_eq!(
            g.k_p,
            GuideParams::default().k_p,
            "a failed set leaves the value"
        );
        assert!(find("guide_cache").is_some() && find("map-rounds").is_some());
        // Settings that must agree may come in either order.
        let (k_p, region) = (find("k_p").unwrap(), find("region_particles").unwrap());
        set_all(&mut g, &mut m, &[(k_p, "500"), (region, "600")]).unwrap();
        assert_eq!((g.k_p, g.region_particles), (500, 600));
        let e = set(&mut g, &mut m, k_p, "700").expect_err("k_p over region_particles");
        assert_eq!(e.key, "region_particles", "{e}");
        assert_eq!(g.k_p, 500);
        assert!(find("no_such").is_none());
    }
}
