//! The comparison's machine-readable files: `metrics.csv` and `metrics.json`.

use super::metrics::{BUDGET_TOLERANCE, SPOT_FACTOR};
use super::rows::{MethodSummary, Row};
use anyhow::Result;

pub fn csv(rows: &[Row]) -> Result<String> {
    let mut w = csv::Writer::from_writer(Vec::new());
    for r in rows {
        w.serialize(r)?;
    }
    Ok(String::from_utf8(
        w.into_inner().map_err(|e| anyhow::anyhow!("{e}"))?,
    )?)
}
pub fn json(
    scene: &str,
    reference: &str,
    rows: &[Row],
    summary: &[MethodSummary],
    target: f64,
) -> Result<String> {
    let report = serde_json::json!({
        "scene": scene,
        "reference": reference,
        "spot_factor": SPOT_FACTOR,
        "budget_tolerance": BUDGET_TOLERANCE,
        "budgets_missed": rows.iter().filter(|r| r.budget_missed).count(),
        "target_rel_mse": target,
        "rows": rows,
        "methods": summary,
    });
    Ok(serde_json::to_string_pretty(&report)? + "\n")
}
