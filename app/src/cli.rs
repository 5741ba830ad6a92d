//! The `footprint` command line: the commands ([`crate::commands`]), the global flags, and
//! the exit codes (1 for bad input, whether clap or the renderer finds it; 0 for `--help`).

use crate::args::keyword;
use crate::commands::{bench, compare, export, maps, merge, metrics, render};
use anyhow::Result;
use clap::{Parser, Subcommand};

#[derive(Parser, Debug)]
#[command(
    name = "footprint",
    version,
    about = "A physically based CPU renderer that guides light and view paths with particle maps",
    long_about = "footprint renders scenes described in TOML (docs/scene-format.md) or \
                  Mitsuba 3 XML (docs/mitsuba.md) with path tracing, light tracing or both, guided \
                  by particle maps.\n\nExamples:\n  footprint render scenes/desk/desk.toml\n  \
                  footprint render scene.xml -D resx=128 -D resy=72"
)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Acceleration structure: Embree 3 where the system has it (`libembree3`, loaded at
    /// run time; Debian: libembree3-3), else footprint's own CWBVH [default:
    /// FOOTPRINT_ACCEL, else auto]
    #[arg(long, global = true, value_parser = keyword::<footprint::scene::accel::Backend>())]
    accel: Option<footprint::scene::accel::Backend>,
}

#[derive(Subcommand, Debug)]
enum Command {
    Render(render::RenderArgs),
    Merge(merge::MergeArgs),
    Maps(maps::MapsArgs),
    Compare(compare::CompareArgs),
    Metrics(metrics::MetricsArgs),
    Export(export::ExportArgs),
    Bench(bench::BenchArgs),
}

/// Parses the command line and runs the command; exits with 1 on bad input.
pub fn main() {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            std::process::exit(if e.use_stderr() { 1 } else { 0 });
        }
    };
    if let Some(backend) = cli.accel {
        footprint::scene::accel::set_backend(backend);
    }
    if let Err(e) = run(cli.command) {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}

fn run(command: Command) -> Result<()> {
    match command {
        Command::Render(a) => render::run(a),
        Command::Merge(a) => merge::run(a),
        Command::Maps(a) => maps::run(a),
        Command::Compare(a) => compare::run(a),
        Command::Metrics(a) => metrics::run(a),
        Command::Export(a) => export::run(a),
        Command::Bench(a) => bench::run(a),
    }
}
