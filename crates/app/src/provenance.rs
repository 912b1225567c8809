//! Where a result comes from, for `report.json`: the slc build, the command, the machine and
//! the scene's files with their content hashes, so a number can be traced to the run that
//! made it.
use serde::Serialize;
use sha2::{Digest, Sha256};
use slc_core::Scene;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::time::SystemTime;

/// The version of the `report.json` layout: 2 added `provenance` and `skipped_by_defect`,
/// 3 added `ignored`, 4 added `gpu_readback`.
pub const SCHEMA_VERSION: u32 = 4;

#[derive(Serialize, Debug, Clone)]
pub struct Provenance {
    pub schema_version: u32,
    pub slc_version: &'static str,
    /// The git commit slc was built from (`-dirty` with local changes); `null` outside git.
    pub git_commit: Option<&'static str>,
    pub command_line: Vec<String>,
    /// When the command started, UTC (RFC 3339).
    pub started_at: String,
    /// The CPU's model name (`/proc/cpuinfo`), `null` where unknown.
    pub cpu: Option<String>,
    /// Hardware threads available to the process.
    pub cpu_threads: usize,
    /// The operating system and kernel.
    pub os: String,
    /// The files the scene was read from, with their SHA-256; empty for built-in scenes.
    pub scene_files: Vec<SceneFile>,
}

#[derive(Serialize, Debug, Clone)]
pub struct SceneFile {
    pub path: String,
    pub sha256: Option<String>,
}

static START: OnceLock<SystemTime> = OnceLock::new();
/// A command renders one scene: its files are hashed once, by the first report.
static SCENE_FILES: OnceLock<Vec<SceneFile>> = OnceLock::new();

/// Marks the start of the command (call first thing in `main`).
pub fn start() {
    START.get_or_init(SystemTime::now);
}

impl Provenance {
    /// The provenance of a result rendered from `scene` (loaded from `spec`).
    pub fn new(spec: Option<&str>, scene: &Scene) -> Self {
        let started = *START.get_or_init(SystemTime::now);
        Self {
            schema_version: SCHEMA_VERSION,
            slc_version: env!("CARGO_PKG_VERSION"),
            git_commit: Some(env!("SLC_GIT_COMMIT")).filter(|c| !c.is_empty()),
            command_line: std::env::args_os()
                .map(|a| a.to_string_lossy().into_owned())
                .collect(),
            started_at: rfc3339(started),
            cpu: cpu_model(),
            cpu_threads: std::thread::available_parallelism().map_or(1, |n| n.get()),
            os: os(),
            scene_files: SCENE_FILES.get_or_init(|| scene_files(spec, scene)).clone(),
        }
    }
}

/// The settings file (if the scene came through one) and the scene file, hashed.
fn scene_files(spec: Option<&str>, scene: &Scene) -> Vec<SceneFile> {
    let mut paths: Vec<PathBuf> = spec
        .map(PathBuf::from)
        .filter(|p| p.is_file())
        .into_iter()
        .collect();
    if let Some(source) = &scene.source {
        if !paths.contains(source) {
            paths.push(source.clone());
        }
    }
    paths
        .iter()
        .map(|p| SceneFile {
            path: p.display().to_string(),
            sha256: sha256(p),
        })
        .collect()
}

fn sha256(path: &Path) -> Option<String> {
    let mut file = std::fs::File::open(path).ok()?;
    let mut hasher = Sha256::new();
    std::io::copy(&mut file, &mut hasher).ok()?;
    Some(
        hasher
            .finalize()
            .iter()
            .map(|b| format!("{b:02x}"))
            .collect(),
    )
}

fn cpu_model() -> Option<String> {
    let info = std::fs::read_to_string("/proc/cpuinfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("model name"))?;
    Some(line.split_once(':')?.1.trim().to_string())
}

fn os() -> String {
    let pretty = std::fs::read_to_string("/etc/os-release")
        .ok()
        .and_then(|s| {
            s.lines()
                .find_map(|l| l.strip_prefix("PRETTY_NAME="))
                .map(|v| v.trim_matches('"').to_string())
        });
    let kernel = std::fs::read_to_string("/proc/sys/kernel/osrelease")
        .ok()
        .map(|k| k.trim().to_string());
    let mut parts = vec![format!(
        "{} {}",
        std::env::consts::OS,
        std::env::consts::ARCH
    )];
    parts.extend(pretty);
    parts.extend(kernel.map(|k| format!("kernel {k}")));
    parts.join(", ")
}

/// `YYYY-MM-DDTHH:MM:SSZ` of a time (UTC), by the civil-from-days algorithm of
/// H. Hinnant ("chrono-Compatible Low-Level Date Algorithms").
fn rfc3339(t: SystemTime) -> String {
    let secs = t
        .duration_since(SystemTime::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs()) as i64;
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn rfc3339_of_known_times() {
        let at = |s: u64| rfc3339(SystemTime::UNIX_EPOCH + Duration::from_secs(s));
        assert_eq!(at(0), "1970-01-01T00:00:00Z");
        assert_eq!(at(951_782_400), "2000-02-29T00:00:00Z");
        assert_eq!(at(1_795_392_000 + 3661), "2026-11-23T01:01:01Z");
    }

    #[test]
    fn scene_files_are_hashed() {
        let dir = std::env::temp_dir().join(format!("slc-prov-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("a.obj");
        std::fs::write(&f, "abc").unwrap();
        let scene = Scene {
            source: Some(f.clone()),
            ..Scene::default()
        };
        let files = scene_files(None, &scene);
        assert_eq!(
            files[0].sha256.as_deref(),
            Some("ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad")
        );
        assert!(scene_files(None, &Scene::default()).is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
