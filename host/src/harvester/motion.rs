//! How the machine moves: it stands still while the field settles, then its frame travels
//! along +x at the forward speed, and a shaking part is displaced along its normal by
//! d(τ) = A sin(2π f τ), τ the machine's time since it set off.
//!
//! The core moves a kinematic body with the velocity it is given. The rig steps in chunks
//! and, before each chunk, gives every part the velocity that takes it from where it *is*
//! to where the motion law puts it at the chunk's end ([`tracking_velocity_m_s`]). The path
//! between is a chord of the sine, and rounding never accumulates: each chunk starts again
//! from the body's actual position.
//!
//! ```
//! use arachis::harvester::motion::Travel;
//! let t = Travel { start_x_m: -0.3, speed_m_s: 1.0, settle_s: 0.1 };
//! assert!((t.origin_x_m(0.6) - 0.2).abs() < 1e-12);
//! ```

use super::parts::Part;
use super::Shake;
use arachis_core::units::LENGTH_M_TO_MM;

/// The machine frame's travel along the ridge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Travel {
    /// x of the machine's origin (the shovel's edge) at t = 0, m.
    pub start_x_m: f64,
    /// Forward speed, m/s.
    pub speed_m_s: f64,
    /// Time the machine stands still first, s.
    pub settle_s: f64,
}

impl Travel {
    /// The machine's time at run time `t_s`: τ = max(0, t − settle), s.
    pub fn machine_s(&self, t_s: f64) -> f64 {
        (t_s - self.settle_s).max(0.0)
    }

    /// x of the machine's origin at `t_s`, m: x0 + v τ.
    pub fn origin_x_m(&self, t_s: f64) -> f64 {
        self.start_x_m + self.speed_m_s * self.machine_s(t_s)
    }

    /// Where `part`'s centre is at `t_s`, world frame, m.
    pub fn centre_m(&self, part: &Part, t_s: f64) -> [f64; 3] {
        let d = shake_m(part.shake, self.machine_s(t_s));
        let x0 = self.origin_x_m(t_s);
        [
            x0 + part.centre_m[0] + d * part.shake_normal[0],
            part.centre_m[1] + d * part.shake_normal[1],
            part.centre_m[2] + d * part.shake_normal[2],
        ]
    }

    /// A world point `p_m` in the machine frame at `t_s`.
    pub fn to_machine_m(&self, p_m: [f64; 3], t_s: f64) -> [f64; 3] {
        [p_m[0] - self.origin_x_m(t_s), p_m[1], p_m[2]]
    }
}

/// The shake's displacement at `t_s`, m: A sin(2π f t) (0 without a shake).
pub fn shake_m(shake: Shake, t_s: f64) -> f64 {
    shake.amplitude_mm / LENGTH_M_TO_MM * (std::f64::consts::TAU * shake.frequency_hz * t_s).sin()
}

/// The velocity, m/s, that carries a body from `now_m` to `target_m` in `dt_s`.
pub fn tracking_velocity_m_s(now_m: [f64; 3], target_m: [f64; 3], dt_s: f64) -> [f64; 3] {
    [
        (target_m[0] - now_m[0]) / dt_s,
        (target_m[1] - now_m[1]) / dt_s,
        (target_m[2] - now_m[2]) / dt_s,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::harvester::parts::PartKind;

    /// Followed chunk by chunk, a shaking part's centre, sampled at the chunk ends, has the
    /// file's amplitude (its largest displacement within 0.1 % when 100 chunks cover one
    /// period: cos(π/100) = 0.9995) and returns to its rest position after one period.
    #[test]
    fn shake_has_its_amplitude_and_period() {
        let part = Part {
            kind: PartKind::Shovel,
            centre_m: [-0.1, 0.0, -0.05],
            spheres_m: vec![],
            radius_m: 0.005,
            spin_rad_s: [0.0; 3],
            shake: Shake {
                frequency_hz: 9.0,
                amplitude_mm: 3.2,
            },
            shake_normal: [0.6, 0.0, 0.8],
        };
        let travel = Travel {
            start_x_m: 0.0,
            speed_m_s: 1.0,
            settle_s: 0.0,
        };
        let period = 1.0 / 9.0;
        let chunk = period / 100.0;
        let mut at = travel.centre_m(&part, 0.0);
        let mut largest: f64 = 0.0;
        for k in 0..100 {
            let t1 = (k + 1) as f64 * chunk;
            let v = tracking_velocity_m_s(at, travel.centre_m(&part, t1), chunk);
            at = [0, 1, 2].map(|i| at[i] + v[i] * chunk);
            let rest = travel.centre_m(
                &Part {
                    shake: Shake::default(),
                    ..part.clone()
                },
                t1,
            );
            let d = (0..3)
                .map(|i| (at[i] - rest[i]).powi(2))
                .sum::<f64>()
                .sqrt();
            largest = largest.max(d);
        }
        assert!(
            (largest * LENGTH_M_TO_MM / 3.2 - 1.0).abs() < 1e-3,
            "{largest}"
        );
        let back = travel.centre_m(&part, period);
        assert!((back[2] - part.centre_m[2]).abs() < 1e-12);
        assert!((back[0] - (period + part.centre_m[0])).abs() < 1e-12);
    }
}
