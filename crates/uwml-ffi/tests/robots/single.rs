//! The robots' numbers as C gives them in f32 (`(float)x`, each field rounded once).

use super::*;

/// The f32 loss parameters, as C would convert them.
pub fn losses32(p: &UwmlJointLossParamsF64) -> UwmlJointLossParamsF32 {
    let n = f32::narrow;
    let (d, o, s) = (&p.drive, &p.oil, &p.seal);
    UwmlJointLossParamsF32 {
        drive: UwmlDriveParamsF32 {
            torque_constant: n(d.torque_constant),
            ratio: n(d.ratio),
            efficiency: n(d.efficiency),
            rated_current: n(d.rated_current),
        },
        oil: UwmlOilParamsF32 {
            k_oil: n(o.k_oil),
            exponent: n(o.exponent),
            pressure_sensitivity: n(o.pressure_sensitivity),
            temperature_sensitivity: n(o.temperature_sensitivity),
            reference_pressure: n(o.reference_pressure),
            reference_temperature: n(o.reference_temperature),
        },
        seal: UwmlSealParamsF32 { c: s.c.map(n), s: s.s.map(n), d: s.d.map(n), stribeck_speed: n(s.stribeck_speed) },
        epsilon: n(p.epsilon),
        has_oil: p.has_oil,
        has_seal: p.has_seal,
    }
}

fn f3(x: [f64; 3]) -> [f32; 3] {
    x.map(f32::narrow)
}

/// The f32 parameters, as C would convert them.
pub struct Params32 {
    pub joints: Vec<UwmlTreeJointF32>,
    pub links: Vec<UwmlBodyF32>,
    pub base: Option<UwmlBodyF32>,
    pub segments: Vec<UwmlRobotSegmentF32>,
}

pub fn body32(b: &UwmlBodyF64) -> UwmlBodyF32 {
    UwmlBodyF32 { mass: f32::narrow(b.mass), com: f3(b.com), volume: f32::narrow(b.volume), cob: f3(b.cob) }
}

pub fn params32(p: &Params) -> Params32 {
    Params32 {
        joints: p
            .joints
            .iter()
            .map(|j| UwmlTreeJointF32 { parent: j.parent, kind: j.kind, origin: f3(j.origin), axis: f3(j.axis) })
            .collect(),
        links: p.links.iter().map(body32).collect(),
        base: p.base.as_ref().map(body32),
        segments: p
            .segments
            .iter()
            .map(|s| UwmlRobotSegmentF32 {
                owner: s.owner,
                section: s.section,
                start: f3(s.start),
                axis: f3(s.axis),
                length: f32::narrow(s.length),
                area: f32::narrow(s.area),
                normals: s.normals.map(f3),
                widths: s.widths.map(f32::narrow),
                diameter: f32::narrow(s.diameter),
                cd: s.cd.map(f32::narrow),
                cm: s.cm.map(f32::narrow),
                cd_axial: f32::narrow(s.cd_axial),
                axial_area: f32::narrow(s.axial_area),
            })
            .collect(),
    }
}

pub fn motion32(m: &UwmlBaseMotionF64) -> UwmlBaseMotionF32 {
    UwmlBaseMotionF32 {
        orientation: m.orientation.map(f32::narrow),
        velocity: f3(m.velocity),
        angular_velocity: f3(m.angular_velocity),
        acceleration: f3(m.acceleration),
        angular_acceleration: f3(m.angular_acceleration),
    }
}

pub fn current32(c: &UwmlCurrentF64) -> UwmlCurrentF32 {
    UwmlCurrentF32 { velocity: f3(c.velocity), acceleration: f3(c.acceleration) }
}
