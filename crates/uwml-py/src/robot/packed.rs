//! The robot model from the packed arrays `uwml.Robot` sends: joints, bodies, segments.

use uwml_core::nalgebra::Vector3;
use uwml_core::{JointKind, ModelError, Owner, Problem, RigidBody, RobotSegment, Section, TreeJoint};

use super::{BODY_WIDTH, Model, SEGMENT_WIDTH, TREE_JOINT_WIDTH};

pub(super) fn v3(x: &[f64]) -> Vector3<f64> {
    Vector3::from_iterator(x.iter().copied().chain(core::iter::repeat(f64::NAN)).take(3))
}

pub(super) fn body(row: &[f64]) -> RigidBody<f64> {
    let at = |i: usize| row.get(i).copied().unwrap_or(f64::NAN);
    let tail = |i: usize| row.get(i..).unwrap_or(&[]);
    RigidBody { mass: at(0), com: v3(tail(1)), volume: at(4), cob: v3(tail(5)) }
}

/// An index from a float, or an error naming the field.
pub(super) fn index(x: f64, field: &'static str, i: usize) -> Result<Option<usize>, ModelError> {
    if x == -1.0 {
        Ok(None)
    } else if x >= 0.0 && x.fract() == 0.0 && x < 1e9 {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        Ok(Some(x as usize))
    } else {
        Err(ModelError { field, index: Some(i), problem: Problem::OutOfRange })
    }
}

pub(super) fn build(joints: &[f64], links: &[f64], base: &[f64], segments: &[f64]) -> Result<Model, ModelError> {
    let joint_list = joints
        .chunks_exact(TREE_JOINT_WIDTH)
        .enumerate()
        .map(|(i, r)| {
            let tail = |k: usize| r.get(k..).unwrap_or(&[]);
            Ok(TreeJoint {
                parent: index(r.first().copied().unwrap_or(f64::NAN), "joint.parent", i)?,
                kind: match r.get(1) {
                    Some(&0.0) => JointKind::Revolute,
                    Some(&1.0) => JointKind::Prismatic,
                    _ => return Err(ModelError { field: "joint.kind", index: Some(i), problem: Problem::OutOfRange }),
                },
                origin: v3(tail(2)),
                axis: v3(tail(5)),
            })
        })
        .collect::<Result<Vec<_>, ModelError>>()?;
    let link_list: Vec<_> = links.chunks_exact(BODY_WIDTH).map(body).collect();
    let segment_list = segments
        .chunks_exact(SEGMENT_WIDTH)
        .enumerate()
        .map(|(i, r)| {
            let at = |k: usize| r.get(k).copied().unwrap_or(f64::NAN);
            let tail = |k: usize| r.get(k..).unwrap_or(&[]);
            let section = match at(1) {
                0.0 => Section::Rectangular { normals: [v3(tail(10)), v3(tail(13))], widths: [at(16), at(17)] },
                1.0 => Section::Circular { diameter: at(18) },
                _ => return Err(ModelError { field: "segment.section", index: Some(i), problem: Problem::OutOfRange }),
            };
            Ok(RobotSegment {
                owner: index(at(0), "segment.owner", i)?.map_or(Owner::Base, Owner::Link),
                start: v3(tail(2)),
                axis: v3(tail(5)),
                length: at(8),
                area: at(9),
                section,
                cd: [at(19), at(20)],
                cm: [at(21), at(22)],
            })
        })
        .collect::<Result<Vec<_>, ModelError>>()?;
    Model::new(&joint_list, &link_list, body(base), &segment_list)
}
