//! A user's measurement held against a run (issue 15: "let a user hold the model against
//! their own measurements"): a CSV of (time, lateral position) read strictly, every
//! problem a named error with its line, and the comparison with a channel of the run's
//! history — the model interpolated linearly at each measured time, the difference
//! model − measured, its RMS and largest magnitude.
//!
//! **File format**: UTF-8 text, one sample a line, two numbers separated by a comma (or
//! a semicolon, or a tab): time t (s, counted from the start of the drums' rotation, as
//! the scene's steering histories) and the lateral position (m, +z along the drum axes,
//! the belt's centre line from its position on aligned drums). Blank lines and lines
//! starting with `#` are skipped; the first other line may be a header (e.g.
//! `time,lateral`) when its first field is not a number. Times finite and strictly
//! increasing; at least one sample.

use std::path::{Path, PathBuf};

use drive::result::{MeasuredComparison, TimeSeries};

/// Why a measurement file is refused (nothing is solved or written).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeasuredError {
    /// The file cannot be read (or is not UTF-8).
    #[error("measured file {}: cannot read it: {message}", .file.display())]
    Io {
        /// The file.
        file: PathBuf,
        /// The system's message.
        message: String,
    },
    /// A data line that is not two numbers.
    #[error("measured file {}, line {line}: {reason} (found {found:?}); each line is `time,lateral` — two numbers separated by a comma, semicolon or tab", .file.display())]
    Malformed {
        /// The file.
        file: PathBuf,
        /// 1-based line.
        line: usize,
        /// What is wrong.
        reason: &'static str,
        /// The line as found (clipped).
        found: String,
    },
    /// A value that is NaN or infinite.
    #[error("measured file {}, line {line}: {what} is not finite ({value})", .file.display())]
    NotFinite {
        /// The file.
        file: PathBuf,
        /// 1-based line.
        line: usize,
        /// `time` or `lateral position`.
        what: &'static str,
        /// The value.
        value: f64,
    },
    /// Times not strictly increasing.
    #[error("measured file {}, line {line}: time {time} s does not follow {previous} s (times must increase strictly)", .file.display())]
    NotIncreasing {
        /// The file.
        file: PathBuf,
        /// 1-based line.
        line: usize,
        /// Its time, s.
        time: f64,
        /// The previous sample's, s.
        previous: f64,
    },
    /// No data line.
    #[error("measured file {}: no samples (blank lines, `#` comments and one header only)", .file.display())]
    Empty {
        /// The file.
        file: PathBuf,
    },
    /// The run has no history channel of that name.
    #[error("the run has no history channel `{channel}` to compare with (channels: {})", .available.join(", "))]
    NoChannel {
        /// The channel asked for.
        channel: String,
        /// The channels there are.
        available: Vec<String>,
    },
    /// No measured time falls inside the simulated time of the rotation.
    #[error("no measured time lies in the simulated rotation 0 … {end} s (measured {first} … {last} s; times count from the start of the drums' rotation)")]
    NoOverlap {
        /// End of the simulated rotation, s.
        end: f64,
        /// First measured time, s.
        first: f64,
        /// Last measured time, s.
        last: f64,
    },
}

/// A measured series: (t, lateral position) samples.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    /// The file it was read from.
    pub file: PathBuf,
    /// Times, s, strictly increasing.
    pub time: Vec<f64>,
    /// Lateral positions, m.
    pub lateral: Vec<f64>,
}

fn clip(line: &str) -> String {
    line.chars().take(60).collect()
}

impl Measured {
    /// Reads and checks a measurement file (module documentation).
    ///
    /// # Errors
    /// The first problem, named with its line ([`MeasuredError`]).
    pub fn read(file: &Path) -> Result<Measured, MeasuredError> {
        let text = std::fs::read_to_string(file).map_err(|e| MeasuredError::Io { file: file.to_path_buf(), message: e.to_string() })?;
        Measured::parse(&text, file)
    }

    /// Parses the text of a measurement file named `file` (for messages).
    ///
    /// # Errors
    /// As [`Measured::read`].
    pub fn parse(text: &str, file: &Path) -> Result<Measured, MeasuredError> {
        let file = file.to_path_buf();
        let (mut time, mut lateral) = (Vec::new(), Vec::new());
        let mut header_allowed = true;
        for (k, raw) in text.strip_prefix('\u{FEFF}').unwrap_or(text).lines().enumerate() {
            let line = k + 1;
            let trimmed = raw.trim();
            if trimmed.is_empty() || trimmed.starts_with('#') {
                continue;
            }
            let fields: Vec<&str> = trimmed.split([',', ';', '\t']).map(str::trim).collect();
            let malformed = |reason| MeasuredError::Malformed { file: file.clone(), line, reason, found: clip(raw) };
            if header_allowed && fields.first().is_some_and(|f| f.parse::<f64>().is_err()) {
                header_allowed = false;
                if fields.len() != 2 {
                    return Err(malformed("a header line must name two columns"));
                }
                continue;
            }
            header_allowed = false;
            if fields.len() != 2 {
                return Err(malformed(if fields.len() < 2 { "one field, two expected" } else { "more than two fields" }));
            }
            let t: f64 = fields[0].parse().map_err(|_| malformed("the time is not a number"))?;
            let z: f64 = fields[1].parse().map_err(|_| malformed("the lateral position is not a number"))?;
            if !t.is_finite() {
                return Err(MeasuredError::NotFinite { file, line, what: "time", value: t });
            }
            if !z.is_finite() {
                return Err(MeasuredError::NotFinite { file, line, what: "lateral position", value: z });
            }
            if let Some(&previous) = time.last() {
                if t <= previous {
                    return Err(MeasuredError::NotIncreasing { file, line, time: t, previous });
                }
            }
            time.push(t);
            lateral.push(z);
        }
        if time.is_empty() {
            return Err(MeasuredError::Empty { file });
        }
        Ok(Measured { file, time, lateral })
    }

    /// The comparison with `channel` of `history`, whose rotation starts at
    /// `rotation_start` (s, run time): at each measured time t in [0, end of the run −
    /// start] the model at start + t (linear between its samples), the difference model −
    /// measured; samples outside are counted, not compared.
    ///
    /// # Errors
    /// [`MeasuredError::NoChannel`], [`MeasuredError::NoOverlap`].
    pub fn compare(&self, history: &TimeSeries, channel: &str, rotation_start: f64) -> Result<MeasuredComparison, MeasuredError> {
        let values = history.channel(channel).ok_or_else(|| MeasuredError::NoChannel { channel: channel.to_string(), available: history.series.keys().cloned().collect() })?;
        let times: Vec<f64> = history.time.iter().map(|t| t - rotation_start).collect();
        let end = times.last().copied().unwrap_or(0.0);
        let slack = 1e-9 * end.abs().max(1.0);
        let mut out = MeasuredComparison { file: self.file.display().to_string(), channel: channel.to_string(), ..Default::default() };
        for (&t, &z) in self.time.iter().zip(&self.lateral) {
            if t < -slack || t > end + slack || times.is_empty() {
                out.outside += 1;
                continue;
            }
            let i = times.partition_point(|&x| x <= t).clamp(1, times.len().max(2) - 1);
            let model = if times.len() == 1 {
                values[0]
            } else {
                let (t0, t1) = (times[i - 1], times[i]);
                let w = if t1 > t0 { ((t - t0) / (t1 - t0)).clamp(0.0, 1.0) } else { 0.0 };
                values[i - 1] + w * (values[i] - values[i - 1])
            };
            out.time.push(t);
            out.measured.push(z);
            out.model.push(model);
            out.difference.push(model - z);
        }
        if out.time.is_empty() {
            return Err(MeasuredError::NoOverlap { end, first: self.time[0], last: self.time[self.time.len() - 1] });
        }
        let n = out.difference.len() as f64;
        out.rms_difference = (out.difference.iter().map(|d| d * d).sum::<f64>() / n).sqrt();
        out.max_difference = out.difference.iter().fold(0.0_f64, |m, d| m.max(d.abs()));
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Measured, MeasuredError> {
        Measured::parse(text, Path::new("m.csv"))
    }

    /// Header, comments, blank lines and three separators are read; every malformed
    /// input is refused with its line.
    #[test]
    fn reads_strictly_and_names_the_line() {
        let m = parse("# test stand\ntime,lateral\n0.0, 0.0\n\n0.5;1e-4\n1.0\t2e-4\n").unwrap();
        assert_eq!(m.time, vec![0.0, 0.5, 1.0]);
        assert_eq!(m.lateral, vec![0.0, 1e-4, 2e-4]);
        assert!(matches!(parse("0,0\n1\n"), Err(MeasuredError::Malformed { line: 2, .. })));
        assert!(matches!(parse("0,0\n1,2,3\n"), Err(MeasuredError::Malformed { line: 2, .. })));
        assert!(matches!(parse("0,0\n1,abc\n"), Err(MeasuredError::Malformed { line: 2, reason: "the lateral position is not a number", .. })));
        assert!(matches!(parse("0,0\nx,1\n"), Err(MeasuredError::Malformed { line: 2, reason: "the time is not a number", .. })));
        assert!(matches!(parse("0,0\n1,NaN\n"), Err(MeasuredError::NotFinite { line: 2, what: "lateral position", .. })));
        assert!(matches!(parse("0,0\n0,1\n"), Err(MeasuredError::NotIncreasing { line: 2, .. })));
        assert!(matches!(parse("# nothing\ntime,lateral\n"), Err(MeasuredError::Empty { .. })));
        assert!(matches!(parse("a,b,c\n0,0\n"), Err(MeasuredError::Malformed { line: 1, .. })));
        let e = parse("0,0\n1,abc\n").unwrap_err().to_string();
        assert!(e.contains("m.csv, line 2") && e.contains("\"1,abc\""), "{e}");
    }

    /// On a linear model z = 2t the comparison interpolates exactly: the difference is
    /// model − measured at each time inside the run, samples outside are counted.
    #[test]
    fn compares_at_the_measured_times() {
        let mut h = TimeSeries::default();
        for k in 0..=10 {
            let t = 3.0 + 0.5 * k as f64;
            h.push(t, &[("lateral_offset", 2.0 * (t - 3.0))]);
        }
        let m = parse("0.25,0.4\n1.0,2.0\n4.9,0\n9.0,1\n").unwrap();
        let c = m.compare(&h, "lateral_offset", 3.0).unwrap();
        assert_eq!(c.time, vec![0.25, 1.0, 4.9]);
        assert_eq!(c.outside, 1);
        for (d, e) in c.difference.iter().zip([0.1, 0.0, 9.8]) {
            assert!((d - e).abs() < 1e-12, "{d} vs {e}");
        }
        assert!((c.max_difference - 9.8).abs() < 1e-12);
        assert!(matches!(m.compare(&h, "nope", 3.0), Err(MeasuredError::NoChannel { .. })));
        let late = parse("100,0\n").unwrap();
        assert!(matches!(late.compare(&h, "lateral_offset", 3.0), Err(MeasuredError::NoOverlap { .. })));
    }
}
