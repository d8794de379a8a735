//! The order of a track's frames while some wait for a block of lanes (`Queue`), and the
//! warnings about a segment (`check_segment`).

use super::{ANTIPODE_TOL, Frame};
use crate::curve::{Curve, Segment, antipode_gap};
use crate::error::{Message, Setting};
use crate::message;
use std::io;

/// Where frames go on their way to `emit`: frames of segments holding fewer than four wait here
/// until four of them fill a block of lanes — gathered ([`Segment::gather`]) or, for a scheme
/// that evaluates them directly ([`Segment::direct`]), as their segment and parameter — and the
/// frames after them wait behind them, so that `emit` sees every frame in order.
/// [`Queue::flush`] at the end.
pub(super) struct Queue<S: Segment> {
    /// Frames in order; a pending one's rotation is filled in when its block is done.
    frames: Vec<Frame>,
    /// The pending gathered frames: their place in `frames` and their lanes.
    pending: Vec<(usize, S::Pending)>,
    /// The pending direct frames: their place in `frames`, their segment and parameter.
    pub(super) direct: Vec<(usize, usize, f64)>,
    /// The last segment of a direct block whose blends were checked (a segment's frames may
    /// fall in two blocks).
    checked: Option<usize>,
}

/// Where a [`Queue`]'s frames go, and what its direct blocks need: the curve (its keys and
/// name) and the warnings' sink.
pub(super) struct Out<'a, 'c> {
    pub(super) curve: &'c Curve,
    pub(super) warn: &'a mut dyn FnMut(&Message),
    pub(super) emit: &'a mut dyn FnMut(Frame) -> io::Result<()>,
}

impl<S: Segment> Queue<S> {
    pub(super) fn new() -> Self {
        Queue {
            frames: Vec::new(),
            pending: Vec::with_capacity(4),
            direct: Vec::with_capacity(4),
            checked: None,
        }
    }

    /// A finished frame: to `emit` now, or behind the pending frames before it.
    pub(super) fn ready(&mut self, f: Frame, out: &mut Out) -> io::Result<()> {
        if self.pending.is_empty() && self.direct.is_empty() {
            (out.emit)(f)
        } else {
            self.frames.push(f);
            Ok(())
        }
    }

    /// A frame up to its last blends; the block is done when it holds four.
    pub(super) fn pending(&mut self, f: Frame, lane: S::Pending, out: &mut Out) -> io::Result<()> {
        self.pending.push((self.frames.len(), lane));
        self.frames.push(f);
        if self.pending.len() == 4 {
            self.flush(out)
        } else {
            Ok(())
        }
    }

    /// A frame of segment `s` at `u`, evaluated directly; the block is done when it holds four.
    pub(super) fn direct(&mut self, f: Frame, s: usize, u: f64, out: &mut Out) -> io::Result<()> {
        self.direct.push((self.frames.len(), s, u));
        self.frames.push(f);
        if self.direct.len() == 4 {
            self.flush(out)
        } else {
            Ok(())
        }
    }

    /// Every waiting frame to `emit` (a block not full is filled with copies of its first lane).
    pub(super) fn flush(&mut self, out: &mut Out) -> io::Result<()> {
        if let Some(&(_, first)) = self.pending.first() {
            let lanes = std::array::from_fn(|i| self.pending.get(i).map_or(first, |p| p.1));
            let q = S::finish4(&lanes);
            for (i, &(at, _)) in self.pending.iter().enumerate() {
                self.frames[at].2 = q[i];
            }
            self.pending.clear();
        }
        if let Some(&(_, s0, u0)) = self.direct.first() {
            let at = |i: usize| self.direct.get(i).map_or((s0, u0), |d| (d.1, d.2));
            let (keys, blend) = (out.curve.knots(), out.curve.blend());
            let (q, bounds) = S::direct4(
                keys,
                blend,
                std::array::from_fn(|i| at(i).0),
                std::array::from_fn(|i| at(i).1),
            );
            for (i, &(place, s, _)) in self.direct.iter().enumerate() {
                self.frames[place].2 = q[i];
                if self.checked != Some(s) {
                    self.checked = Some(s);
                    if bounds[i] >= BLEND_BOUND {
                        check_segment(out.curve, &S::new(keys, s, blend), s, out.warn);
                    }
                }
            }
            self.direct.clear();
        }
        self.frames.drain(..).try_for_each(&mut *out.emit)
    }
}

/// The blend bound from which a segment's blends are searched for a near antipode
/// ([`antipode_gap`]).
const BLEND_BOUND: f64 = std::f64::consts::PI - 1e-6;

/// The warnings about segment `s`: its scheme's limitation, a blend within
/// [`ANTIPODE_TOL`] of an antipode.
pub(super) fn check_segment<S: Segment>(
    curve: &Curve,
    seg: &S,
    s: usize,
    warn: &mut dyn FnMut(&Message),
) {
    let times = &curve.knots().times;
    let (t0, t1) = (times[s], times[s + 1]);
    let name = || {
        curve.name().map_or(String::new(), |n| {
            format!("track \"{}\", ", crate::error::shorten(n))
        })
    };
    if let Some(note) = seg.limitation() {
        warn(&message![format!("{}segment {s} ({t0} s to {t1} s): ", name())].append(note));
    }
    if let Some((gap, u)) = antipode_gap(seg)
        && gap < ANTIPODE_TOL
    {
        warn(&message![
            format!(
                "{}segment {s} ({t0} s to {t1} s): a blend of the {} curve comes within \
                 {gap:.1e} of an antipode at u = {u:.4}, where the curve may jump; add keys or \
                 use ",
                name(),
                curve.scheme().name()
            ),
            Setting::Scheme,
            " minaccel"
        ]);
    }
}
