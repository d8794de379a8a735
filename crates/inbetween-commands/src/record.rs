//! What one input came to: the line a batch's manifest gets and the dict Python's `process_file`
//! returns, one type, so that the two cannot drift apart.

use serde_json::Value;

/// How an input ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// Its output was written.
    Ok,
    /// Nothing was done: its output is up to date, or it is no input (a link out of the folder,
    /// a FIFO); the record's `reason` says which.
    Skipped,
    /// Refused or failed; the record's `error` says why.
    Failed,
}

impl Status {
    /// The manifest's word: `ok`, `skipped`, `failed`.
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::Skipped => "skipped",
            Status::Failed => "failed",
        }
    }
}

/// What a command found in an input: set by the command as it runs.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Figures {
    /// Frames: written (`interp`, all tracks together), read (`reduce`), or the key rows read
    /// (`convert`).
    pub frames: Option<u64>,
    /// Tracks.
    pub tracks: Option<usize>,
    /// Keys: kept (`reduce`) or written (`convert`), all tracks together.
    pub keys: Option<usize>,
    /// `reduce`: the largest error of any track, in the angle unit of the command (with a
    /// distance, a length).
    pub largest_error: Option<f64>,
}

/// One input's record.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// The input, as named.
    pub input: String,
    /// Its output, when it has one.
    pub output: Option<String>,
    /// How it ended.
    pub status: Status,
    /// Seconds it took, to the millisecond (none for an input passed over before any work).
    pub seconds: Option<f64>,
    /// Why it was skipped.
    pub reason: Option<String>,
    /// What the command found, for an input that did not fail.
    pub figures: Option<Figures>,
    /// Why it failed, naming the file.
    pub error: Option<String>,
}

impl Record {
    /// A record of `input` with nothing else known yet.
    pub fn new(input: impl Into<String>, output: Option<String>, status: Status) -> Record {
        Record {
            input: input.into(),
            output,
            status,
            seconds: None,
            reason: None,
            figures: None,
            error: None,
        }
    }

    /// The manifest's JSON object: `input`, `output` (`null` for none), `status`, then what is
    /// known of `seconds`, `reason`, `frames`, `tracks`, `keys`, `largest_error`, `error`.
    pub fn to_json(&self) -> Value {
        let mut line = serde_json::Map::new();
        line.insert("input".into(), self.input.clone().into());
        line.insert("output".into(), self.output.clone().into());
        line.insert("status".into(), self.status.as_str().into());
        let mut put = |k: &str, v: Option<Value>| {
            if let Some(v) = v {
                line.insert(k.into(), v);
            }
        };
        put("seconds", self.seconds.map(Into::into));
        put("reason", self.reason.clone().map(Into::into));
        if let Some(f) = &self.figures {
            put("frames", f.frames.map(Into::into));
            put("tracks", f.tracks.map(Into::into));
            put("keys", f.keys.map(Into::into));
            put("largest_error", f.largest_error.map(Into::into));
        }
        put("error", self.error.clone().map(Into::into));
        Value::Object(line)
    }
}

std::thread_local! {
    static STATS: std::cell::RefCell<Option<Figures>> = const { std::cell::RefCell::new(None) };
}

/// Records figures of the input being processed on this thread, when it runs as one input of a
/// batch or of `process_file` ([`crate::batch::run_job`]; else nothing).
pub fn note(f: impl FnOnce(&mut Figures)) {
    STATS.with(|s| {
        if let Some(stats) = s.borrow_mut().as_mut() {
            f(stats)
        }
    });
}

/// Starts collecting this thread's figures ([`note`]).
pub(crate) fn collect_figures() {
    STATS.with(|s| *s.borrow_mut() = Some(Figures::default()));
}

/// The figures collected on this thread since [`collect_figures`], and stops collecting.
pub(crate) fn collected_figures() -> Option<Figures> {
    STATS.with(|s| s.borrow_mut().take())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_manifest_line_says_only_what_is_known() {
        let mut r = Record::new("in/a.bvh", Some("out/a.json".into()), Status::Ok);
        r.seconds = Some(0.012);
        r.figures = Some(Figures {
            frames: Some(120),
            tracks: Some(2),
            ..Figures::default()
        });
        assert_eq!(
            r.to_json().to_string(),
            r#"{"frames":120,"input":"in/a.bvh","output":"out/a.json","seconds":0.012,"status":"ok","tracks":2}"#
        );
        let passed = Record::new("in/fifo", None, Status::Skipped);
        assert_eq!(
            passed.to_json().to_string(),
            r#"{"input":"in/fifo","output":null,"status":"skipped"}"#
        );
    }
}
