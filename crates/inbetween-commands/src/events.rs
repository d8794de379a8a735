//! What a command tells as it runs, besides its result: warnings about the input or options, and
//! the lines of a report asked for (`-v`). The library prints nothing; the caller gives the sink
//! and prints, collects or drops what it is told.

/// A command's sink for what it tells.
pub trait Events {
    /// A warning: the result is written, but something in the input or the options deserves a
    /// look (the command line prints `inbetween: warning: …`).
    fn warning(&mut self, message: &str);
    /// A line of a report the user asked for: figures, not problems (the command line prints it
    /// as it is).
    fn report(&mut self, line: &str);
}

/// Events kept in order of kind, for a caller that hands them on later (a batch's job, Python).
#[derive(Debug, Default, Clone, PartialEq)]
pub struct Collected {
    /// The warnings, in order.
    pub warnings: Vec<String>,
    /// The report lines, in order.
    pub reports: Vec<String>,
}

impl Events for Collected {
    fn warning(&mut self, message: &str) {
        self.warnings.push(message.to_string());
    }

    fn report(&mut self, line: &str) {
        self.reports.push(line.to_string());
    }
}
