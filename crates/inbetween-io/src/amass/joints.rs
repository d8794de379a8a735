//! The SMPL-H and SMPL-X kinematic trees: joint names and parents, fixed by the models (the
//! order of `poses`' triples). Names as smplx's `joint_names.py` spells them (SMPL-X's eyes are
//! `left_eye_smplhf`, `right_eye_smplhf` there); parents as the models' `kintree_table`: the 22
//! body joints of SMPL, then SMPL-X's jaw and eyes on the head, then each hand's 15 finger joints
//! (index, middle, pinky, ring, thumb; three each, the first on the wrist).

/// The 22 body joints shared by SMPL-H and SMPL-X.
const BODY: [(&str, i8); 22] = [
    ("pelvis", -1),
    ("left_hip", 0),
    ("right_hip", 0),
    ("spine1", 0),
    ("left_knee", 1),
    ("right_knee", 2),
    ("spine2", 3),
    ("left_ankle", 4),
    ("right_ankle", 5),
    ("spine3", 6),
    ("left_foot", 7),
    ("right_foot", 8),
    ("neck", 9),
    ("left_collar", 9),
    ("right_collar", 9),
    ("head", 12),
    ("left_shoulder", 13),
    ("right_shoulder", 14),
    ("left_elbow", 16),
    ("right_elbow", 17),
    ("left_wrist", 18),
    ("right_wrist", 19),
];

const FINGERS: [&str; 5] = ["index", "middle", "pinky", "ring", "thumb"];

/// The body model a `poses` array is for, by its width.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Model {
    /// SMPL-H (AMASS's own files): 52 joints, `poses` of 156 columns.
    SmplH,
    /// SMPL-X (AMASS's SMPL-X release): 55 joints, `poses` of 165 columns.
    SmplX,
}

impl Model {
    /// The model whose `poses` rows have `width` values, if any.
    pub fn of_width(width: u64) -> Option<Model> {
        match width {
            156 => Some(Model::SmplH),
            165 => Some(Model::SmplX),
            _ => None,
        }
    }

    /// `SMPL-H` or `SMPL-X`.
    pub fn name(self) -> &'static str {
        match self {
            Model::SmplH => "SMPL-H",
            Model::SmplX => "SMPL-X",
        }
    }

    /// The number of joints: 52 or 55.
    pub fn joint_count(self) -> usize {
        match self {
            Model::SmplH => 52,
            Model::SmplX => 55,
        }
    }

    /// The first joint of the left hand (22 or 25); the right hand's is 15 further.
    fn hands(self) -> usize {
        self.joint_count() - 30
    }

    /// The joints' names, in `poses` order.
    pub fn names(self) -> Vec<String> {
        let mut out: Vec<String> = BODY.iter().map(|(n, _)| n.to_string()).collect();
        if self == Model::SmplX {
            out.extend(["jaw", "left_eye_smplhf", "right_eye_smplhf"].map(String::from));
        }
        for side in ["left", "right"] {
            for f in FINGERS {
                out.extend((1..=3).map(|k| format!("{side}_{f}{k}")));
            }
        }
        out
    }

    /// Each joint's parent (`None` for the pelvis), in `poses` order; a parent comes first.
    pub fn parents(self) -> Vec<Option<usize>> {
        let mut out: Vec<Option<usize>> =
            BODY.iter().map(|&(_, p)| usize::try_from(p).ok()).collect();
        if self == Model::SmplX {
            out.extend([Some(15); 3]);
        }
        for wrist in [20, 21] {
            for _ in FINGERS {
                let first = out.len();
                out.extend([Some(wrist), Some(first), Some(first + 1)]);
            }
        }
        out
    }

    /// The joints of AMASS's split pose arrays, by key: `root_orient`, `pose_body`,
    /// `pose_hand`, and SMPL-X's `pose_jaw` and `pose_eye`; `None` for any other key.
    pub fn split_key(self, key: &str) -> Option<std::ops::Range<usize>> {
        let hands = self.hands();
        match (key, self) {
            ("root_orient", _) => Some(0..1),
            ("pose_body", _) => Some(1..22),
            ("pose_hand", _) => Some(hands..hands + 30),
            ("pose_jaw", Model::SmplX) => Some(22..23),
            ("pose_eye", Model::SmplX) => Some(23..25),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trees_have_their_joints_and_parents_first() {
        for (m, n) in [(Model::SmplH, 52), (Model::SmplX, 55)] {
            let (names, parents) = (m.names(), m.parents());
            assert_eq!((names.len(), parents.len()), (n, n));
            assert!(
                parents
                    .iter()
                    .enumerate()
                    .all(|(i, p)| p.is_none_or(|p| p < i))
            );
            assert_eq!(parents.iter().filter(|p| p.is_none()).count(), 1);
        }
        let (names, parents) = (Model::SmplH.names(), Model::SmplH.parents());
        assert_eq!((names[22].as_str(), parents[22]), ("left_index1", Some(20)));
        assert_eq!((names[24].as_str(), parents[24]), ("left_index3", Some(23)));
        assert_eq!(
            (names[49].as_str(), parents[49]),
            ("right_thumb1", Some(21))
        );
        let (names, parents) = (Model::SmplX.names(), Model::SmplX.parents());
        assert_eq!((names[22].as_str(), parents[22]), ("jaw", Some(15)));
        assert_eq!((names[25].as_str(), parents[25]), ("left_index1", Some(20)));
        assert_eq!(
            (names[54].as_str(), parents[54]),
            ("right_thumb3", Some(53))
        );
        assert_eq!(Model::SmplX.split_key("pose_hand"), Some(25..55));
        assert_eq!(Model::SmplH.split_key("pose_jaw"), None);
    }
}
