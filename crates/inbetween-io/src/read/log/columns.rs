//! Column maps of timestamped logs: which input column holds the time, the quaternion and the
//! translation, given by the user (`time=…,w=…`) or by a preset of a published layout (TUM,
//! EuRoC, `rostopic echo -p`), and found in a header row.

use super::stamp::{TimeOrigin, TimeUnit};
use inbetween::error::{InputResult, shorten};

/// The fields a log row gives, in the order of [`FIELD_NAMES`].
pub(crate) const FIELDS: usize = 8;

/// The fields' names in a column map: the time, the quaternion's `w,x,y,z`, the translation's
/// `tx,ty,tz` (optional, all three or none).
pub(crate) const FIELD_NAMES: [&str; FIELDS] = ["time", "w", "x", "y", "z", "tx", "ty", "tz"];

/// Where a field is in a row.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Column {
    /// The column of this number, counted from 1 (as `cut -f` and `awk` count): no header
    /// needed.
    Number(usize),
    /// The column of this header name (ASCII case-insensitive; a trailing unit in brackets, as
    /// in EuRoC's `p_RS_R_x [m]`, may be left out).
    Name(String),
}

impl Column {
    /// A number (`8`) is a column number, anything else a name.
    pub fn parse(s: &str) -> InputResult<Column> {
        let s = s.trim();
        if s.is_empty() {
            return Err(input_err!(
                "expected a column name or number, found nothing"
            ));
        }
        match s.parse::<usize>() {
            Ok(0) => Err(input_err!(
                "expected a column number from 1 (the first column), found 0"
            )),
            Ok(n) => Ok(Column::Number(n)),
            Err(_) => Ok(Column::Name(s.to_string())),
        }
    }
}

/// A published log layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Preset {
    /// TUM RGB-D trajectories: `timestamp tx ty tz qx qy qz qw`, whitespace-separated, `#`
    /// comment lines, stamps in seconds.
    Tum,
    /// EuRoC MAV (ASL) poses: `#timestamp, p_RS_R_x [m], …, q_RS_w [], q_RS_x [], …`,
    /// nanosecond stamps (`state_groundtruth_estimate0/data.csv`, `vicon0/data.csv`).
    Euroc,
    /// `rostopic echo -p` of a topic carrying one quaternion: `%time` (nanoseconds) and the
    /// columns `…x,…y,…z,…w` of one prefix (`field.pose.orientation.`, `field.orientation.`,
    /// `field.`), with the sibling `position.`/`translation.` columns when there are.
    Rostopic,
}

impl Preset {
    /// `tum`, `euroc` or `rostopic`.
    pub fn parse(s: &str) -> Option<Preset> {
        match s {
            "tum" => Some(Preset::Tum),
            "euroc" => Some(Preset::Euroc),
            "rostopic" => Some(Preset::Rostopic),
            _ => None,
        }
    }

    /// The unit of the preset's stamps.
    fn unit(self) -> TimeUnit {
        match self {
            Preset::Tum => TimeUnit::Seconds,
            Preset::Euroc | Preset::Rostopic => TimeUnit::Nanos,
        }
    }
}

/// How to read a timestamped log (docs/formats.md, *Timestamped logs*): a preset and the
/// fields set over it, the unit of the stamps and where times count from.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct ColumnMap {
    /// The preset the fields start from, if any.
    pub preset: Option<Preset>,
    /// Fields set by name (index into `FIELD_NAMES`), over the preset's.
    pub fields: Vec<(usize, Column)>,
    /// The unit of the stamps; default the preset's, else seconds.
    pub time_unit: Option<TimeUnit>,
    /// Whether key times count from the first stamp (the default) or are the stamps.
    pub times: TimeOrigin,
}

impl ColumnMap {
    /// `tum`, `euroc`, `rostopic`, or `time=…,w=…,x=…,y=…,z=…[,tx=…,ty=…,tz=…]`, optionally
    /// after a preset (`rostopic,time=field.header.stamp`).
    pub fn parse(s: &str) -> InputResult<ColumnMap> {
        let mut map = ColumnMap::default();
        for (i, item) in s.split(',').enumerate() {
            let item = item.trim();
            match item.split_once('=') {
                Some((field, column)) => map.set(field.trim(), Column::parse(column)?)?,
                None => match Preset::parse(item) {
                    Some(p) if i == 0 => map.preset = Some(p),
                    _ => {
                        return Err(input_err!(
                            "expected a preset (tum, euroc, rostopic) or FIELD=COLUMN items \
                             (time=…,w=…,x=…,y=…,z=…), found \"{}\"",
                            shorten(item)
                        ));
                    }
                },
            }
        }
        Ok(map)
    }

    /// Sets `field` (one of `FIELD_NAMES`) to `column`; a field set twice is an error.
    pub fn set(&mut self, field: &str, column: Column) -> InputResult<()> {
        let Some(i) = FIELD_NAMES.iter().position(|f| *f == field) else {
            return Err(input_err!(
                "unknown field \"{}\": expected {}",
                shorten(field),
                FIELD_NAMES.join(", ")
            ));
        };
        if self.fields.iter().any(|(j, _)| *j == i) {
            return Err(input_err!("field \"{field}\" is given twice"));
        }
        self.fields.push((i, column));
        Ok(())
    }

    /// The unit of the stamps.
    pub(crate) fn unit(&self) -> TimeUnit {
        self.time_unit
            .or(self.preset.map(Preset::unit))
            .unwrap_or(TimeUnit::Seconds)
    }

    /// Whether the map names a column (so that the log needs a header row).
    pub(crate) fn needs_header(&self) -> bool {
        matches!(self.preset, Some(Preset::Euroc | Preset::Rostopic))
            || self
                .fields
                .iter()
                .any(|(_, c)| matches!(c, Column::Name(_)))
    }

    /// Each field's 0-based column, given the header's names if there is one; the message
    /// (without location) when a named column is missing, or a field has no column.
    pub(crate) fn resolve(
        &self,
        header: Option<&[&str]>,
    ) -> Result<[Option<usize>; FIELDS], String> {
        let mut columns: [Option<Column>; FIELDS] = Default::default();
        match self.preset {
            Some(Preset::Tum) => {
                // timestamp tx ty tz qx qy qz qw
                for (field, n) in [
                    (0, 1),
                    (5, 2),
                    (6, 3),
                    (7, 4),
                    (2, 5),
                    (3, 6),
                    (4, 7),
                    (1, 8),
                ] {
                    columns[field] = Some(Column::Number(n));
                }
            }
            Some(Preset::Euroc) => {
                let names = [
                    "timestamp",
                    "q_RS_w",
                    "q_RS_x",
                    "q_RS_y",
                    "q_RS_z",
                    "p_RS_R_x",
                    "p_RS_R_y",
                    "p_RS_R_z",
                ];
                for (slot, n) in columns.iter_mut().zip(names) {
                    *slot = Some(Column::Name(n.to_string()));
                }
                // Translation columns are optional: a layout without them still reads.
                if let Some(h) = header
                    && (5..8).any(|f| find(h, names[f]).is_none())
                {
                    columns[5..].fill(None);
                }
            }
            Some(Preset::Rostopic) => {
                columns[0] = Some(Column::Name("%time".to_string()));
                if let Some(h) = header {
                    for (slot, name) in columns[1..].iter_mut().zip(rostopic_columns(h)?) {
                        *slot = name.map(Column::Name);
                    }
                }
            }
            None => {}
        }
        for (i, c) in &self.fields {
            columns[*i] = Some(c.clone());
        }
        let mut out = [None; FIELDS];
        for (i, (slot, c)) in out.iter_mut().zip(&columns).enumerate() {
            *slot = match c {
                None => None,
                Some(Column::Number(n)) => Some(n - 1),
                Some(Column::Name(name)) => {
                    let h = header.unwrap_or_default();
                    Some(find(h, name).ok_or_else(|| {
                        format!(
                            "no column \"{}\" for field {} (columns: {})",
                            shorten(name),
                            FIELD_NAMES[i],
                            shorten(&h.join(","))
                        )
                    })?)
                }
            };
        }
        if let Some(i) = (0..5).find(|&i| out[i].is_none()) {
            return Err(format!(
                "the column map gives no column for field {} (it needs time, w, x, y, z)",
                FIELD_NAMES[i]
            ));
        }
        if out[5..].iter().any(Option::is_some) && out[5..].iter().any(Option::is_none) {
            return Err("the column map gives some of tx, ty, tz: give all three or none".into());
        }
        Ok(out)
    }
}

/// Whether a header name is `name`: equal ignoring ASCII case, or once a trailing unit in
/// brackets is removed (`p_RS_R_x [m]` is `p_RS_R_x`).
fn matches(header: &str, name: &str) -> bool {
    let header = header.trim();
    let bare = match header.rfind('[') {
        Some(i) if header.ends_with(']') => header[..i].trim_end(),
        _ => header,
    };
    header.eq_ignore_ascii_case(name) || bare.eq_ignore_ascii_case(name)
}

/// The first header column that is `name` ([`matches`]).
fn find(header: &[&str], name: &str) -> Option<usize> {
    header.iter().position(|h| matches(h, name))
}

/// `rostopic echo -p` columns of the one quaternion of a topic: `P w`, `P x`, `P y`, `P z` for
/// the one prefix `P` (`field.pose.orientation.`) whose four columns are all there, and the
/// translation beside it (`P` with `orientation.` → `position.`, `rotation.` → `translation.`)
/// when its three columns are.
fn rostopic_columns(header: &[&str]) -> Result<[Option<String>; 7], String> {
    let has = |n: &str| find(header, n).is_some();
    let mut prefixes: Vec<&str> = header
        .iter()
        .filter_map(|h| h.trim().strip_suffix('w'))
        .filter(|p| ["x", "y", "z"].iter().all(|c| has(&format!("{p}{c}"))))
        .filter(|p| p.is_empty() || p.ends_with('.'))
        .collect();
    prefixes.dedup();
    let prefix = match prefixes.as_slice() {
        [p] => *p,
        [] => {
            return Err(format!(
                "no quaternion columns (…x, …y, …z, …w of one prefix such as \
                 field.pose.orientation.) among the columns: {}",
                shorten(&header.join(","))
            ));
        }
        several => {
            return Err(format!(
                "several quaternions ({}): choose one with a column map \
                 (w=…,x=…,y=…,z=…)",
                several
                    .iter()
                    .map(|p| format!("{p}w"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
    };
    let mut out: [Option<String>; 7] = Default::default();
    for (slot, c) in out.iter_mut().zip(["w", "x", "y", "z"]) {
        *slot = Some(format!("{prefix}{c}"));
    }
    let sibling = [("orientation.", "position."), ("rotation.", "translation.")]
        .iter()
        .find_map(|(r, t)| prefix.strip_suffix(r).map(|base| format!("{base}{t}")));
    if let Some(base) = sibling {
        let names = ["x", "y", "z"].map(|c| format!("{base}{c}"));
        if names.iter().all(|n| has(n)) {
            for (slot, n) in out[4..].iter_mut().zip(names) {
                *slot = Some(n);
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn maps_and_presets() {
        let m = ColumnMap::parse("time=1, w=8,x=5,y=6,z=7").unwrap();
        assert_eq!(
            m.resolve(None).unwrap(),
            [
                Some(0),
                Some(7),
                Some(4),
                Some(5),
                Some(6),
                None,
                None,
                None
            ]
        );
        assert!(!m.needs_header());
        let m = ColumnMap::parse("rostopic,time=field.header.stamp").unwrap();
        assert!(m.needs_header());
        let h = [
            "%time",
            "field.header.seq",
            "field.header.stamp",
            "field.header.frame_id",
            "field.pose.position.x",
            "field.pose.position.y",
            "field.pose.position.z",
            "field.pose.orientation.x",
            "field.pose.orientation.y",
            "field.pose.orientation.z",
            "field.pose.orientation.w",
        ];
        assert_eq!(
            m.resolve(Some(&h)).unwrap(),
            [2, 10, 7, 8, 9, 4, 5, 6].map(Some)
        );
        let imu = [
            "%time",
            "field.orientation.x",
            "field.orientation.y",
            "field.orientation.z",
            "field.orientation.w",
            "field.orientation_covariance0",
            "field.angular_velocity.x",
        ];
        let r = ColumnMap::parse("rostopic")
            .unwrap()
            .resolve(Some(&imu))
            .unwrap();
        assert_eq!(r[..5], [0, 4, 1, 2, 3].map(Some));
        assert_eq!(r[5..], [None; 3]);
        let two = [
            "%time",
            "field.a.x",
            "field.a.y",
            "field.a.z",
            "field.a.w",
            "field.b.x",
            "field.b.y",
            "field.b.z",
            "field.b.w",
        ];
        assert!(
            ColumnMap::parse("rostopic")
                .unwrap()
                .resolve(Some(&two))
                .unwrap_err()
                .starts_with("several quaternions (field.a.w, field.b.w)")
        );
        let euroc = [
            "timestamp [ns]",
            "p_RS_R_x [m]",
            "p_RS_R_y [m]",
            "p_RS_R_z [m]",
            "q_RS_w []",
            "q_RS_x []",
            "q_RS_y []",
            "q_RS_z []",
        ];
        assert_eq!(
            ColumnMap::parse("euroc")
                .unwrap()
                .resolve(Some(&euroc))
                .unwrap(),
            [0, 4, 5, 6, 7, 1, 2, 3].map(Some)
        );
        assert_eq!(ColumnMap::parse("euroc").unwrap().unit(), TimeUnit::Nanos);
        assert_eq!(
            ColumnMap::parse("time=t,w=a,x=b,y=c,z=d")
                .unwrap()
                .resolve(Some(&["t", "a", "b", "c"]))
                .unwrap_err(),
            "no column \"d\" for field z (columns: t,a,b,c)"
        );
        assert!(
            ColumnMap::parse("time=1,w=2,x=3,y=4")
                .unwrap()
                .resolve(None)
                .unwrap_err()
                .contains("field z")
        );
        assert!(
            ColumnMap::parse("time=1,w=2,x=3,y=4,z=5,tx=6")
                .unwrap()
                .resolve(None)
                .is_err()
        );
        assert!(ColumnMap::parse("time=1,time=2").is_err());
        assert!(
            ColumnMap::parse("tim=1")
                .unwrap_err()
                .message()
                .contains("unknown field \"tim\"")
        );
        assert!(ColumnMap::parse("time=0").is_err());
        assert!(ColumnMap::parse("time=1,tum").is_err());
    }
}
