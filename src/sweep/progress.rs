//! How a sweep shows its progress on stderr ([`Progress`]): a bar, log lines or nothing. Every
//! write ignores a closed stderr: a sweep does not stop because nobody reads its progress.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::{IsTerminal, Write};
use std::time::{Duration, Instant};

/// One line on stderr; a closed stderr is ignored.
pub(crate) fn note(line: &str) {
    let _ = writeln!(std::io::stderr(), "{line}");
}

/// How progress is shown on stderr.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Progress {
    /// A bar when stderr is a terminal, else log lines.
    Auto,
    /// A progress bar with the failure count and ETA.
    Bar,
    /// Log lines: when another tenth of the cases is done, when a case finishes 30 s or more
    /// after the previous line, at the end, and after [`IDLE_LINE`] without a case finishing
    /// (long cases in progress).
    Log,
    /// Nothing.
    None,
}

/// In log mode, the silence after which a line says that no case has finished.
pub const IDLE_LINE: Duration = Duration::from_secs(60);

/// The progress of one run on stderr: a bar, log lines or nothing ([`Progress`]).
pub(crate) struct Reporter {
    bar: Option<ProgressBar>,
    log: bool,
    prefix: String,
    total: usize,
    start: Instant,
    last_log: Instant,
    last_logged_decile: usize,
    /// Cases done and failed at the last update, and when a case last finished.
    done: usize,
    failed: usize,
    last_case: Instant,
    /// The silence after which [`Reporter::idle`] writes a line.
    idle_after: Duration,
}

impl Reporter {
    /// A reporter of `total` cases, its lines prefixed by `prefix`.
    pub(crate) fn new(mode: Progress, prefix: String, total: usize) -> Self {
        let tty = std::io::stderr().is_terminal();
        let (bar, log) = match mode {
            Progress::None => (false, false),
            Progress::Bar => (true, false),
            Progress::Log => (false, true),
            Progress::Auto => (tty, !tty),
        };
        let bar = bar.then(|| {
            let pb =
                ProgressBar::with_draw_target(Some(total as u64), ProgressDrawTarget::stderr());
            let style = ProgressStyle::with_template(
                "{prefix} [{bar:30}] {pos}/{len} {msg} elapsed {elapsed} ETA {eta}",
            )
            .map(|s| s.progress_chars("=> "))
            .unwrap_or_else(|_| ProgressStyle::default_bar());
            pb.set_style(style);
            pb.set_prefix(prefix.clone());
            pb.set_message("failures 0");
            pb
        });
        Reporter {
            bar,
            log,
            prefix,
            total,
            start: Instant::now(),
            last_log: Instant::now(),
            last_logged_decile: 0,
            done: 0,
            failed: 0,
            last_case: Instant::now(),
            idle_after: IDLE_LINE,
        }
    }

    /// `done` cases finished, `failed` of them failures.
    pub(crate) fn update(&mut self, done: usize, failed: usize) {
        if done != self.done {
            self.last_case = Instant::now();
        }
        (self.done, self.failed) = (done, failed);
        if let Some(pb) = &self.bar {
            pb.set_position(done as u64);
            pb.set_message(format!("failures {failed}"));
        }
        if self.log {
            let decile = done * 10 / self.total.max(1);
            let due = self.last_log.elapsed() >= Duration::from_secs(30);
            if decile > self.last_logged_decile || due || done == self.total {
                self.last_logged_decile = decile;
                self.last_log = Instant::now();
                let el = self.start.elapsed().as_secs_f64();
                let eta = if done > 0 {
                    el / done as f64 * (self.total - done) as f64
                } else {
                    f64::NAN
                };
                note(&format!(
                    "{}: {done}/{} done, {failed} failures, {el:.1} s elapsed, ETA {eta:.1} s",
                    self.prefix, self.total
                ));
            }
        }
    }

    /// No row arrived lately: in log mode, a line once [`IDLE_LINE`] has passed since the last
    /// case finished and since the last line, so that a log shows a run working through long
    /// cases.
    pub(crate) fn idle(&mut self) {
        if let Some(line) = self.idle_line() {
            self.last_log = Instant::now();
            note(&line);
        }
    }

    /// The line [`Reporter::idle`] writes now, if one is due.
    fn idle_line(&self) -> Option<String> {
        let quiet = self.last_case.elapsed();
        let due = quiet >= self.idle_after && self.last_log.elapsed() >= self.idle_after;
        (self.log && due && self.done < self.total).then(|| {
            format!(
                "{}: {}/{} done, {} failures, {:.1} s elapsed; no case finished in the last {:.0} \
                 s (long cases in progress)",
                self.prefix,
                self.done,
                self.total,
                self.failed,
                self.start.elapsed().as_secs_f64(),
                quiet.as_secs_f64()
            )
        })
    }

    /// The run is over.
    pub(crate) fn finish(&self) {
        if let Some(pb) = &self.bar {
            pb.finish();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_idle_line_is_due_after_the_silence_in_log_mode_only() {
        let mut r = Reporter::new(Progress::Log, "sweep s".into(), 4);
        // Just started: nothing is due.
        assert_eq!(r.idle_line(), None);
        r.idle_after = Duration::ZERO;
        r.update(1, 0);
        let line = r.idle_line().expect("due");
        assert!(
            line.starts_with("sweep s: 1/4 done, 0 failures")
                && line.contains("no case finished in the last"),
            "{line}"
        );
        // Not in the other modes, and not once every case is done.
        let mut quiet = Reporter::new(Progress::None, "s".into(), 4);
        quiet.idle_after = Duration::ZERO;
        assert_eq!(quiet.idle_line(), None);
        r.update(4, 1);
        assert_eq!(r.idle_line(), None);
    }
}
