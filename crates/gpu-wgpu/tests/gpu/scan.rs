//! The exclusive scan of `device/scan.wesl` against the plain prefix sum: counts from none to
//! runs of 35,157 values per invocation, the total after the values and in the status, and a
//! total beyond u32 flagged there. Walked one value per iteration, those runs took 70,314
//! iterations in the kernel's two loops, past the 65,535 llvmpipe runs in one invocation, and
//! the offsets came out wrong there; walked eight at a time they take a fraction of it.
use crate::common::gpu;
use slc_gpu_wgpu::cull::records::GpuCullStatus;
use slc_gpu_wgpu::device::buffers::{read_back, upload};
use slc_gpu_wgpu::device::scan::ScanPass;
use slc_gpu_wgpu::device::GpuContext;

/// The scanned values (n + 1, the total last) and the status record after scanning `values`.
fn scanned(ctx: &GpuContext, scan: &ScanPass, values: &[u32]) -> (Vec<u32>, GpuCullStatus) {
    let mut padded = values.to_vec();
    padded.push(0);
    let buffer = upload(ctx, "scan values", &padded).unwrap();
    let status = upload(ctx, "scan status", &[GpuCullStatus::CLEAR]).unwrap();
    ctx.submit("scan test", |encoder| {
        scan.encode(ctx, encoder, &buffer, values.len() as u32, &status)
    })
    .unwrap();
    let out = read_back(ctx, "scan values", &buffer, padded.len()).unwrap();
    let status = read_back::<GpuCullStatus>(ctx, "scan status", &status, 1).unwrap();
    (out, status[0])
}

#[test]
fn the_scan_is_the_exclusive_prefix_sum() {
    let Some(ctx) = gpu() else { return };
    let scan = ScanPass::new(&ctx);
    for n in [
        0usize,
        1,
        7,
        8,
        255,
        256,
        257,
        2_048,
        2_051,
        3_840,
        10_257,
        (1 << 21) + 13,
        9_000_001,
    ] {
        let values: Vec<u32> = (0..n as u32)
            .map(|i| i.wrapping_mul(2_654_435_761) >> 24)
            .collect();
        let mut want = Vec::with_capacity(n + 1);
        let mut sum = 0u32;
        for &v in &values {
            want.push(sum);
            sum += v;
        }
        want.push(sum);
        let (got, status) = scanned(&ctx, &scan, &values);
        assert!(got == want, "n {n}");
        assert_eq!((status.total, status.total_overflow), (sum, 0), "n {n}");
    }
    let (_, status) = scanned(&ctx, &scan, &[u32::MAX; 3000]);
    assert_eq!(status.total_overflow, 1);
    // A sum beyond u32 within the first invocation's run alone (runs of 9 values), which
    // wraps to 0 before the runs' sums are scanned: only the run's walk can flag it.
    let mut values = vec![0u32; 2_051];
    values[..2].copy_from_slice(&[u32::MAX, 1]);
    let (_, status) = scanned(&ctx, &scan, &values);
    assert_eq!(status.total_overflow, 1);
}
