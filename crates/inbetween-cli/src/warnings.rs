//! Warnings on stderr, bounded: each kind of warning is printed at most [`PER_KIND`] times per
//! run, then one line says how many more there were.
//!
//! The kind of a warning is its text with the numbers and the quoted parts taken out, so that
//! "keys.csv:12: quaternion norm 1.5 …" and "keys.csv:13: quaternion norm 0.9 …" are one kind,
//! and the same warning about two tracks (names in quotes) is one kind too.

use std::collections::HashMap;

/// How many warnings of one kind are printed.
pub const PER_KIND: usize = 10;

/// Counts warnings by kind and prints the first [`PER_KIND`] of each.
#[derive(Default)]
pub struct Warnings {
    /// Kind → its index in `kinds`.
    seen: HashMap<String, usize>,
    /// The first warning of each kind and how many there were, in order of first appearance.
    kinds: Vec<(String, usize)>,
}

/// The kind of a warning: its text without digits and without `"…"` quoted parts.
fn kind(msg: &str) -> String {
    let mut out = String::with_capacity(msg.len());
    let mut quoted = false;
    for c in msg.chars() {
        if c == '"' {
            quoted = !quoted;
            out.push(c);
        } else if !quoted && !c.is_ascii_digit() {
            out.push(c);
        }
    }
    out
}

/// `msg` without its leading location: the `: `-ended segments with no space outside
/// parentheses and quotes but before a parenthesis (`clip.gltf: `, `keys.csv:3: `,
/// `animations[0].channels[1] (node "Hips"): `). The whole message when nothing else would be
/// left.
fn without_location(msg: &str) -> &str {
    let mut rest = msg;
    while let Some(end) = rest.find(": ") {
        let (mut depth, mut quoted) = (0i32, false);
        let segment = &rest[..end];
        let spaced = segment.char_indices().any(|(i, c)| {
            match c {
                '"' => quoted = !quoted,
                '(' if !quoted => depth += 1,
                ')' if !quoted => depth -= 1,
                _ => {}
            }
            // A space that opens a parenthesis belongs to the location.
            c == ' ' && depth == 0 && !quoted && !segment[i + 1..].starts_with('(')
        });
        if spaced || rest[end + 2..].is_empty() {
            break;
        }
        rest = &rest[end + 2..];
    }
    rest
}

impl Warnings {
    /// Records `msg`; returns the line to print, if it is among the first of its kind.
    pub fn note(&mut self, msg: &str) -> Option<String> {
        let k = kind(msg);
        let i = match self.seen.get(&k) {
            Some(&i) => i,
            None => {
                self.seen.insert(k, self.kinds.len());
                self.kinds.push((msg.to_string(), 0));
                self.kinds.len() - 1
            }
        };
        self.kinds[i].1 += 1;
        (self.kinds[i].1 <= PER_KIND).then(|| format!("inbetween: warning: {msg}"))
    }

    /// One line per kind that was cut short: `… and N more like "<first>"`.
    pub fn summary(&self) -> Vec<String> {
        self.kinds
            .iter()
            .filter(|(_, n)| *n > PER_KIND)
            .map(|(first, n)| {
                // A long warning is quoted from its words, not its location (a glTF channel's
                // path alone would fill the 60 characters).
                let quoted = if first.chars().count() > 60 {
                    without_location(first)
                } else {
                    first
                };
                let mut s: String = quoted.chars().take(60).collect();
                if quoted.chars().count() > 60 {
                    s.push('…');
                }
                format!(
                    "inbetween: warning: … and {} more warnings like \"{s}\"",
                    n - PER_KIND
                )
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ten_of_a_kind_then_a_count() {
        let mut w = Warnings::default();
        let mut printed = 0;
        for i in 0..25 {
            let msg = format!("k.csv:{}: quaternion norm {}.5 normalized", i + 2, i);
            printed += usize::from(w.note(&msg).is_some());
        }
        assert!(w.note("track \"a\": other thing").is_some());
        assert!(w.note("track \"b\": other thing").is_some());
        assert_eq!(printed, 10);
        assert_eq!(
            w.summary(),
            [
                "inbetween: warning: … and 15 more warnings like \"k.csv:2: quaternion norm 0.5 normalized\""
            ]
        );
    }

    /// A long warning's summary quotes its words, not its location.
    #[test]
    fn a_long_warning_is_summarised_by_its_words() {
        let mut w = Warnings::default();
        for c in 0..12 {
            w.note(&format!(
                "fixtures/gltf/walk.gltf: animations[0].channels[{c}] (animation \"Walk\", node \
                 \"Hips\"): translation channel {c} has other key times than the rotation"
            ));
        }
        assert_eq!(
            w.summary(),
            [
                "inbetween: warning: … and 2 more warnings like \"translation channel 0 has other \
                 key times than the rotation\""
            ]
        );
        assert_eq!(without_location("keys.csv:3: a b: c"), "a b: c");
        assert_eq!(
            without_location("t.json: track \"a b\": x"),
            "track \"a b\": x"
        );
        assert_eq!(
            without_location("CSV has no place for the rate: x"),
            "CSV has no place for the rate: x"
        );
        assert_eq!(without_location("a: "), "a: ");
    }
}
