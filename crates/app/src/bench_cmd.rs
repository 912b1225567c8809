//! `slc bench`: per-pass times of the stochastic pipeline over resolutions and VPL counts, for
//! each culling strategy, in one run (so ratios are measured on the same machine state).
//! Writes `bench.json` / `bench.csv` (every setting a column; medians over `--repeat` runs with
//! the min and max of culling + shading), `bench.md`, and culling and shading against the VPL
//! count with each strategy's slope ([`crate::scaling`]: `scaling_culling.svg`,
//! `scaling_shading.svg`).
use crate::args::{count, positive, strategies, FrameArgs, PipelineArgs, Shader};
use crate::backend::{message, run_on, OnBackend};
use crate::ceiling;
use crate::pdf::write_figure;
use crate::print::PrintWidth;
use crate::scaling::{self, Sample};
use crate::table::{write_csv, SettingsColumns};
use clap::Args;
use serde::Serialize;
use slc_app::cpu_frames::CpuFrames;
use slc_app::limits::check_frames;
use slc_app::out_dir::OutDir;
use slc_app::provenance::Provenance;
use slc_app::repeat::{repeated, Spread};
use slc_core::frame::counts::{HEIGHT, REPEAT, RSM, WIDTH};
use slc_core::frame::PassTime;
use slc_core::frame::{Method, RenderSettings, Stochastic};
use slc_core::shader::frame_timings_of;
use slc_core::{PreparedFrame, Scene, Strategy, Timings};
use std::fmt::Write;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct BenchArgs {
    #[command(flatten)]
    pub frame: FrameArgs,
    #[command(flatten)]
    pub pipeline: PipelineArgs,
    #[arg(long, default_value = "bench")]
    pub out: PathBuf,
    /// Resolutions WxH, comma separated (overrides --width/--height).
    #[arg(long, value_delimiter = ',', default_value = "1280x720,1920x1080")]
    pub resolutions: Vec<String>,
    #[arg(long, value_delimiter = ',', default_value = "128,256", value_parser = count(RSM),
          help = RSM.help("RSM resolutions per face, comma separated (overrides --rsm)"))]
    pub rsms: Vec<u32>,
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "ellipsoid,sphere",
        help = crate::args::culling_help("Strategies to time, comma separated, of")
    )]
    pub culling: Vec<String>,
    /// δ of eq. (2) (a finite number above 0).
    #[arg(long, default_value_t = 1e-3, value_parser = positive)]
    pub delta: f32,
    #[arg(long, default_value_t = 1, value_parser = count(REPEAT),
          help = REPEAT.help("Timing repetitions per strategy and frame, after one warm-up when more than one: the tables give the median of each pass and the min and max of culling + shading"))]
    pub repeat: u32,
    /// Seconds of frames rendered before the first timed run of each frame (the first
    /// strategy), then on until the last five culling + shading times lie within 3% of their
    /// median or twice as long has passed: a GPU raises its clocks under load, and times taken
    /// while it does are not the GPU's (`warmup` in bench.json says how it ended).
    #[arg(long, default_value_t = 0.0, value_parser = warmup_seconds)]
    pub warmup: f64,
}

/// `--warmup`: finite seconds from 0 to an hour.
fn warmup_seconds(s: &str) -> Result<f64, String> {
    let v: f64 = s.parse().map_err(|e| format!("{e}"))?;
    if (0.0..=3600.0).contains(&v) {
        Ok(v)
    } else {
        Err(format!("{v} is not between 0 and 3600 seconds"))
    }
}

fn parse_resolution(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once('x')
        .ok_or_else(|| format!("resolution '{s}' is not WxH"))?;
    let at = |e: String| format!("resolution '{s}': {e}");
    Ok((count(WIDTH)(w).map_err(at)?, count(HEIGHT)(h).map_err(at)?))
}

const PASSES: [&str; 7] = [
    "gbuffer",
    "rsm",
    "vpl_generation",
    "direct",
    "culling",
    "shading",
    "denoise",
];

pub fn run(args: &BenchArgs) -> Result<(), String> {
    if args.frame.shader == Shader::Vsgl {
        return Err(
            "slc bench times the VPL passes; the VSGL passes are timed by \
                    slc sweep --shader vsgl (vsgl_sweep.md)"
                .into(),
        );
    }
    let out = OutDir::open(&args.out)?;
    out.expect([
        "bench.json",
        "bench.csv",
        "bench.md",
        "scaling_culling.svg",
        "scaling_culling.pdf",
        "scaling_shading.svg",
        "scaling_shading.pdf",
    ])?;
    let scene = args.frame.load_renderable()?;
    let strategies = strategies(&args.culling)?;
    let resolutions = args
        .resolutions
        .iter()
        .map(|r| parse_resolution(r))
        .collect::<Result<Vec<_>, _>>()?;
    if args.repeat == 0 || strategies.is_empty() {
        return Err("--repeat must be at least 1 and --culling name a strategy".into());
    }
    run_on(
        args.frame.backend_choice()?,
        Bench {
            args,
            scene,
            strategies,
            resolutions,
            out,
        },
    )
}

struct Bench<'a> {
    args: &'a BenchArgs,
    scene: Scene,
    strategies: Vec<Strategy>,
    resolutions: Vec<(u32, u32)>,
    out: OutDir,
}

impl OnBackend for Bench<'_> {
    fn run<R: CpuFrames>(self, r: &R) -> Result<(), String> {
        let Bench {
            args,
            scene,
            strategies,
            resolutions,
            mut out,
        } = self;
        let base = args.pipeline.stochastic(args.delta, strategies[0], false);
        // The device as the first strategy sees it; every frame is checked below.
        let first = args.frame.settings(Method::Stochastic(base), 1);
        let device = r.info(&first);
        let provenance = Provenance::new(&scene);
        // The listed pairs, and so the ceiling, are counted by the CPU only. The ceiling is
        // measured right before every run: this machine's speed drifts from minute to minute,
        // and a share against a ceiling measured once at the start drifts with it.
        let measure_ceiling = device.backend == "cpu";
        let mut rows = Vec::new();
        // (frame, strategy, culling + shading ms) for the paper's Table 2 layout.
        let mut table2 = Vec::new();
        let mut warmups = Vec::new();
        let mut samples = Vec::new();
        // The GPU passes under each row: markdown lines, and (row, pass) for bench.json.
        let mut passes = Vec::new();
        let mut pass_json: Vec<(usize, PassRow)> = Vec::new();
        let mut md = format!(
            "# slc bench: {}\n\nBackend {}, adapter {}, {} rayon threads, δ = {}, K = {}, lobes {:?}, median (min–max) of {} runs. Milliseconds per pass; M pairs/s: the pixel-VPL pairs the lists hold over the shading time (the CPU counts them; n/a on the GPU, whose lists stay there); ceiling: {}.\n\n{}| resolution | VPLs | strategy | {} | culling + shading | M pairs/s | ceiling M pairs/s | of ceiling | timed by |\n|---|---|---|{}---|---|---|---|---|\n",
            scene.name,
            device.backend,
            device.adapter,
            rayon::current_num_threads(),
            args.delta,
            args.pipeline.interleave,
            args.frame.lobes,
            args.repeat,
            if measure_ceiling {
                "the eight-lane exit test alone on VPLs in L1 with every thread busy \
                 (docs/cpu-ceiling.md), measured right before every run; each run's pairs per \
                 second over its own ceiling, the median of those shares (and of the ceilings) \
                 per row"
            } else {
                "n/a"
            },
            device
                .notes
                .iter()
                .map(|n| format!("- {n}\n"))
                .chain((!device.notes.is_empty()).then(|| "\n".to_string()))
                .collect::<String>(),
            PASSES.join(" | "),
            "---|".repeat(PASSES.len())
        );
        let frame = |(w, h): (u32, u32), rsm: u32| FrameArgs {
            width: w,
            height: h,
            rsm,
            ..args.frame.clone()
        };
        let frames: Vec<_> = resolutions
            .iter()
            .flat_map(|&res| args.rsms.iter().map(move |&rsm| (res, rsm)))
            .map(|(res, rsm)| frame(res, rsm).settings(Method::Stochastic(base), 1))
            .collect();
        check_frames(&scene, &frames)?;
        // Every strategy on every frame, before the first is timed.
        for settings in &frames {
            for &strategy in &strategies {
                let s = Stochastic { strategy, ..base };
                let settings = RenderSettings {
                    method: Method::Stochastic(s),
                    ..settings.clone()
                };
                r.check(&settings).map_err(message)?;
            }
        }
        // One BVH or scene upload for every frame.
        let loaded = r.load(&scene).map_err(message)?;
        for &(w, h) in &resolutions {
            for &rsm in &args.rsms {
                let frame = frame((w, h), rsm);
                let settings = frame.settings(Method::Stochastic(base), 1);
                eprintln!("{w}x{h}, RSM {rsm}²");
                // Every frame's G-buffer, RSM, VPLs and direct light are timed cold, as the
                // first frame's: not in the memory the frame before left.
                r.start_cold();
                let p = r
                    .prepare(&scene, &loaded, &settings, None, &|_| {})
                    .map_err(message)?;
                let input = frame.input(&scene, &loaded, &p);
                let vpl_count = p.vpl_count().map_err(message)?;
                // The passes alone, nothing read back between frames: a GPU that idles while
                // an image travels back lowers its clocks (an H200 fell from 1980 to 345-600
                // MHz between such frames, and every pass took 3-4 times as long).
                let time = |s: Stochastic| -> Result<TimedRun, String> {
                    let out = s.passes(r, input, &|_| {}).map_err(message)?;
                    let (mut t, gpu_timings) =
                        frame_timings_of(&p, &out.timings, out.gpu_timings.as_ref());
                    // The GPU's own times of its passes replace the wall clock where the
                    // adapter has timestamp queries.
                    if let Some(g) = &gpu_timings {
                        for (name, ms) in &g.0 {
                            t.0.retain(|(n, _)| n != name);
                            t.add(name, *ms);
                        }
                    }
                    Ok(TimedRun {
                        timings: t,
                        timestamps: gpu_timings.is_some(),
                        passes: r.last_pass_times().unwrap_or_default(),
                        listed_pairs: r.listed_pairs(&out.lists),
                    })
                };
                if args.warmup > 0.0 {
                    let s = Stochastic {
                        strategy: strategies[0],
                        ..base
                    };
                    let warm = warm_up(args.warmup, || time(s))?;
                    eprintln!(
                        "  warm-up: {} frames of {} in {:.1} s, {}",
                        warm.runs,
                        strategies[0],
                        warm.seconds,
                        if warm.stable { "stable" } else { "not stable" }
                    );
                    warmups.push(serde_json::json!({
                        "resolution": format!("{w}x{h}"),
                        "rsm": rsm,
                        "strategy": strategies[0].name(),
                        "frames": warm.runs,
                        "seconds": warm.seconds,
                        "stable": warm.stable,
                        "last_culling_plus_shading_ms": warm.last_ms,
                        "culling_plus_shading_ms": warm.times,
                    }));
                }
                for &strategy in &strategies {
                    let s = Stochastic { strategy, ..base };
                    let mut ceilings = Vec::new();
                    let runs = repeated(args.repeat, || {
                        ceilings.push(measure_ceiling.then(ceiling::exit_test_mpairs_per_s));
                        time(s)
                    })?;
                    // `repeated` runs one warm-up first where it repeats: its ceiling goes too.
                    let ceilings = &ceilings[ceilings.len() - runs.len()..];
                    let row = BenchRow::of(s, &runs, ceilings);
                    let cs = row.culling_plus_shading_ms;
                    let _ = writeln!(
                        md,
                        "| {w}x{h} | {vpl_count} | {strategy} | {} | {} | {} | {} | {} | {} |",
                        row.pass_medians().map(|ms| format!("{ms:.1}")).join(" | "),
                        row.culling_plus_shading().text(row.runs),
                        row.shading_mpairs_per_s
                            .map_or("n/a".into(), |v| format!("{v:.1}")),
                        row.ceiling_mpairs_per_s
                            .map_or("n/a".into(), |v| format!("{v:.0}")),
                        row.ceiling_share
                            .map_or("n/a".into(), |v| format!("{:.1}%", 100.0 * v)),
                        row.timed_by
                    );
                    for p in pass_rows(&runs) {
                        passes.push(format!(
                            "| {w}x{h} | {vpl_count} | {strategy} | {} | {} | {} | {:.3} |",
                            p.stage, p.pass, p.count, p.ms
                        ));
                        pass_json.push((rows.len(), p));
                    }
                    let settings = SettingsColumns::new(
                        &provenance,
                        &scene,
                        &device,
                        &frame,
                        &args.pipeline,
                        vpl_count,
                    );
                    samples.push(Sample {
                        resolution: (w, h),
                        strategy,
                        vpls: vpl_count,
                        culling_ms: row.culling_ms,
                        shading_ms: row.shading_ms,
                    });
                    rows.push((settings, row));
                    table2.push((format!("{w}x{h}, {vpl_count} VPLs"), strategy, cs));
                    eprintln!("  {strategy}: culling + shading {cs:.1} ms");
                }
            }
        }
        md.push_str(&paper_layout(&table2, &format!("{:?}", args.frame.lobes)));
        let slopes = scaling::slopes(&samples);
        md.push_str(&scaling::markdown(&slopes));
        let style = PrintWidth::Screen.style();
        for (name, svg) in scaling::plots(&samples, &slopes, &scene.name, device.backend, &style)? {
            write_figure(&mut out, name, &svg)?;
        }
        if !passes.is_empty() {
            let _ = write!(
                md,
                "\n## GPU passes\n\nEach pass label's timestamp time summed over its passes \
                 in one frame, median over the runs (ms).\n\n| resolution | VPLs | strategy | \
                 stage | pass | passes | ms |\n|---|---|---|---|---|---|---|\n{}\n",
                passes.join("\n")
            );
        }
        let json = serde_json::json!({
            "provenance": provenance,
            "warmup": warmups,
            "slopes": slopes,
            "rows": rows
                .iter()
                .enumerate()
                .map(|(i, (settings, row))| {
                    let gpu_passes: Vec<&PassRow> =
                        pass_json.iter().filter(|(r, _)| *r == i).map(|(_, p)| p).collect();
                    serde_json::json!({ "settings": settings, "times": row, "gpu_passes": gpu_passes })
                })
                .collect::<Vec<_>>(),
        });
        let json = serde_json::to_string_pretty(&json).map_err(|e| e.to_string())?;
        out.write("bench.json", (json + "\n").as_bytes())?;
        write_csv(&mut out, "bench", rows.iter().map(|(s, r)| (s, r)))?;
        out.write("bench.md", md.as_bytes())?;
        out.commit()?;
        println!("wrote {}", args.out.display());
        Ok(())
    }
}

/// The paper's Table 2 layout of `cells` (frame, strategy, culling + shading ms): one row per
/// strategy under the paper's names, one column per frame, each time followed by its ratio
/// to the tiled ellipsoid's ("ours") on the same frame where that was run.
fn paper_layout(cells: &[(String, Strategy, f64)], lobes: &str) -> String {
    let mut frames: Vec<&str> = Vec::new();
    let mut strategies: Vec<Strategy> = Vec::new();
    for (frame, strategy, _) in cells {
        if !frames.contains(&frame.as_str()) {
            frames.push(frame);
        }
        if !strategies.contains(strategy) {
            strategies.push(*strategy);
        }
    }
    let time = |frame: &str, strategy: Strategy| {
        cells
            .iter()
            .find(|(f, s, _)| f == frame && *s == strategy)
            .map(|c| c.2)
    };
    let mut md = format!(
        "\n## Table 2 layout: culling + shading (ms), {lobes} VPLs\n\nThe paper's Table 2 \
         (its rows; this run's frames as columns); in brackets the ratio to the tiled \
         ellipsoid's time on the same frame.\n\n| method | {} |\n|---|{}\n",
        frames.join(" | "),
        "---|".repeat(frames.len())
    );
    for strategy in strategies {
        let name = match strategy {
            Strategy::Splatting => "Splatting [DS06]".to_string(),
            Strategy::ClusteredRaster => "Clustered shading [OP16]".to_string(),
            Strategy::Ellipsoid => "Our culling & shading (ellipsoid)".to_string(),
            other => other.name().to_string(),
        };
        let row: Vec<String> = frames
            .iter()
            .map(
                |&f| match (time(f, strategy), time(f, Strategy::Ellipsoid)) {
                    (Some(t), Some(ours)) if ours > 0.0 => format!("{t:.2} ({:.2}×)", t / ours),
                    (Some(t), _) => format!("{t:.2}"),
                    (None, _) => "—".into(),
                },
            )
            .collect();
        let _ = writeln!(md, "| {name} | {} |", row.join(" | "));
    }
    md
}

/// One strategy on one frame in `bench.json` / `bench.csv`: the median of each pass over the
/// runs (ms) and the min and max of culling + shading.
#[derive(Serialize)]
struct BenchRow {
    strategy: &'static str,
    delta: f32,
    runs: usize,
    gbuffer_ms: f64,
    rsm_ms: f64,
    vpl_generation_ms: f64,
    direct_ms: f64,
    culling_ms: f64,
    shading_ms: f64,
    denoise_ms: f64,
    culling_plus_shading_ms: f64,
    culling_plus_shading_ms_min: f64,
    culling_plus_shading_ms_max: f64,
    /// Pixel-VPL pairs in the lists (empty where the backend keeps its lists to itself).
    listed_pairs: Option<u64>,
    /// Listed pairs shaded per second (millions), over the median shading time.
    shading_mpairs_per_s: Option<f64>,
    /// The median of the ceilings measured right before each run (`ceiling`), millions of
    /// pairs per second.
    ceiling_mpairs_per_s: Option<f64>,
    /// The median over the runs of each run's listed pairs per second over the ceiling
    /// measured right before it.
    ceiling_share: Option<f64>,
    /// `timestamps` where every run's passes were timed by the GPU's timestamp queries, else
    /// `wall clock`.
    timed_by: &'static str,
}

/// One timed frame of a strategy: its pass times (the GPU's where it has timestamps), the
/// GPU passes under them and the pairs its lists hold.
struct TimedRun {
    timings: Timings,
    timestamps: bool,
    passes: Vec<PassTime>,
    listed_pairs: Option<u64>,
}

/// One GPU pass label of a row in `bench.json`: the median over the runs of its summed
/// timestamp milliseconds.
#[derive(Serialize)]
struct PassRow {
    stage: &'static str,
    pass: &'static str,
    ms: f64,
    /// Passes of this label in one frame.
    count: u32,
}

/// The median time of each GPU pass label over `runs` (labels in the order of the first run;
/// a label missing from a run counts 0 there).
fn pass_rows(runs: &[TimedRun]) -> Vec<PassRow> {
    let Some(first) = runs.first() else {
        return Vec::new();
    };
    first
        .passes
        .iter()
        .map(|p| {
            let of = |r: &TimedRun| {
                r.passes
                    .iter()
                    .find(|q| q.stage == p.stage && q.pass == p.pass)
                    .map_or(0.0, |q| q.ms)
            };
            PassRow {
                stage: p.stage,
                pass: p.pass,
                ms: Spread::of(&runs.iter().map(of).collect::<Vec<_>>()).median,
                count: p.count,
            }
        })
        .collect()
}

/// How a warm-up ended ([`warm_up`]).
struct WarmUp {
    runs: usize,
    seconds: f64,
    stable: bool,
    last_ms: f64,
    /// Culling + shading of every warm-up frame, in order (ms).
    times: Vec<f64>,
}

/// Runs `run` for at least `seconds`, then on until the culling + shading times of the last
/// five runs lie within 3% of their median, or `2 seconds` have passed.
fn warm_up(
    seconds: f64,
    mut run: impl FnMut() -> Result<TimedRun, String>,
) -> Result<WarmUp, String> {
    let start = std::time::Instant::now();
    let mut times = Vec::new();
    loop {
        let t = run()?.timings;
        times.push(t.get("culling") + t.get("shading"));
        let elapsed = start.elapsed().as_secs_f64();
        if let Some(stable) = warmed(&times, elapsed, seconds) {
            return Ok(WarmUp {
                runs: times.len(),
                seconds: elapsed,
                stable,
                last_ms: times[times.len() - 1],
                times,
            });
        }
    }
}

/// Whether a warm-up of `seconds` that took `times` in `elapsed` seconds is over: `Some(true)`
/// once its time is up and the last five times lie within 3% of their median, `Some(false)`
/// at twice its time without that, `None` while it goes on.
fn warmed(times: &[f64], elapsed: f64, seconds: f64) -> Option<bool> {
    let stable = times.len() >= 5 && within(&times[times.len() - 5..], 0.03);
    if elapsed >= seconds && stable {
        Some(true)
    } else if elapsed >= 2.0 * seconds {
        Some(false)
    } else {
        None
    }
}

/// Whether every value lies within `tolerance` (relative) of the values' median.
fn within(values: &[f64], tolerance: f64) -> bool {
    let median = Spread::of(values).median;
    values
        .iter()
        .all(|v| (v - median).abs() <= tolerance * median.abs())
}

impl BenchRow {
    fn of(s: Stochastic, runs: &[TimedRun], ceilings: &[Option<f64>]) -> Self {
        let listed_pairs = runs.last().and_then(|r| r.listed_pairs);
        let timings: Vec<Timings> = runs.iter().map(|r| r.timings.clone()).collect();
        let [gbuffer_ms, rsm_ms, vpl_generation_ms, direct_ms, culling_ms, shading_ms, denoise_ms] =
            PASSES.map(|n| Spread::of_passes(&timings, &[n]).median);
        let cs = Spread::of_passes(&timings, &["culling", "shading"]);
        let shading_mpairs_per_s = listed_pairs
            .filter(|_| shading_ms > 0.0)
            .map(|pairs| pairs as f64 / (shading_ms * 1e3));
        Self {
            strategy: s.strategy.name(),
            delta: s.delta,
            runs: runs.len(),
            gbuffer_ms,
            rsm_ms,
            vpl_generation_ms,
            direct_ms,
            culling_ms,
            shading_ms,
            denoise_ms,
            culling_plus_shading_ms: cs.median,
            culling_plus_shading_ms_min: cs.min,
            culling_plus_shading_ms_max: cs.max,
            listed_pairs,
            shading_mpairs_per_s,
            ceiling_mpairs_per_s: median_of(ceilings.iter().copied()),
            ceiling_share: median_of(timings.iter().zip(ceilings).map(|(t, c)| {
                let shading_ms = t.get("shading");
                let pairs = listed_pairs.filter(|_| shading_ms > 0.0)?;
                Some(pairs as f64 / (shading_ms * 1e3) / (*c)?)
            })),
            timed_by: if !runs.is_empty() && runs.iter().all(|r| r.timestamps) {
                "timestamps"
            } else {
                "wall clock"
            },
        }
    }

    /// The median of each pass, in the order of [`PASSES`].
    fn pass_medians(&self) -> [f64; 7] {
        [
            self.gbuffer_ms,
            self.rsm_ms,
            self.vpl_generation_ms,
            self.direct_ms,
            self.culling_ms,
            self.shading_ms,
            self.denoise_ms,
        ]
    }

    fn culling_plus_shading(&self) -> Spread {
        Spread {
            median: self.culling_plus_shading_ms,
            min: self.culling_plus_shading_ms_min,
            max: self.culling_plus_shading_ms_max,
        }
    }
}

/// The median of `values`, `None` where any is missing or there are none.
fn median_of(values: impl Iterator<Item = Option<f64>>) -> Option<f64> {
    let values: Option<Vec<f64>> = values.collect();
    values
        .filter(|v| !v.is_empty())
        .map(|v| Spread::of(&v).median)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stochastic settings of the rows under test.
    const ELLIPSOID: Stochastic = Stochastic {
        denoise: false,
        ..Stochastic::PAPER
    };

    /// Each run's share is its own pairs per second over the ceiling measured before it: a
    /// machine slowing down between runs slows both and leaves the share where it was.
    #[test]
    fn each_runs_share_is_against_its_own_ceiling() {
        let run = |shading_ms: f64, listed_pairs: Option<u64>| {
            let mut t = Timings::default();
            t.add("shading", shading_ms);
            TimedRun {
                timings: t,
                timestamps: false,
                passes: Vec::new(),
                listed_pairs,
            }
        };
        // 1e6 pairs in 1 ms is 1,000 M pairs/s; in 2 ms, 500.
        let runs = [1.0, 2.0, 2.0].map(|ms| run(ms, Some(1_000_000)));
        let ceilings = [Some(4000.0), Some(2000.0), Some(2000.0)];
        let row = BenchRow::of(ELLIPSOID, &runs, &ceilings);
        assert_eq!(row.ceiling_share, Some(0.25));
        assert_eq!(row.ceiling_mpairs_per_s, Some(2000.0));
        assert_eq!(row.shading_mpairs_per_s, Some(500.0));
        assert_eq!(row.timed_by, "wall clock");
        // No share without a ceiling (a GPU run) or without the listed pairs.
        assert_eq!(
            BenchRow::of(ELLIPSOID, &runs, &[None; 3]).ceiling_share,
            None
        );
        let unlisted = [1.0, 2.0, 2.0].map(|ms| run(ms, None));
        assert_eq!(
            BenchRow::of(ELLIPSOID, &unlisted, &ceilings).ceiling_share,
            None
        );
    }

    /// A row is timed by timestamps only where every run was; each GPU pass label gets its
    /// median over the runs, 0 in a run that lacks it.
    #[test]
    fn rows_say_how_they_were_timed_and_give_each_pass_its_median() {
        let run = |timestamps: bool, tiled: f64, bounds: Option<f64>| {
            let mut passes = vec![PassTime {
                stage: "shading",
                pass: "tiled shade",
                ms: tiled,
                count: 1,
            }];
            passes.extend(bounds.map(|ms| PassTime {
                stage: "culling",
                pass: "bounds",
                ms,
                count: 2,
            }));
            TimedRun {
                timings: Timings::default(),
                timestamps,
                passes,
                listed_pairs: None,
            }
        };
        let runs = [
            run(true, 3.0, Some(0.5)),
            run(true, 1.0, None),
            run(true, 2.0, Some(0.25)),
        ];
        assert_eq!(
            BenchRow::of(ELLIPSOID, &runs, &[None; 3]).timed_by,
            "timestamps"
        );
        let rows = pass_rows(&runs);
        assert_eq!(rows.len(), 2);
        assert_eq!((rows[0].pass, rows[0].ms), ("tiled shade", 2.0));
        assert_eq!(
            (rows[1].stage, rows[1].ms, rows[1].count),
            ("culling", 0.25, 2)
        );
        let mixed = [run(true, 1.0, None), run(false, 1.0, None)];
        assert_eq!(
            BenchRow::of(ELLIPSOID, &mixed, &[None; 2]).timed_by,
            "wall clock"
        );
    }

    /// The warm-up runs until its time is up and the last five times agree within 3%, or
    /// gives up, not stable, at twice its time.
    #[test]
    fn warm_up_waits_for_stable_times() {
        // Falling like clocks rising, then flat.
        let times: Vec<f64> = (1..=14)
            .map(|i| if i < 10 { 100.0 / i as f64 } else { 5.0 })
            .collect();
        assert_eq!(warmed(&times[..13], 1.5, 1.0), None);
        assert_eq!(warmed(&times, 1.5, 1.0), Some(true));
        // Stable early, but its time is not up.
        assert_eq!(warmed(&times, 0.5, 1.0), None);
        // Never stable: given up at twice its time.
        let alternating = [1.0, 1.1, 1.0, 1.1, 1.0, 1.1];
        assert_eq!(warmed(&alternating, 1.5, 1.0), None);
        assert_eq!(warmed(&alternating, 2.0, 1.0), Some(false));
        assert!(within(&[1.0, 1.02, 0.98], 0.03) && !within(&[1.0, 1.1, 1.0], 0.03));
        // The loop: a run a time, stopping where `warmed` says.
        let mut i = 0.0;
        let w = warm_up(0.0, || {
            i += 1.0;
            let mut t = Timings::default();
            t.add("culling", i);
            Ok(TimedRun {
                timings: t,
                timestamps: true,
                passes: Vec::new(),
                listed_pairs: None,
            })
        })
        .unwrap();
        assert!(!w.stable && w.runs == 1 && w.last_ms == 1.0);
    }

    /// Rows under the paper's names, one column per frame, ratios to the ellipsoid's time,
    /// a dash where a strategy did not run on a frame.
    #[test]
    fn paper_layout_has_the_papers_rows_and_ratios() {
        let cells = vec![
            ("64x48, 10 VPLs".to_string(), Strategy::Ellipsoid, 2.0),
            ("64x48, 10 VPLs".to_string(), Strategy::Splatting, 5.0),
            ("64x48, 10 VPLs".to_string(), Strategy::ClusteredRaster, 3.0),
            ("128x96, 40 VPLs".to_string(), Strategy::Splatting, 7.0),
        ];
        let md = paper_layout(&cells, "Glossy");
        assert!(md.contains("Glossy VPLs"), "{md}");
        assert!(
            md.contains("| method | 64x48, 10 VPLs | 128x96, 40 VPLs |"),
            "{md}"
        );
        assert!(
            md.contains("| Our culling & shading (ellipsoid) | 2.00 (1.00×) | — |"),
            "{md}"
        );
        assert!(
            md.contains("| Splatting [DS06] | 5.00 (2.50×) | 7.00 |"),
            "{md}"
        );
        assert!(
            md.contains("| Clustered shading [OP16] | 3.00 (1.50×) | — |"),
            "{md}"
        );
    }
}
