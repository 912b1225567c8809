//! Where a result comes from, for `report.json`: the slc build (version, commit, compiler,
//! profile), the command, the machine, every file that went into the scene with its content
//! hash (settings, scene file, material libraries, buffers, textures) and a hash of the whole
//! scene description, so a number can be traced to the run and the scene that made it.
use serde::Serialize;
use sha2::{Digest, Sha256};
use slc_core::Scene;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock, PoisonError};
use std::time::SystemTime;

/// The version of the `report.json` layout: 2 added `provenance` and `skipped_by_defect`,
/// 3 added `ignored`, 4 added `gpu_readback`, 5 added `rustc`, `build_profile` and
/// `scene_sha256` and lists every file the scene was read from in `scene_files`.
pub const SCHEMA_VERSION: u32 = 5;

#[derive(Serialize, Debug, Clone)]
pub struct Provenance {
    pub schema_version: u32,
    pub slc_version: &'static str,
    /// The git commit slc was built from (`-dirty` with local changes); `null` outside git.
    pub git_commit: Option<&'static str>,
    /// The compiler slc was built with (`rustc --version`).
    pub rustc: &'static str,
    /// The Cargo profile slc was built with and its optimisation level, e.g.
    /// `release (opt-level 3)`: a debug build's times say little.
    pub build_profile: &'static str,
    pub command_line: Vec<String>,
    /// When the command started, UTC (RFC 3339).
    pub started_at: String,
    /// The CPU's model name (`/proc/cpuinfo`), `null` where unknown.
    pub cpu: Option<String>,
    /// Hardware threads available to the process.
    pub cpu_threads: usize,
    /// The operating system and kernel.
    pub os: String,
    /// Every file the scene was read from, in the order read (the settings file, the scene
    /// file, its material libraries, buffers and textures), with its SHA-256; empty for
    /// built-in scenes.
    pub scene_files: Vec<SceneFile>,
    /// SHA-256 of the whole scene description: the content of every file in `scene_files`
    /// (not their paths), the built-in scene's name where it has no file, and the camera,
    /// lights and materials as rendered (after settings files and overrides). Two results
    /// with the same value rendered the same scene.
    pub scene_sha256: String,
}

#[derive(Serialize, Debug, Clone, PartialEq)]
pub struct SceneFile {
    pub path: String,
    /// `null` where the file can no longer be read.
    pub sha256: Option<String>,
}

static START: OnceLock<SystemTime> = OnceLock::new();

/// Marks the start of the command (call first thing in `main`).
pub fn start() {
    START.get_or_init(SystemTime::now);
}

impl Provenance {
    /// The provenance of a result rendered from `scene`.
    pub fn new(scene: &Scene) -> Self {
        let started = *START.get_or_init(SystemTime::now);
        let scene_files = scene_files(scene);
        Self {
            schema_version: SCHEMA_VERSION,
            slc_version: env!("CARGO_PKG_VERSION"),
            git_commit: Some(env!("SLC_GIT_COMMIT")).filter(|c| !c.is_empty()),
            rustc: env!("SLC_RUSTC_VERSION"),
            build_profile: env!("SLC_BUILD_PROFILE"),
            command_line: std::env::args_os()
                .map(|a| a.to_string_lossy().into_owned())
                .collect(),
            started_at: rfc3339(started),
            cpu: cpu_model(),
            cpu_threads: std::thread::available_parallelism().map_or(1, |n| n.get()),
            os: os(),
            scene_sha256: scene_sha256(scene, &scene_files),
            scene_files,
        }
    }
}

/// The files the scene was read from, hashed.
fn scene_files(scene: &Scene) -> Vec<SceneFile> {
    scene
        .report
        .files
        .iter()
        .map(|p| SceneFile {
            path: p.display().to_string(),
            sha256: sha256_cached(p),
        })
        .collect()
}

/// SHA-256 of what `scene` is (see [`Provenance::scene_sha256`]).
fn scene_sha256(scene: &Scene, files: &[SceneFile]) -> String {
    let mut h = Sha256::new();
    h.update(b"slc scene description 1\n");
    for f in files {
        h.update(format!(
            "file {}\n",
            f.sha256.as_deref().unwrap_or("unreadable")
        ));
    }
    if files.is_empty() {
        h.update(format!("built-in {}\n", scene.name));
    }
    h.update(format!("camera {:?}\n", scene.camera));
    for light in &scene.lights {
        h.update(format!("light {light:?}\n"));
    }
    for material in &scene.materials {
        h.update(format!("material {material:?}\n"));
    }
    hex(&h.finalize())
}

/// A file's SHA-256, computed once per content: the hashes are kept by path, size and
/// modification time, so a process that renders one scene many times (the Python package)
/// reads its files once.
fn sha256_cached(path: &Path) -> Option<String> {
    type Key = (PathBuf, u64, Option<SystemTime>);
    static KNOWN: OnceLock<Mutex<HashMap<Key, String>>> = OnceLock::new();
    let meta = std::fs::metadata(path).ok()?;
    let key = (path.to_path_buf(), meta.len(), meta.modified().ok());
    let known = KNOWN.get_or_init(Mutex::default);
    if let Some(h) = known
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .get(&key)
    {
        return Some(h.clone());
    }
    let h = sha256(path)?;
    known
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .insert(key, h.clone());
    Some(h)
}

fn sha256(path: &Path) -> Option<String> {
    let mut file = std::fs::File::open(path).ok()?;
    let mut hasher = Sha256::new();
    std::io::copy(&mut file, &mut hasher).ok()?;
    Some(hex(&hasher.finalize()))
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
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
    fn every_file_is_hashed_and_the_description_hash_follows_the_scene() {
        let dir = std::env::temp_dir().join(format!("slc-prov-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (obj, mtl) = (dir.join("a.obj"), dir.join("a.mtl"));
        std::fs::write(&obj, "abc").unwrap();
        std::fs::write(&mtl, "newmtl x").unwrap();
        let mut scene = slc_core::builtin("default").unwrap();
        let builtin = Provenance::new(&scene);
        assert!(builtin.scene_files.is_empty());
        scene.report.files = vec![obj.clone(), mtl.clone()];
        let p = Provenance::new(&scene);
        assert_eq!(p.scene_files.len(), 2);
        assert_eq!(
            p.scene_files[0].sha256.as_deref(),
            Some("ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad")
        );
        assert!(p.scene_files[1].path.ends_with("a.mtl"));
        assert_ne!(p.scene_sha256, builtin.scene_sha256);
        // The same files and scene: the same hash; another light or a changed file: another.
        assert_eq!(Provenance::new(&scene).scene_sha256, p.scene_sha256);
        let mut lit = scene.clone();
        lit.lights.push(slc_core::Light::Point {
            position: glam::Vec3::Y,
            intensity: glam::Vec3::ONE,
        });
        assert_ne!(Provenance::new(&lit).scene_sha256, p.scene_sha256);
        std::fs::write(&mtl, "newmtl y2").unwrap();
        let changed = Provenance::new(&scene);
        assert_ne!(changed.scene_files[1], p.scene_files[1]);
        assert_ne!(changed.scene_sha256, p.scene_sha256);
        assert!(p.rustc.starts_with("rustc ") && !p.build_profile.is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
