//! The tables of `compare` and `sweep` for scripts: `NAME.json` (provenance, the settings
//! shared by every row, the rows) and `NAME.csv` (one line per row, every setting as a
//! column), written through serde and the `csv` crate (which quotes what needs quoting).
use crate::args::{FrameArgs, PipelineArgs};
use crate::out_dir::OutDir;
use crate::provenance::Provenance;
use serde::Serialize;
use slc_core::{BackendInfo, Scene};

/// The settings every row of a table shares, one column each.
#[derive(Serialize, Debug, Clone)]
pub struct SettingsColumns {
    pub scene: String,
    /// SHA-256 of the scene's file (the last of `provenance.scene_files`); empty for built-in
    /// scenes.
    pub scene_sha256: String,
    pub backend: &'static str,
    pub adapter: String,
    pub width: u32,
    pub height: u32,
    /// RSM texels per side and face.
    pub rsm: u32,
    pub lobes: String,
    pub vpls: usize,
    pub seed: u32,
    /// K of K x K interleaving.
    pub interleave: u32,
    pub denoise: bool,
    pub visibility: bool,
    /// Threads the CPU work ran on.
    pub threads: usize,
}

impl SettingsColumns {
    pub fn new(
        provenance: &Provenance,
        scene: &Scene,
        device: &BackendInfo,
        f: &FrameArgs,
        pipeline: &PipelineArgs,
        vpls: usize,
    ) -> Self {
        Self {
            scene: scene.name.clone(),
            scene_sha256: provenance
                .scene_files
                .last()
                .and_then(|s| s.sha256.clone())
                .unwrap_or_default(),
            backend: device.backend,
            adapter: device.adapter.clone(),
            width: f.width,
            height: f.height,
            rsm: f.rsm,
            lobes: format!("{:?}", f.lobes).to_lowercase(),
            vpls,
            seed: f.seed,
            interleave: pipeline.interleave,
            denoise: !pipeline.no_denoise,
            visibility: f.visibility,
            threads: rayon::current_num_threads(),
        }
    }
}

#[derive(Serialize)]
struct JsonTable<'a, R> {
    provenance: &'a Provenance,
    settings: &'a SettingsColumns,
    rows: &'a [R],
}

/// Stages `name.json` and `name.csv` in `out`.
pub fn write_table<R: Serialize>(
    out: &mut OutDir,
    name: &str,
    provenance: &Provenance,
    settings: &SettingsColumns,
    rows: &[R],
) -> Result<(), String> {
    let json = serde_json::to_string_pretty(&JsonTable {
        provenance,
        settings,
        rows,
    })
    .map_err(|e| e.to_string())?;
    out.write(format!("{name}.json"), (json + "\n").as_bytes())?;
    let mut csv = csv::Writer::from_writer(Vec::new());
    for row in rows {
        csv.serialize((settings, row))
            .map_err(|e| format!("{name}.csv: {e}"))?;
    }
    let bytes = csv.into_inner().map_err(|e| format!("{name}.csv: {e}"))?;
    out.write(format!("{name}.csv"), &bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(clap::Parser)]
    struct Args {
        #[command(flatten)]
        f: FrameArgs,
        #[command(flatten)]
        p: PipelineArgs,
    }

    #[derive(Serialize)]
    struct Row {
        strategy: &'static str,
        ms: Option<f64>,
    }

    #[test]
    fn csv_quotes_and_repeats_the_settings() {
        let root = std::env::temp_dir().join(format!("slc-table-{}", std::process::id()));
        std::fs::remove_dir_all(&root).ok();
        let mut out = OutDir::open(&root).unwrap();
        let scene = Scene {
            name: "a, \"quoted\" scene".into(),
            ..Scene::default()
        };
        let provenance = Provenance::new(None, &scene);
        let device = BackendInfo {
            backend: "cpu",
            adapter: "CPU".into(),
            notes: Vec::new(),
        };
        let args: Args = clap::Parser::parse_from(["x"]);
        let settings = SettingsColumns::new(&provenance, &scene, &device, &args.f, &args.p, 7);
        let rows = [
            Row {
                strategy: "ellipsoid",
                ms: Some(1.5),
            },
            Row {
                strategy: "none",
                ms: None,
            },
        ];
        write_table(&mut out, "t", &provenance, &settings, &rows).unwrap();
        out.commit().unwrap();
        let csv = std::fs::read_to_string(root.join("t.csv")).unwrap();
        let lines: Vec<&str> = csv.lines().collect();
        assert!(lines[0].starts_with("scene,scene_sha256,backend,adapter,width,height"));
        assert!(lines[0].ends_with(",strategy,ms"), "{}", lines[0]);
        assert!(
            lines[1].starts_with("\"a, \"\"quoted\"\" scene\",,cpu,CPU,"),
            "{}",
            lines[1]
        );
        assert!(lines[1].ends_with(",ellipsoid,1.5") && lines[2].ends_with(",none,"));
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(root.join("t.json")).unwrap()).unwrap();
        assert_eq!(json["settings"]["vpls"], 7);
        assert_eq!(json["rows"][1]["ms"], serde_json::Value::Null);
        assert_eq!(json["provenance"]["schema_version"], 2);
        std::fs::remove_dir_all(&root).ok();
    }
}
