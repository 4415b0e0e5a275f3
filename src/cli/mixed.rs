//! `ehlmap mixed DATASET... [--out DIR] [--json]`: the mixed-lubrication map of sweep datasets
//! with a roughness axis: per smooth case and orientation, H/H_smooth and the asperity share of
//! the load against Lambda = H_min/sigma (report.md, mixed.json, mixed.png). Exit 2 when a
//! dataset cannot be read or holds no rough row, 1 when the report cannot be written.

use crate::cli::error::{input, io, CliError};
use crate::cli::output::{beside_dataset, note, outln, prepare_dir};
use ehlmap::render::mixed_map::mixed_chart;
use ehlmap::report::mixed::{mixed_map, mixed_markdown};
use ehlmap::store::results::read_dataset;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct MixedArgs {
    /// Sweep dataset directories (all part files inside are read).
    #[arg(required = true)]
    pub datasets: Vec<PathBuf>,
    /// Where report.md, mixed.json and mixed.png go (default: DATASET-mixed beside the first
    /// dataset).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print mixed.json to stdout instead of the Markdown report.
    #[arg(long)]
    pub json: bool,
}

/// Run `ehlmap mixed`.
pub fn run_mixed(a: &MixedArgs) -> Result<(), CliError> {
    let mut rows = vec![];
    for d in &a.datasets {
        rows.extend(read_dataset(d).map_err(|e| input(format!("{}: {e}", d.display())))?);
    }
    if !rows.iter().any(|r| r.sigma.is_some()) {
        return Err(input(format!(
            "{}: no rough case (sigma) in the data: give the sweep spec an axis sigma",
            a.datasets[0].display()
        )));
    }
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| beside_dataset(&a.datasets[0], "mixed"));
    prepare_dir("--out", &out)?;
    let map = mixed_map(&rows);
    let mut md = mixed_markdown(&map);
    let json = serde_json::to_string_pretty(&map).expect("the map serialises");
    if !map.curves.is_empty() {
        mixed_chart(&out.join("mixed.png"), &map)
            .map_err(|e| io(format!("--out {}: chart: {e}", out.display())))?;
        md.push_str("\n## Chart\n\n![mixed](mixed.png)\n");
    }
    for (name, text) in [("report.md", &md), ("mixed.json", &json)] {
        std::fs::write(out.join(name), text)
            .map_err(|e| io(format!("--out {}: {e}", out.join(name).display())))?;
    }
    if a.json {
        outln!("{json}")
    } else {
        outln!("{md}")?;
        note!(
            "wrote {}/report.md, mixed.json and mixed.png",
            out.display()
        );
        Ok(())
    }
}
