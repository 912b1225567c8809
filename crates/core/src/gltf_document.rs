//! Parsing a glTF 2.0 file leniently: what slc uses is validated, what it ignores may be
//! anything the specification allows (and some things it does not).
//!
//! - **GLB**: the chunks within the header's length are walked; the first JSON and the first
//!   BIN chunk are used, chunks of unknown type are skipped (as the specification asks), and
//!   bytes after the last whole chunk or beyond the header's length are ignored.
//! - **Required extensions** (`extensionsRequired`) must be ones slc reads
//!   ([`SUPPORTED_EXTENSIONS`]); any other (Draco, meshopt, KTX2 textures, ...) is an
//!   `unsupported: NAME` error. Other used extensions are ignored and listed
//!   (`Parsed::ignored_extensions`).
//! - **Animations** are dropped with a note (slc renders the rest pose); their channels need
//!   not target a node.
//! - **Textures** whose image comes only through an extension (`EXT_texture_webp`,
//!   `KHR_texture_basisu`, `MSFT_texture_dds`, `EXT_texture_avif`) use that image (decoded
//!   where the format can be: WebP); a texture without any image is left out of the
//!   materials that use it, with a warning.
//! - **Versions**: `asset.version` must be 2.x and `asset.minVersion`, if given, at most 2.0.
//! - **JSON numbers**: integers may be written as floats (`1.0`); scenes may lack `nodes`.
//! - **What nothing reads** cannot fail a file: accessors no primitive or skin uses (of any
//!   type, even one that is no glTF type), and buffers no used view reads (a `.gltf` buffer
//!   without `uri`, which only a GLB's first buffer may be); primitives without `POSITION`
//!   are skipped with a warning (the loader, `gltf_loader.rs`).
//! - The `gltf` crate's validation then runs on what is left; errors in the textures left
//!   out are ignored.
use serde_json::Value;

/// The extensions slc reads, which a file may require.
pub const SUPPORTED_EXTENSIONS: [&str; 5] = [
    "KHR_lights_punctual",
    "KHR_materials_anisotropy",
    "KHR_materials_ior",
    "KHR_mesh_quantization",
    "EXT_texture_webp",
];

/// Image extensions of textures, whose `source` replaces the texture's own.
const IMAGE_EXTENSIONS: [&str; 4] = [
    "EXT_texture_webp",
    "KHR_texture_basisu",
    "MSFT_texture_dds",
    "EXT_texture_avif",
];

/// A parsed document and the GLB binary chunk, if any.
pub(crate) struct Parsed {
    pub document: gltf::Document,
    pub blob: Option<Vec<u8>>,
    /// The used extensions slc does not read.
    pub ignored_extensions: Vec<String>,
}

/// Parses a `.gltf` or `.glb` file's bytes as the module documentation says. A GLB's binary
/// chunk becomes [`Parsed::blob`] in the file's own allocation (moved to its front, not
/// copied: a large GLB is held once).
pub(crate) fn parse(bytes: Vec<u8>, warnings: &mut Vec<String>) -> Result<Parsed, String> {
    let within = |part: &[u8]| {
        let start = part.as_ptr() as usize - bytes.as_ptr() as usize;
        start..start + part.len()
    };
    let (json, blob) = if bytes.starts_with(b"glTF") {
        let (json, blob) = split_glb(&bytes, warnings)?;
        (within(json), blob.map(within))
    } else {
        (0..bytes.len(), None)
    };
    let mut root: Value =
        serde_json::from_slice(&bytes[json]).map_err(|e| format!("invalid JSON: {e}"))?;
    let object = root.as_object_mut().ok_or("the JSON is not an object")?;
    check_version(object)?;
    let ignored_extensions = check_extensions(object)?;
    for scene in object
        .get_mut("scenes")
        .and_then(Value::as_array_mut)
        .into_iter()
        .flatten()
        .filter_map(Value::as_object_mut)
    {
        // `nodes` is optional (a scene may be empty); the `gltf` crate requires it.
        scene
            .entry("nodes")
            .or_insert_with(|| Value::Array(Vec::new()));
    }
    if let Some(Value::Array(a)) = object.remove("animations") {
        if !a.is_empty() {
            warnings.push(format!(
                "{} animation(s) ignored: the rest pose is rendered",
                a.len()
            ));
        }
    }
    let left_out = resolve_texture_sources(object, warnings);
    integers_from_floats(&mut root);
    let json: gltf::json::Root =
        serde_json::from_value(root).map_err(|e| format!("invalid glTF JSON: {e}"))?;
    let document = gltf::Document::from_json_without_validation(json);
    validate(&document, &left_out)?;
    Ok(Parsed {
        document,
        blob: blob.map(|range| {
            let mut bytes = bytes;
            bytes.truncate(range.end);
            bytes.drain(..range.start);
            bytes
        }),
        ignored_extensions,
    })
}

/// Refuses versions a glTF 2.0 loader does not know: `asset.version` of another major
/// version, or an `asset.minVersion` above 2.0 (glTF 2.0 section 3.2: a loader reads
/// 2.x files it does not know the minor version of, unless their minVersion exceeds its own).
fn check_version(object: &serde_json::Map<String, Value>) -> Result<(), String> {
    let asset = object
        .get("asset")
        .ok_or("no asset (its version is required)")?;
    let version = |key: &str| -> Result<Option<(u64, u64)>, String> {
        let Some(v) = asset.get(key) else {
            return Ok(None);
        };
        let text = v.as_str().unwrap_or_default();
        let parsed = text
            .split_once('.')
            .and_then(|(a, b)| Some((a.parse().ok()?, b.parse().ok()?)));
        parsed
            .map(Some)
            .ok_or_else(|| format!("asset.{key} {v} is not MAJOR.MINOR"))
    };
    match version("version")? {
        None => return Err("asset.version is missing".into()),
        Some((2, _)) => {}
        Some((major, minor)) => {
            return Err(format!(
                "asset.version {major}.{minor}: slc reads glTF 2.x files"
            ))
        }
    }
    match version("minVersion")? {
        Some((major, minor)) if (major, minor) > (2, 0) => Err(format!(
            "asset.minVersion {major}.{minor}: the file needs a loader of glTF {major}.{minor}; slc reads glTF 2.0"
        )),
        _ => Ok(()),
    }
}

/// Writes every float of the document that is a whole number as an integer: JSON does not
/// tell `1` from `1.0`, and the `gltf` crate reads indices and counts as integers only.
/// (Float properties read integers as well.)
fn integers_from_floats(value: &mut Value) {
    match value {
        Value::Number(n) if n.is_f64() => {
            let f = n.as_f64().unwrap_or(f64::NAN);
            let whole = f.fract() == 0.0 && f.abs() < 2f64.powi(53);
            if whole {
                // Exact below 2^53.
                *value = match f < 0.0 {
                    true => Value::from(f as i64),
                    false => Value::from(f as u64),
                };
            }
        }
        Value::Array(a) => a.iter_mut().for_each(integers_from_floats),
        Value::Object(o) => o.values_mut().for_each(integers_from_floats),
        _ => {}
    }
}

/// Which accessors something reads: those of mesh primitives (attributes, indices, morph
/// targets) and skins. Errors inside the others do not fail a file.
pub(crate) fn used_accessors(root: &gltf::json::Root) -> Vec<bool> {
    let mut used = vec![false; root.accessors.len()];
    let mut mark = |i: usize| {
        if let Some(u) = used.get_mut(i) {
            *u = true;
        }
    };
    for primitive in root.meshes.iter().flat_map(|m| &m.primitives) {
        primitive.attributes.values().for_each(|a| mark(a.value()));
        primitive.indices.iter().for_each(|a| mark(a.value()));
        for target in primitive.targets.iter().flatten() {
            let attributes = [&target.positions, &target.normals, &target.tangents];
            attributes
                .into_iter()
                .flatten()
                .for_each(|a| mark(a.value()));
        }
    }
    for skin in &root.skins {
        skin.inverse_bind_matrices
            .iter()
            .for_each(|a| mark(a.value()));
    }
    used
}

/// The JSON chunk and the first BIN chunk of a GLB file (glTF 2.0 section 4.4).
fn split_glb<'a>(
    bytes: &'a [u8],
    warnings: &mut Vec<String>,
) -> Result<(&'a [u8], Option<&'a [u8]>), String> {
    let word = |at: usize| {
        bytes
            .get(at..at + 4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
    };
    let version = word(4).ok_or("GLB header: shorter than 12 bytes")?;
    if version != 2 {
        return Err(format!("GLB version {version}; only version 2 is glTF 2.0"));
    }
    let length = word(8).ok_or("GLB header: shorter than 12 bytes")?;
    if length < 12 {
        return Err("GLB header: total length below the header's 12 bytes".into());
    }
    if length > bytes.len() {
        return Err(format!(
            "GLB header: total length {length} bytes, but the file has {}",
            bytes.len()
        ));
    }
    if length < bytes.len() {
        warnings.push(format!(
            "{} byte(s) after the GLB's declared length are ignored",
            bytes.len() - length
        ));
    }
    let (mut json, mut bin) = (None, None);
    let mut at = 12;
    while at < length {
        let (Some(len), Some(kind)) = (word(at), bytes.get(at + 4..at + 8)) else {
            warnings.push(format!("{} trailing GLB byte(s) ignored", length - at));
            break;
        };
        let Some(data) = at
            .checked_add(8 + len)
            .filter(|&end| end <= length)
            .map(|end| &bytes[at + 8..end])
        else {
            if json.is_none() {
                return Err(format!(
                    "GLB chunk at byte {at}: {len} bytes do not fit the file"
                ));
            }
            warnings.push(format!("{} trailing GLB byte(s) ignored", length - at));
            break;
        };
        match kind {
            b"JSON" if json.is_none() => json = Some(data),
            b"BIN\0" if bin.is_none() && json.is_some() => bin = Some(data),
            _ => {}
        }
        at += 8 + len;
    }
    Ok((json.ok_or("GLB: no JSON chunk")?, bin))
}

/// Refuses required extensions slc does not read; returns the used ones it ignores. Removes
/// `extensionsRequired` (checked here, not by the `gltf` crate's own list).
fn check_extensions(object: &mut serde_json::Map<String, Value>) -> Result<Vec<String>, String> {
    let names = |v: Option<&Value>| -> Vec<String> {
        v.and_then(Value::as_array)
            .map(|a| {
                a.iter()
                    .filter_map(|e| e.as_str().map(str::to_string))
                    .collect()
            })
            .unwrap_or_default()
    };
    let required = names(object.remove("extensionsRequired").as_ref());
    if let Some(e) = required
        .iter()
        .find(|e| !SUPPORTED_EXTENSIONS.contains(&e.as_str()))
    {
        return Err(format!(
            "unsupported: {e} (the file requires it; slc reads {})",
            SUPPORTED_EXTENSIONS.join(", ")
        ));
    }
    Ok(names(object.get("extensionsUsed"))
        .into_iter()
        .filter(|e| !SUPPORTED_EXTENSIONS.contains(&e.as_str()))
        .collect())
}

/// Gives textures without `source` the image of their image extension; returns the indices
/// of textures without any image, after removing them from every material.
fn resolve_texture_sources(
    object: &mut serde_json::Map<String, Value>,
    warnings: &mut Vec<String>,
) -> Vec<usize> {
    let mut left_out = Vec::new();
    let Some(Value::Array(textures)) = object.get_mut("textures") else {
        return left_out;
    };
    for (i, texture) in textures.iter_mut().enumerate() {
        let Some(t) = texture.as_object_mut() else {
            continue;
        };
        if t.contains_key("source") {
            continue;
        }
        let from_extension = IMAGE_EXTENSIONS.iter().find_map(|e| {
            let source = t.get("extensions")?.get(e)?.get("source")?.clone();
            Some((e, source))
        });
        match from_extension {
            Some((_, source)) => {
                t.insert("source".into(), source);
            }
            None => {
                // A placeholder the validation of left-out textures may reject.
                t.insert("source".into(), Value::from(0));
                left_out.push(i);
            }
        }
    }
    if left_out.is_empty() {
        return left_out;
    }
    if let Some(Value::Array(materials)) = object.get_mut("materials") {
        for (m, material) in materials.iter_mut().enumerate() {
            for name in strip_texture_refs(material, &left_out) {
                warnings.push(format!(
                    "materials[{m}].{name}: its texture has no image slc can find; the factor is used"
                ));
            }
        }
    }
    left_out
}

/// Removes texture-info objects (`{"index": i, ...}`) naming a left-out texture anywhere in
/// a material; returns the keys removed.
fn strip_texture_refs(value: &mut Value, left_out: &[usize]) -> Vec<String> {
    let mut removed = Vec::new();
    if let Value::Object(map) = value {
        map.retain(|key, v| {
            let index = v.get("index").and_then(Value::as_u64);
            let drop = v.is_object() && index.is_some_and(|i| left_out.contains(&(i as usize)));
            if drop {
                removed.push(key.clone());
            }
            !drop
        });
        for v in map.values_mut() {
            removed.extend(strip_texture_refs(v, left_out));
        }
    }
    removed
}

/// The `gltf` crate's validation, preceded by the check it assumes (and panics without):
/// every primitive's `POSITION` names an existing accessor. Errors inside textures that were
/// left out and inside accessors nothing reads are ignored, and so are accessors without a
/// buffer view (zeros, as the specification says).
fn validate(document: &gltf::Document, left_out: &[usize]) -> Result<(), String> {
    use gltf::json::validation::{Checked, Validate};
    let root = document.as_json();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let position = primitive
                .attributes
                .get(&Checked::Valid(gltf::Semantic::Positions));
            if position.is_some_and(|a| a.value() >= root.accessors.len()) {
                return Err(format!(
                    "meshes[{m}].primitives[{p}]: POSITION names no accessor"
                ));
            }
        }
    }
    let unused = used_accessors(root)
        .into_iter()
        .enumerate()
        .filter(|(_, used)| !used)
        .map(|(i, _)| format!("accessors[{i}]"));
    let ignored: Vec<String> = left_out
        .iter()
        .map(|i| format!("textures[{i}]"))
        .chain(unused)
        .collect();
    let mut errors = Vec::new();
    root.validate(root, gltf::json::Path::new, &mut |path, e| {
        let path = path().to_string();
        // An accessor without a buffer view is zeros (read by `gltf_accessor`).
        let zeros = path.starts_with("accessors[")
            && path.ends_with("].bufferView")
            && e == gltf::json::validation::Error::Missing;
        // A primitive without POSITION is allowed (and skipped by the loader).
        let no_position = path.ends_with(".attributes[\"POSITION\"]")
            && e == gltf::json::validation::Error::Missing;
        if !zeros && !no_position && !ignored.iter().any(|t| path.starts_with(t.as_str())) {
            errors.push(format!("{path}: {e}"));
        }
    });
    match errors.len() {
        0 => Ok(()),
        n => Err(format!(
            "{n} validation error(s): {}",
            errors[..n.min(5)].join("; ")
        )),
    }
}
