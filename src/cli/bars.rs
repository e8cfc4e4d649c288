//! Progress bars on a terminal (indicatif): over derivation steps, and
//! over the stages of making a picture; never in a pipe or on CI.

use super::Io;
use crate::driver::picture;
use crate::driver::RunOptions;

/// Whether progress is shown: on a terminal, outside CI.
fn show_progress(io: &Io<'_>) -> bool {
    io.terminal && std::env::var_os("CI").is_none()
}

/// A progress bar for a long stage (`stage`: drawing, encoding, mesh,
/// frames), counting `unit`s, when [`show_progress`]; its length is set
/// when the stage starts. Never in pipes: `io.terminal` is false there.
pub(crate) fn stage_bar(io: &Io<'_>, stage: &str, unit: &str) -> Option<indicatif::ProgressBar> {
    show_progress(io).then(|| new_stage_bar(stage, unit))
}

/// A bar for `stage`, counting `unit`s.
fn new_stage_bar(stage: &str, unit: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(0);
    let template = format!("{stage:9} {{bar:30}} {{pos}}/{{len}} {unit}");
    bar.set_style(indicatif::ProgressStyle::with_template(&template).expect("valid template"));
    bar.set_draw_target(indicatif::ProgressDrawTarget::stderr_with_hz(10));
    bar
}

/// The progress bars of a picture being made, each started when its
/// stage first reports ([`picture::Progress`]), when [`show_progress`].
pub(super) struct Bars {
    show: bool,
    steps: Option<indicatif::ProgressBar>,
    stage: Option<indicatif::ProgressBar>,
}

impl Bars {
    pub(super) fn new(io: &Io<'_>) -> Bars {
        Bars {
            show: show_progress(io),
            steps: None,
            stage: None,
        }
    }

    /// Clears the bars from the terminal.
    pub(super) fn clear(self) {
        self.steps
            .iter()
            .chain(&self.stage)
            .for_each(|b| b.finish_and_clear());
    }
}

impl picture::Progress for Bars {
    fn derived(&mut self, step: u64, steps: u64, symbols: usize) {
        if !self.show || steps == 0 {
            return;
        }
        let bar = self.steps.get_or_insert_with(|| new_step_bar(steps));
        bar.set_position(step);
        bar.set_message(format!("{symbols} symbols"));
    }

    fn advanced(&mut self, stage: picture::Stage, done: u64, total: u64) {
        if !self.show {
            return;
        }
        if let Some(steps) = self.steps.take() {
            steps.finish_and_clear();
        }
        let (name, unit) = match stage {
            picture::Stage::Drawing => ("drawing", "segments"),
            picture::Stage::Meshing => ("meshing", "primitives"),
            picture::Stage::Frames => ("frames", "frames"),
        };
        let bar = self.stage.get_or_insert_with(|| new_stage_bar(name, unit));
        bar.set_length(total);
        bar.set_position(done);
    }
}

/// A progress bar over derivation steps, when [`show_progress`].
pub(super) fn step_bar(
    io: &Io<'_>,
    sys: &crate::ir::System,
    opts: &RunOptions,
) -> Option<indicatif::ProgressBar> {
    let steps = opts.derive_options(sys).steps;
    (show_progress(io) && steps > 0).then(|| new_step_bar(steps))
}

/// A bar over `steps` derivation steps.
fn new_step_bar(steps: u64) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(steps);
    bar.set_style(
        indicatif::ProgressStyle::with_template("deriving {bar:30} step {pos}/{len} {msg}")
            .expect("valid template"),
    );
    bar.set_draw_target(indicatif::ProgressDrawTarget::stderr_with_hz(10));
    bar
}
