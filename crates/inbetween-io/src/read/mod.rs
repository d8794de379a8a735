//! Readers of keyframe documents: one module per format, each turning text into a
//! [`Document`](crate::document::Document) with every key converted to a unit quaternion and
//! its source location kept for messages.

pub mod csv;
pub mod json;
pub mod log;
