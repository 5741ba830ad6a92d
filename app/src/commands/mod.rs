//! One file a command: its flags (a clap `Args` struct whose doc comment is the command's
//! help) and what it runs.

pub mod bench;
pub mod compare;
pub mod export;
pub mod maps;
pub mod merge;
pub mod metrics;
pub mod render;
