//! One multi-layer EXR per frame, for tev and scripts: layers `direct`, `indirect` and `total`
//! (channels R, G, B) and, where culling metrics were measured, a layer `metrics` with the
//! per-pixel channels `lights` (list length) and `fdr` (false discovery rate); the provenance
//! JSON is in the header attribute `slc.provenance`.
use crate::out_dir::OutDir;
use crate::provenance::Provenance;
use exr::prelude::*;
use slc_core::CullMetrics;
use std::path::Path;

/// The per-pixel culling metrics of a frame, row-major: VPLs listed and false discovery rate.
#[derive(Clone, Copy, Debug)]
pub struct PixelMetrics<'a> {
    pub lights: &'a [u32],
    pub fdr: &'a [f32],
}

impl<'a> From<&'a CullMetrics> for PixelMetrics<'a> {
    fn from(m: &'a CullMetrics) -> Self {
        Self {
            lights: &m.lights_per_pixel,
            fdr: &m.fdr_per_pixel,
        }
    }
}

/// Stages `dir/layers.exr` in `out`.
pub fn write_layers(
    out: &mut OutDir,
    dir: &str,
    images: &[(&'static str, &slc_core::Image)],
    metrics: Option<&CullMetrics>,
    provenance: &Provenance,
) -> std::result::Result<(), String> {
    let relative = Path::new(dir).join("layers.exr");
    let json = serde_json::to_string(provenance).map_err(|e| e.to_string())?;
    let metrics = metrics.map(PixelMetrics::from);
    out.write_with(&relative, |path| {
        write_layers_file(path, images, metrics, &json)
    })
}

/// Writes the layered EXR of `images` (and `metrics`) to `path`, with `provenance` (JSON) in
/// the header. The error does not name the path (the caller knows where the file goes).
pub fn write_layers_file(
    path: &Path,
    images: &[(&'static str, &slc_core::Image)],
    metrics: Option<PixelMetrics>,
    provenance: &str,
) -> std::result::Result<(), String> {
    let (w, h) = images
        .first()
        .map_or((1, 1), |(_, i)| (i.width as usize, i.height as usize));
    let size = Vec2(w, h);
    let mut layers: Vec<Layer<AnyChannels<FlatSamples>>> = images
        .iter()
        .map(|(name, image)| {
            let channel = |c: usize, label: &str| {
                AnyChannel::new(
                    label,
                    FlatSamples::F32(image.pixels.iter().map(|p| p[c]).collect()),
                )
            };
            let channels = vec![channel(0, "R"), channel(1, "G"), channel(2, "B")];
            layer(size, name, channels)
        })
        .collect();
    if let Some(m) = metrics {
        let lights = m.lights.iter().map(|&n| n as f32).collect();
        let channels = vec![
            AnyChannel::new("lights", FlatSamples::F32(lights)),
            AnyChannel::new("fdr", FlatSamples::F32(m.fdr.to_vec())),
        ];
        layers.push(layer(size, "metrics", channels));
    }
    let mut attributes = ImageAttributes::new(IntegerBounds::from_dimensions(size));
    let text = Text::new_or_none(ascii_escaped(provenance)).ok_or("provenance is not ASCII")?;
    attributes
        .other
        .insert(Text::from("slc.provenance"), AttributeValue::Text(text));
    let image = exr::image::Image::from_layers(attributes, layers);
    image
        .write()
        .to_file(path)
        .map_err(|e| format!("cannot write EXR: {e}"))
}

fn layer(
    size: Vec2<usize>,
    name: &str,
    channels: Vec<AnyChannel<FlatSamples>>,
) -> Layer<AnyChannels<FlatSamples>> {
    Layer::new(
        size,
        LayerAttributes::named(name),
        Encoding::FAST_LOSSLESS,
        AnyChannels::sort(channels.into()),
    )
}

/// JSON with every non-ASCII character as a `\uXXXX` escape (UTF-16, as JSON specifies), so
/// it fits an EXR text attribute and still parses to the same value.
fn ascii_escaped(json: &str) -> String {
    let mut out = String::with_capacity(json.len());
    for c in json.chars() {
        if c.is_ascii() {
            out.push(c);
        } else {
            for unit in c.encode_utf16(&mut [0; 2]) {
                out.push_str(&format!("\\u{unit:04x}"));
            }
        }
    }
    out
}

/// What `write_layers` wrote, read back: layer name -> channel name -> samples, and the
/// provenance attribute.
#[cfg(test)]
pub fn read_layers(
    path: &std::path::Path,
) -> (
    std::collections::BTreeMap<String, std::collections::BTreeMap<String, Vec<f32>>>,
    String,
) {
    let image = read_all_flat_layers_from_file(path).unwrap();
    // Image attributes are written into every layer's header and read back per layer.
    let key = Text::from("slc.provenance");
    let found = image.attributes.other.get(&key).or_else(|| {
        image
            .layer_data
            .iter()
            .find_map(|l| l.attributes.other.get(&key))
    });
    let provenance = match found {
        Some(AttributeValue::Text(t)) => t.to_string(),
        other => panic!("{other:?}"),
    };
    let layers = image
        .layer_data
        .iter()
        .map(|l| {
            let name = l.attributes.layer_name.as_ref().unwrap().to_string();
            let channels = l
                .channel_data
                .list
                .iter()
                .map(|c| (c.name.to_string(), c.sample_data.values_as_f32().collect()))
                .collect();
            (name, channels)
        })
        .collect();
    (layers, provenance)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use slc_core::{Image, Scene};

    #[test]
    fn layers_metrics_and_provenance_round_trip() {
        let root = std::env::temp_dir().join(format!("slc-layers-{}", std::process::id()));
        std::fs::remove_dir_all(&root).ok();
        let mut out = OutDir::open(&root).unwrap();
        let mut direct = Image::new(3, 2);
        direct.pixels[4] = Vec3::new(0.25, 4.5, 1e-7);
        let indirect = Image::new(3, 2);
        let metrics = CullMetrics {
            lights_per_pixel: vec![0, 1, 2, 3, 4, 5],
            fdr_per_pixel: vec![0.0, 0.5, 1.0, 0.25, 0.0, 0.75],
            ..CullMetrics::default()
        };
        let scene = Scene {
            name: "s".into(),
            source: Some("/tmp/scène.obj".into()),
            ..Scene::default()
        };
        let provenance = Provenance::new(&scene);
        let images = [("direct", &direct), ("indirect", &indirect)];
        write_layers(&mut out, "x", &images, Some(&metrics), &provenance).unwrap();
        out.commit().unwrap();
        let (layers, json) = read_layers(&root.join("x/layers.exr"));
        assert_eq!(layers["direct"]["G"][4], 4.5);
        assert_eq!(layers["direct"]["B"][4], 1e-7);
        assert_eq!(layers["metrics"]["lights"], [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]);
        assert_eq!(layers["metrics"]["fdr"][5], 0.75);
        let p: serde_json::Value = serde_json::from_str(&json).unwrap();
        assert_eq!(p["schema_version"], 5);
        std::fs::remove_dir_all(&root).ok();
    }

    #[test]
    fn non_ascii_is_escaped_as_json_reads_it() {
        let s = ascii_escaped("\"scène 🎨\"");
        assert!(s.is_ascii());
        assert_eq!(serde_json::from_str::<String>(&s).unwrap(), "scène 🎨");
    }
}
