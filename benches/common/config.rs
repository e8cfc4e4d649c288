//! The criterion settings of the benchmarks whose one run takes seconds
//! (drawing and meshing whole plants): ten samples, five seconds each.

use criterion::Criterion;
use std::time::Duration;

pub fn seconds_long() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(5))
}
