//! The binary FBX container, version 7.4 (7400): a tree of named nodes, each with typed
//! properties, encoded into bytes. What the nodes mean is [`super::write`]'s job (kept apart
//! from the container as Blender's `encode_bin.py` keeps it apart from its exporter).
//!
//! ```text
//! file    = "Kaydara FBX Binary  \0" 0x1a 0x00  u32 version   node*  null-record  footer
//! node    = u32 end_offset  u32 property_count  u32 property_bytes  u8 name_len  name
//!           property*  [node* null-record]
//! null    = 13 zero bytes (the 3 u32 and the name length of an empty node)
//! property= type byte, then: 'C' u8 bool | 'Y' i16 | 'I' i32 | 'L' i64 | 'F' f32 | 'D' f64
//!           | 'S' u32 len bytes | 'R' u32 len bytes
//!           | 'f' 'd' 'l' 'i' arrays: u32 count  u32 encoding (0: raw)  u32 bytes  values
//! footer  = 16-byte footer id, 4 zero bytes, zero padding to a multiple of 16 (16 when
//!           aligned), u32 version, 120 zero bytes, 16-byte magic
//! ```
//!
//! All numbers little-endian; `end_offset` is the absolute offset of the byte after the node.
//! The null record closes a node's children; as Blender's writer does, it also ends a node with
//! neither properties nor children (unless it is the last of its list) and an `AnimationStack`
//! or `AnimationLayer` (the SDK's habit). 32-bit offsets bound the file to 4 GiB: a larger scene
//! is refused before anything is written. The footer and the fixed `FileId` and `CreationTime`
//! are the ones Blender's exporter writes (Autodesk's SDK derives the footer id from the
//! creation time; readers, ufbx and Blender's importer among them, do not check it).

use std::io;

/// The FBX version written: 7.4, as Blender's exporter writes it (32-bit node offsets).
pub(crate) const VERSION: u32 = 7400;

const MAGIC: &[u8] = b"Kaydara FBX Binary  \x00\x1a\x00";
const NULL_RECORD: [u8; 13] = [0; 13];
pub(crate) const FILE_ID: &[u8] =
    b"\x28\xb3\x2a\xeb\xb6\x24\xcc\xc2\xbf\xc8\xb0\x2a\xa9\x2b\xfc\xf1";
pub(crate) const CREATION_TIME: &str = "1970-01-01 10:00:00:000";
const FOOTER_ID: &[u8] = b"\xfa\xbc\xab\x09\xd0\xc8\xd4\x66\xb1\x76\xfb\x83\x1c\xf7\x26\x7e";
const FOOTER_MAGIC: &[u8] = b"\xf8\x5a\x8c\x6a\xde\xf5\xd9\x7e\xec\xe9\x0c\xe3\x75\x8f\x29\x0b";

/// A property value of a node.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Prop {
    /// `I`: a 32-bit integer.
    I32(i32),
    /// `L`: a 64-bit integer (object ids, times in ticks).
    I64(i64),
    /// `D`: a double.
    F64(f64),
    /// `S`: a string (binary FBX writes `name\0\x01Class` for object names).
    Str(String),
    /// `R`: raw bytes.
    Raw(Vec<u8>),
    /// `l`: an array of 64-bit integers.
    I64s(Vec<i64>),
    /// `i`: an array of 32-bit integers.
    I32s(Vec<i32>),
    /// `f`: an array of floats.
    F32s(Vec<f32>),
}

impl Prop {
    fn encode(&self, out: &mut Vec<u8>) {
        fn array<T: Copy>(out: &mut Vec<u8>, code: u8, v: &[T], bytes: impl Fn(T) -> Vec<u8>) {
            out.push(code);
            let size = std::mem::size_of_val(v);
            out.extend_from_slice(&(v.len() as u32).to_le_bytes());
            out.extend_from_slice(&0u32.to_le_bytes());
            out.extend_from_slice(&(size as u32).to_le_bytes());
            out.reserve(size);
            for &x in v {
                out.extend_from_slice(&bytes(x));
            }
        }
        match self {
            Prop::I32(x) => {
                out.push(b'I');
                out.extend_from_slice(&x.to_le_bytes());
            }
            Prop::I64(x) => {
                out.push(b'L');
                out.extend_from_slice(&x.to_le_bytes());
            }
            Prop::F64(x) => {
                out.push(b'D');
                out.extend_from_slice(&x.to_le_bytes());
            }
            Prop::Str(s) => {
                out.push(b'S');
                out.extend_from_slice(&(s.len() as u32).to_le_bytes());
                out.extend_from_slice(s.as_bytes());
            }
            Prop::Raw(b) => {
                out.push(b'R');
                out.extend_from_slice(&(b.len() as u32).to_le_bytes());
                out.extend_from_slice(b);
            }
            Prop::I64s(v) => array(out, b'l', v, |x| x.to_le_bytes().to_vec()),
            Prop::I32s(v) => array(out, b'i', v, |x| x.to_le_bytes().to_vec()),
            Prop::F32s(v) => array(out, b'f', v, |x| x.to_le_bytes().to_vec()),
        }
    }

    /// The bytes the property takes, its type byte included.
    fn size(&self) -> u64 {
        let n = |len: usize, each: usize| 1 + 12 + (len * each) as u64;
        match self {
            Prop::I32(_) => 5,
            Prop::I64(_) | Prop::F64(_) => 9,
            Prop::Str(s) => 5 + s.len() as u64,
            Prop::Raw(b) => 5 + b.len() as u64,
            Prop::I64s(v) => n(v.len(), 8),
            Prop::I32s(v) => n(v.len(), 4),
            Prop::F32s(v) => n(v.len(), 4),
        }
    }
}

/// A node: its name, properties and children.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Node {
    pub(crate) name: &'static str,
    pub(crate) props: Vec<Prop>,
    pub(crate) children: Vec<Node>,
}

impl Node {
    /// A node with properties and no children.
    pub(crate) fn new(name: &'static str, props: Vec<Prop>) -> Node {
        Node {
            name,
            props,
            children: Vec::new(),
        }
    }

    /// A node with properties and children.
    pub(crate) fn with(name: &'static str, props: Vec<Prop>, children: Vec<Node>) -> Node {
        Node {
            name,
            props,
            children,
        }
    }

    /// Whether a null record follows the node's properties (see the module documentation).
    fn closed(&self, last: bool) -> bool {
        !self.children.is_empty()
            || (self.props.is_empty() && !last)
            || matches!(self.name, "AnimationStack" | "AnimationLayer")
    }

    /// The bytes the node takes, its children and null record included.
    fn size(&self, last: bool) -> u64 {
        let props: u64 = self.props.iter().map(Prop::size).sum();
        // The children's list ends with its null record; a node without children may have one.
        let tail = if !self.children.is_empty() {
            list_size(&self.children)
        } else if self.closed(last) {
            13
        } else {
            0
        };
        13 + self.name.len() as u64 + props + tail
    }

    fn encode(&self, out: &mut Vec<u8>, last: bool) {
        let start = out.len() as u64;
        let end = start + self.size(last);
        let props: u64 = self.props.iter().map(Prop::size).sum();
        // The sizes were checked against 32 bits before any node was encoded.
        out.extend_from_slice(&(end as u32).to_le_bytes());
        out.extend_from_slice(&(self.props.len() as u32).to_le_bytes());
        out.extend_from_slice(&(props as u32).to_le_bytes());
        out.push(self.name.len() as u8);
        out.extend_from_slice(self.name.as_bytes());
        for p in &self.props {
            p.encode(out);
        }
        encode_list(&self.children, out);
        if self.closed(last) && self.children.is_empty() {
            out.extend_from_slice(&NULL_RECORD);
        }
        debug_assert_eq!(out.len() as u64, end, "node {}", self.name);
    }
}

/// The bytes of a list of sibling nodes with its closing null record.
fn list_size(nodes: &[Node]) -> u64 {
    if nodes.is_empty() {
        return 0;
    }
    let n = nodes.len();
    let kids: u64 = nodes
        .iter()
        .enumerate()
        .map(|(i, c)| c.size(i + 1 == n))
        .sum();
    kids + 13
}

fn encode_list(nodes: &[Node], out: &mut Vec<u8>) {
    if nodes.is_empty() {
        return;
    }
    let n = nodes.len();
    for (i, c) in nodes.iter().enumerate() {
        c.encode(out, i + 1 == n);
    }
    out.extend_from_slice(&NULL_RECORD);
}

/// The file of the top-level `nodes` (see the module documentation). Errors (`InvalidInput`):
/// a file of 4 GiB or more, which 32-bit offsets cannot address.
pub(crate) fn encode(nodes: &[Node]) -> io::Result<Vec<u8>> {
    let head = (MAGIC.len() + 4) as u64;
    let body = list_size(nodes).max(13);
    let total = head + body + 16 + 4 + 16 + 4 + 120 + 16;
    if total > u64::from(u32::MAX) {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "the FBX file would take {total} bytes, more than the 4 GiB FBX 7.4 can address"
            ),
        ));
    }
    let mut out = Vec::with_capacity(total as usize);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    if nodes.is_empty() {
        out.extend_from_slice(&NULL_RECORD);
    } else {
        encode_list(nodes, &mut out);
    }
    out.extend_from_slice(FOOTER_ID);
    out.extend_from_slice(&[0; 4]);
    let pad = match out.len() % 16 {
        0 => 16,
        r => 16 - r,
    };
    out.resize(out.len() + pad, 0);
    out.extend_from_slice(&VERSION.to_le_bytes());
    out.resize(out.len() + 120, 0);
    out.extend_from_slice(FOOTER_MAGIC);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn u32_at(b: &[u8], i: usize) -> u32 {
        u32::from_le_bytes(b[i..i + 4].try_into().unwrap())
    }

    #[test]
    fn a_node_is_laid_out_as_the_format_says() {
        let nodes = [Node::with(
            "A",
            vec![Prop::I32(7), Prop::Str("x".into())],
            vec![Node::new("B", vec![Prop::F32s(vec![1.0, 2.0])])],
        )];
        let b = encode(&nodes).unwrap();
        assert_eq!(&b[..23], MAGIC);
        assert_eq!(u32_at(&b, 23), 7400);
        // Node A at 27: end, 2 properties of 5 + 6 bytes, name "A".
        let a = 27;
        let b_node = a + 13 + 1 + 5 + 6;
        // Node B: 13 + 1 + (1 + 12 + 8) bytes, then A's null record, then the file's.
        let b_end = b_node + 13 + 1 + 21;
        assert_eq!(u32_at(&b, a) as usize, b_end + 13);
        assert_eq!((u32_at(&b, a + 4), u32_at(&b, a + 8)), (2, 11));
        assert_eq!(&b[a + 12..a + 14], b"\x01A");
        assert_eq!(b[a + 14], b'I');
        assert_eq!(u32_at(&b, a + 15), 7);
        assert_eq!(&b[a + 19..a + 25], b"S\x01\x00\x00\x00x");
        assert_eq!(u32_at(&b, b_node) as usize, b_end);
        assert_eq!(&b[b_node + 14..b_node + 15], b"f");
        assert_eq!(
            (
                u32_at(&b, b_node + 15),
                u32_at(&b, b_node + 19),
                u32_at(&b, b_node + 23)
            ),
            (2, 0, 8)
        );
        assert_eq!(&b[b_end..b_end + 26], &[0u8; 26]);
        // The footer: its id, 4 zeros, padding to 16, the version, 120 zeros, the magic.
        let f = b_end + 26;
        assert_eq!(&b[f..f + 16], FOOTER_ID);
        let v = (f + 20).div_ceil(16) * 16;
        let v = if v == f + 20 { v + 16 } else { v };
        assert_eq!(u32_at(&b, v), 7400);
        assert_eq!(&b[b.len() - 16..], FOOTER_MAGIC);
        assert_eq!(b.len(), v + 4 + 120 + 16);
    }

    #[test]
    fn an_empty_node_and_the_animation_nodes_are_closed_by_a_null_record() {
        let empty = Node::new("E", vec![]);
        assert!(empty.closed(false) && !empty.closed(true));
        assert!(Node::new("AnimationLayer", vec![Prop::I64(1)]).closed(true));
        assert!(!Node::new("X", vec![Prop::I64(1)]).closed(false));
        let b = encode(&[empty.clone(), Node::new("F", vec![])]).unwrap();
        // E: 14 bytes and a null record; F (last): 14 bytes; the list's null record.
        assert_eq!(u32_at(&b, 27), 27 + 14 + 13);
        assert_eq!(u32_at(&b, 27 + 27), 27 + 27 + 14);
    }
}
