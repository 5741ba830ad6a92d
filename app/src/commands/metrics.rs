//! `footprint metrics`: `compare`'s error metrics of any image against a reference.

use crate::compare::{mae, rel_mse, spots};
use anyhow::{Result, bail};
use clap::Args;
use footprint::film::image_io::read_exr;
use std::path::PathBuf;

/// Print the error metrics of `footprint compare` (relative MSE, mean absolute error,
/// spots) of an image against a reference, e.g. for another renderer's image
#[derive(Args, Debug)]
pub struct MetricsArgs {
    /// Image (EXR)
    image: PathBuf,
    /// Reference (EXR, same size)
    #[arg(long)]
    reference: PathBuf,
}

pub fn run(a: MetricsArgs) -> Result<()> {
    let x = read_exr(&a.image)?;
    let r = read_exr(&a.reference)?;
    if (x.width, x.height) != (r.width, r.height) {
        bail!(
            "{} is {}x{}, the reference {}x{}",
            a.image.display(),
            x.width,
            x.height,
            r.width,
            r.height
        );
    }
    println!(
        "rel_mse={:.6e} mae={:.6e} spots={}",
        rel_mse(&x, &r),
        mae(&x, &r),
        spots(&x, &r)
    );
    Ok(())
}
