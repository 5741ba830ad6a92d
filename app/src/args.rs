//! Command-line arguments shared by several commands: the Mitsuba import flags, the
//! `[guide]` and `[maps]` settings (one flag per row of `footprint::schema::SETTINGS`),
//! the resolution, the thread count, and loading a scene with them.

use anyhow::{Context, Result, bail};
use clap::builder::PossibleValuesParser;
use clap::{Arg, ArgAction, ArgMatches, Args, FromArgMatches};
use footprint::keyword::Keyword;
use footprint::scene::Scene;
use footprint::schema::{self, Kind, SETTINGS, Setting};
use footprint::settings::{GuideParams, MapSettings};
use std::path::Path;

/// The heap bytes in use (the binary's counting allocator), for the maps' summaries.
pub fn heap_bytes() -> Option<usize> {
    Some(footprint::heap::heap_bytes())
}

/// A flag's values from a [`Keyword`] type: its names, with a line of help each.
pub fn keyword<T: Keyword + Clone>() -> impl clap::builder::TypedValueParser<Value = T> {
    use clap::builder::{PossibleValue, TypedValueParser};
    PossibleValuesParser::new(
        T::ALL
            .iter()
            .map(|v| PossibleValue::new(v.name()).help(v.about())),
    )
    .map(|name| T::from_name(&name).expect("clap accepts the listed names only"))
}

/// Scene-import flags (Mitsuba 3 XML scenes).
#[derive(Args, Debug, Clone)]
pub struct ImportArgs {
    /// Set a Mitsuba XML parameter, overriding its <default> (repeatable), as Mitsuba's own
    /// -D: `-D resx=128 -D resy=72`
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = footprint::scene::mitsuba::parse_define)]
    pub define: Vec<(String, String)>,
    /// Replace unsupported Mitsuba elements with documented stand-ins (listed on stderr)
    /// instead of stopping with an error
    #[arg(long)]
    pub lenient: bool,
}

impl ImportArgs {
    /// Loads the scene file with these flags; prints what a lenient import replaced.
    pub fn load(&self, path: &Path) -> Result<Scene> {
        let opts = footprint::scene::mitsuba::ImportOptions {
            defines: self.define.clone(),
            lenient: self.lenient,
        };
        let sc = footprint::scene::load::load_scene_with(path, &opts)?;
        for n in &sc.import_notes {
            eprintln!("note: {n}");
        }
        Ok(sc)
    }
}

/// The `[guide]` and `[maps]` settings given on the command line, one flag per setting of
/// the schema (`--k-p 30`, `--guide-cache off`), in the order given.
#[derive(Debug, Clone, Default)]
pub struct SettingArgs {
    pub values: Vec<(&'static Setting, String)>,
}

/// A setting's flag: its help with its default, and the values its kind accepts.
fn setting_arg(s: &'static Setting) -> Arg {
    let default = schema::get(&GuideParams::default(), &MapSettings::default(), s);
    let default = if default == "auto" {
        String::new()
    } else {
        format!(", else {default}")
    };
    let arg = Arg::new(s.flag)
        .long(s.flag)
        .action(ArgAction::Set)
        .help(format!(
            "{} [default: the scene's {}.{}{default}]",
            s.help,
            s.table.name(),
            s.key
        ));
    match s.kind {
        Kind::Count => arg.value_name("N"),
        Kind::Number => arg.value_name("X").allow_negative_numbers(true),
        Kind::Switch => arg.value_parser(PossibleValuesParser::new(["on", "off"])),
        Kind::Name(names) => arg.value_parser(PossibleValuesParser::new(names.iter().copied())),
        Kind::Size => arg.value_name("SIZE"),
    }
}

impl FromArgMatches for SettingArgs {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let mut out = SettingArgs::default();
        out.update_from_arg_matches(m)?;
        Ok(out)
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        for s in SETTINGS {
            if let Some(v) = m.get_one::<String>(s.flag) {
                self.values.push((s, v.clone()));
            }
        }
        Ok(())
    }
}

impl Args for SettingArgs {
    fn augment_args(cmd: clap::Command) -> clap::Command {
        cmd.args(SETTINGS.iter().map(setting_arg))
    }

    fn augment_args_for_update(cmd: clap::Command) -> clap::Command {
        Self::augment_args(cmd)
    }
}

impl SettingArgs {
    /// Applies the flags to `guide` and `maps`; an error names the flag.
    pub fn apply(&self, guide: &mut GuideParams, maps: &mut MapSettings) -> Result<()> {
        let values: Vec<(&'static Setting, &str)> =
            self.values.iter().map(|(s, v)| (*s, v.as_str())).collect();
        schema::set_all(guide, maps, &values).map_err(|e| {
            let flag = schema::find(e.key).map_or(e.key.replace('_', "-"), |s| s.flag.into());
            anyhow::anyhow!("--{flag} {}", e.message)
        })
    }
}

/// The settings flags as markdown lists, one per table, for `docs/cli.md` (a test keeps
/// the file's copy equal to this).
pub fn settings_markdown() -> String {
    let mut out = String::new();
    for (table, intro) in [
        (
            schema::Table::Guide,
            "Guide flags ([guiding.md](guiding.md); the scene's `[guide]` table):",
        ),
        (
            schema::Table::Maps,
            "Map flags ([guiding.md](guiding.md#particle-maps); the scene's `[maps]` table):",
        ),
    ] {
        out += intro;
        out += "\n\n";
        for s in SETTINGS.iter().filter(|s| s.table == table) {
            let value = match s.kind {
                Kind::Count => "N".to_string(),
                Kind::Number => "X".to_string(),
                Kind::Switch => "on|off".to_string(),
                Kind::Name(names) => names.join("|"),
                Kind::Size => "SIZE".to_string(),
            };
            let default = schema::get(&GuideParams::default(), &MapSettings::default(), s);
            let default = if default == "auto" {
                String::new()
            } else {
                format!(" [default: {default}]")
            };
            out += &format!("- `--{} <{value}>`: {}.{default}\n", s.flag, s.help);
        }
        out += "\n";
    }
    out
}

/// Parses `WIDTHxHEIGHT`.
pub fn parse_resolution(s: &str) -> std::result::Result<(u32, u32), String> {
    let (w, h) = s
        .split_once('x')
        .ok_or_else(|| format!("expected WIDTHxHEIGHT, got '{s}'"))?;
    let w: u32 = w
        .trim()
        .parse()
        .map_err(|_| format!("bad width in '{s}'"))?;
    let h: u32 = h
        .trim()
        .parse()
        .map_err(|_| format!("bad height in '{s}'"))?;
    if w == 0 || h == 0 || w > 32768 || h > 32768 {
        return Err(format!(
            "resolution must be between 1x1 and 32768x32768, got {w}x{h}"
        ));
    }
    Ok((w, h))
}

/// Sets the worker thread count (all cores when `None`).
pub fn set_threads(threads: Option<usize>) -> Result<()> {
    if let Some(n) = threads {
        if n == 0 {
            bail!("--threads must be at least 1");
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
            .context("cannot set up the thread pool")?;
    }
    Ok(())
}

/// Loads a scene, applies the setting flags (the scene's `[guide]` and `[maps]` with the
/// flags over them) and a resolution override.
pub fn load_scene(
    path: &Path,
    import: &ImportArgs,
    settings: &SettingArgs,
    resolution: Option<(u32, u32)>,
) -> Result<Scene> {
    let mut sc = import.load(path)?;
    settings.apply(&mut sc.guide, &mut sc.maps)?;
    if let Some((w, h)) = resolution {
        sc.camera = sc
            .camera
            .with_resolution(w, h)
            .map_err(|e| anyhow::anyhow!("--resolution: {e}"))?;
    }
    Ok(sc)
}
