//! A glTF reader's findings about channels, one per kind: an asset exported with the same quirk
//! on every channel (Mixamo's sign flips, CUBICSPLINE corners, translation channels keyed apart)
//! gives one warning naming the first channel and how many others share it, not one per
//! channel.

use std::collections::HashMap;

/// How many of the other channels a grouped warning names.
const NAMED: usize = 3;

/// Findings by kind (the text without its digits), in order of first appearance.
#[derive(Debug, Default)]
pub(crate) struct ChannelWarnings {
    kinds: Vec<(String, String, Vec<String>)>,
    index: HashMap<String, usize>,
}

impl ChannelWarnings {
    /// A finding `text` about the channel at `location` (`clip.glb: animations[0].channels[3]
    /// (node "Hips")`).
    pub(crate) fn add(&mut self, location: String, text: String) {
        let kind: String = text.chars().filter(|c| !c.is_ascii_digit()).collect();
        match self.index.get(&kind) {
            Some(&i) => self.kinds[i].2.push(location),
            None => {
                self.index.insert(kind, self.kinds.len());
                self.kinds.push((text, location, Vec::new()));
            }
        }
    }

    /// One line per kind: `location: text`, and for a kind several channels share, `(and N other
    /// channels: a, b, c, …)`.
    pub(crate) fn into_lines(self) -> Vec<String> {
        self.kinds
            .into_iter()
            .map(|(text, first, others)| {
                if others.is_empty() {
                    return format!("{first}: {text}");
                }
                let mut named: Vec<&str> = others.iter().take(NAMED).map(String::as_str).collect();
                if others.len() > NAMED {
                    named.push("…");
                }
                format!(
                    "{first}: {text} (and {} other channel{}: {})",
                    others.len(),
                    if others.len() == 1 { "" } else { "s" },
                    named.join("; ")
                )
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn findings_of_one_kind_are_one_line_with_a_count() {
        let mut w = ChannelWarnings::default();
        for c in 0..5 {
            w.add(
                format!("a.glb: channel {c}"),
                format!("key {c} flips its sign"),
            );
        }
        w.add("a.glb: channel 9".into(), "a corner".into());
        assert_eq!(
            w.into_lines(),
            [
                "a.glb: channel 0: key 0 flips its sign (and 4 other channels: a.glb: channel 1; \
                 a.glb: channel 2; a.glb: channel 3; …)",
                "a.glb: channel 9: a corner",
            ]
        );
    }
}
