//! A track's keys, interpreted: times or frames, rotations in the document's representation and
//! unit, velocities and TCB values.

use super::wire::{FIRST_ROTATION, KEY_FIELDS, KeyWire};
use crate::ReadOptions;
use crate::document::{Document, EulerKeys, Key, KeyTime, Loc, push_shape, push_sparse};
use glam::DVec3;
use inbetween::clock::Fps;
use inbetween::error::{InputError, InputResult, MessagePart, Setting};
use inbetween::message;
use inbetween::rotation::{AngleUnit, Repr};
use std::fmt;

pub(super) struct KeyContext<'a> {
    pub(super) source: &'a str,
    pub(super) angles: AngleUnit,
    pub(super) euler_seq: Option<inbetween::rotation::EulerSeq>,
    /// The convention of `rot6d` keys: the document's `rotation` (or `--from`).
    pub(super) rot6d: Option<Repr>,
    /// The rate of `frame` values, declared (`"fps"`) or given, and which.
    pub(super) rate: Option<(Fps, RateFrom)>,
    pub(super) opts: &'a ReadOptions,
}

/// An angle unit shown as the flag's value (`deg`), for [`settle`]'s message.
#[derive(Clone, Copy, PartialEq)]
pub(super) struct Unit(pub(super) AngleUnit);

impl fmt::Display for Unit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0.as_str())
    }
}

/// A key with both `time` and `frame` (interp's output) is at its `time`; when the rate of its
/// frame numbers is known, the two must agree within this many seconds.
pub(crate) const FRAME_TIME_AGREEMENT: f64 = 1e-9;

/// Checks that frame `frame` at `rate` is at `time` (within [`FRAME_TIME_AGREEMENT`]), for a key
/// that gives both; `rate_from` says where the rate comes from, for the message.
pub(crate) fn check_frame_time(
    frame: f64,
    time: f64,
    rate: Fps,
    rate_from: RateFrom,
) -> InputResult<()> {
    let at = rate.frame_to_time(frame);
    if (at - time).abs() <= FRAME_TIME_AGREEMENT {
        return Ok(());
    }
    let from = match rate_from {
        RateFrom::Declared => MessagePart::from("\"fps\""),
        RateFrom::Given => MessagePart::from(Setting::KeyRate),
    };
    Err(InputError::new(message![
        format!(
            "expected frame {} at {rate} fps (",
            inbetween::error::num(frame)
        ),
        from,
        format!(
            ") to be at time {} s (within 1e-9 s), found {} s",
            inbetween::error::num(time),
            inbetween::error::num(at)
        )
    ]))
}

/// Where the rate of a document's `frame` values comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum RateFrom {
    /// The document's own `"fps"`.
    Declared,
    /// The reader's options ([`ReadOptions::key_fps`]).
    Given,
}

/// A track's keys as read, with their Euler angles and their own velocities and TCB values
/// (see [`DocTrack`]).
pub(super) struct KeysRead {
    pub(super) translations: Vec<Option<DVec3>>,
    pub(super) keys: Vec<Key>,
    pub(super) euler: Option<EulerKeys>,
    pub(super) velocities: Vec<Option<DVec3>>,
    pub(super) tcb: Vec<[Option<f64>; 3]>,
}

impl KeyContext<'_> {
    pub(super) fn keys(
        &self,
        wires: Vec<KeyWire>,
        track: Option<usize>,
        frames: bool,
        doc: &mut Document,
    ) -> InputResult<KeysRead> {
        let mut keys = Vec::with_capacity(wires.len());
        let (mut velocities, mut tcbs, mut translations) = (Vec::new(), Vec::new(), Vec::new());
        // The keys' Euler angles as written, while every key so far is Euler in one sequence.
        let mut euler: Option<EulerKeys> = None;
        let mut all_euler = true;
        for (i, w) in wires.into_iter().enumerate() {
            let loc = Loc::Json {
                track,
                key: i,
                frames,
            };
            let here = |e: InputError| e.at(format!("{}:{loc}", self.source));
            if w.angular_velocity && !frames {
                return Err(here(input_err!(
                    "\"angular_velocity\": expected only in \"frames\" (interp's output), \
                     found in \"keys\""
                )));
            }
            let when = match (w.time, w.frame) {
                (Some(t), None) => KeyTime::Seconds(t),
                (None, Some(f)) => KeyTime::Frame(f),
                // interp's frames: the time is used, the frame number checked against it.
                (Some(t), Some(f)) => {
                    if let Some((rate, from)) = self.rate
                        && t.is_finite()
                        && f.is_finite()
                    {
                        check_frame_time(f, t, rate, from)
                            .map_err(|e| here(e.at("\"frame\" and \"time\"")))?;
                    }
                    KeyTime::Seconds(t)
                }
                (None, None) => {
                    return Err(here(input_err!(
                        "expected \"time\" or \"frame\", found neither"
                    )));
                }
            };
            let present = |r: usize| w.rotations & (1 << r) != 0;
            let seq = match self.euler_seq {
                Some(seq) => seq,
                None if present(1) => {
                    return Err(here(InputError::new(message![
                        "\"euler\": the sequence is unknown: set the document's \"rotation\" \
                         (e.g. \"euler:ZYX\") or pass ",
                        Setting::Rotation,
                        " euler:SEQ"
                    ])));
                }
                // Unused: there is no euler key.
                None => inbetween::rotation::EulerSeq::parse("XYZ").expect("valid"),
            };
            let repr = match w.rotations.count_ones() {
                1 => match w.rotations.trailing_zeros() {
                    0 => Repr::Quat,
                    1 => Repr::Euler(seq),
                    2 => Repr::Matrix,
                    3 => Repr::AxisAngle,
                    4 => Repr::RotVec,
                    _ => match self.rot6d {
                        Some(r) => r,
                        None => {
                            return Err(here(InputError::new(message![
                                "\"rot6d\": the convention is unknown: set the document's \
                                 \"rotation\" (\"rot6d:rows\", pytorch3d's, or \
                                 \"rot6d:columns\", Zhou et al.'s) or pass ",
                                Setting::Rotation,
                                " rot6d:rows"
                            ])));
                        }
                    },
                },
                0 => {
                    return Err(here(input_err!(
                        "expected a rotation (\"quat\", \"euler\", \"matrix\", \"axis_angle\", \
                         \"rotvec\" or \"rot6d\"), found none"
                    )));
                }
                _ => {
                    return Err(here(input_err!(
                        "expected one rotation, found {}",
                        KEY_FIELDS[FIRST_ROTATION..FIRST_ROTATION + 6]
                            .iter()
                            .enumerate()
                            .filter(|&(r, _)| present(r))
                            .map(|(_, f)| format!("\"{f}\""))
                            .collect::<Vec<_>>()
                            .join(" and ")
                    )));
                }
            };
            let mut values = w.values;
            if repr == Repr::Quat {
                let q = [values[0], values[1], values[2], values[3]];
                values[..4].copy_from_slice(&self.opts.quat_order.to_wxyz(q));
            }
            let (rot, warning) = repr
                .to_quat(&values[..repr.width()], self.angles)
                .map_err(|e| here(e.at(format!("\"{}\"", repr.json_key()))))?;
            if let Some(w) = warning {
                doc.warnings.push(format!("{}:{loc}: {w}", self.source));
            }
            if doc.rotation.is_none() {
                doc.rotation = Some(repr);
            }
            match (repr, &mut euler) {
                (Repr::Euler(seq), None) if all_euler => {
                    euler = Some((seq, Vec::with_capacity(keys.capacity())));
                }
                (Repr::Euler(seq), Some((s, _))) if *s == seq => {}
                _ => all_euler = false,
            }
            if let (true, Some((_, angles))) = (all_euler, &mut euler) {
                let r = |x: f64| self.angles.to_rad(x);
                angles.push(DVec3::new(r(values[0]), r(values[1]), r(values[2])));
            }
            keys.push(Key { when, rot });
            let velocity = w
                .velocity
                .map(|v| DVec3::from_array(v.map(|x| self.angles.to_rad(x))));
            push_shape(&mut velocities, &mut tcbs, keys.len(), velocity, w.tcb);
            push_sparse(
                &mut translations,
                keys.len(),
                w.translation.map(DVec3::from_array),
            );
        }
        Ok(KeysRead {
            translations,
            keys,
            euler: euler.filter(|_| all_euler),
            velocities,
            tcb: tcbs,
        })
    }
}
