//! Cancellation on the CPU backend: a raised [`Cancel`] stops a frame within the tile, row or
//! pass it is in (every method), with [`RenderError::Cancelled`] and nothing returned; a flag
//! never raised changes nothing.
use slc_core::frame::{
    DiffuseEmission, Importance, LightSampling, LobeSelection, Method, RenderError, RenderSettings,
    Stochastic,
};
use slc_core::{builtin, Cancel, Strategy};
use slc_cpu_ref::render;
use std::sync::atomic::{AtomicU64, Ordering};

const SIZE: (u32, u32) = (192, 128);
const SPP: u32 = 3;

fn settings(method: Method) -> RenderSettings {
    RenderSettings {
        width: SIZE.0,
        height: SIZE.1,
        rsm_resolution: 24,
        seed: 5,
        method,
        visibility: false,
        spp: SPP,
        lobes: LobeSelection::Both,
    }
}

fn methods() -> [Method; 4] {
    [
        Method::Stochastic(Stochastic {
            delta: 1e-3,
            strategy: Strategy::Ellipsoid,
            interleave: 4,
            denoise: true,
            metrics: true,
        }),
        Method::VplReference,
        Method::Path,
        Method::Vsgl(LightSampling {
            count: 256,
            importance: Importance::Flux,
            diffuse: DiffuseEmission::ClampedCosine,
        }),
    ]
}

/// The flag raised by the monitor itself once the first pixels are reported: the frame stops
/// where it is, long before its last pixel-pass.
#[test]
fn a_raised_flag_stops_every_method_within_its_pass() {
    let scene = builtin("default").unwrap();
    let total = u64::from(SIZE.0 * SIZE.1 * SPP);
    for method in methods() {
        let cancel = Cancel::new();
        let done = AtomicU64::new(0);
        let report = |n| {
            done.fetch_add(n, Ordering::Relaxed);
            cancel.cancel();
        };
        let result = render(&scene, &settings(method), &cancel.reporting(&report));
        assert!(
            matches!(result, Err(RenderError::Cancelled)),
            "{method:?}: {:?}",
            result.map(|f| f.vpl_count)
        );
        // Tiles or rows already begun on the other threads finish; none is begun after.
        let done = done.load(Ordering::Relaxed);
        assert!(
            done > 0 && done <= total / u64::from(SPP) / 2,
            "{method:?}: {done} of {total} pixel-passes reported after the cancel"
        );
    }
}

/// A flag raised before the frame stops it before any work; one never raised gives the same
/// frame, bit for bit, as a plain closure.
#[test]
fn a_flag_raised_before_stops_at_once_and_one_never_raised_changes_nothing() {
    let scene = builtin("default").unwrap();
    let s = settings(methods()[0]);
    let cancel = Cancel::new();
    cancel.cancel();
    let reported = AtomicU64::new(0);
    let report = |n| {
        reported.fetch_add(n, Ordering::Relaxed);
    };
    assert!(matches!(
        render(&scene, &s, &cancel.reporting(&report)),
        Err(RenderError::Cancelled)
    ));
    assert_eq!(reported.load(Ordering::Relaxed), 0);
    cancel.reset();
    let watched = render(&scene, &s, &cancel).unwrap();
    let plain = render(&scene, &s, &|_| {}).unwrap();
    assert_eq!(watched.indirect, plain.indirect);
    assert_eq!(watched.direct, plain.direct);
    assert_eq!(watched.metrics, plain.metrics);
}

/// A monitor cancelled after a number of checks, whatever thread makes them.
struct CancelledAfter {
    checks_left: std::sync::atomic::AtomicI64,
    advanced: AtomicU64,
}

impl slc_core::Monitor for CancelledAfter {
    fn advance(&self, done: u64) {
        self.advanced.fetch_add(done, Ordering::Relaxed);
    }

    fn cancelled(&self) -> bool {
        self.checks_left.fetch_sub(1, Ordering::Relaxed) <= 0
    }
}

/// Cancelled while the G-buffer is traced (it checks every pixel), the frame stops before any
/// pixel is shaded.
#[test]
fn a_frame_cancelled_while_it_is_prepared_shades_nothing() {
    let scene = builtin("default").unwrap();
    let monitor = CancelledAfter {
        checks_left: 500.into(),
        advanced: AtomicU64::new(0),
    };
    let result = render(&scene, &settings(methods()[0]), &monitor);
    assert!(matches!(result, Err(RenderError::Cancelled)));
    assert_eq!(monitor.advanced.load(Ordering::Relaxed), 0);
    // The G-buffer's pixels are far more than the checks it was allowed.
    assert!(monitor.checks_left.load(Ordering::Relaxed) < -1000);
}
