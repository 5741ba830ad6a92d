//! The documentation is kept true by tests: `docs/cli.md` names every flag of every
//! command as clap defines it (and no flag that does not exist), its settings lists are the
//! ones the schema generates, the README's first lines are the two commands, and every
//! relative link in the README and `docs/` points at a file and heading that exist.

use clap::CommandFactory;
use footprint_app::cli::Cli;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn read(rel: &str) -> String {
    std::fs::read_to_string(root().join(rel)).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

/// The `--flags` written in `text`.
fn flags_in(text: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let b = text.as_bytes();
    let mut i = 0;
    while let Some(p) = text[i..].find("--") {
        let start = i + p;
        let before = start.checked_sub(1).map(|k| b[k]);
        let mut end = start + 2;
        while end < b.len()
            && (b[end].is_ascii_lowercase() || b[end].is_ascii_digit() || b[end] == b'-')
        {
            end += 1;
        }
        // A flag starts after a non-word character and is a word itself (not `---`).
        let word = end > start + 2 && b[start + 2].is_ascii_lowercase();
        if word && !before.is_some_and(|c| c.is_ascii_alphanumeric() || c == b'-') {
            out.insert(text[start..end].trim_end_matches('-').to_string());
        }
        i = end.max(start + 2);
    }
    out
}

/// The sections of `docs/cli.md`: `## footprint NAME` headings and their text (HTML
/// comments left out).
fn sections(doc: &str) -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = Vec::new();
    for line in doc.lines().filter(|l| !l.starts_with("<!--")) {
        if let Some(name) = line.strip_prefix("## footprint") {
            out.push((name.trim().to_string(), String::new()));
        } else if let Some((_, text)) = out.last_mut() {
            text.push_str(line);
            text.push('\n');
        }
    }
    out
}

/// Every long flag of every command is in the command's section of `docs/cli.md`, and
/// every flag a section names exists for that command (the global `--accel` and `--help`
/// count for all, `--version` for `footprint` itself; other commands' flags may be named in
/// prose as
/// `COMMAND --flag`, which this test does not take for the section's own).
#[test]
fn the_command_line_reference_names_every_flag_and_no_other() {
    let doc = read("docs/cli.md");
    let secs = sections(&doc);
    let cli = Cli::command();
    let global: BTreeSet<String> = ["--accel", "--help"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let mut commands: Vec<(String, &clap::Command)> = vec![(String::new(), &cli)];
    commands.extend(cli.get_subcommands().map(|c| (c.get_name().to_string(), c)));
    for (name, cmd) in commands {
        let text = &secs
            .iter()
            .find(|(n, _)| *n == name)
            .unwrap_or_else(|| panic!("docs/cli.md has no section '## footprint {name}'"))
            .1;
        let mut defined: BTreeSet<String> = cmd
            .get_arguments()
            .filter_map(|a| a.get_long())
            .map(|l| format!("--{l}"))
            .collect();
        defined.extend(global.iter().cloned());
        if name.is_empty() {
            defined.insert("--version".into());
        }
        let written = flags_in(text);
        let missing: Vec<&String> = defined.difference(&written).collect();
        assert!(
            missing.is_empty(),
            "docs/cli.md, footprint {name}: flags not described: {missing:?}"
        );
        // A flag written in the section but not defined, unless it is quoted in code that
        // runs another command that has it (`render --integrator combined --guide ...`).
        let quoted_elsewhere = |f: &str| {
            text.split('`').skip(1).step_by(2).any(|code| {
                let code = code.trim_start_matches("footprint ");
                cli.get_subcommands().any(|c| {
                    code.starts_with(&format!("{} ", c.get_name()))
                        && flags_in(code).contains(f)
                        && c.get_arguments()
                            .any(|a| a.get_long() == f.strip_prefix("--"))
                })
            })
        };
        let unknown: Vec<&String> = written
            .difference(&defined)
            .filter(|f| !quoted_elsewhere(f))
            .collect();
        assert!(
            unknown.is_empty(),
            "docs/cli.md, footprint {name}: flags that do not exist: {unknown:?}"
        );
    }
}

/// The settings flags' lists in `docs/cli.md` are the ones the schema generates
/// (`footprint_app::args::settings_markdown`). `FOOTPRINT_BLESS=1` rewrites them.
#[test]
fn the_settings_flags_in_the_reference_are_generated_from_the_schema() {
    const BEGIN: &str = "<!-- settings: generated from footprint::schema by footprint_app::args::settings_markdown; FOOTPRINT_BLESS=1 cargo test --release --test docs rewrites it -->\n";
    const END: &str = "<!-- end of the generated settings -->\n";
    let path = root().join("docs/cli.md");
    let doc = read("docs/cli.md");
    let (a, b) = (
        doc.find(BEGIN)
            .expect("docs/cli.md marks its generated settings"),
        doc.find(END)
            .expect("docs/cli.md ends its generated settings"),
    );
    let generated = footprint_app::args::settings_markdown();
    let current = &doc[a + BEGIN.len()..b];
    if std::env::var_os("FOOTPRINT_BLESS").is_some() && current != generated {
        let new = format!("{}{BEGIN}{generated}{}", &doc[..a], &doc[b..]);
        std::fs::write(&path, new).unwrap();
        return;
    }
    assert_eq!(
        current, generated,
        "docs/cli.md's settings differ from the schema's: rerun with FOOTPRINT_BLESS=1"
    );
}

/// The README's first lines are the two commands a new user runs: one renders a bundled
/// scene, one runs the tests (the command `.ci/run` runs).
#[test]
fn the_readme_opens_with_the_two_commands() {
    let readme = read("README.md");
    let head: Vec<&str> = readme.lines().take(8).collect();
    let head = head.join("\n");
    assert!(
        head.contains("cargo run --release -- render scenes/"),
        "{head}"
    );
    assert!(head.contains("cargo test --release --workspace"), "{head}");
    let ci = read(".ci/run");
    assert!(ci.contains("cargo test --release --workspace"), "{ci}");
}

/// A heading's anchor as GitHub makes it: lower case, punctuation dropped but `-` and `_`,
/// spaces as `-`.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || *c == ' ' || *c == '-' || *c == '_')
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

fn anchors(md: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut fenced = false;
    for line in md.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        }
        if !fenced && line.starts_with('#') {
            out.insert(anchor(line.trim_start_matches('#')));
        }
    }
    out
}

/// The relative links `[text](target)` of a markdown file.
fn links(md: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = md;
    while let Some(p) = rest.find("](") {
        rest = &rest[p + 2..];
        if let Some(end) = rest.find(')') {
            out.push(rest[..end].to_string());
        }
    }
    out.into_iter()
        .filter(|l| !l.contains("://") && !l.starts_with("mailto:") && !l.contains(' '))
        .collect()
}

fn markdown_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            markdown_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "md") {
            out.push(p);
        }
    }
}

/// Every relative link in the README, `docs/` and `scenes/` names a file that exists, and
/// a heading of it that exists when it names one.
#[test]
fn every_relative_link_in_the_docs_resolves() {
    let mut files = vec![root().join("README.md")];
    markdown_files(&root().join("docs"), &mut files);
    markdown_files(&root().join("scenes"), &mut files);
    let mut broken = Vec::new();
    for f in &files {
        let md = std::fs::read_to_string(f).unwrap();
        for l in links(&md) {
            let (file, frag) = l.split_once('#').unwrap_or((&l, ""));
            let target = if file.is_empty() {
                f.clone()
            } else {
                f.parent().unwrap().join(file)
            };
            if !target.exists() {
                broken.push(format!("{}: {l}", f.display()));
                continue;
            }
            let is_md = target.extension().is_some_and(|x| x == "md");
            if !frag.is_empty() && is_md {
                let text = std::fs::read_to_string(&target).unwrap();
                if !anchors(&text).contains(frag) {
                    broken.push(format!("{}: {l} (no such heading)", f.display()));
                }
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}
