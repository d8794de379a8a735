//! The nodes a clip's tracks animate, with their ancestors, as an
//! [`inbetween::skeleton::Skeleton`] (world-space measures; docs/spec.md §3 *glTF*).

use super::GltfClip;
use glam::{DQuat, DVec3};
use inbetween::skeleton::{Joint, Skeleton};
use std::collections::HashMap;

impl GltfClip {
    /// The skeleton of the clip's tracks: each animated node and its ancestors, parents first,
    /// at their rest transforms (`translation`, `rotation`, `scale`, or `matrix` decomposed), a
    /// node's children that are neither animated nor ancestors of an animated node its end
    /// points (their rest translations). Track `i` animates the node of its rotation channel.
    /// `None` when the tracks come from more than one animation (each would pose the nodes
    /// apart), or when the nodes do not form a forest (a node with two parents, a cycle: the
    /// specification forbids both).
    pub fn skeleton(&self) -> Option<Skeleton> {
        let first = self.tracks.first()?.0;
        if self.tracks.iter().any(|&(a, _)| a != first) {
            return None;
        }
        let doc = self.asset.document();
        // The nodes by index, once (`nth` walks the iterator: quadratic in nodes).
        let nodes: Vec<gltf::Node<'_>> = doc.nodes().collect();
        let n = nodes.len();
        let mut parent: Vec<Option<usize>> = vec![None; n];
        for node in &nodes {
            for child in node.children() {
                if parent[child.index()].replace(node.index()).is_some() {
                    return None;
                }
            }
        }
        let mut track_of: HashMap<usize, usize> = HashMap::new();
        for i in 0..self.tracks.len() {
            track_of.entry(self.channel(i).node()).or_insert(i);
        }
        // The animated nodes and their ancestors (a walk up longer than the node count is a cycle).
        let mut wanted = vec![false; n];
        for &node in track_of.keys() {
            let (mut at, mut steps) = (Some(node), 0);
            while let Some(j) = at {
                if wanted[j] {
                    break;
                }
                wanted[j] = true;
                at = parent[j];
                steps += 1;
                if steps > n {
                    return None;
                }
            }
        }
        // Depth first from the roots, so that parents come first.
        let mut order = Vec::new();
        let mut stack: Vec<usize> = (0..n)
            .rev()
            .filter(|&j| wanted[j] && parent[j].is_none())
            .collect();
        while let Some(j) = stack.pop() {
            order.push(j);
            let node = &nodes[j];
            let kids: Vec<usize> = node
                .children()
                .map(|c| c.index())
                .filter(|&c| wanted[c])
                .collect();
            stack.extend(kids.into_iter().rev());
        }
        let position: HashMap<usize, usize> =
            order.iter().enumerate().map(|(i, &j)| (j, i)).collect();
        let joints = order
            .iter()
            .map(|&j| {
                let node = &nodes[j];
                let (t, r, s) = node.transform().decomposed();
                let name = node
                    .name()
                    .map_or_else(|| format!("node{j}"), str::to_string);
                let mut joint = Joint::new(name, parent[j].map(|p| position[&p]), vec3(t));
                joint.rotation =
                    DQuat::from_xyzw(r[0].into(), r[1].into(), r[2].into(), r[3].into())
                        .normalize();
                joint.scale = vec3(s);
                joint.track = track_of.get(&j).copied();
                joint.ends = node
                    .children()
                    .filter(|c| !wanted[c.index()])
                    .map(|c| vec3(c.transform().decomposed().0))
                    .collect();
                joint
            })
            .collect();
        Skeleton::new(joints).ok()
    }
}

fn vec3(v: [f32; 3]) -> DVec3 {
    DVec3::new(v[0].into(), v[1].into(), v[2].into())
}
