//! The settings the side panel edits: what to render (strategy, δ, K, RSM size, shader,
//! lobes, denoise) and how to show it (layer, exposure, overlay).
use super::ViewArgs;
use crate::args::{EstimateArgs, ImportanceArgs, Lobes, PipelineArgs, Shader};
use clap::ValueEnum;
use slc_core::frame::RenderSettings;
use slc_core::Strategy;

/// Which light the picture shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Layer {
    Direct,
    Indirect,
    Total,
}

/// What is drawn over the picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Overlay {
    /// The picture alone.
    None,
    /// Lights per pixel (brightness) and false discovery rate (colour), as the paper's Fig. 9,
    /// with a colour bar; measured by brute force on the CPU (VPL shader only).
    Heatmap,
    /// The tiles culling works on: 16 x 16 pixels of each interleaved subregion image, so
    /// cells of 16K x 16K screen pixels (clustered strategies also split them in depth).
    Grid,
}

/// The state of the panel's controls.
#[derive(Clone, Debug)]
pub struct Controls {
    pub estimate: EstimateArgs,
    pub pipeline: PipelineArgs,
    pub importance: ImportanceArgs,
    pub shader: Shader,
    pub rsm: u32,
    pub lobes: Lobes,
    pub seed: u32,
    pub exposure: f32,
    pub layer: Layer,
    pub overlay: Overlay,
    /// Lights per pixel at full heat-map brightness.
    pub heat_max: u32,
    /// Measure lights per pixel and FDR (CPU brute force) even without the heat map.
    pub measure: bool,
}

impl Controls {
    /// The controls as the command line sets them.
    pub fn from_args(args: &ViewArgs) -> Self {
        Self {
            estimate: args.estimate.clone(),
            pipeline: args.pipeline.clone(),
            importance: args.importance.clone(),
            shader: args.shader,
            rsm: args.rsm,
            lobes: args.lobes,
            seed: args.seed,
            exposure: args.exposure,
            layer: args.show,
            overlay: args.overlay,
            heat_max: args.heat_max,
            measure: args.measure,
        }
    }

    /// The culling strategy (the command line's name checked when the view starts).
    pub fn strategy(&self) -> Result<Strategy, String> {
        crate::args::strategy(&self.estimate.culling)
    }

    /// Whether frames measure lights per pixel and FDR: asked for, or the heat map shows them.
    pub fn measures(&self) -> bool {
        self.shader == Shader::Vpl && (self.measure || self.overlay == Overlay::Heatmap)
    }

    /// One `width` x `height` GPU frame with these controls.
    pub fn settings(&self, width: u32, height: u32) -> Result<RenderSettings, String> {
        let method = self.estimate.method(
            self.shader,
            &self.pipeline,
            &self.importance,
            self.measures(),
        )?;
        Ok(RenderSettings {
            width,
            height,
            rsm_resolution: self.rsm,
            seed: self.seed,
            method,
            visibility: false,
            spp: 1,
            lobes: self.lobes.selection(),
        })
    }

    /// The `slc render` options that render what these controls show (for saved settings).
    pub fn render_options(&self, width: u32, height: u32) -> String {
        let mut o = format!(
            "--backend gpu --width {width} --height {height} --rsm {} --seed {} --lobes {} \
             --exposure {}",
            self.rsm,
            self.seed,
            value_name(self.lobes),
            self.exposure
        );
        match self.shader {
            Shader::Vsgl => {
                let i = &self.importance;
                o += &format!(
                    " --shader vsgl --vsgls {} --vsgl-importance {} --camera-vsgls {} \
                     --vsgl-diffuse {}",
                    self.estimate.vsgls,
                    value_name(i.vsgl_importance),
                    i.camera_vsgls,
                    value_name(i.vsgl_diffuse)
                )
            }
            Shader::Vpl => {
                o += &format!(
                    " --culling {} --delta {} --interleave {}",
                    self.estimate.culling, self.estimate.delta, self.pipeline.interleave
                );
                if self.pipeline.no_denoise {
                    o += " --no-denoise";
                }
            }
        }
        o
    }
}

/// The command-line spelling of an option value.
pub fn value_name(v: impl ValueEnum) -> String {
    v.to_possible_value()
        .map_or_else(String::new, |p| p.get_name().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render_cmd::RenderArgs;
    use clap::Parser;

    #[derive(Parser)]
    struct Render {
        #[command(flatten)]
        render: RenderArgs,
    }

    #[derive(Parser)]
    struct View {
        #[command(flatten)]
        view: ViewArgs,
    }

    #[test]
    fn render_options_are_options_of_slc_render_with_the_same_values() {
        for view_args in [
            vec!["--culling", "clustered", "--delta", "0.01", "--no-denoise"],
            vec!["--shader", "vsgl", "--vsgls", "77", "--vsgl-diffuse", "sg"],
        ] {
            let view = View::parse_from(std::iter::once("slc").chain(view_args)).view;
            let controls = Controls::from_args(&view);
            let options = controls.render_options(40, 30);
            let words = ["slc", "scene.toml"].into_iter().chain(options.split(' '));
            let r = Render::try_parse_from(words).expect(&options).render;
            assert_eq!((r.frame.width, r.frame.height), (40, 30));
            assert_eq!(r.frame.shader, controls.shader);
            assert_eq!(r.estimate.culling, controls.estimate.culling);
            assert_eq!(r.estimate.delta, controls.estimate.delta);
            assert_eq!(r.estimate.vsgls, controls.estimate.vsgls);
            assert_eq!(r.pipeline.no_denoise, controls.pipeline.no_denoise);
            assert_eq!(r.importance.vsgl_diffuse, controls.importance.vsgl_diffuse);
            let settings = r
                .estimate
                .method(r.frame.shader, &r.pipeline, &r.importance, false)
                .unwrap();
            assert_eq!(settings, controls.settings(40, 30).unwrap().method);
        }
    }
}
