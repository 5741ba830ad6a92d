//! `footprint metrics`: `compare`'s error metrics of any image against a reference.

use crate::compare::{mae, reference_noise, rel_mse, spots};
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
    /// The reference's per-pixel standard error (EXR, same size; Mitsuba references carry
    /// one beside their mean): also print what the reference's own noise adds to the
    /// relative MSE, and the relative MSE less it
    #[arg(long, value_name = "EXR")]
    reference_stderr: Option<PathBuf>,
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
    let err = rel_mse(&x, &r);
    let noise = match &a.reference_stderr {
        Some(path) => {
            let s = read_exr(path)?;
            if (s.width, s.height) != (r.width, r.height) {
                bail!(
                    "{} is {}x{}, the reference {}x{}",
                    path.display(),
                    s.width,
                    s.height,
                    r.width,
                    r.height
                );
            }
            format!(
                " reference_noise={:.6e} rel_mse_less_reference={:.6e}",
                reference_noise(&r, &s),
                err - reference_noise(&r, &s)
            )
        }
        None => String::new(),
    };
    println!(
        "rel_mse={:.6e} mae={:.6e} spots={}{noise}",
        err,
        mae(&x, &r),
        spots(&x, &r)
    );
    Ok(())
}
