//! The tables of `compare` and `sweep` for scripts: `NAME.json` (provenance, the settings
//! shared by every row, the rows) and `NAME.csv` (one line per row, every setting as a
//! column), written through serde and the `csv` crate (which quotes what needs quoting).
use crate::args::{FrameArgs, PipelineArgs};
use serde::Serialize;
use slc_app::out_dir::OutDir;
use slc_app::provenance::Provenance;
use slc_core::{BackendInfo, Scene};

/// The settings every row of a table shares, one column each.
#[derive(Serialize, Debug, Clone)]
pub struct SettingsColumns {
    pub scene: String,
    /// SHA-256 of the whole scene description (`provenance.scene_sha256`: every file it was
    /// read from, the camera, lights and materials).
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
            scene_sha256: provenance.scene_sha256.clone(),
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

/// A table as text, for a page: column names and formatted cells.
#[derive(Debug, Clone, PartialEq)]
pub struct TextTable {
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

/// A cell for people: numbers with at most four significant digits (integers in full).
fn display_cell(cell: &str) -> String {
    match cell.parse::<f64>() {
        Ok(v) if cell.contains(['.', 'e', 'E']) && v.is_finite() && v != 0.0 => {
            let magnitude = v.abs().log10().floor() as i32;
            if (-3..6).contains(&magnitude) {
                let decimals = (3 - magnitude).max(0) as usize;
                let fixed = format!("{v:.decimals$}");
                if fixed.contains('.') {
                    fixed
                        .trim_end_matches('0')
                        .trim_end_matches('.')
                        .to_string()
                } else {
                    fixed
                }
            } else {
                format!("{v:.3e}")
            }
        }
        _ => cell.to_string(),
    }
}

impl TextTable {
    /// The rows as the `csv` crate writes them (so the columns are the serialized fields in
    /// order), with numbers shortened for reading.
    pub fn of<R: Serialize>(rows: &[R]) -> Result<Self, String> {
        let mut writer = csv::Writer::from_writer(Vec::new());
        for row in rows {
            writer.serialize(row).map_err(|e| e.to_string())?;
        }
        let bytes = writer.into_inner().map_err(|e| e.to_string())?;
        let mut reader = csv::Reader::from_reader(bytes.as_slice());
        let header = reader
            .headers()
            .map_err(|e| e.to_string())?
            .iter()
            .map(str::to_string)
            .collect();
        let rows = reader
            .records()
            .map(|r| {
                r.map(|r| r.iter().map(display_cell).collect())
                    .map_err(|e| e.to_string())
            })
            .collect::<Result<_, _>>()?;
        Ok(Self { header, rows })
    }

    /// A one-row table turned on its side: one (name, value) row per column.
    pub fn transposed(&self) -> Self {
        Self {
            header: vec!["setting".into(), "value".into()],
            rows: self
                .header
                .iter()
                .enumerate()
                .map(|(i, h)| {
                    let v = self.rows.first().and_then(|r| r.get(i)).cloned();
                    vec![h.clone(), v.unwrap_or_default()]
                })
                .collect(),
        }
    }
}

/// Stages `name.json` and `name.csv` in `out`; returns the rows and the settings as text for
/// the folder's page.
pub fn write_table<R: Serialize>(
    out: &mut OutDir,
    name: &str,
    provenance: &Provenance,
    settings: &SettingsColumns,
    rows: &[R],
) -> Result<(TextTable, TextTable), String> {
    let json = serde_json::to_string_pretty(&JsonTable {
        provenance,
        settings,
        rows,
    })
    .map_err(|e| e.to_string())?;
    out.write(format!("{name}.json"), (json + "\n").as_bytes())?;
    write_csv(out, name, rows.iter().map(|row| (settings, row)))?;
    let text = |e: String| format!("{name}: {e}");
    Ok((
        TextTable::of(rows).map_err(text)?,
        TextTable::of(std::slice::from_ref(settings))
            .map_err(text)?
            .transposed(),
    ))
}

/// Stages `name.csv`: one line per (settings, row) pair, the settings' columns first.
pub fn write_csv<S: Serialize, R: Serialize>(
    out: &mut OutDir,
    name: &str,
    rows: impl Iterator<Item = (S, R)>,
) -> Result<(), String> {
    let mut csv = csv::Writer::from_writer(Vec::new());
    for row in rows {
        csv.serialize(row).map_err(|e| format!("{name}.csv: {e}"))?;
    }
    let bytes = csv.into_inner().map_err(|e| format!("{name}.csv: {e}"))?;
    out.write(format!("{name}.csv"), &bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_are_shortened_for_reading_but_integers_kept() {
        assert_eq!(display_cell("123456789"), "123456789");
        assert_eq!(display_cell("0.000123456"), "1.235e-4");
        assert_eq!(display_cell("12.3456789"), "12.35");
        assert_eq!(display_cell("0.0010000000474974513"), "0.001");
        assert_eq!(display_cell("ellipsoid"), "ellipsoid");
        assert_eq!(display_cell(""), "");
        assert_eq!(display_cell("0.0"), "0.0");
    }

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
        let provenance = Provenance::new(&scene);
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
        let (table, settings_table) =
            write_table(&mut out, "t", &provenance, &settings, &rows).unwrap();
        out.commit().unwrap();
        assert_eq!(table.header, ["strategy", "ms"]);
        assert_eq!(table.rows, [["ellipsoid", "1.5"], ["none", ""]]);
        assert_eq!(settings_table.rows[0], ["scene", "a, \"quoted\" scene"]);
        assert_eq!(settings_table.rows.len(), 14);
        let csv = std::fs::read_to_string(root.join("t.csv")).unwrap();
        let lines: Vec<&str> = csv.lines().collect();
        assert!(lines[0].starts_with("scene,scene_sha256,backend,adapter,width,height"));
        assert!(lines[0].ends_with(",strategy,ms"), "{}", lines[0]);
        let start = format!(
            "\"a, \"\"quoted\"\" scene\",{},cpu,CPU,",
            provenance.scene_sha256
        );
        assert!(lines[1].starts_with(&start), "{}", lines[1]);
        assert!(lines[1].ends_with(",ellipsoid,1.5") && lines[2].ends_with(",none,"));
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(root.join("t.json")).unwrap()).unwrap();
        assert_eq!(json["settings"]["vpls"], 7);
        assert_eq!(json["rows"][1]["ms"], serde_json::Value::Null);
        assert_eq!(json["provenance"]["schema_version"], 5);
        std::fs::remove_dir_all(&root).ok();
    }
}
